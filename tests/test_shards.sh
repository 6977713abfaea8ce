#!/usr/bin/env bash
# compare --shard K/N and obscura merge (issue 49, items 1 and 2): a run split over 2 and over 3
# shards, and one split by rows over 5, merged is the unsharded run's report: the same files, every image byte for byte, and
# every number of results.json equal but the timings (GPU ms and what is ranked by them: the
# Pareto front) and the run's own facts (its date, command line, whether a reference came from the
# cache). Each shard runs only the views the cost-balanced assignment gives it. A missing, repeated
# or foreign shard is one line naming it, exit 2, and no report.
# usage: test_shards.sh OBSCURA
set -u
OBSCURA=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

run=(--scene corner:diagonal --scene cornell:front --scene sphere-on-plane:contact --methods ssao,gtao,ssdo
    --size 48x36 --spp 16)
"$OBSCURA" compare "${run[@]}" --report "$dir/whole" >/dev/null 2>"$dir/err" && ok || bad "unsharded: $(tail -1 "$dir/err")"
for n in 2 3; do
    for ((k = 0; k < n; ++k)); do
        "$OBSCURA" compare "${run[@]}" --shard "$k/$n" --report "$dir/s$k-of-$n" >/dev/null 2>"$dir/err" ||
            bad "shard $k/$n: $(tail -1 "$dir/err")"
    done
done
# Three views of equal cost over two shards: in turn (0, 1, 0); over three, one each.
[ -d "$dir/s0-of-2/corner_diagonal" ] && [ -d "$dir/s0-of-2/sphere-on-plane_contact" ] &&
    [ ! -e "$dir/s0-of-2/cornell_front" ] && [ -d "$dir/s1-of-2/cornell_front" ] &&
    [ ! -e "$dir/s1-of-2/corner_diagonal" ] && [ -d "$dir/s2-of-3/sphere-on-plane_contact" ] && ok ||
    bad "the shards' views: $(ls "$dir"/s*)"
python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["shard"] == {"index": 1, "count": 2, "views": [{"view": "corner:diagonal", "shard": 0},
    {"view": "cornell:front", "shard": 1}, {"view": "sphere-on-plane:contact", "shard": 0}]}, d["shard"]
assert [v["camera"] for v in d["views"]] == ["front"], d["views"]
# The shards share the reference cache the unsharded run filled: each finds the entry of its view.
assert d["views"][0]["reference"]["cached"] is True, d["views"][0]["reference"]
' "$dir/s1-of-2/results.json" && ok || bad "shard 1/2's results.json"

# same WHOLE MERGED: the unsharded run's report, up to timings (tests/report_same.py).
same() { python3 "$(dirname "$0")/report_same.py" "$1" "$2"; }
# Given in any order.
"$OBSCURA" merge "$dir/s1-of-2" "$dir/s0-of-2" --report "$dir/merged2" >"$dir/out" 2>"$dir/err" && ok ||
    bad "merge of 2: $(cat "$dir/err")"
grep -qx "report: $dir/merged2/index.html" "$dir/out" && ok || bad "merge's stdout: $(cat "$dir/out")"
same "$dir/whole" "$dir/merged2" && ok || bad "2 shards merged differ from the unsharded run"
"$OBSCURA" merge "$dir/s2-of-3" "$dir/s0-of-3" "$dir/s1-of-3" --report "$dir/merged3" >/dev/null 2>"$dir/err" && ok ||
    bad "merge of 3: $(cat "$dir/err")"
same "$dir/whole" "$dir/merged3" && ok || bad "3 shards merged differ from the unsharded run"

# Bad input: one line naming the shard, exit 2 (3 for a file that is not what it claims), no report.
expect() { # CODE PATTERN ARGS...
    local code=$1 pattern=$2
    shift 2
    "$OBSCURA" "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    if [ $got -ne "$code" ] || [ "$(wc -l <"$dir/stderr")" -ne 1 ] || ! grep -qE -e "$pattern" "$dir/stderr"; then
        bad "$* exited $got: $(cat "$dir/stderr") (want $code and /$pattern/)"
    else ok; fi
}
expect 2 "shard 1/2 is missing \(1 of 2 given\)" merge "$dir/s0-of-2" --report "$dir/bad"
expect 2 "shard 0/2 is given twice: $dir/s0-of-2 and $dir/s0-of-2" merge "$dir/s0-of-2" "$dir/s0-of-2" "$dir/s1-of-2" --report "$dir/bad"
expect 2 "are shards of different runs" merge "$dir/s0-of-2" "$dir/s1-of-3" --report "$dir/bad"
expect 2 "$dir/whole: not a shard" merge "$dir/whole" --report "$dir/bad"
expect 3 "$dir/nowhere: cannot read results.json" merge "$dir/nowhere" --report "$dir/bad"
expect 2 "merge: no shard directories" merge --report "$dir/bad"
expect 2 "unknown option '--reprot'; did you mean '--report'" merge "$dir/s0-of-2" --reprot "$dir/bad"
"$OBSCURA" compare "${run[@]}" --spp 8 --shard 1/2 --report "$dir/other" >/dev/null 2>&1
expect 2 "are shards of different runs" merge "$dir/s0-of-2" "$dir/other" --report "$dir/bad"
# A shard.bin cut short, or of another build: exit 3, named.
cp -r "$dir/s1-of-2" "$dir/cut"
head -c 300 "$dir/s1-of-2/shard.bin" >"$dir/cut/shard.bin"
expect 3 "$dir/cut/shard.bin: (truncated|not a shard file)" merge "$dir/s0-of-2" "$dir/cut" --report "$dir/bad"
printf 'obscura compare shard 1\n0.0.0\n' >"$dir/cut/shard.bin"
expect 3 "$dir/cut/shard.bin: not a shard file of this obscura" merge "$dir/s0-of-2" "$dir/cut" --report "$dir/bad"
[ ! -e "$dir/bad" ] && ! ls "$dir"/bad.tmp-* >/dev/null 2>&1 && ok || bad "a failed merge left $(ls -d "$dir"/bad*)"
for s in 2/2 -1/2 1/0 x 1/2/3; do
    expect 2 "^obscura: --shard: expected K/N" compare --scene corner --shard "$s" --report "$dir/bad"
done

# A moving camera's flicker rows (--orbit) are merged too: their numbers and worst frames.
orbit=(--scene corner:diagonal --scene sphere-on-plane:contact --methods ssao,vbao --size 32x24 --spp 16 --orbit 10
    --path-frames 3)
"$OBSCURA" compare "${orbit[@]}" --report "$dir/orbit" >/dev/null 2>"$dir/err" || bad "orbit: $(tail -1 "$dir/err")"
for k in 0 1; do
    "$OBSCURA" compare "${orbit[@]}" --shard "$k/2" --report "$dir/orbit$k" >/dev/null 2>"$dir/err" ||
        bad "orbit shard $k/2: $(tail -1 "$dir/err")"
done
"$OBSCURA" merge "$dir/orbit0" "$dir/orbit1" --report "$dir/orbit-merged" >/dev/null 2>"$dir/err" ||
    bad "orbit merge: $(cat "$dir/err")"
same "$dir/orbit" "$dir/orbit-merged" && python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert all(len(v["flicker"]["rows"]) == 2 and len(v["flicker"]["rows"][1]["temporal_on"]["rmse_frames"]) == 3
           for v in d["views"]), d["views"]
' "$dir/orbit-merged/results.json" && ok || bad "the orbit shards merged differ from the unsharded orbit run"

# Rows as units (--shard-unit row): more shards (5) than views (2). The references come first
# (--references-only traces them into the cache, a fresh one here, and writes no report); then each
# row of each view goes to the least-loaded shard by its samples per pixel (12 at low, 36 at high),
# each shard finds its views' references in the cache, and the merge puts every view's rows back
# together and draws its Pareto front and chart from all of them.
export XDG_CACHE_HOME="$dir/cache-rows"
rows=(--scene corner:diagonal --scene cornell:front --methods ssao,gtao,vbao --quality low,high --size 48x36 --spp 16)
"$OBSCURA" compare "${rows[@]}" --references-only >"$dir/out" 2>"$dir/err" || bad "references only: $(tail -1 "$dir/err")"
[ "$(grep -c 'traced into the cache' "$dir/out")" -eq 2 ] && [ ! -e obscura-report ] && ok ||
    bad "--references-only: $(cat "$dir/out")"
"$OBSCURA" compare "${rows[@]}" --references-only >"$dir/out" 2>&1
[ "$(grep -c 'was in the cache' "$dir/out")" -eq 2 ] && ok || bad "--references-only again: $(cat "$dir/out")"
for k in 0 1 2 3 4; do
    "$OBSCURA" compare "${rows[@]}" --shard "$k/5" --shard-unit row --report "$dir/r$k" >/dev/null 2>"$dir/err" ||
        bad "row shard $k/5: $(tail -1 "$dir/err")"
done
python3 -c '
import json, sys
# 12 rows, each run once; by cost (36 against 12) the five shards carry 72, 72, 72, 72 and 96 of 384.
seen, load = [], []
for k in range(5):
    d = json.load(open(sys.argv[1] + "/r%d/results.json" % k))
    assert d["shard"]["index"] == k and d["shard"]["count"] == 5, d["shard"]
    rows = [(v["scene"] + ":" + v["camera"], m["label"]) for v in d["views"] for m in v["methods"]]
    assert all(v["reference"]["cached"] is True for v in d["views"]), k
    seen += rows
    load.append(sum(36 if "high" in label else 12 for _, label in rows))
assert len(seen) == 12 and len(set(seen)) == 12, seen
assert max(load) - min(load) <= 36, load
' "$dir" && ok || bad "the row shards' split"
"$OBSCURA" compare "${rows[@]}" --report "$dir/rows-whole" >/dev/null 2>"$dir/err" || bad "rows unsharded: $(tail -1 "$dir/err")"
"$OBSCURA" merge "$dir"/r4 "$dir"/r0 "$dir"/r1 "$dir"/r2 "$dir"/r3 --report "$dir/rows-merged" >/dev/null 2>"$dir/err" ||
    bad "row merge: $(cat "$dir/err")"
same "$dir/rows-whole" "$dir/rows-merged" && ok || bad "the row shards merged differ from the unsharded run"
# Along an orbit, --references-only traces every frame's reference too: the row shards then trace
# nothing (the cache gains no entry) and merge into the unsharded orbit run.
export XDG_CACHE_HOME="$dir/cache-orbit-rows"
orows=(--scene corner:diagonal --scene sphere-on-plane:contact --methods ssao,vbao --size 32x24 --spp 16 --orbit 10
    --path-frames 3)
"$OBSCURA" compare "${orows[@]}" --references-only >"$dir/out" 2>/dev/null || bad "orbit references only"
grep -q "corner:diagonal along the orbit, 3 frames, in the cache" "$dir/out" && ok || bad "orbit references: $(cat "$dir/out")"
entries=$(find "$XDG_CACHE_HOME/obscura" -type f | wc -l) # (Mesa keeps its shader cache beside it)
for k in 0 1 2; do
    "$OBSCURA" compare "${orows[@]}" --shard "$k/3" --shard-unit row --report "$dir/or$k" >/dev/null 2>"$dir/err" ||
        bad "orbit row shard $k/3: $(tail -1 "$dir/err")"
done
[ "$entries" -gt 6 ] && [ "$(find "$XDG_CACHE_HOME/obscura" -type f | wc -l)" -eq "$entries" ] && ok ||
    bad "the orbit row shards traced references ($entries entries before, $(find "$XDG_CACHE_HOME/obscura" -type f | wc -l) after)"
"$OBSCURA" merge "$dir"/or0 "$dir"/or1 "$dir"/or2 --report "$dir/orows-merged" >/dev/null 2>"$dir/err" ||
    bad "orbit row merge: $(cat "$dir/err")"
same "$dir/orbit" "$dir/orows-merged" && ok || bad "the orbit row shards merged differ from the unsharded orbit run"

# A row given by a shard that does not own it: exit 3, named.
cp -r "$dir/r1" "$dir/r1-foreign"
python3 -c '
import struct, sys
b = bytearray(open(sys.argv[1], "rb").read())
at = b.index(b"\n", b.index(b"\n") + 1) + 1
view_size = struct.unpack_from("<I", b, at)[0]
row = at + 20 + view_size                       # the first view'"'"'s first row index
struct.pack_into("<I", b, row, (struct.unpack_from("<I", b, row)[0] + 1) % 6)
open(sys.argv[1], "wb").write(b)
' "$dir/r1-foreign/shard.bin"
expect 3 "$dir/r1-foreign/shard.bin: a row that is not this run's shard 1's" merge "$dir"/r0 "$dir/r1-foreign" "$dir"/r2 "$dir"/r3 "$dir"/r4 --report "$dir/bad"
expect 2 "^obscura: --shard-unit: expected view or row, got 'rows'" compare --scene corner --shard-unit rows --report "$dir/bad"
expect 2 "^obscura: --references-only writes no report" compare --scene corner --references-only --report "$dir/bad"
[ ! -e "$dir/bad" ] && ok || bad "a failed run left $dir/bad"

# obscura --help lists the command.
"$OBSCURA" --help | grep -q "^  merge " && ok || bad "obscura --help does not list merge"

echo "shards: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
