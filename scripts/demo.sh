#!/usr/bin/env bash
# make demo: render the built-in scenes, the bunny (in a corner) and FZK-Haus with and without AO
# into out/, side by side with the AO map, measure how much of the AO reaches the final image, and
# write out/index.html with the shot whose AO shows most first.
# usage: scripts/demo.sh OBSCURA_BINARY OUT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-build/obscura}
out=${2:-out}
size=${DEMO_SIZE:-640x480}
mkdir -p "$out"
timings="$out/timings.txt"
: >"$timings"

# scene camera: every scene with its preferred camera, plus a second view of the real scenes.
shots=(
    "cornell front"
    "corner diagonal"
    "sphere-on-plane contact"
    "cornell-obj front"
    "bunny-corner front"
    "bunny-corner side"
    "fzk-haus exterior"
    "fzk-haus bedroom"
    "fzk-haus stair"
)

start=$(date +%s)
# The default method (OB_DEFAULT_METHOD, the one closest to the ray-traced AO_R), from the binary.
method=$("$bin" list --json | python3 -c 'import json, sys; print(json.load(sys.stdin)["default_method"])')
"$bin" render --scene corner --size 32x24 --out "$out/.probe.png" -v 2>&1 | sed '/^obscura: hdr: /d; s/^obscura: /demo: /'
rm -f "$out/.probe.png"
for shot in "${shots[@]}"; do
    read -r scene camera <<<"$shot"
    name="${scene}_${camera}"
    printf 'demo: %-26s' "$name"
    t0=$(date +%s.%N)
    # Five frames: the first pays for shader compilation, the medians are of warm frames.
    # -v: the frame's exposure (stderr), which the no-AO frame then shares.
    if ! "$bin" render --scene "$scene" --camera "$camera" --size "$size" --method "$method" --frames 5 --timings -v \
        --out "$out/$name.png" --ao-png "$out/${name}_ao.png" --ao-out "$out/${name}_ao.pfm" >>"$timings" \
        2>"$out/.render.log"; then
        cat "$out/.render.log" >&2
        exit 1
    fi
    "$here/noao_frame.sh" "$bin" "$out/.render.log" "$out/${name}_noao.png" --scene "$scene" --camera "$camera" \
        --size "$size"
    # Without AO | with AO | the AO map: what the AO changes, and where.
    python3 "$here/side_by_side.py" "$out/${name}_sidebyside.png" "$out/${name}_noao.png" "$out/$name.png" \
        "$out/${name}_ao.png"
    awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf " %5.1f s\n", b - a }'
    echo >>"$timings"
done
# Contact sheets: every method side by side (final image and AO map), with its AO pass time.
for shot in "cornell front" "bunny-corner front" "fzk-haus stair"; do
    read -r scene camera <<<"$shot"
    printf 'demo: %-26s' "sheet_$scene"
    t0=$(date +%s.%N)
    "$bin" sheet --scene "$scene" --camera "$camera" --size 320x240 --out "$out/sheet_$scene.png" >/dev/null
    awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf " %5.1f s\n", b - a }'
done
# Every method against the ray-traced ground truth (cached after the first run).
# compare's stage lines (stderr) go under their own label, indented, not onto the label's line.
echo "demo: report (every method against the ground truth)"
t0=$(date +%s.%N)
"$bin" compare --scene cornell:front --scene bunny-corner:front --scene fzk-haus:stair --size 320x240 \
    --report "$out/report" 2>&1 >/dev/null | sed 's/^/demo:   /'
awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "demo: %-26s %5.1f s\n", "report", b - a }'
# How much of the AO the final image shows (issue 20), on the report's views, where the reference
# AO_R is known: the default method against none, both composed with the same lights and tone
# mapped at the default method's frame's exposure (the report's own none_final has its own, which
# hides part of the AO and shifts the open areas instead).
for view in cornell_front bunny-corner_front fzk-haus_stair; do
    v="$out/report/$view"
    scene=${view%_*}
    camera=${view##*_}
    pair=(--scene "$scene" --camera "$camera" --size 320x240)
    if ! "$bin" render "${pair[@]}" --method "$method" -v --out "$out/visibility_${view}_$method.png" 2>"$out/.render.log"; then
        cat "$out/.render.log" >&2
        exit 1
    fi
    "$here/noao_frame.sh" "$bin" "$out/.render.log" "$out/visibility_${view}_noao.png" "${pair[@]}"
    python3 "$here/side_by_side.py" "$out/visibility_$view.png" "$out/visibility_${view}_noao.png" \
        "$out/visibility_${view}_$method.png" "$v/${method}_ao.png" "$v/reference_ao.png"
    python3 "$here/ao_visibility.py" --label "demo: visibility $view ($method)" "$out/visibility_${view}_$method.png" \
        "$out/visibility_${view}_noao.png" "$v/reference_ao.png"
done
rm -f "$out/.render.log"
# The front page: every shot, the one whose AO changes its image most first (measured above's way,
# on this run's images).
names=()
for shot in "${shots[@]}"; do
    read -r scene camera <<<"$shot"
    names+=("${scene}_${camera}")
done
ranked=$(python3 "$here/demo_index.py" "$out" "${names[@]}")
printf '%s\n' "$ranked" | sed -n '1,3s/^/demo: strongest: /p'
echo "demo: $(ls "$out"/*.png | wc -l) images in $out/ in $(( $(date +%s) - start )) s; GPU time per pass in $timings"
echo "demo: *_sidebyside.png: without AO | with AO | AO map, both frames at the with-AO frame's exposure;"
echo "demo:   visibility_*.png: the same at the report's size"
echo "demo:   and the reference AO_R beside them"
echo "demo: open $out/index.html first (every shot, the clearest AO first), then"
echo "demo:   $out/report/index.html (every method against the ground truth)"
