#!/usr/bin/env bash
# Hostile names (issue 44): every command that takes a path gets names holding ' " $( ) ` ; & |
# < > \, spaces, a leading '-', a newline and bytes that are not UTF-8, under a working directory
# (and so a cache, a data directory, a model's directory) named the same way. No name may run a
# command: the names hold `touch PWNED` three ways, and touch is a logging wrapper first on PATH,
# so a shell that ever parses one leaves a trace even outside this directory. Each command either
# works (every output under its exact name) or fails at once: exit 2, 3 or 4 with one stderr line
# "obscura: ...". Honest names ("Bob's report") must work. The programs the CLI runs (gnuplot for
# the report's chart, git for the commit bench --json and results.json record) are wrappers that
# count their calls: gnuplot once per report, git once per bench --json and once per report, none
# anywhere else.
# usage: test_hostile_names.sh OBSCURA
set -u
OBSCURA=$(realpath "$1")
top=$(mktemp -d)
trap 'rm -rf "$top"' EXIT
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); printf 'FAIL: %q\n' "$*" >&2; }

real_gnuplot=$(command -v gnuplot) || { echo "gnuplot missing: scripts/install-deps.sh (gnuplot-nox)" >&2; exit 1; }
# git is optional (bench then records "unknown"): without it the commit checks are skipped.
real_git=$(command -v git) || real_git=
real_touch=$(command -v touch)

# The wrappers and their log live in a plain directory; everything the CLI sees is under `work`.
mkdir "$top/bin"
log=$top/spawned.log
: >"$log"
for prog in gnuplot git touch; do
    real_var=real_$prog
    [ -n "${!real_var}" ] || continue
    printf '#!/bin/sh\necho %s >>"%s"\nexec "%s" "$@"\n' "$prog" "$log" "${!real_var}" >"$top/bin/$prog"
    chmod +x "$top/bin/$prog"
done

inject='$(touch PWNED)`touch PWNED`;touch PWNED;'
work="$top/w'$inject\"&|<>\\ "$'\n\xff'
mkdir "$work" && cd "$work" || exit 1
export XDG_CACHE_HOME="$work/cache $inject"

names=(
    "Bob's report"                                  # honest: must work
    "Zoë's \"best\" (v2) & more"                    # honest too, in UTF-8
    # Quotes that pair up, so that a shell which ever gets this inside '...' runs both touches
    # (the old `gnuplot '%s'` did); a leading '-' for the programs that take it as an option.
    "-x'\$(touch PWNED)'\`touch PWNED\`';touch PWNED;'y"
    "a\"b&c|d<e>f\\g $inject h"                     # the other metacharacters
    $'two\nlines \xff\xfe'                          # a newline, bytes that are not UTF-8
)
honest=2 # the first two

# A corner (floor and two walls) and its sidecar: two cameras and a camera path named like an
# injection too.
path_name="walk $inject"
write_scene() { # NAME, as ./NAME: a leading '-' is no option to mkdir, cp or git
    set -- "./$1"
    printf '%s\n' 'v -1 0 -1' 'v 1 0 -1' 'v 1 0 1' 'v -1 0 1' 'v -1 1 -1' 'v 1 1 -1' 'v -1 1 1' \
        'f 1 4 3' 'f 1 3 2' 'f 1 2 6' 'f 1 6 5' 'f 1 5 7' 'f 1 7 4' >"$1.obj"
    local cams='"cameras": [{"name": "front", "eye": [0.3, 1.2, 2.5], "target": [0, 0.3, -0.5]},
                             {"name": "side", "eye": [2, 1.2, 1.5], "target": [0, 0.3, -0.5]}]'
    printf '{%s, "paths": [{"name": "%s", "keys": [
        {"time": 0, "eye": [0.3, 1.2, 2.5], "target": [0, 0.3, -0.5]},
        {"time": 1, "eye": [1.5, 1.2, 2], "target": [0, 0.3, -0.5]}]}]}\n' "$cams" "$path_name" >"$1.obscura.json"
    printf '{%s}\n' "$cams" >"$1.side.json"
    printf '{"method": "ssao", "params": {"radius_scale": 1.5}}\n' >"$1.settings.json"
    mkdir "$1.settings.d" && cp "$1.settings.json" "$1.settings.d/${1#./}.json"
    # A 4 x 2 environment map: Radiance RGBE, flat rows (too narrow for run-length encoding).
    { printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n'; for _ in 1 2 3 4 5 6 7 8; do printf '\x80\x80\x80\x81'; done; } >"$1.env.hdr"
    # bench --json records the data directory's commit (git -C DIR).
    mkdir -p "$1.data/scenes"
    if [ -n "$real_git" ]; then
        "$real_git" init -q "$1.data" && "$real_git" -C "$1.data" -c user.name=t -c user.email=t@t commit -q --allow-empty -m t
    fi
}

reports=0
benches=0
idx=0
# run OUTPUTS... -- ARGS...: the case's verdict. OUTPUTS: the files it must make when it works.
run() {
    local outs=()
    while [ "$1" != -- ]; do outs+=("$1"); shift; done
    shift
    idx=$((idx + 1))
    local err="$top/stderr.$idx"
    PATH="$top/bin:$PATH" "$OBSCURA" "$@" >"$top/stdout.$idx" 2>"$err.all"
    local got=$?
    # Progress (a line per stage with its percentage) is not the error.
    grep -avE '[0-9] ?% \(' "$err.all" >"$err"
    if [ "$got" -eq 0 ]; then
        for f in "${outs[@]}"; do
            [ -e "$f" ] || { bad "obscura $* exited 0 without writing $f"; return 1; }
        done
        ok
        return 0
    fi
    if [ "$idx_honest" -eq 1 ]; then bad "obscura $* failed on an honest name ($got): $(cat "$err")"; return 1; fi
    case $got in 2 | 3 | 4) ;; *) bad "obscura $* exited $got, not 2, 3 or 4: $(cat "$err")"; return 1 ;; esac
    if [ "$(wc -l <"$err")" -ne 1 ] || ! head -c 9 "$err" | grep -q '^obscura: '; then
        bad "obscura $*: not one 'obscura: ' line on stderr: $(cat "$err")"
        return 1
    fi
    for f in "${outs[@]}"; do
        [ ! -e "$f" ] || { bad "obscura $* failed ($got) but left $f"; return 1; }
    done
    ok
    return 1
}

# must_fail CODE ARGS...: a name that cannot work (nothing by it exists) fails with CODE and one
# line that shows the name, a newline in it included (as \n).
must_fail() {
    local code=$1
    shift
    idx=$((idx + 1))
    local err="$top/stderr.$idx"
    PATH="$top/bin:$PATH" "$OBSCURA" "$@" >/dev/null 2>"$err"
    local got=$?
    if [ "$got" -ne "$code" ] || [ "$(wc -l <"$err")" -ne 1 ] || ! head -c 9 "$err" | grep -q '^obscura: '; then
        bad "obscura $* exited $got (want $code), stderr not one line: $(cat "$err")"
    else
        ok
    fi
}

S=(--size 32x24)
k=0
for n in "${names[@]}"; do
    k=$((k + 1))
    idx_honest=$((k <= honest ? 1 : 0))
    write_scene "$n"
    model="./$n.obj"

    must_fail 2 render --scene corner "${S[@]}" --settings "$n.missing.json" --out "$n.never.png"
    must_fail 3 render --scene "./$n.missing.obj" "${S[@]}" --out "$n.never.png"
    run "$n.png" "$n.ao.pfm" "$n.ao.jpg" "$n.depth.pfm" "$n.normal.pfm" -- \
        render --scene corner "${S[@]}" --method ssao --filter none --out "$n.png" --ao-out "$n.ao.pfm" \
        --ao-png "$n.ao.jpg" --depth-out "$n.depth.pfm" --normal-out "$n.normal.pfm"
    run "$n.sheet.png" -- sheet --scene corner "${S[@]}" --methods ssao --out "$n.sheet.png"
    # The model, its sidecar beside it, a settings file, a camera from the sidecar.
    run "$n.model.png" -- render --scene "$model" --camera front "${S[@]}" --settings "$n.settings.json" \
        --out "$n.model.png"
    # An explicit sidecar, a directory of settings, an environment map.
    run "$n.env.png" -- render --scene "$model" --sidecar "$n.side.json" --camera side "${S[@]}" \
        --settings "$n.settings.d" --ambient env --env "$n.env.hdr" --out "$n.env.png"
    # The sidecar's camera path, itself named like an injection; --out is numbered per frame.
    run "$n.walk-0000.png" "$n.walk-0001.png" -- render --scene "$model" --path "$path_name" \
        --path-frames 2 "${S[@]}" --method ssao --out "$n.walk.png"
    run "$n.tuned.json" -- tune --method ssao --params ssao.radius_scale --train "$model:front" \
        --validate "$model:side" --passes 1 --steps 2 --spp 4 "${S[@]}" --out "$n.tuned.json"
    if OBSCURA_DATA_DIR="$work/$n.data" run "$n.bench.json" "$n.bench.csv" -- \
        bench --scene corner "${S[@]}" --methods ssao --frames 1 --warmup 0 --json "$n.bench.json" --csv "$n.bench.csv"; then
        benches=$((benches + 1))
        want=unknown
        [ -z "$real_git" ] || want=$("$real_git" -C "./$n.data" rev-parse --short HEAD)
        grep -q "\"commit\":[[:space:]]*\"$want\"" "./$n.bench.json" && ok ||
            bad "bench with OBSCURA_DATA_DIR=$work/$n.data: commit is not $want: $(grep -a commit "./$n.bench.json")"
    fi
    if run "$n.report/index.html" "$n.report/results.json" -- \
        compare --scene "$model:front" --methods ssao "${S[@]}" --spp 4 --report "$n.report"; then
        reports=$((reports + 1))
        [ -n "$(find "./$n.report" -name chart.svg -exec grep -l '</svg>' {} +)" ] && ok ||
            bad "compare --report $n.report: no whole chart.svg"
    fi
done

# Without gnuplot the report fails with one line that says so (exit 1: the run's own failure).
idx=$((idx + 1))
PATH="$top/bin-none" "$OBSCURA" compare --scene corner "${S[@]}" --methods ssao --spp 4 --report "Bob's report 2" \
    >/dev/null 2>"$top/nognuplot.all"
got=$?
grep -avE '[0-9] ?% \(' "$top/nognuplot.all" >"$top/nognuplot"
if [ "$got" -eq 1 ] && [ "$(wc -l <"$top/nognuplot")" -eq 1 ] &&
    grep -q "^obscura: --report Bob's report 2: cannot draw .*gnuplot is not installed" "$top/nognuplot" &&
    [ ! -e "Bob's report 2" ]; then
    ok
else
    bad "compare without gnuplot exited $got: $(cat "$top/nognuplot")"
fi

# Nothing ran: no PWNED anywhere below the test's directories, touch never called, and the CLI
# ran gnuplot once per report and git once per bench --json and once per report.
if [ -n "$(find "$top" -name 'PWNED*' -print -quit)" ] || grep -q touch "$log"; then
    bad "a name ran a command: $(find "$top" -name 'PWNED*') $(grep -c touch "$log") touch call(s)"
else
    ok
fi
[ "$(grep -c '^gnuplot$' "$log")" -eq "$reports" ] && ok ||
    bad "gnuplot ran $(grep -c '^gnuplot$' "$log") times for $reports reports"
[ -z "$real_git" ] || [ "$(grep -c '^git$' "$log")" -eq $((benches + reports)) ] && ok ||
    bad "git ran $(grep -c '^git$' "$log") times for $benches benches and $reports reports"
# Honest names work end to end, whatever the others do.
[ -e "Bob's report.report/index.html" ] && [ -e "Zoë's \"best\" (v2) & more.report/index.html" ] && ok ||
    bad "an honest --report name did not make its report"

echo "hostile_names: $passed passed, $failed failed ($reports reports, $benches benches)"
[ "$failed" -eq 0 ]
