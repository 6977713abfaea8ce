#!/usr/bin/env bash
# Inputs that must neither hang nor mislead (issue 44, classes 6 and 7): every file the tool reads
# (models, sidecars, settings files and folders, environment maps) may be a FIFO, a directory or a
# device, and each such case fails at once with one line naming the file and what it is; a sidecar
# radius that no scene can mean is refused; a path frame that sees nothing is never a 0 in a mean;
# a settings or tune value too long for its field is refused, never cut. Each command runs under
# `timeout`: a hang fails the case instead of the suite.
# usage: test_hostile_inputs.sh OBSCURA
set -u
OBSCURA=$(realpath "$1")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
export XDG_CACHE_HOME="$dir/cache" # references of its own: no entry of another run in the way
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# expect CODE PATTERN -- ARGS...: exit code, one stderr line (progress aside) matching PATTERN,
# within 60 s.
expect() {
    local code=$1 pattern=$2
    shift 3
    timeout 60 "$OBSCURA" "$@" >stdout 2>stderr.all </dev/null
    local got=$?
    sed 's/.*\r//' stderr.all | grep -vE '[0-9] ?%' >stderr
    if [ "$got" -eq 124 ]; then bad "obscura $* hung (killed after 60 s)"; return; fi
    if [ "$got" -ne "$code" ]; then bad "obscura $* exited $got, want $code: $(cat stderr)"; return; fi
    if [ "$(wc -l <stderr)" -ne 1 ] || [ ! -s stderr ]; then bad "obscura $*: not one stderr line: $(cat stderr)"; return; fi
    if ! grep -qE -e "$pattern" stderr; then bad "obscura $*: '$(cat stderr)' lacks /$pattern/"; return; fi
    ok
}

R=(render --size 32x24 --method ssao --filter none --out o.png)
# A tiny model: a floor and a wall.
printf 'v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nf 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\n' >m.obj
cp m.obj n.obj

# ---- 6. special files never hang -----------------------------------------------------------------
mkfifo fifo.json fifo.obj fifo.hdr
mkdir settings.d dir.json
printf '{"method": "ssao", "params": {"intensity": 1.5}}\n' >settings.d/a.json
mkfifo settings.d/b.json
expect 2 "^obscura: --settings fifo.json: cannot read it: it is a FIFO, not a regular file$" -- "${R[@]}" --settings fifo.json
expect 2 "^obscura: --settings settings.d/b.json: cannot read it: it is a FIFO, not a regular file$" -- "${R[@]}" --settings settings.d
expect 2 "^obscura: --settings /dev/zero: cannot read it: it is a character device, not a regular file$" -- "${R[@]}" --settings /dev/zero
expect 3 "cannot read sidecar fifo.json: it is a FIFO, not a regular file" -- "${R[@]}" --scene m.obj --sidecar fifo.json
expect 3 "cannot read sidecar dir.json: it is a directory, not a regular file" -- "${R[@]}" --scene m.obj --sidecar dir.json
expect 3 "cannot read model 'fifo.obj': it is a FIFO, not a model file" -- "${R[@]}" --scene fifo.obj
# The sidecar found beside a model (MODEL.obscura.json) is read as well: a FIFO there is no hang.
mkfifo n.obscura.json
expect 3 "cannot read sidecar ./n.obscura.json: it is a FIFO, not a regular file" -- "${R[@]}" --scene n.obj
rm -f n.obscura.json
expect 3 "cannot read environment map fifo.hdr: it is a FIFO, not a regular file" -- "${R[@]}" --ambient env --env fifo.hdr
[ -p fifo.json ] && [ -p settings.d/b.json ] && ok || bad "a FIFO was removed or replaced"

# ---- 7. no silent wrong result, no vague message ------------------------------------------------------
# A radius no scene can mean: AO with no occlusion at exit 0 before.
printf '{"ao_radius": 3e38}\n' >m.obscura.json
expect 3 "m.obscura.json: ao_radius: 3e\+38 is longer than the whole scene \(the diagonal of its bounds.* is 1\.73205\)" -- \
    "${R[@]}" --scene m.obj
printf '{"ao_radius": 1.4}\n' >m.obscura.json
timeout 60 "$OBSCURA" "${R[@]}" --scene m.obj >/dev/null 2>&1 && ok || bad "a sidecar radius within the scene was refused"
rm -f m.obscura.json

# Settings values cut at 63 characters used to turn into other values silently.
long=$(printf 'x%.0s' $(seq 100))
printf '{"method": "ssao", "params": {"noise": "%s"}}\n' "$long" >long_value.json
expect 2 "^obscura: --settings long_value.json: ssao.noise: a value of 100 characters" -- "${R[@]}" --settings long_value.json
printf '{"method": "ssao", "params": {"%s": 1}}\n' "$long" >long_name.json
expect 2 "^obscura: --settings long_name.json: (parameter name|ssao has no parameter)" -- "${R[@]}" --settings long_name.json
T=(tune --method ssao --size 24x18 --train cornell --validate corner --spp 4 --out t.json)
expect 2 "^obscura: --params ssao\.${long:0:60}.*a parameter name of 100 characters" -- "${T[@]}" --params "ssao.$long"
expect 2 "^obscura: --params ssao\.intensity=.*a range of 1?[0-9][0-9] characters; expected LO:HI" -- "${T[@]}" \
    --params "ssao.intensity=0.5:1.$(printf '0%.0s' $(seq 90))1"
[ ! -e t.json ] && ok || bad "a refused tune wrote t.json"

# Messages that name the option or file, what was expected and what was found.
printf '{\n  "method": "ssao",\n  "params": {\n' >broken.json
printf '[]\n' >array.json
expect 2 "^obscura: --settings broken.json: not valid JSON \(error near line 4, column 1\); expected an object" -- "${R[@]}" --settings broken.json
expect 2 "^obscura: --settings array.json: expected a JSON object .*, got an array$" -- "${R[@]}" --settings array.json
expect 2 "^obscura: --settings nope.json: cannot read it: no such file$" -- "${R[@]}" --settings nope.json
expect 2 "^obscura: --set ssao.bias=abc: ssao.bias expects a number, got 'abc'" -- "${R[@]}" --set ssao.bias=abc
expect 2 "^obscura: --method: unknown method 'nosuch' \(known: none, ssao" -- "${R[@]}" --method nosuch
expect 3 "^obscura: cannot read environment map m.obj: not a Radiance .hdr image" -- "${R[@]}" --ambient env --env m.obj

# Path key times whose differences overflow a float made every camera between them NaN, reported
# without naming the path.
cat >m.obscura.json <<'JSON'
{"paths": [{"name": "far", "keys": [
  {"time": -3e38, "eye": [0.5, 0.5, 2], "target": [0.5, 0.4, 0]},
  {"time": 3e38, "eye": [0.6, 0.5, 2], "target": [0.5, 0.4, 0]}]}]}
JSON
expect 3 "m.obscura.json: paths\[0\]\.keys\[0\]\.time: -3e\+38 is beyond \+-1e9$" -- "${R[@]}" --scene m.obj --path far --path-frames 3

# A path frame that sees nothing: its RMSE used to count as 0 in the path's mean. The path looks at
# the wall, then at the empty sky behind the camera, then back.
cat >m.obscura.json <<'JSON'
{"paths": [{"name": "away", "keys": [
  {"time": 0, "eye": [0.5, 0.5, 2], "target": [0.5, 0.4, 0]},
  {"time": 1, "eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 6]},
  {"time": 2, "eye": [0.5, 0.5, 2], "target": [0.5, 0.4, 0]}]}]}
JSON
C=(compare --scene m.obj --size 24x18 --spp 4 --methods ssao --filters none --path away --path-frames 5 --report rep)
expect 3 "^obscura: --path away: frame [0-9] of 5 sees nothing \(it covers no pixel\)" -- "${C[@]}"
[ ! -e rep ] && ok || bad "a refused compare left its report"
if timeout 300 "$OBSCURA" "${C[@]}" --allow-empty >stdout 2>stderr </dev/null; then
    python3 - rep/results.json <<'PY' && ok || bad "--allow-empty: an empty frame counted in the path's means"
import json, math, sys
v = json.load(open(sys.argv[1]))["views"][0]["flicker"]
assert v["path_frames"] == 5 and v["path_frames_empty"] >= 1, v
for row in v["rows"]:
    for side in ("temporal_off", "temporal_on"):
        x = row[side]
        frames = x["rmse_frames"]
        assert frames[2] is None, frames          # the empty frame has no error, not 0
        seen = [e for e in frames if e is not None]
        assert all(e > 0 for e in seen), frames
        assert math.isclose(x["rmse_mean"], sum(seen) / len(seen), rel_tol=2e-5), (x["rmse_mean"], seen)  # 6 digits each
        assert x["worst_frame"] != 2 and x["rmse_last"] == frames[-1]
PY
else
    bad "compare --allow-empty on a path with an empty frame failed: $(cat stderr)"
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
