#!/usr/bin/env bash
# What each library exports (issue 46): libobscura.so exactly the functions obscura/obscura.h and
# obscura/scene.h declare, plus the internal functions marked OB_EVAL_SHARED in src/ (what
# libobscura-eval calls in it: not API, declared in no installed header); libobscura-eval.so
# exactly the functions obscura/eval.h adds. Nothing internal (hidden by -fvisibility=hidden),
# nothing declared but missing; every exported name starts with ob_.
# usage: test_exports.sh LIBOBSCURA_SO LIBOBSCURA_EVAL_SO INCLUDE_DIR SRC_DIR C_COMPILER
set -euo pipefail
core=$1 eval=$2 include=$3 src=$4 cc=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Declared functions: names followed by "(" in the preprocessed header (types and macros are
# gone; function-pointer typedefs read "(*name)(" and are not matched).
declared() { "$cc" -E -P -x c -I"$include" "$1" | grep -oE '\bob_[a-z0-9_]+ *\(' | sed 's/ *($//' | sort -u; }
declared "$include/obscura/scene.h" >"$tmp/core_public" # scene.h includes obscura.h
declared "$include/obscura/eval.h" | comm -23 - "$tmp/core_public" >"$tmp/eval_declared"
grep -rhoE 'OB_EVAL_SHARED [^;(]*\bob_[a-z0-9_]+ *\(' "$src" --include='*.h' | grep -oE 'ob_[a-z0-9_]+ *\($' |
    sed 's/ *($//' | sort -u >"$tmp/private"
sort -u "$tmp/core_public" "$tmp/private" >"$tmp/core_declared"
[ -s "$tmp/private" ] || { echo "no OB_EVAL_SHARED declarations found under $src"; exit 1; }

status=0
check() { # LIB DECLARED_LIST WHAT
    nm -D --defined-only "$1" | awk '{print $NF}' | sort -u >"$tmp/exported"
    local extra missing
    extra=$(comm -13 "$2" "$tmp/exported")
    missing=$(comm -23 "$2" "$tmp/exported")
    if [ -n "$extra" ]; then echo "$(basename "$1") exports what $3 do not declare:"; echo "$extra" | sed 's/^/  /'; status=1; fi
    if [ -n "$missing" ]; then echo "$(basename "$1") lacks what $3 declare:"; echo "$missing" | sed 's/^/  /'; status=1; fi
    echo "$(basename "$1"): $(wc -l <"$tmp/exported") dynamic symbols, $(wc -l <"$2") functions in $3"
}
check "$core" "$tmp/core_declared" "obscura.h, scene.h and OB_EVAL_SHARED ($(wc -l <"$tmp/private") internal)"
check "$eval" "$tmp/eval_declared" "eval.h"
# The evaluation library's functions are its own: none of them is also in the core.
both=$(nm -D --defined-only "$core" | awk '{print $NF}' | grep -Fxf "$tmp/eval_declared" || true)
[ -z "$both" ] || { echo "in both libraries: $both"; status=1; }
exit $status
