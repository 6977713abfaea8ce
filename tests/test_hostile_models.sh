#!/bin/sh
# Hostile models and environment maps (issue 19): tests/hostile/make_corpus.py writes the corpus
# at test time; each case runs `obscura render` at 16x16 and must give the documented exit code,
# exactly one non-empty stderr line naming the file (and saying what expect.tsv says it must),
# no output file (nor a temporary one) left behind, and a peak resident memory under the ceiling.
#
# usage: test_hostile_models.sh OBSCURA [cpu|gpu|all]
#   cpu: the cases that fail before a GL context (the ASan build runs these); gpu: the others
#   (environment maps, positive controls); all: every case.
# Other harnesses (tests/test_hostile_outputs.sh) may reuse the corpus format: see make_corpus.py.
set -u
BIN=$1
GROUPS_TO_RUN=${2:-all}
HERE=$(cd "$(dirname "$0")" && pwd)
# The ceiling: the worst of these inputs reached 11.7 GB before issue 19. A sanitized build keeps
# shadow memory and a quarantine, so it gets more room than the plain one.
case "$BIN" in
*asan*) CEILING_KB=1048576 ;;
*) CEILING_KB=524288 ;;
esac
[ -n "${OB_HOSTILE_CEILING_KB:-}" ] && CEILING_KB=$OB_HOSTILE_CEILING_KB

WORK=$(mktemp -d "${TMPDIR:-/tmp}/obscura_hostile_XXXXXX")
trap 'rm -rf "$WORK"' EXIT
python3 "$HERE/hostile/make_corpus.py" "$WORK/corpus" >/dev/null || { echo "FAIL: make_corpus.py"; exit 1; }

fail=0 ran=0 worst_kb=0 worst_case=""
TAB=$(printf '\t')
while IFS="$TAB" read -r name expect group rest; do
    [ "$GROUPS_TO_RUN" != all ] && [ "$group" != "$GROUPS_TO_RUN" ] && continue
    ran=$((ran + 1))
    out="$WORK/out/$name"
    mkdir -p "$out"
    # The case's arguments (tab-separated; none holds a tab or a newline).
    old_ifs=$IFS
    IFS=$TAB
    # shellcheck disable=SC2086
    set -- $rest
    IFS=$old_ifs
    target=""
    for a in "$@"; do case "$a" in /*) target=$a ;; esac; done
    # A FIFO model must not hang the test if confinement ever regresses.
    timeout 120 /usr/bin/time -f %M -o "$out/mem" "$BIN" render "$@" --size 16x16 --out "$out/ao.png" \
        >"$out/stdout" 2>"$out/stderr" </dev/null
    code=$?
    kb=$(tail -n 1 "$out/mem" 2>/dev/null)
    case "$kb" in '' | *[!0-9]*) kb=0 ;; esac
    lines=$(wc -l <"$out/stderr")
    why=""
    [ "$code" = "$expect" ] || why="exit $code, expected $expect"
    if [ "$expect" != 0 ]; then
        [ "$lines" = 1 ] || why="$why; $lines stderr lines, expected 1"
        [ -s "$out/stderr" ] || why="$why; empty stderr"
        base=$(basename "$target")
        grep -qF -- "$base" "$out/stderr" || why="$why; stderr does not name $base"
        want=$(awk -F "$TAB" -v n="$name" '$1 == n { print $2 }' "$WORK/corpus/expect.tsv")
        [ -z "$want" ] || grep -qF -- "$want" "$out/stderr" || why="$why; stderr does not say '$want'"
        leftover=$(ls -A "$out" | grep -v -e '^mem$' -e '^stdout$' -e '^stderr$')
        [ -z "$leftover" ] || why="$why; left behind: $leftover"
    else
        [ -s "$out/ao.png" ] || why="$why; no output written"
    fi
    [ "$kb" -le "$CEILING_KB" ] || why="$why; peak memory ${kb} KB over the ${CEILING_KB} KB ceiling"
    if [ "$kb" -gt "$worst_kb" ]; then worst_kb=$kb worst_case=$name; fi
    if [ -n "$why" ]; then
        fail=$((fail + 1))
        echo "FAIL $name: ${why#; }"
        sed 's/^/    stderr: /' "$out/stderr" | head -n 5
    else
        printf 'ok   %-32s exit %s  %6d KB  %s\n' "$name" "$code" "$kb" "$(head -n 1 "$out/stderr")"
    fi
done <"$WORK/corpus/cases.tsv"

echo "hostile models: $ran cases, $fail failed; worst peak memory ${worst_kb} KB ($worst_case), ceiling ${CEILING_KB} KB"
[ "$ran" -gt 0 ] || { echo "FAIL: no cases ran"; exit 1; }
[ "$fail" = 0 ]
