#!/usr/bin/env bash
# The ABI check (issue 46): a library's ABI (libobscura or libobscura-eval) as abidw reads it from
# its DWARF, restricted to the types of include/obscura/ (abidiff --headers-dir), against the
# committed baseline abi/NAME.abi. Any difference fails: a compatible one (an added function) until the
# baseline is remade with scripts/abi-baseline.sh, an incompatible one until the version and with
# it the soname moved too (the script refuses otherwise). Also: the soname is the one the header's
# version gives (NAME.so.0.MINOR before 1.0, NAME.so.MAJOR after): both libraries carry the one
# version of obscura.h.
# usage: test_abi.sh LIB.SO SOURCE_DIR [NAME (default libobscura)]
set -uo pipefail
lib=$1 src=$2 name=${3:-libobscura}
base=$src/abi/$name.abi
for tool in abidw abidiff readelf; do
    command -v $tool >/dev/null || { echo "abi: $tool not found (scripts/install-deps.sh installs abigail-tools, binutils)"; exit 1; }
done
# An incompatible change: abidiff's ABIDIFF_ABI_INCOMPATIBLE_CHANGE bit, or any function or
# variable removed or changed (a public struct's layout reaches a host through every function that
# takes it: abidiff lists those as changed and leaves the decision to us). Only additions pass.
incompatible() { # incompatible RC REPORT
    [ $(($1 & 8)) -ne 0 ] && return 0
    echo "$2" | grep -Eq "(Functions|Variables) changes summary: [1-9][0-9]* Removed|(Functions|Variables) changes summary: [0-9]+ Removed(\\([^)]*\\))?, [1-9][0-9]* Changed"
}
fails=0
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }

ver() { sed -n "s/^#define OB_VERSION_$1 \([0-9]*\)$/\1/p" "$src/include/obscura/obscura.h"; }
major=$(ver MAJOR) minor=$(ver MINOR)
[ -n "$major" ] && [ -n "$minor" ] || { echo "abi: no OB_VERSION_MAJOR/MINOR in obscura.h"; exit 1; }
if [ "$major" -eq 0 ]; then want=$name.so.0.$minor; else want=$name.so.$major; fi
soname=$(readelf -d "$lib" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
[ "$soname" = "$want" ] || bad "soname $soname; the header's version $major.$minor gives $want"
[ -f "$base" ] || { echo "abi: no baseline abi/$name.abi: make it (scripts/abi-baseline.sh)"; exit 1; }
grep -q "soname='$want'" "$base" || bad "abi/$name.abi is not the baseline of $want: remake it (scripts/abi-baseline.sh)"

# Both sides as scripts/abi-baseline.sh writes them: abidw with the same options (the public
# headers' types alone, no source locations), then abidiff of the two.
current=$(mktemp)
trap 'rm -f "$current"' EXIT
abidw --no-show-locs --no-corpus-path --headers-dir "$src/include/obscura" --drop-private-types "$lib" >"$current" ||
    { echo "abi: abidw failed on $lib"; exit 1; }
report=$(abidiff "$base" "$current" 2>&1)
rc=$?
if [ $rc -ne 0 ]; then
    echo "$report" | head -60
    if incompatible $rc "$report"; then
        bad "an incompatible ABI change (abidiff exit $rc): raise OB_VERSION_MINOR (OB_VERSION_MAJOR from 1.0 on) in include/obscura/obscura.h, say what changed in docs/changelog.md, and remake the baseline (scripts/abi-baseline.sh)"
    elif [ $((rc & 4)) -ne 0 ]; then
        bad "the ABI changed compatibly (abidiff exit $rc): remake the baseline (scripts/abi-baseline.sh) and add the change to docs/changelog.md"
    else
        bad "abidiff failed (exit $rc)"
    fi
fi
if [ $fails -gt 0 ]; then echo "abi: $fails failure(s)"; exit 1; fi
echo "abi: ok ($soname, $(grep -c '<elf-symbol ' "$base") symbols, no change against abi/$name.abi)"
