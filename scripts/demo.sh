#!/usr/bin/env bash
# make demo: render the built-in scenes, the bunny and FZK-Haus with and without AO into out/,
# side by side with the AO map, and measure how much of the AO reaches the final image.
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
    "bunny front"
    "bunny side"
    "fzk-haus exterior"
    "fzk-haus bedroom"
    "fzk-haus stair"
)

start=$(date +%s)
"$bin" render --scene corner --size 32x24 --out "$out/.probe.png" -v 2>&1 | sed 's/^obscura: /demo: /'
rm -f "$out/.probe.png"
for shot in "${shots[@]}"; do
    read -r scene camera <<<"$shot"
    name="${scene}_${camera}"
    printf 'demo: %-26s' "$name"
    t0=$(date +%s.%N)
    # Five frames: the first pays for shader compilation, the medians are of warm frames.
    "$bin" render --scene "$scene" --camera "$camera" --size "$size" --method gtao --frames 5 --timings \
        --out "$out/$name.png" --ao-png "$out/${name}_ao.png" --ao-out "$out/${name}_ao.pfm" >>"$timings"
    "$bin" render --scene "$scene" --camera "$camera" --size "$size" --method none --out "$out/${name}_noao.png"
    # Without AO | with AO | the AO map: what the AO changes, and where.
    python3 "$here/side_by_side.py" "$out/${name}_sidebyside.png" "$out/${name}_noao.png" "$out/$name.png" \
        "$out/${name}_ao.png"
    awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf " %5.1f s\n", b - a }'
    echo >>"$timings"
done
# Contact sheets: every method side by side (final image and AO map), with its AO pass time.
for shot in "cornell front" "bunny front" "fzk-haus stair"; do
    read -r scene camera <<<"$shot"
    printf 'demo: %-26s' "sheet_$scene"
    t0=$(date +%s.%N)
    "$bin" sheet --scene "$scene" --camera "$camera" --size 320x240 --out "$out/sheet_$scene.png" >/dev/null
    awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf " %5.1f s\n", b - a }'
done
# Every method against the ray-traced ground truth (cached after the first run).
printf 'demo: %-26s' "report"
t0=$(date +%s.%N)
"$bin" compare --scene cornell:front --scene bunny:front --scene fzk-haus:stair --size 320x240 \
    --report "$out/report" >/dev/null
awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf " %5.1f s\n", b - a }'
# How much of the AO the final image shows (issue 20), on the report's views, where the reference
# AO_R is known: the default method (gtao) against none, both composed with the same lights.
for view in cornell_front bunny_front fzk-haus_stair; do
    v="$out/report/$view"
    python3 "$here/side_by_side.py" "$out/visibility_$view.png" "$v/none_final.png" "$v/gtao_final.png" \
        "$v/gtao_ao.png" "$v/reference_ao.png"
    python3 "$here/ao_visibility.py" --label "demo: visibility $view" "$v/gtao_final.png" "$v/none_final.png" \
        "$v/reference_ao.png"
done
echo "demo: $(ls "$out"/*.png | wc -l) images in $out/ in $(( $(date +%s) - start )) s; GPU time per pass in $timings"
echo "demo: *_sidebyside.png: without AO | with AO | AO map; visibility_*.png: the same at the report's size"
echo "demo:   and the reference AO_R beside them"
echo "demo: open $out/report/index.html (every method against the ground truth)"
