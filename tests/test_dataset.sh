#!/usr/bin/env bash
# `obscura dataset` (issue 49, item 6): per view the G-buffer and AO_R as PFM with a manifest.
# Three small views: the files are there with their sizes and channels, the values keep the
# manifest's conventions (AO_R in [0, 1] and 1 on sky, unit normals on geometry), AO_R is the one
# compare grades against (its reference_ao.png), two shards write every view once and each file
# byte for byte as the whole run did, and bad input is one line, its exit code and no output.
# usage: test_dataset.sh OBSCURA
set -u
OBSCURA=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

views=(--scene corner:diagonal --scene cornell:front --scene sphere-on-plane:contact)
run=(--size 48x36 --spp 16 --bounce)
if "$OBSCURA" dataset "${views[@]}" "${run[@]}" --out "$dir/all" >"$dir/stdout" 2>"$dir/stderr"; then ok
else bad "dataset failed: $(tail -2 "$dir/stderr")"; fi
grep -qx "dataset: 3 of 3 views (shard 0/1) in $dir/all" "$dir/stdout" && ok || bad "stdout: $(cat "$dir/stdout")"

# The files, their headers and values (standard library only: no numpy on a fresh machine).
if python3 - "$dir/all" <<'PY'
import json, math, os, struct, sys
root = sys.argv[1]
m = json.load(open(os.path.join(root, "manifest.json")))
assert m["version"] and m["commit"] and m["command_line"][0] == "dataset", m
assert m["shard"] == {"index": 0, "count": 1, "views": [
    {"view": "corner:diagonal", "shard": 0}, {"view": "cornell:front", "shard": 0},
    {"view": "sphere-on-plane:contact", "shard": 0}]}, m["shard"]
for key in ("pfm", "depth", "normal", "albedo", "ao", "bounce"):
    assert m["conventions"][key], key

def pfm(path):
    data = open(path, "rb").read()
    kind, dims, scale, body = data.split(b"\n", 3)
    w, h = map(int, dims.split())
    c = {b"PF": 3, b"Pf": 1}[kind]
    assert float(scale) < 0, "little-endian"
    assert len(body) == 4 * w * h * c, (path, len(body))
    v = struct.unpack("<%df" % (w * h * c), body)
    return w, h, c, [v[i * c:(i + 1) * c] for i in range(w * h)]

assert [v["dir"] for v in m["views"]] == ["corner_diagonal", "cornell_front", "sphere-on-plane_contact"], m["views"]
for v in m["views"]:
    assert v["width"] == 48 and v["height"] == 36 and v["reference_spp"] == 16 and v["radius"] > 0, v
    assert len(v["camera_pose"]["camera_to_world"]) == 16 and len(v["camera_pose"]["proj_info"]) == 4, v
    files = {k: pfm(os.path.join(root, v["dir"], f)) for k, f in v["files"].items()}
    assert set(files) == {"depth", "normal", "albedo", "ao", "ao_stderr", "bounce"}, files.keys()
    for k, (w, h, c, px) in files.items():
        assert (w, h) == (48, 36) and c == (3 if k in ("normal", "albedo", "bounce") else 1), (k, w, h, c)
    depth, normal, ao, se = (files[k][3] for k in ("depth", "normal", "ao", "ao_stderr"))
    geometry = [i for i, d in enumerate(depth) if d[0] > 0]
    assert 0 < len(geometry) < len(depth), (v["dir"], len(geometry))
    for i, d in enumerate(depth):
        if d[0] > 0:
            assert 0.0 <= ao[i][0] <= 1.0 and abs(math.sqrt(sum(x * x for x in normal[i])) - 1.0) < 2e-3, (v["dir"], i)
            p = ao[i][0]
            assert abs(se[i][0] - math.sqrt(p * (1 - p) / 15)) < 1e-6, (v["dir"], i)
        else:
            assert ao[i][0] == 1.0 and normal[i] == (0.0, 0.0, 0.0), (v["dir"], i)
    # Some of each view is occluded: the corner, the box and the contact all are.
    assert min(ao[i][0] for i in geometry) < 0.7, v["dir"]
PY
then ok; else bad "the dataset's files"; fi

# AO_R is compare's reference: the same points, rays and cache (its PNG quantises to 8 bits).
if "$OBSCURA" compare --scene cornell:front --methods none --size 48x36 --spp 16 --report "$dir/report" \
    >/dev/null 2>"$dir/stderr" &&
    python3 - "$(dirname "$0")/../scripts" "$dir/all/cornell_front/ao.pfm" "$dir/report/cornell_front/reference_ao.png" <<'PY'
import struct, sys
sys.path.insert(0, sys.argv[1])
from ao_visibility import read_png  # the demo's PNG reader (standard library only)
data = open(sys.argv[2], "rb").read()
kind, dims, scale, body = data.split(b"\n", 3)
w, h = map(int, dims.split())
ao = struct.unpack("<%df" % (w * h), body)
pw, ph, ch, px = read_png(sys.argv[3])
rows = [px[y * pw * ch:(y + 1) * pw * ch] for y in range(ph)]
assert (pw, ph) == (w, h), (pw, ph, w, h)
worst = 0
for y in range(h):
    for x in range(w):
        level = rows[h - 1 - y][x * ch]  # the PNG is top row first, the PFM bottom row first
        worst = max(worst, abs(level - ao[y * w + x] * 255.0))
assert worst <= 1.0, worst
PY
then ok; else bad "dataset's AO_R is not compare's reference"; fi

# Two shards: every view once, each file the same bytes as the whole run's; the views go to the
# shards by their cost (equal here: in turn, 0, 1, 0).
for k in 0 1; do
    "$OBSCURA" dataset "${views[@]}" "${run[@]}" --shard "$k/2" --out "$dir/s$k" >"$dir/s$k.out" 2>"$dir/stderr" ||
        bad "shard $k/2: $(tail -1 "$dir/stderr")"
done
[ -d "$dir/s0/corner_diagonal" ] && [ -d "$dir/s0/sphere-on-plane_contact" ] && [ -d "$dir/s1/cornell_front" ] &&
    [ ! -e "$dir/s1/corner_diagonal" ] && [ ! -e "$dir/s0/cornell_front" ] && ok ||
    bad "the shards' views: $(ls "$dir/s0" "$dir/s1")"
same=1
for v in corner_diagonal cornell_front sphere-on-plane_contact; do
    for f in "$dir"/all/"$v"/*.pfm; do
        s=$(ls -d "$dir"/s?/"$v")
        cmp -s "$f" "$s/$(basename "$f")" || { same=0; echo "differs: $v/$(basename "$f")" >&2; }
    done
done
[ $same -eq 1 ] && ok || bad "a shard's file differs from the whole run's"
python3 -c '
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert a["shard"]["views"] == b["shard"]["views"] and a["shard"]["count"] == b["shard"]["count"] == 2
assert [v["view"] for v in a["views"]] == ["corner:diagonal", "sphere-on-plane:contact"], a["views"]
assert [v["view"] for v in b["views"]] == ["cornell:front"], b["views"]
' "$dir/s0/manifest.json" "$dir/s1/manifest.json" && ok || bad "the shards' manifests"

# Bad input: one line on stderr naming what is wrong, the exit code, nothing left behind.
expect() { # CODE PATTERN ARGS...
    local code=$1 pattern=$2
    shift 2
    "$OBSCURA" dataset "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    if [ $got -ne "$code" ] || [ "$(wc -l <"$dir/stderr")" -ne 1 ] || ! grep -qE -e "$pattern" "$dir/stderr"; then
        bad "dataset $* exited $got: $(cat "$dir/stderr") (want $code and /$pattern/)"
    else ok; fi
}
for s in 2/2 1 0/0 a/b 1/2x -1/2; do
    expect 2 "^obscura: --shard: expected K/N with 0 <= K < N" --scene corner --shard "$s" --out "$dir/bad"
done
expect 2 "--scene is required" --out "$dir/bad"
expect 2 "unknown scene 'bunyn'; did you mean 'bunny'" --scene bunyn --size 32x24 --spp 4 --out "$dir/bad"
expect 2 "--spp: expected 2..1048576" --scene corner --spp 1 --out "$dir/bad"
expect 2 "unknown option '--shards'" --scene corner --shards 0/2 --out "$dir/bad"
[ ! -e "$dir/bad" ] && ! ls "$dir"/bad.tmp-* >/dev/null 2>&1 && ok || bad "a failed run left $(ls -d "$dir"/bad*)"
# An existing output is never lost: a regular file, or a directory holding something else.
echo keep >"$dir/file"
expect 4 "--out" --scene corner --size 32x24 --spp 4 --out "$dir/file"
[ "$(cat "$dir/file")" = keep ] && ok || bad "--out FILE was touched"
mkdir -p "$dir/mine" && echo keep >"$dir/mine/notes.txt"
expect 4 "--out" --scene corner --size 32x24 --spp 4 --out "$dir/mine"
[ "$(cat "$dir/mine/notes.txt")" = keep ] && ok || bad "a foreign file in --out was touched"
# A dataset replaces its own earlier run whole.
if "$OBSCURA" dataset --scene corner --size 32x24 --spp 4 --out "$dir/all" >/dev/null 2>&1 && [ -d "$dir/all/corner_default" ] &&
    [ ! -e "$dir/all/cornell_front" ]; then ok; else bad "rerun into its own directory: $(ls "$dir/all")"; fi

# obscura --help lists the command.
"$OBSCURA" --help | grep -q "^  dataset " && ok || bad "obscura --help does not list dataset"

echo "dataset: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
