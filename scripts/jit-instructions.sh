#!/usr/bin/env bash
# How many instructions does llvmpipe's compiled code of a method run? A count that machine load
# does not move, for the shared 2-core machines where the same AO pass times 30-50 % apart between
# runs (bench/README.md): one frame rendered under valgrind's callgrind, llvmpipe's JIT code (it has
# no object file, callgrind's "[???]") counted per function, and the functions that the same frame
# with --method none does not run are the method's: its AO pass and the pre-passes and texel-fetch
# functions it calls. Valgrind reports AVX2, FMA and F16C, so llvmpipe compiles the code it compiles
# natively. Instructions are not time (a texel fetch waits on memory), but an arithmetic change
# shows to the instruction. One run takes about a minute at 160x120.
#   scripts/jit-instructions.sh [-b OBSCURA] METHOD [render options, e.g. --set ssdo.packed=off]
# Prints the method's functions (instructions, largest first; those under 1 % summed) and the total. Default view
# fzk-haus:stair at 160x120, no filter, no shadow maps, no tone mapping (later options win).
set -euo pipefail
bin=build/obscura
if [ "${1:-}" = -b ]; then bin=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: $0 [-b OBSCURA] METHOD [render options]" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "$0: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
method=$1
shift
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
count() { # METHOD OUT: callgrind one frame, the JIT functions' counts one per line
    valgrind --tool=callgrind --smc-check=all --callgrind-out-file="$dir/$1.cg" "$bin" render --scene fzk-haus \
        --camera stair --size 160x120 --filter none --shadow none --hdr off --method "$1" --out "$dir/$1.png" \
        "${@:3}" >"$dir/$1.log" 2>&1 || { echo "$0: render --method $1 failed:" >&2; tail -3 "$dir/$1.log" >&2; exit 1; }
    callgrind_annotate --threshold=100 "$dir/$1.cg" | awk '/\[\?\?\?\]/ { gsub(",", "", $1); print $1 }' >"$2"
}
# The baseline frame takes the same options but the method's --set ones (none refuses them).
opts=("$@") base=()
while [ $# -gt 0 ]; do
    case $1 in
    --set) shift ;;
    --set=*) ;;
    *) base+=("$1") ;;
    esac
    shift
done
count none "$dir/none.txt" "${base[@]}"
count "$method" "$dir/method.txt" "${opts[@]}"
python3 - "$dir/none.txt" "$dir/method.txt" "$method" <<'PY'
import collections, sys
base = collections.Counter(int(x) for x in open(sys.argv[1]).read().split())
own = []
for x in sorted((int(x) for x in open(sys.argv[2]).read().split()), reverse=True):
    if base[x] > 0:
        base[x] -= 1
    else:
        own.append(x)
total = sum(own)
big = [x for x in own if x >= 0.01 * total]
for x in big:
    print("%14d" % x)
if len(own) > len(big):
    print("%14d  (%d functions under 1 %% each)" % (total - sum(big), len(own) - len(big)))
print("%14d  %s: instructions in its own JIT functions" % (total, sys.argv[3]))
PY
