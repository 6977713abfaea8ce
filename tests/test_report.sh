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
        # sRGB PSNR (XeGTAO's measure) beside the linear one: no method here matches the
        # reference exactly, and the encoding changes the number.
        for k in ("psnr", "psnr_srgb"):
            assert isinstance(m[k], (int, float)) and math.isfinite(m[k]) and 0 < m[k] < 100, (m["method"], k, m[k])
        assert m["psnr_srgb"] != m["psnr"], m
    # Directional methods (SSDO's M, vbgi's bounce) are also compared as radiance against the
    # one-bounce reference.
    listed = {m["name"]: m for m in json.loads(subprocess.check_output([sys.argv[2], "list", "--json"]))["methods"]}
    for m in v["methods"]:
        if m["method"].startswith("ssdo") or m["method"] == "vbgi":
            assert "radiance" in m and math.isfinite(m["radiance"]["rmse"]) and m["radiance"]["rmse"] >= 0, m
        else:
            assert "radiance" not in m, m
    none = next(m for m in v["methods"] if m["method"] == "none")
    # none reports 1 everywhere: its bias is 1 - mean(AO_R), the most a method can miss.
    assert none["bias"] >= 0, none
# scenes/views.json's sets: corner:diagonal is a choose view, the hostile model in none; the choose
# means are that one view's RMSEs, and there is no check view here.
assert [v["set"] for v in r["views"]] == ["choose", None], [v["set"] for v in r["views"]]
# The rows' ms are GPU time, frame_ms the sum of the frame's passes, not wall-clock time.
assert "GL_TIMESTAMP" in r["timing"] and "frame_ms the sum of every timed pass" in r["timing"] and \
    "not wall-clock time" in r["timing"], r["timing"]
assert r["sets"]["check"] is None and r["sets"]["choose"]["views"] == 1, r["sets"]
for m in r["views"][0]["methods"]:
    assert abs(r["sets"]["choose"]["mean_rmse"][m["label"]] - m["rmse"]) < 1e-12, m["label"]
PY
then ok; else bad "results.json"; fi
grep -q "<h2>Choose and check views</h2>" "$dir/report/index.html" && grep -q "diagonal <span class=\"note\">(a choose view)" "$dir/report/index.html" &&
    ok || bad "the report does not show the views' sets"

# Error where it matters: every view has the four metric masks (settings, pixel counts, an image
# each), and every method its RMSE and bias inside each (null where the mask is empty).
if python3 - "$dir/report" "$IMGCHECK" <<'PY'
import json, math, os, subprocess, sys
report, imgcheck = sys.argv[1], sys.argv[2]
r = json.load(open(os.path.join(report, "results.json")))
names = ["occluded", "silhouette", "thin", "border"]
html = open(os.path.join(report, "index.html"), encoding="utf-8").read()
assert html.count('class="sortable masks"') == len(r["views"]), "one mask table per view"
assert "<th>silhouette RMSE</th>" in html
def stats(*args):
    return [float(x) for x in subprocess.check_output([imgcheck, *args], text=True).split()]
for v in r["views"]:
    s = v["mask_settings"]
    # 64 wide: the band and the reach never go below one pixel.
    assert (s["occluded_below"], s["edge_relative"], s["edge_band_px"], s["thin_reach_px"], s["border_fraction"]) == \
        (0.75, 0.1, 1, 1, 0.05), s
    assert abs(s["thin_depth"] - v["radius"]) <= 1e-6 * v["radius"], s
    assert list(v["masks"]) == names, list(v["masks"])
    geometry = v["methods"][0]["pixels"]
    for name in names:
        mask = v["masks"][name]
        assert isinstance(mask["pixels"], int) and 0 <= mask["pixels"] <= geometry, (name, mask)
        assert mask["image"] == "%s/mask_%s.png" % (v["dir"], name), mask
        path = os.path.join(report, mask["image"])
        assert os.path.exists(path) and 'src="%s"' % mask["image"] in html, path
        # White marks the mask and nothing else does: the image holds 255 exactly when the mask
        # has pixels.
        w, h, c, lo, hi, mean = stats(path)
        assert (w, h, c) == (64, 64, 3) and (hi == 255) == (mask["pixels"] > 0), (path, hi, mask)
    # A crease (corner) and a box on a floor: both have occluded pixels and silhouettes.
    assert v["masks"]["occluded"]["pixels"] > 0 and v["masks"]["silhouette"]["pixels"] > 0, v["masks"]
    # The border band is 3 pixels (5 % of 64) wide: at most 64^2 - 58^2 pixels, none inside.
    assert v["masks"]["border"]["pixels"] <= 64 * 64 - 58 * 58, v["masks"]["border"]
    inner = stats("region", "3", "3", "58", "58", os.path.join(report, v["masks"]["border"]["image"]))
    assert inner[1] < 255, ("border mask inside the band", inner)
    for m in v["methods"]:
        assert list(m["masks"]) == names, (m["method"], list(m["masks"]))
        for name in names:
            e = m["masks"][name]
            assert e["pixels"] == v["masks"][name]["pixels"], (m["method"], name, e)
            if e["pixels"] == 0:
                assert e["rmse"] is None and e["bias"] is None, (m["method"], name, e)
                continue
            assert math.isfinite(e["rmse"]) and math.isfinite(e["bias"]), (m["method"], name, e)
            assert 0 <= e["rmse"] <= 1 and -1 <= e["bias"] <= 1 and abs(e["bias"]) <= e["rmse"] + 1e-12, \
                (m["method"], name, e)
    # none reports 1 everywhere and the occluded mask is where AO_R < 0.75: its bias there is
    # over 0.25.
    none = next(m for m in v["methods"] if m["method"] == "none")
    assert none["masks"]["occluded"]["bias"] > 0.25, none["masks"]["occluded"]
PY
then ok; else bad "results.json: metric masks"; fi

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
grep -q '<th>frame GPU ms</th>' "$dir/report/index.html" && grep -q "which is not the frame's wall-clock time" "$dir/report/index.html" &&
    ok || bad "the report does not say what frame ms is"

# expect_compare CODE PATTERN -- ARGS...: exit code, one stderr line matching PATTERN, and no report
# left: bad input is found before anything is written.
expect_compare() {
    local code=$1 pattern=$2
    shift 3
    rm -rf "$dir/bad"
    "$OBSCURA" compare "$@" --report "$dir/bad" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    local lines
    lines=$(wc -l <"$dir/stderr")
    if [ "$got" -ne "$code" ]; then bad "compare $* exited $got, want $code: $(cat "$dir/stderr")"; return; fi
    if [ "$lines" -ne 1 ]; then bad "compare $* printed $lines lines on stderr: $(cat "$dir/stderr")"; return; fi
    if ! grep -qiE -e "$pattern" "$dir/stderr"; then bad "compare $*: '$(cat "$dir/stderr")' lacks /$pattern/"; return; fi
    if [ -e "$dir/bad" ]; then bad "compare $* left a report: $(ls -R "$dir/bad")"; return; fi
    ok
}
C=(--scene corner --size 32x24 --spp 8)
expect_compare 2 "^obscura: --filters: unknown filter 'nosuch'" -- "${C[@]}" --filters none,nosuch
expect_compare 2 "^obscura: --filters: expected a comma list, got ''$" -- "${C[@]}" --filters ''
expect_compare 2 "^obscura: --filters: empty element in 'none,,geometry'$" -- "${C[@]}" --filters none,,geometry
expect_compare 2 "^obscura: --filters: 'none' is listed twice" -- "${C[@]}" --filters none,none
expect_compare 2 "^obscura: --ao-scales: expected 1, 0.5 or 0.25, got '0.3'$" -- "${C[@]}" --ao-scales 0.3
expect_compare 2 "^obscura: --ao-scales: '0.5' is listed twice" -- "${C[@]}" --ao-scales 1,0.5,0.5
expect_compare 2 "^obscura: --methods: expected a comma list, got ''$" -- "${C[@]}" --methods ''
expect_compare 2 "^obscura: --methods: unknown method 'nosuch'" -- "${C[@]}" --methods ssao,nosuch
expect_compare 2 "^obscura: --quality: expected low, medium, high or ultra, got 'bogus' in 'low,bogus'$" -- "${C[@]}" --quality low,bogus
expect_compare 2 "exclude each other" -- "${C[@]}" --quality low --samples 12
expect_compare 2 "hbao.radius=0.5: method 'hbao' is not in --methods" -- "${C[@]}" --methods ssao --set hbao.radius=0.5
expect_compare 2 "unknown camera 'nosuch'" -- "${C[@]}" --scene corner:nosuch
expect_compare 2 "GL_MAX_TEXTURE_SIZE" -- "${C[@]}" --size 100000x8
# A report directory that exists keeps what it had.
mkdir -p "$dir/kept" && echo keep >"$dir/kept/notes.txt"
"$OBSCURA" compare "${C[@]}" --filters none,none --report "$dir/kept" >/dev/null 2>&1
[ "$(ls "$dir/kept")" = "notes.txt" ] && ok || bad "a failed compare changed an existing report: $(ls "$dir/kept")"

# Lists: every combination of --methods x --filters x --ao-scales is its own row, labelled with
# the settings that vary, with its own images, in results.json, the table and the chart.
if "$OBSCURA" compare --scene cornell:front --methods hbao --filters none,geometry --ao-scales 1,0.5 --size 48x36 --spp 16 \
    --report "$dir/lists" >"$dir/stdout" 2>"$dir/stderr"; then ok; else bad "compare with lists failed: $(tail -3 "$dir/stderr")"; fi
if python3 - "$dir/lists" <<'PY'
import json, math, os, sys
report = sys.argv[1]
r = json.load(open(os.path.join(report, "results.json")))
(v,) = r["views"]
rows = v["methods"]
want = ["hbao \u00b7 filter none \u00b7 ao 1", "hbao \u00b7 filter none \u00b7 ao 0.5",
        "hbao \u00b7 filter geometry \u00b7 ao 1", "hbao \u00b7 filter geometry \u00b7 ao 0.5"]
assert [m["label"] for m in rows] == want, [m["label"] for m in rows]
assert [(m["method"], m["filter"], m["ao_scale"]) for m in rows] == [
    ("hbao", "none", 1), ("hbao", "none", 0.5), ("hbao", "geometry", 1), ("hbao", "geometry", 0.5)], rows
for m in rows:
    assert math.isfinite(m["rmse"]) and 0 <= m["rmse"] <= 1, m
assert len({m["rmse"] for m in rows}) == 4, "the settings took no effect: %s" % [m["rmse"] for m in rows]
html = open(os.path.join(report, "index.html"), encoding="utf-8").read()
chart = open(os.path.join(report, v["dir"], "chart.svg"), encoding="utf-8").read()
for label in want:
    assert "<td>%s</td>" % label in html, label
    assert label in chart, label
for stem in ("hbao_filter-none_ao-1", "hbao_filter-none_ao-0_5", "hbao_filter-geometry_ao-1", "hbao_filter-geometry_ao-0_5"):
    for kind in ("final", "ao", "error"):
        path = os.path.join(report, v["dir"], "%s_%s.png" % (stem, kind))
        assert os.path.exists(path), path
        assert 'src="%s/%s_%s.png"' % (v["dir"], stem, kind) in html, stem
PY
then ok; else bad "compare with lists: results.json, table, chart or images"; fi

# compare takes the common options: --filter, --ao-scale, --eye/--target and --set take effect.
E=(--scene corner --methods ssao --filter none --ao-scale 0.5 --eye 1.5,1.2,1.8 --target 0,0.2,0 --size 48x36 --spp 16)
if "$OBSCURA" compare "${E[@]}" --report "$dir/common" >/dev/null 2>"$dir/stderr" &&
    "$OBSCURA" compare "${E[@]}" --set ssao.radius=0.05 --report "$dir/common_set" >/dev/null 2>>"$dir/stderr"; then
    ok
else
    bad "compare with the common options failed: $(tail -3 "$dir/stderr")"
fi
if python3 - "$dir/common/results.json" "$dir/common_set/results.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for r in (a, b):
    (v,) = r["views"]
    assert v["camera"] == "explicit", v["camera"]
    (m,) = v["methods"]
    assert (m["method"], m["label"], m["filter"], m["ao_scale"]) == ("ssao", "ssao", "none", 0.5), m
ra, rb = a["views"][0]["methods"][0]["rmse"], b["views"][0]["methods"][0]["rmse"]
assert ra != rb, "--set ssao.radius took no effect (%s)" % ra
PY
then ok; else bad "compare --filter/--ao-scale/--eye/--set did not take effect"; fi

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
    # The sort indicator: a page that loads the report in a frame clicks a view's RMSE header twice
    # and presses Enter on its bias header, and writes what the report did: aria-sort and the
    # header's arrow (::after), and the rows in order.
    cat >"$dir/sort.html" <<'HTML'
<!DOCTYPE html><html><body><pre id="result">not run</pre><iframe id="r" src="report/index.html"></iframe>
<script>
document.getElementById('r').addEventListener('load', function () {
  var out = [];
  try {
    var d = this.contentDocument, table = d.querySelector('section.view table.sortable');
    var rmse = table.tHead.rows[0].cells[1], bias = table.tHead.rows[0].cells[2];
    var state = function (th) {
      var col = Array.prototype.map.call(table.tBodies[0].rows, function (r) { return r.cells[1].textContent; });
      return th.getAttribute('aria-sort') + ' ' + d.defaultView.getComputedStyle(th, '::after').content + ' ' + col.join(',');
    };
    rmse.click();
    out.push('first ' + state(rmse));
    rmse.click();
    out.push('second ' + state(rmse));
    bias.dispatchEvent(new d.defaultView.KeyboardEvent('keydown', {key: 'Enter'}));
    out.push('enter ' + bias.getAttribute('aria-sort') + ' ' + rmse.getAttribute('aria-sort') + ' ' + bias.tabIndex);
  } catch (e) { out.push('error ' + e); }
  document.getElementById('result').textContent = out.join('\n');
});
</script></body></html>
HTML
    timeout 120 "$chrome" "${flags[@]}" --dump-dom "file://$dir/sort.html" >"$dir/sort.dom" 2>/dev/null
    if python3 - "$dir/sort.dom" <<'PY'
import html, re, sys
text = html.unescape(re.search(r'<pre id="result">(.*?)</pre>', open(sys.argv[1], encoding="utf-8").read(), re.S).group(1))
lines = dict(l.split(" ", 1) for l in text.splitlines())
def rows(line):
    return [float(x) for x in line.rsplit(" ", 1)[1].split(",")]
first, second = lines["first"], lines["second"]
assert first.startswith('ascending " \u25b2" '), first
assert rows(first) == sorted(rows(first)) and len(rows(first)) > 2, first
assert second.startswith('descending " \u25bc" '), second
assert rows(second) == sorted(rows(second), reverse=True), second
assert lines["enter"] == "ascending null 0", lines["enter"]
PY
    then ok; else bad "sorting a table: $(grep -A4 'id="result"' "$dir/sort.dom" | head -5)"; fi
fi
# The sort indicator is in the page itself (no external script): the style's arrows follow aria-sort.
grep -q 'th\[aria-sort=ascending\]::after{content:" ▲"}' "$dir/report/index.html" &&
    grep -q 'th\[aria-sort=descending\]::after{content:" ▼"}' "$dir/report/index.html" &&
    grep -q "th.setAttribute('aria-sort'" "$dir/report/index.html" && ! grep -q '<script src' "$dir/report/index.html" &&
    ok || bad "the report has no sort indicator"

# The equal-time shoot-out: every listed preset x scale per method; the best row within the budget
# is within it and is the most accurate such row; the Pareto rows are undominated.
if "$OBSCURA" compare --scene corner:diagonal --size 64x48 --methods gtao,hbao --quality low,high --ao-scales 1,0.5 \
    --budget-ms 1000 --report "$dir/shoot" >/dev/null 2>"$dir/shoot.err" && python3 - "$dir/shoot/results.json" <<'PY'
import json, sys
v = json.load(open(sys.argv[1]))["views"][0]
rows = v["methods"]
assert len(rows) == 8, len(rows)
so = v["shootout"]
assert so["budget_ms"] == 1000 and [m["method"] for m in so["methods"]] == ["gtao", "hbao"], so
html = open(sys.argv[1].replace("results.json", "index.html"), encoding="utf-8").read()
assert '<table class="sortable"><thead><tr><th>method</th><th>best row within budget' in html, "the shoot-out table sorts"
for m in so["methods"]:
    assert m["within_budget"], m
    fits = [r for r in rows if r["method"] == m["method"] and r["chain_ms"] <= 1000]
    assert m["chain_ms"] <= 1000 and m["rmse"] == min(r["rmse"] for r in fits), (m, fits)
front = [r for r in rows if r["pareto"]]
assert front, rows
for a in front:
    for b in rows:
        assert not (b["chain_ms"] <= a["chain_ms"] and b["rmse"] < a["rmse"]), (a, b)
for a in rows:
    assert a["chain_ms"] >= a["ao_ms"] - 1e-9, a
PY
then ok; else bad "compare --budget-ms: $(tail -2 "$dir/shoot.err")"; fi
"$OBSCURA" compare --scene corner:diagonal --size 64x48 --budget-ms -3 --report "$dir/shoot_bad" 2>"$dir/shoot.err"
[ $? -eq 2 ] && grep -q "budget-ms" "$dir/shoot.err" && [ ! -e "$dir/shoot_bad" ] && ok || bad "--budget-ms -3: $(cat "$dir/shoot.err")"

# compare without --report: the report goes to obscura-report/ in the current directory, said
# before the run and after it.
# Its results.json records the tool's version, its commit and the command line, and opens with the
# summary across views (mean RMSE and bias, mean rank, wins, median AO ms, the front), as does the
# HTML.
if (cd "$dir" && "$OBSCURA" compare --scene corner:diagonal --scene sphere-on-plane:contact --size 32x24 --spp 8 \
    --methods ssao,vbao >"$dir/default.out" 2>"$dir/default.err") && [ -f "$dir/obscura-report/index.html" ] &&
    grep -q "no --report: the report goes to obscura-report/" "$dir/default.out" &&
    grep -q "^report: obscura-report/index.html" "$dir/default.out" &&
    python3 - "$dir/obscura-report" "$("$OBSCURA" --version)" <<'PY'
import json, os, sys
report, version = sys.argv[1], sys.argv[2]
r = json.load(open(os.path.join(report, "results.json")))
assert "obscura " + r["version"] == version and r["commit"], (r["version"], r["commit"], version)
assert r["command_line"][:3] == ["compare", "--scene", "corner:diagonal"], r["command_line"]
rows = [m["label"] for m in r["views"][0]["methods"]]
s = r["summary"]
assert [e["label"] for e in s] == rows == ["ssao", "vbao"], (s, rows)
for e in s:
    views = [next(m for m in v["methods"] if m["label"] == e["label"]) for v in r["views"]]
    # Each number is written at 6 significant digits, within 5e-7 of its value below 1: the mean of
    # the written values is within 1e-6 of the written mean.
    assert abs(e["mean_rmse"] - sum(m["rmse"] for m in views) / 2) < 2e-6, e
    assert abs(e["mean_bias"] - sum(m["bias"] for m in views) / 2) < 2e-6, e
    assert 1 <= e["mean_rank"] <= 2 and e["median_ao_ms"] > 0, e
assert sum(e["wins"] for e in s) >= 2 and any(e["front"] for e in s), s
html = open(os.path.join(report, "index.html")).read()
assert "Summary over 2 views" in html and "mean rank" in html, "no summary in the HTML"
PY
then ok
else bad "compare without --report: $(cat "$dir/default.out" "$dir/default.err" | tail -3)"; fi

# compare --orbit: the flicker table (issue 17) in results.json and the HTML, with temporal
# accumulation cutting the still camera's noise, each row's worst frame written, and the
# accumulation's settings recorded; an unknown path is one line and no report.
if "$OBSCURA" compare --scene corner:diagonal --size 48x36 --spp 16 --methods gtao --orbit 10 --path-frames 3 \
    --temporal-detail 0.25 --shadow none --report "$dir/flicker" >"$dir/flicker.out" 2>"$dir/flicker.err" &&
    python3 - "$dir/flicker" <<'PY'
import json, os, sys
report = sys.argv[1]
results = json.load(open(os.path.join(report, "results.json")))
assert results["temporal_settings"] == {"at": "before", "frames": 16, "detail": 0.25, "jitter_positions": 8}, results["temporal_settings"]
v = results["views"][0]
fl = v["flicker"]
assert fl["path"] == "orbit" and fl["orbit_degrees"] == 10 and fl["path_frames"] == 3 and fl["still_frames"] == 64, fl
assert fl["reference_warped_error"] >= 0 and fl["jitter_positions"] == 8, fl
[row] = fl["rows"]
off, on = row["temporal_off"], row["temporal_on"]
assert off["static_noise"] > 2 * on["static_noise"] > 0, row
for x in (off, on):
    assert 0 <= x["worst_frame"] < 3 and x["rmse_worst"] >= x["rmse_last"] > 0, x
    curve = x["rmse_frames"]
    assert len(curve) == 3 and curve[-1] == x["rmse_last"] and max(curve) == x["rmse_worst"], x
    assert curve[x["worst_frame"]] == x["rmse_worst"] and abs(x["rmse_mean"] - sum(curve) / 3) < 2e-6, x
    assert abs(x["warped_error"] - (x["warped_error_raw"] - fl["reference_warped_error"])) < 2e-6, x
assert on["temporal_ms"] > 0 and off["temporal_ms"] == 0, row
html = open(os.path.join(report, "index.html")).read()
assert "Flicker along an orbit of 10" in html and "_temporal_worst.png" in html and "RMSE mean off" in html
assert "before the filter, history 16 frames, detail 0.25" in html
assert "jitter the G-buffer over 8 sub-pixel points" in html
assert any(n.endswith("_temporal_worst.png") for n in os.listdir(os.path.join(report, v["dir"]))), v["dir"]
PY
then ok; else bad "compare --orbit: $(tail -2 "$dir/flicker.err")"; fi
# The path rows' reference with the jitter is AO_R averaged over its 8 points, each traced with
# its own rays: its frame-to-frame change (its Monte Carlo noise, on a static scene) is that of
# the pixel centres' reference with as many rays, where one seed for all 8 made it 2.7x that.
for j in on off; do
    "$OBSCURA" compare --scene cornell --size 64x48 --spp 64 --methods vbao --orbit 10 --path-frames 3 --shadow none \
        --jitter $j --report "$dir/flicker_$j" >"$dir/flicker.out" 2>"$dir/flicker.err" || break
done
if [ -f "$dir/flicker_off/results.json" ] && python3 - "$dir/flicker_on" "$dir/flicker_off" <<'PY'
import json, os, sys
jittered, centre = (json.load(open(os.path.join(d, "results.json")))["views"][0]["flicker"] for d in sys.argv[1:])
assert jittered["jitter_positions"] == 8 and centre["jitter_positions"] == 0, (jittered, centre)
a, b = jittered["reference_warped_error"], centre["reference_warped_error"]
print(f"reference's frame-to-frame change: 8 jitter points {a:.4f}, pixel centres {b:.4f}")
assert 0 < a < 1.5 * b, (a, b)
PY
then ok; else bad "compare --orbit --jitter off: $(tail -2 "$dir/flicker.err")"; fi
"$OBSCURA" compare --scene corner:diagonal --size 48x36 --path nowhere --report "$dir/flicker_bad" 2>"$dir/flicker_bad.err"
[ $? -ne 0 ] && [ "$(wc -l <"$dir/flicker_bad.err")" = 1 ] && grep -q "unknown camera path 'nowhere'" "$dir/flicker_bad.err" &&
    [ ! -e "$dir/flicker_bad" ] && ok || bad "compare --path nowhere: $(cat "$dir/flicker_bad.err")"

# The error-against-time charts (issue 48): every report's chart.gp (kept beside chart.svg) sets the
# axes from 0 (RMSE always; time unless the chart's times spread over more than 10x: then a log
# axis from the decade at or below the fastest row, and the SVG's title says "log scale"), past
# the largest value. In the SVG gnuplot drew, each placed label is there once, and no label's box
# (its characters x 6.2 px, 12 px high, as app/chart_layout.c estimates them) meets another or
# comes within a point's 4.95 px, or leaves the plot area the script's margins set. A run whose
# times spread far (alchemy low at a quarter of the pixels against vbgi ultra at full size) gives
# the log axis its test where the machine's times allow.
"$OBSCURA" compare --scene corner:diagonal --size 160x120 --spp 8 --methods alchemy,vbgi --quality low,ultra \
    --ao-scales 1,0.25 --report "$dir/spread" >/dev/null 2>"$dir/spread.err" || bad "compare for a log chart: $(tail -2 "$dir/spread.err")"
for rep in "$dir"/report "$dir"/lists "$dir"/common "$dir"/shoot "$dir"/obscura-report "$dir"/flicker "$dir"/spread; do
    if python3 - "$rep" <<'PY'
import json, math, os, re, sys
report = sys.argv[1]
W, H, LEFT, RIGHT, TOP, BOTTOM = 720, 420, 78, 704, 14, 362
for v in json.load(open(os.path.join(report, "results.json")))["views"]:
    gp = open(os.path.join(report, v["dir"], "chart.gp"), encoding="utf-8").read()
    svg = open(os.path.join(report, v["dir"], "chart.svg"), encoding="utf-8").read()
    rng = {a: tuple(map(float, re.search(r"^set %srange \[([^:\]]+):([^\]]+)\]$" % a, gp, re.M).groups())) for a in "xy"}
    log = re.search(r"^set logscale x", gp, re.M) is not None
    times = [m["chain_ms"] for m in v["methods"]]
    rmse = [m["rmse"] for m in v["methods"]]
    pos = [t for t in times if t > 0]
    spread = max(pos) / min(pos) if pos else 1.0
    assert log == (spread > 10), (report, v["dir"], log, spread)
    assert rng["y"][0] == 0 and rng["y"][1] >= max(rmse), rng
    if log:
        assert rng["x"][0] == 10 ** math.floor(math.log10(min(pos))), (rng, min(pos))
        assert ("log scale" in svg) and rng["x"][1] >= max(pos), rng
    else:
        assert rng["x"][0] == 0 and rng["x"][1] >= max(times) and "log scale" not in svg, rng
    for what, at in (("lmargin", LEFT / W), ("rmargin", RIGHT / W), ("tmargin", 1 - TOP / H), ("bmargin", 1 - BOTTOM / H)):
        assert abs(float(re.search(r"^set %s at screen ([0-9.]+)$" % what, gp, re.M).group(1)) - at) < 1e-5, what
    # The labels as gnuplot drew them: translate(x, baseline) and the anchor; the points' centres.
    drawn = re.findall(r'<g transform="translate\(([0-9.]+),([0-9.]+)\)"[^>]*font-size="10.00"\s+text-anchor="(\w+)">\s*'
                       r'<text>([^<]*)</text>', svg)
    points = [tuple(map(float, p)) for p in re.findall(r"href='#gpPt6' transform='translate\(([0-9.]+),([0-9.]+)\)", svg)]
    placed = re.findall(r'^[-0-9.e+]+ [-0-9.e+]+ "(.*)"$', gp, re.M)
    assert len(points) == sum(1 for t in times if t > 0 or not log), (len(points), times)
    assert sorted(t for *_, t in drawn) == sorted(placed), (drawn, placed)
    assert len(placed) >= min(len(times), 4) or len(times) > 16, ("too few labels", placed, times)
    boxes = []
    for x, y, anchor, text in drawn:
        x, y, w = float(x), float(y), len(text) * 6.2
        x0 = x if anchor == "start" else x - w if anchor == "end" else x - w / 2
        boxes.append((x0, y - 3.25 - 6, x0 + w, y - 3.25 + 6, text))
    slack = 0.5
    for i, (x0, y0, x1, y1, t) in enumerate(boxes):
        assert LEFT - slack <= x0 and x1 <= RIGHT + slack and TOP - slack <= y0 and y1 <= BOTTOM + slack, ("outside", t)
        for (a0, b0, a1, b1, u) in boxes[i + 1:]:
            assert not (x0 < a1 - slack and a0 < x1 - slack and y0 < b1 - slack and b0 < y1 - slack), ("overlap", t, u)
        for px, py in points:
            dx, dy = max(x0 - px, 0, px - x1), max(y0 - py, 0, py - y1)
            assert math.hypot(dx, dy) >= 4.95 - slack, ("covers a point", t, px, py)
    print("%s/%s: %s axis, times %.3g-%.3g ms, %d of %d labels" % (os.path.basename(report), v["dir"],
          "log" if log else "linear", min(times), max(times), len(placed), len(times)))
PY
    then ok; else bad "the chart of $rep"; fi
done

echo "test_report: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
