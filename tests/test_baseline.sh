#!/usr/bin/env bash
# `--method none` is the cost baseline (issue 20): it records no AO-chain pass at all (no ao,
# filter, downsample, temporal or upsample timing), at full and half AO size and with temporal
# accumulation on, while ssao under the same options records them (so the check can fail).
# usage: test_baseline.sh OBSCURA
set -uo pipefail
OBSCURA=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# The pass names of a --timings table (between its header and the GPU sum).
passes() { awk '/^pass /{on=1; next} /^GPU sum/{on=0} on{print $1}' "$1" | tr '\n' ' '; }

for opts in "--ao-scale 1" "--ao-scale 0.5" "--ao-scale 0.5 --temporal on" "--filter bilateral"; do
    # shellcheck disable=SC2086
    if "$OBSCURA" render --scene corner --size 64x48 --timings --method none $opts --out "$dir/none.png" \
        >"$dir/none.txt" 2>&1; then ok; else bad "none $opts: $(cat "$dir/none.txt")"; fi
    # shellcheck disable=SC2086
    if "$OBSCURA" render --scene corner --size 64x48 --timings --method ssao $opts --out "$dir/ssao.png" \
        >"$dir/ssao.txt" 2>&1; then ok; else bad "ssao $opts: $(cat "$dir/ssao.txt")"; fi
    n=" $(passes "$dir/none.txt")" s=" $(passes "$dir/ssao.txt")"
    for p in ao filter; do
        case "$s" in *" $p "*) ok ;; *) bad "ssao $opts records no $p pass:$s" ;; esac
    done
    for p in gbuffer lighting compose tonemap; do
        case "$n" in *" $p "*) ok ;; *) bad "none $opts lost the frame's own $p pass:$n" ;; esac
    done
    for p in ao filter downsample upsample temporal depth_mips edges; do
        case "$n" in *" $p "*) bad "none $opts records a $p pass:$n" ;; *) ok ;; esac
    done
done
# The picture is unchanged by the skipped passes: AO 1 everywhere, so the AO map is white.
if "$OBSCURA" render --scene corner --size 64x48 --method none --ao-scale 0.5 --out "$dir/n.png" \
    --ao-out "$dir/n.pfm" >/dev/null 2>&1 && python3 - "$dir/n.pfm" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
scale = float(parts[2])
fmt = ("<" if scale < 0 else ">") + "f" * (w * h)
vals = struct.unpack(fmt, parts[3][: 4 * w * h])
assert min(vals) == 1.0 and max(vals) == 1.0, (min(vals), max(vals))
PY
then ok; else bad "none's AO map is not 1 everywhere"; fi

echo "test_baseline: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
