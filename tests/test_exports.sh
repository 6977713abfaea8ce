#!/usr/bin/env bash
# libobscura.so exports exactly the functions obscura.h declares: nothing internal (hidden by
# -fvisibility=hidden), nothing declared but missing. Every exported name starts with ob_.
# usage: test_exports.sh LIBOBSCURA_SO OBSCURA_H C_COMPILER
set -euo pipefail
lib=$1 header=$2 cc=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Declared functions: names followed by "(" in the preprocessed header (types and macros are
# gone; function-pointer typedefs read "(*name)(" and are not matched).
"$cc" -E -P -x c "$header" | grep -oE '\bob_[a-z0-9_]+ *\(' | sed 's/ *($//' | sort -u >"$tmp/declared"
# Defined dynamic symbols of the library, of any kind.
nm -D --defined-only "$lib" | awk '{print $NF}' | sort -u >"$tmp/exported"

status=0
extra=$(comm -13 "$tmp/declared" "$tmp/exported")
missing=$(comm -23 "$tmp/declared" "$tmp/exported")
if [ -n "$extra" ]; then echo "exported but not in obscura.h:"; echo "$extra" | sed 's/^/  /'; status=1; fi
if [ -n "$missing" ]; then echo "declared in obscura.h but not exported:"; echo "$missing" | sed 's/^/  /'; status=1; fi
echo "exports: $(wc -l <"$tmp/exported") dynamic symbols, $(wc -l <"$tmp/declared") functions in obscura.h"
exit $status
