#!/usr/bin/env bash
# make demo's visibility numbers (issue 20) at a small size: with the default method (vbao) the
# final image differs from the no-AO frame (at the same exposure, scripts/noao_frame.sh) where the
# reference AO_R is low, and much less where it is high, on the demo's three report views; and
# scripts/ao_visibility.py itself fails when the AO does not show and refuses bad input with one
# line and exit 2.
set -u
OBSCURA=$1
SCRIPTS=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
vis() { python3 "$SCRIPTS/ao_visibility.py" "$@"; }
# The default method, as the demo takes it (list --json's default_method).
m=$("$OBSCURA" list --json | python3 -c 'import json, sys; print(json.load(sys.stdin)["default_method"])')
[ "$m" = vbao ] && ok || bad "list --json: default_method '$m', want vbao (OB_DEFAULT_METHOD)"

# The demo's lights (the scenes' own, the default constant ambient) and its report views, at 128x96:
# the reference AO_R from compare; the default method and none from render, the none frame at the
# former's exposure.
if "$OBSCURA" compare --scene cornell:front --scene bunny-corner:front --scene fzk-haus:stair --methods "$m",none \
    --size 128x96 --spp 64 --report "$dir/report" >"$dir/stdout" 2>"$dir/stderr"; then ok
else bad "compare failed: $(tail -2 "$dir/stderr")"; fi

# At least 20 % of the pixels with AO_R < 0.75 change by more than 8 levels, and they change more
# on average than the open ones (AO_R > 0.95), which change by less than a level: the pair shares
# one exposure (each at its own, Cornell's open pixels moved 3.9 levels at 320x240).
for view in cornell_front bunny-corner_front fzk-haus_stair; do
    v="$dir/report/$view"
    pair=(--scene "${view%_*}" --camera "${view##*_}" --size 128x96)
    if ! "$OBSCURA" render "${pair[@]}" --method "$m" -v --out "$dir/${view}_$m.png" 2>"$dir/${view}.log" ||
        ! "$SCRIPTS/noao_frame.sh" "$OBSCURA" "$dir/${view}.log" "$dir/${view}_none.png" "${pair[@]}" 2>"$dir/stderr"; then
        bad "$view: the pair failed: $(tail -2 "$dir/${view}.log" "$dir/stderr")"
        continue
    fi
    if out=$(vis --label "$view" --min-share 20 --contrast --max-open 1 "$dir/${view}_$m.png" "$dir/${view}_none.png" \
        "$v/reference_ao.png" 2>&1); then ok; echo "  $out"
    else bad "$out"; fi
done

# The report's final images share one exposure, the view without AO's (compare.c): Cornell's open
# pixels change by less than a level between its none and the default method, and the AO shows as
# in the pair above. The default method's frame exposed for itself (render, above) against the report's none does not:
# its open pixels move by more than a level (--max-open can fail).
v="$dir/report/cornell_front"
if out=$(vis --label "report cornell_front" --min-share 20 --contrast --max-open 1 "$v/${m}_final.png" "$v/none_final.png" "$v/reference_ao.png" 2>&1); then ok; echo "  $out"
else bad "the report's $m and none do not share an exposure: $out"; fi
vis --max-open 1 "$dir/cornell_front_$m.png" "$v/none_final.png" "$v/reference_ao.png" >"$dir/stdout" 2>"$dir/stderr"
[ $? -eq 1 ] && grep -q "a different exposure" "$dir/stderr" && ok ||
    bad "$m at its own exposure against the report's none passed --max-open 1: $(cat "$dir/stdout" "$dir/stderr")"

# noao_frame.sh needs the with-AO frame's exposure line: one line and exit 2 without it, no file.
printf 'obscura: GL_RENDERER llvmpipe\n' >"$dir/nohdr.log"
"$SCRIPTS/noao_frame.sh" "$OBSCURA" "$dir/nohdr.log" "$dir/nohdr.png" --scene corner --size 32x24 \
    >"$dir/stdout" 2>"$dir/stderr"
code=$?
[ $code -eq 2 ] && [ "$(wc -l <"$dir/stderr")" -eq 1 ] && grep -q "nohdr.log: no 'obscura: hdr: log-average' line" \
    "$dir/stderr" && [ ! -e "$dir/nohdr.png" ] && ok || bad "noao_frame.sh without an exposure line: exit $code, $(cat "$dir/stderr")"

# The measure can fail: none against itself changes nothing (exit 1, the line still printed).
vis --min-share 20 "$v/none_final.png" "$v/none_final.png" "$v/reference_ao.png" >"$dir/stdout" 2>"$dir/stderr"
code=$?
[ $code -eq 1 ] && grep -q "0.0 % of pixels" "$dir/stdout" && grep -q "share 0.0 % < 20" "$dir/stderr" && ok ||
    bad "none against none: exit $code, $(cat "$dir/stdout" "$dir/stderr")"
vis --contrast "$v/none_final.png" "$v/none_final.png" "$v/reference_ao.png" >/dev/null 2>&1
[ $? -eq 1 ] && ok || bad "--contrast passed with no change at all"

# Bad input: one line on stderr naming what is wrong, exit 2; side_by_side.py leaves no file.
expect2() {
    local pattern=$1
    shift
    "$@" >"$dir/stdout" 2>"$dir/stderr"
    local code=$?
    if [ $code -ne 2 ] || [ "$(wc -l <"$dir/stderr")" -ne 1 ] || ! grep -qE -e "$pattern" "$dir/stderr"; then
        bad "$* exited $code: $(cat "$dir/stderr") (want 2 and /$pattern/)"
    else ok; fi
}
printf 'not a png' >"$dir/text.png"
"$OBSCURA" render --scene corner --size 32x24 --method none --out "$dir/small.png" 2>/dev/null
expect2 "text.png: not a PNG" vis "$dir/text.png" "$v/none_final.png" "$v/reference_ao.png"
expect2 "missing.png: cannot read" vis "$dir/missing.png" "$v/none_final.png" "$v/reference_ao.png"
expect2 "differ in size" vis "$dir/small.png" "$v/none_final.png" "$v/reference_ao.png"
expect2 "--min-share: expected a number, got 'x'" vis --min-share x "$v/none_final.png" "$v/none_final.png" "$v/reference_ao.png"
expect2 "unknown option '--nope'" vis --nope "$v/none_final.png" "$v/none_final.png" "$v/reference_ao.png"
expect2 "^usage" vis "$v/none_final.png"
expect2 "small.png is 32x24" python3 "$SCRIPTS/side_by_side.py" "$dir/sbs.png" "$v/none_final.png" "$dir/small.png"
[ -e "$dir/sbs.png" ] && bad "side_by_side.py left $dir/sbs.png after an error" || ok

# The strip: three 128x96 images and two 4-px gaps, the middle one the with-AO image.
if python3 "$SCRIPTS/side_by_side.py" "$dir/sbs.png" "$v/none_final.png" "$v/${m}_final.png" "$v/${m}_ao.png"; then
    if python3 - "$SCRIPTS" "$dir/sbs.png" "$v/${m}_final.png" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from ao_visibility import colour, read_png
strip, final = read_png(sys.argv[2]), read_png(sys.argv[3])
assert strip[:3] == (3 * 128 + 2 * 4, 96, 3), strip[:3]
s, f = colour(strip), colour(final)
for y in (0, 47, 95):
    for x in range(128):
        assert s[y * strip[0] + 132 + x] == f[y * 128 + x], (x, y)
    assert s[y * strip[0] + 128] == b"\x80\x80\x80", "grey gap"
PY
    then ok; else bad "side-by-side strip layout"; fi
else bad "side_by_side.py failed"; fi

# make demo's front page (scripts/demo_index.py): the bunny in its corner shows clearly more AO
# than the bunny alone on its floor (0.39 against 1.28/255 at 320x240, issue 48: "give the bunny
# something to be occluded by"), the page lists the stronger shot first, and a missing image is
# one line, exit 2, no page.
mkdir -p "$dir/demo"
for view in bunny_front bunny-corner_front; do
    pair=(--scene "${view%_*}" --camera "${view##*_}" --size 128x96)
    "$OBSCURA" render "${pair[@]}" --method "$m" -v --out "$dir/demo/$view.png" 2>"$dir/demo/$view.log" &&
        "$SCRIPTS/noao_frame.sh" "$OBSCURA" "$dir/demo/$view.log" "$dir/demo/${view}_noao.png" "${pair[@]}" ||
        bad "$view: the demo pair failed: $(tail -2 "$dir/demo/$view.log")"
done
if ranked=$(python3 "$SCRIPTS/demo_index.py" "$dir/demo" bunny_front bunny-corner_front 2>&1); then
    echo "$ranked" | sed 's/^/  demo: /'
    python3 - "$dir/demo/index.html" "$ranked" <<'PY' && ok || bad "demo_index: $ranked"
import re, sys
page, ranked = open(sys.argv[1]).read(), sys.argv[2].splitlines()
means = {l.split(":")[0]: float(re.search(r"([0-9.]+)/255", l).group(1)) for l in ranked}
assert ranked[0].startswith("bunny-corner_front:"), ranked
assert means["bunny-corner_front"] > 2 * means["bunny_front"], means
assert page.index("bunny-corner_front_sidebyside.png") < page.index("bunny_front_sidebyside.png")
PY
else bad "demo_index.py failed: $ranked"; fi
rm -f "$dir/demo/index.html" "$dir/demo/bunny_front_noao.png"
expect2 "bunny_front_noao.png: cannot read" python3 "$SCRIPTS/demo_index.py" "$dir/demo" bunny_front bunny-corner_front
[ -e "$dir/demo/index.html" ] && bad "demo_index.py left index.html after an error" || ok

echo "visibility: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
