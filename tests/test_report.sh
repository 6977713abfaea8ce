#!/usr/bin/env bash
# obscura compare end to end at 64x64: the JSON lists every method with finite numbers, and the
# HTML report opens in headless Chromium (Debian's) with no console error, every image loaded,
# a non-blank screenshot, and a hostile scene name shown as text, not markup.
set -u
OBSCURA=$1
IMGCHECK=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# A model whose name is markup: a floor and a box, as OBJ.
hostile="$dir/<img src=x onerror=alert(1)>.obj"
cat >"$hostile" <<'OBJ'
v -2 0 -2
v 2 0 -2
v 2 0 2
v -2 0 2
v -0.5 0 -0.5
v 0.5 0 -0.5
v 0.5 1 -0.5
v -0.5 1 -0.5
v -0.5 0 0.5
v 0.5 0 0.5
v 0.5 1 0.5
v -0.5 1 0.5
f 1 4 3 2
f 5 6 7 8
f 10 9 12 11
f 9 5 8 12
f 6 10 11 7
f 8 7 11 12
OBJ

if "$OBSCURA" compare --scene corner:diagonal --scene "$hostile" --size 64x64 --spp 32 --report "$dir/report" \
    >"$dir/stdout" 2>"$dir/stderr"; then ok; else bad "compare failed: $(tail -3 "$dir/stderr")"; fi
grep -q "report: $dir/report/index.html" "$dir/stdout" && ok || bad "compare does not print the report path"

if python3 - "$dir/report/results.json" "$OBSCURA" <<'PY'
import json, math, subprocess, sys
r = json.load(open(sys.argv[1]))
names = [m["name"] for m in json.loads(subprocess.check_output([sys.argv[2], "list", "--json"]))["methods"]]
assert len(r["views"]) == 2, len(r["views"])
for v in r["views"]:
    got = [m["method"] for m in v["methods"]]
    assert got == names, (got, names)
    assert v["reference"]["mean_standard_error"] > 0
    for m in v["methods"]:
        for k in ("rmse", "bias", "ssim", "ao_ms"):
            assert isinstance(m[k], (int, float)) and math.isfinite(m[k]), (m["method"], k, m[k])
        assert 0 <= m["rmse"] <= 1 and -1 <= m["bias"] <= 1 and m["ao_ms"] >= 0
    # Directional methods (SSDO) are also compared as radiance against the one-bounce reference.
    listed = {m["name"]: m for m in json.loads(subprocess.check_output([sys.argv[2], "list", "--json"]))["methods"]}
    for m in v["methods"]:
        if m["method"].startswith("ssdo"):
            assert "radiance" in m and math.isfinite(m["radiance"]["rmse"]) and m["radiance"]["rmse"] >= 0, m
        else:
            assert "radiance" not in m, m
    none = next(m for m in v["methods"] if m["method"] == "none")
    # none reports 1 everywhere: its bias is 1 - mean(AO_R), the most a method can miss.
    assert none["bias"] >= 0, none
PY
then ok; else bad "results.json"; fi

# Every image the page names exists and decodes.
imgs=$(grep -o 'src="[^"]*\.png"' "$dir/report/index.html" | sed 's/src="//; s/"$//')
count=0
for i in $imgs; do
    count=$((count + 1))
    "$IMGCHECK" "$dir/report/$i" >/dev/null 2>&1 || bad "image $i does not decode"
done
[ "$count" -gt 10 ] && ok || bad "the page names only $count images"
grep -q '&lt;img src=x onerror=alert(1)&gt;' "$dir/report/index.html" && ok || bad "the hostile name is not escaped"
grep -q '<img src=x' "$dir/report/index.html" && bad "the hostile name reached the page as markup" || ok
grep -q '<svg' "$dir/report/index.html" && ok || bad "no chart in the page"

# Headless Chromium: no console errors or failed loads, and a screenshot that is not blank.
chrome=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chrome" ]; then
    bad "chromium is not installed (scripts/install-deps.sh installs it)"
else
    flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
           --disable-component-update --disable-sync --user-data-dir="$dir/profile" --enable-logging=stderr --v=0
           --allow-file-access-from-files --window-size=1200,1600)
    timeout 120 "$chrome" "${flags[@]}" --screenshot="$dir/shot.png" "file://$dir/report/index.html" \
        >"$dir/chrome.out" 2>"$dir/chrome.err"
    [ -s "$dir/shot.png" ] && ok || bad "no screenshot: $(tail -3 "$dir/chrome.err")"
    if grep -E 'CONSOLE|Uncaught|ERR_FILE_NOT_FOUND|Failed to load resource' "$dir/chrome.err" >"$dir/console"; then
        bad "console messages: $(head -5 "$dir/console")"
    else
        ok
    fi
    read -r w h c lo hi mean < <("$IMGCHECK" "$dir/shot.png")
    [ "${hi:-0}" -gt "${lo:-0}" ] && ok || bad "the screenshot is blank ($lo..$hi)"
    timeout 120 "$chrome" "${flags[@]}" --dump-dom "file://$dir/report/index.html" >"$dir/dom.html" 2>/dev/null
    grep -q 'class="sortable"' "$dir/dom.html" && ok || bad "the DOM has no sortable table"
fi

echo "test_report: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
