#!/usr/bin/env bash
# obscura bench: a tiny sweep runs and writes a JSON with every number (schema checked, every time
# positive and finite) and a CSV with a header and rows; bad options give exit 2 and one line.
# No timing thresholds: the numbers depend on the machine.
set -u
OBSCURA=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# expect CODE PATTERN -- ARGS...: exit code, a one-line stderr matching PATTERN, no output left.
expect() {
    local code=$1 pattern=$2
    shift 3
    rm -f "$dir"/b.json "$dir"/b.csv
    "$OBSCURA" "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    local lines
    lines=$(wc -l <"$dir/stderr")
    if [ "$got" -ne "$code" ]; then bad "obscura $* exited $got, want $code: $(cat "$dir/stderr")"; return; fi
    if [ "$lines" -ne 1 ]; then bad "obscura $* printed $lines lines on stderr: $(cat "$dir/stderr")"; return; fi
    if ! grep -qiE -e "$pattern" "$dir/stderr"; then bad "obscura $*: '$(cat "$dir/stderr")' lacks /$pattern/"; return; fi
    if [ -e "$dir/b.json" ] || [ -e "$dir/b.csv" ]; then bad "obscura $* left files"; return; fi
    ok
}

B=(bench --scene corner --frames 2 --warmup 1 --size 64x64 --json "$dir/b.json" --csv "$dir/b.csv")
expect 2 "unknown method 'nosuch'" -- "${B[@]}" --methods ssao,nosuch
expect 2 "--frames" -- "${B[@]}" --frames 0
expect 2 "WIDTHxHEIGHT" -- "${B[@]}" --size 64x
expect 2 "WIDTHxHEIGHT" -- "${B[@]}" --size 0x0
expect 2 "--samples" -- "${B[@]}" --samples 12,abc
expect 2 "--radius" -- "${B[@]}" --radius -1
expect 2 "--sizes" -- "${B[@]}" --scaling --sizes 64
expect 2 "unknown camera" -- "${B[@]}" --cameras nosuch
expect 2 "exclude" -- "${B[@]}" --stereo --scaling
expect 2 "unknown option" -- "${B[@]}" --frobnicate 1
expect 4 "cannot write" -- bench --scene corner --json /nonexistent-dir/b.json
# The lists: one line naming the option and the bad value, before anything is measured.
expect 2 "^obscura: --filters: unknown filter 'nosuch'" -- "${B[@]}" --filters none,nosuch
expect 2 "^obscura: --filters: expected a comma list, got ''$" -- "${B[@]}" --filters ''
expect 2 "^obscura: --filters: empty element in 'none,,geometry'$" -- "${B[@]}" --filters none,,geometry
expect 2 "^obscura: --filters: 'none' is listed twice" -- "${B[@]}" --filters none,none
expect 2 "^obscura: --ao-scales: expected 1, 0.5 or 0.25, got '0.3'$" -- "${B[@]}" --ao-scales 0.3
expect 2 "^obscura: --ao-scale: expected 1, 0.5 or 0.25, got '0.3'$" -- "${B[@]}" --ao-scale 0.3
expect 2 "^obscura: --adaptive: expected on or off, got 'maybe'$" -- "${B[@]}" --adaptive maybe
expect 2 "^obscura: --quality: expected low, medium, high or ultra, got 'bogus' in 'low,bogus'$" -- "${B[@]}" --quality low,bogus
expect 2 "^obscura: --samples: '12' is listed twice" -- "${B[@]}" --samples 12,12

# check_json FILE MODE: the schema, and every time positive and finite.
check_json() {
    python3 - "$1" "$2" <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
mode = sys.argv[2]
def pos(x, what):
    assert isinstance(x, (int, float)) and math.isfinite(x) and x > 0, f"{what} = {x!r}"
for k in ("renderer", "gl_version", "date", "commit", "cpu", "scene"):
    assert isinstance(d.get(k), str) and d[k], f"missing {k}"
assert d["mode"] == mode, d["mode"]
# The command line as given: every option that shaped the run, --json among them.
cl = d["command_line"]
assert cl[0] == "bench" and "--json" in cl and sys.argv[1] in cl, cl
cfgs = d["configurations"]
assert cfgs, "no configurations"
methods = set()
for c in cfgs:
    for k in ("method", "samples", "radius", "camera", "passes", "frame_ms", "fps", "ao_ms", "vs_none"):
        assert k in c, f"configuration lacks {k}"
    methods.add(c["method"])
    assert c["passes"], "no passes"
    for p in c["passes"]:
        assert isinstance(p["name"], str) and p["name"]
        for k in ("median", "min", "max"):
            pos(p[k], f'{c["method"]} {p["name"]} {k}')
        assert p["min"] <= p["median"] <= p["max"]
    names = [p["name"] for p in c["passes"]]
    if c["method"] == "none":
        # The baseline runs no AO and no filter (issue 20): its frame is the true no-AO frame.
        assert "ao" not in names and "filter" not in names and "upsample" not in names, names
    else:
        assert "ao" in names, "no ao pass"
    for k in ("median", "min", "max"):
        pos(c["frame_ms"][k], f"frame {k}")
    pos(c["fps"], "fps")
    # Both written at 6 significant digits: each within 5e-6 of its value, relative.
    assert abs(c["fps"] - 1000.0 / c["frame_ms"]["median"]) < 2e-5 * c["fps"]
    if mode != "scaling":
        v = c["vs_none"]
        for k in ("ao_minus_ms", "frame_minus_ms"):
            assert isinstance(v[k], (int, float)) and math.isfinite(v[k]), k
        pos(v["frame_ratio"], "frame_ratio")
        if c["method"] == "ssao":
            assert c["samples"] == 12 and c["radius"] == 4, (c["samples"], c["radius"])
            pos(c["radius_world"], "radius_world")
if mode != "scaling":
    assert "none" in methods and "ssao" in methods, methods
else:
    assert d["scaling"] and "flat_in_triangles" in d["scaling"][0] and "linear_in_pixels" in d["scaling"][0]
    assert sorted({c["tessellation_levels"] for c in cfgs}) == [0, 1, 2]
    tris = sorted({c["triangles"] for c in cfgs})
    assert tris[-1] == 16 * tris[0], tris
PY
}

if "$OBSCURA" "${B[@]}" --methods ssao --samples 12 --radius 4 >"$dir/stdout" 2>"$dir/stderr"; then ok; else bad "bench run: $(cat "$dir/stderr")"; fi
if check_json "$dir/b.json" sweep; then ok; else bad "bench JSON"; fi
if head -1 "$dir/b.csv" | grep -q '^scene,camera,method,samples,r,radius_world,.*,pass,median_ms,min_ms,max_ms' &&
    [ "$(wc -l <"$dir/b.csv")" -gt 4 ] && grep -q ',ssao,12,4,.*,ao,' "$dir/b.csv" && grep -q ',frame,' "$dir/b.csv"; then
    ok
else
    bad "bench CSV: $(head -3 "$dir/b.csv")"
fi
# One sample count and one radius: one table, a row per method (N, r, the cell, frame / none).
# Every ms is GPU time, and the frame's is the sum of its passes, not wall-clock time: said in the
# table's header, in the JSON (timing) and in --help.
if grep -qE "^method +N +r +AO-pass ms / frame ms \(GPU\) +frame / none" "$dir/stdout" &&
    grep -q "^== corner, camera .*, GPU ms, median of 2 frames" "$dir/stdout" &&
    grep -q "frame ms = the sum of the frame's passes, not wall-clock time" "$dir/stdout" &&
    grep -q '"timing":.*frame_ms is the sum of a frame.s timed passes.*not wall-clock time' "$dir/b.json" &&
    "$OBSCURA" bench --help | grep -q "frame ms is the sum of the" &&
    grep -qE "^ssao +12 +4 +[0-9.]+ / [0-9.]+ +[0-9.]+x" "$dir/stdout"; then ok; else bad "bench table: $(cat "$dir/stdout")"; fi
# Two sample counts: a table per method, rows N, columns r.
if "$OBSCURA" "${B[@]}" --methods ssao --samples 12,24 --radius 4 >"$dir/stdout" 2>"$dir/stderr" &&
    grep -q "^ssao: AO-pass ms / frame ms" "$dir/stdout" && grep -q "N = 12" "$dir/stdout" && grep -q "N = 24" "$dir/stdout" &&
    grep -q "r = 4" "$dir/stdout"; then ok; else bad "bench sweep table: $(cat "$dir/stdout" "$dir/stderr")"; fi

# --ao-scale and --adaptive take effect: the AO runs at half size (downsample and upsample passes)
# in every configuration with an AO pass, and the edge pre-pass only for the method that takes
# adaptive counts (ssao). none's frame, the baseline, runs no AO-grid pass at all (AO 1 straight
# into the output), so downsample, upsample and edges count as ssao's cost.
if "$OBSCURA" "${B[@]}" --methods ssao --samples 12 --radius 4 --ao-scale 0.5 --adaptive on >"$dir/stdout" 2>"$dir/stderr" &&
    check_json "$dir/b.json" sweep && python3 - "$dir/b.json" <<'PY' &&
import json, sys
for c in json.load(open(sys.argv[1]))["configurations"]:
    passes = [p["name"] for p in c["passes"]]
    assert c["ao_scale"] == 0.5, c["ao_scale"]
    ssao = c["label"].startswith("ssao")
    for p in ("downsample", "upsample", "edges"):
        assert (p in passes) == ssao, (c["label"], passes)
PY
    ! grep -q "note" "$dir/stderr"
then ok; else bad "bench --ao-scale 0.5 --adaptive on: $(cat "$dir/stderr")"; fi

# Lists: each combination of --filters x --ao-scales is its own table and labelled rows, each
# against the none frame of its own filter and AO scale.
if "$OBSCURA" "${B[@]}" --methods ssao --samples 12 --radius 4 --cameras default --filters none,geometry --ao-scales 1,0.5 \
    >"$dir/stdout" 2>"$dir/stderr" && check_json "$dir/b.json" sweep && python3 - "$dir/b.json" "$dir/b.csv" <<'PY'
import csv, json, sys
d = json.load(open(sys.argv[1]))
cfgs = d["configurations"]
dot = " \u00b7 "
combos = [("none", 1), ("none", 0.5), ("geometry", 1), ("geometry", 0.5)]
want = ["none%sfilter %s%sao %g" % (dot, f, dot, a) for f, a in combos]
want += ["ssao%sfilter %s%sao %g%sN 12%sr 4" % (dot, f, dot, a, dot, dot) for f, a in combos]
assert [c["label"] for c in cfgs] == want, [c["label"] for c in cfgs]
assert [(c["filter"], c["ao_scale"]) for c in cfgs] == combos + combos
assert d["filter"] == "none,geometry", d["filter"]
rows = list(csv.DictReader(open(sys.argv[2], encoding="utf-8")))
assert {r["label"] for r in rows} == set(want), {r["label"] for r in rows}
assert {(r["filter"], float(r["ao_scale"])) for r in rows} == set(combos)
PY
then ok; else bad "bench lists: $(cat "$dir/stderr")"; fi
grep -qE "^ssao · filter none · ao 0.5 +12 +4 " "$dir/stdout" && ok || bad "bench lists table: $(cat "$dir/stdout")"

# Stereo (two renderers) and scaling (sizes and tessellation), tiny.
if "$OBSCURA" "${B[@]}" --methods ssao --samples 12 --radius 4 --stereo --cameras default >"$dir/stdout" 2>"$dir/stderr" &&
    check_json "$dir/b.json" stereo && grep -q '"eyes":	2' "$dir/b.json"; then
    ok
else
    bad "bench --stereo: $(cat "$dir/stderr")"
fi
if "$OBSCURA" "${B[@]}" --methods ssao --samples 12 --radius 4 --scaling --sizes 32x32,64x48 --size 32x32 >"$dir/stdout" 2>"$dir/stderr" &&
    check_json "$dir/b.json" scaling && grep -q "flat in triangles" "$dir/stdout"; then
    ok
else
    bad "bench --scaling: $(cat "$dir/stderr") $(cat "$dir/stdout")"
fi

# --host (issue 45): the host path beside the frame's AO chain, four paths per configuration in one
# run. Rows, columns and the (b)/(a) ratio are there and every time is positive and finite; no
# speed is asserted (bench/results/ holds the measurements).
expect 2 "^obscura: --host and --stereo exclude each other$" -- "${B[@]}" --host --stereo
expect 2 "^obscura: --host and --floor exclude each other$" -- "${B[@]}" --host --floor
expect 2 "^obscura: --host and --guard exclude" -- "${B[@]}" --host --guard 8
expect 2 "^obscura: --host-rmse needs --host$" -- "${B[@]}" --host-rmse corner:diagonal
expect 2 "^obscura: --host-rmse: empty scene or camera in 'corner:'$" -- "${B[@]}" --host --host-rmse corner:
expect 2 "^obscura: --host: no method to time" -- "${B[@]}" --host --methods none
expect 2 "unknown camera 'nosuch'" -- "${B[@]}" --host --host-rmse corner:nosuch

check_host() { # JSON CSV STDOUT [rmse]
    python3 - "$@" <<'PY'
import csv, json, math, sys
d = json.load(open(sys.argv[1]))
out = open(sys.argv[3]).read()
want_rmse = len(sys.argv) > 4
def pos(x, what):
    assert isinstance(x, (int, float)) and math.isfinite(x) and x > 0, f"{what} = {x!r}"
assert d["mode"] == "host", d["mode"]
assert [p["name"] for p in d["host_paths"]] == ["frame", "host_linear", "host_packed", "host_no_normals"]
chain = {"downsample", "edges", "depth_mips", "second_back", "ao", "temporal", "filter", "upsample"}
cfgs = d["configurations"]
assert [c["label"] for c in cfgs] == ["vbao \u00b7 ao 1 \u00b7 N 12 \u00b7 r 4", "vbao \u00b7 ao 0.5 \u00b7 N 12 \u00b7 r 4"], [c["label"] for c in cfgs]
for c in cfgs:
    paths = c["paths"]
    assert list(paths) == ["frame", "host_linear", "host_packed", "host_no_normals"], list(paths)
    for name, p in paths.items():
        names = [q["name"] for q in p["passes"]]
        assert "ao" in names and "filter" in names, (name, names)
        assert ("upsample" in names) == (c["ao_scale"] == 0.5), (name, names)
        for q in p["passes"]:
            for k in ("median", "min", "max"):
                pos(q[k], f'{c["label"]} {name} {q["name"]} {k}')
        for k in ("chain_ms", "total_ms", "ratio_to_frame", "call_cpu_ms"):
            pos(p[k]["median"], f"{name} {k}")
            assert p[k]["min"] <= p[k]["median"] <= p[k]["max"], (name, k, p[k])
        # (a) counts its chain passes only; (b) runs no input or output pass; (c) and (d) both.
        if name == "frame":
            assert set(names) <= chain, names
        if name in ("frame", "host_linear"):
            assert p["input_ms"] is None and p["output_ms"] is None, (name, p["input_ms"], p["output_ms"])
        else:
            assert names[0] == "input" and names[-1] == "output", (name, names)
            pos(p["input_ms"]["median"], f"{name} input")
            pos(p["output_ms"]["median"], f"{name} output")
    assert abs(paths["frame"]["ratio_to_frame"]["median"] - 1.0) < 1e-9
    pos(c["host_ratio"], "host_ratio")
    assert c["host_ratio"] == paths["host_linear"]["ratio_to_frame"]["median"]
    assert isinstance(c["host_within_target"], bool)
rows = list(csv.DictReader(open(sys.argv[2], encoding="utf-8")))
assert len(rows) == 4 * len(cfgs), len(rows)
assert [r["path"] for r in rows[:4]] == ["frame", "host_linear", "host_packed", "host_no_normals"]
for r in rows:
    for k in ("chain_ms", "total_ms", "ratio_frame", "call_cpu_ms"):
        pos(float(r[k]), k)
    assert float(r["call_cpu_min_ms"]) <= float(r["call_cpu_ms"]) <= float(r["call_cpu_max_ms"]), r
    assert (r["input_ms"] == "") == (r["path"] in ("frame", "host_linear")), r
assert out.count("(b)/(a) = ") == len(cfgs), out
for p in ("(a) frame ", "(b) host_linear ", "(c) host_packed ", "(d) host_no_normals "):
    assert out.count(p) >= len(cfgs), p
if want_rmse:
    acc = d["host_rmse"]
    assert acc["width"] == 320 and acc["reference_spp"] == 512, acc
    views = acc["views"]
    assert [(v["scene"], v["camera"], v["label"]) for v in views] == [("corner", "diagonal", "vbao \u00b7 ao 1"), ("corner", "diagonal", "vbao \u00b7 ao 0.5")], views
    for v in views:
        for p in ("frame", "host_linear", "host_packed", "host_no_normals"):
            pos(v[p]["rmse"], f'{v["label"]} {p} rmse')
        # One chain, two front doors: the host call on the frame's own G-buffer grades as the frame.
        assert abs(v["frame"]["rmse"] - v["host_linear"]["rmse"]) < 1e-3, v
    assert "host path accuracy" in out and "corner:diagonal" in out, out
else:
    assert d["host_rmse"] is None
PY
}
H=(bench --scene corner --cameras diagonal --size 64x48 --frames 2 --warmup 1 --methods vbao --samples 12 --radius 4
    --ao-scales 1,0.5 --json "$dir/b.json" --csv "$dir/b.csv")
if "$OBSCURA" "${H[@]}" --host >"$dir/stdout" 2>"$dir/stderr" && check_host "$dir/b.json" "$dir/b.csv" "$dir/stdout"; then
    ok
else
    bad "bench --host: $(cat "$dir/stderr")"
fi
# --host-rmse: the reference traced into a cache of the test's own (320x240, 512 rays a pixel).
if XDG_CACHE_HOME="$dir/cache" "$OBSCURA" "${H[@]}" --host --host-rmse corner:diagonal >"$dir/stdout" 2>"$dir/stderr" &&
    check_host "$dir/b.json" "$dir/b.csv" "$dir/stdout" rmse; then
    ok
else
    bad "bench --host --host-rmse: $(cat "$dir/stderr") $(tail -5 "$dir/stdout")"
fi

echo "test_bench: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
