#!/usr/bin/env bash
# A command's outputs are replaced all together or not at all (issue 44, class 2). The shim
# tests/fault_inject.c (LD_PRELOAD) counts the renames and links a command makes while it writes
# and commits its outputs; for every step N the command runs again with step N failing (EIO), and
# with SIGINT, SIGTERM or SIGHUP arriving just before step N (raised in the calling thread, and
# sent to the process). Each time: exit 4 and one stderr line for a failure, 128 + the signal for
# a signal, and the work directory exactly as before: every existing output byte-identical, no new
# output, nothing temporary or backed up left.
# usage: test_transaction.sh OBSCURA FAULT_INJECT_SO
set -u
OBSCURA=$(realpath "$1")
SHIM=$(realpath "$2")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
export XDG_CACHE_HOME=$dir/cache
# A sanitizer build: the shim comes before the ASan runtime.
export ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# Everything under w: each name, and each file's checksum.
state() { (cd w && find . -mindepth 1 | LC_ALL=C sort && find . -type f -exec md5sum {} + | LC_ALL=C sort -k2); }
# stderr without progress lines (a bar redrawn with \r, or a line with its percentage).
errors() { sed 's/.*\r//' err | grep -vE '[0-9] ?%'; }
# Runs obscura in w under the shim with the given OB_FAULT_* settings: shimmed VAR=VALUE... -- ARGS...
shimmed() {
    local vars=()
    while [ "$1" != -- ]; do vars+=("$1"); shift; done
    shift
    # The braces take the shell's own "Terminated" line for a run that a signal ends.
    { (cd w && exec env LD_PRELOAD="$SHIM" OB_FAULT_SKIP="$skip" "${faults[@]}" "${vars[@]}" "$OBSCURA" "$@") >out 2>err; } 2>/dev/null
}
signals=(INT TERM HUP)
declare -A signum=([INT]=2 [TERM]=15 [HUP]=1)

# transaction NAME SETUP OUTPUTS -- ARGS...: SETUP makes w as it is before the run; OUTPUTS is how
# many outputs the command writes (a run that counts fewer steps did not reach the shim).
transaction() {
    local name=$1 setup=$2 outputs=$3
    shift 4
    $setup
    local before
    before=$(state)
    rm -f steps.log
    shimmed OB_FAULT_LOG="$dir/steps.log" -- "$@"
    local got=$? steps=0
    [ -f steps.log ] && steps=$(wc -l <steps.log)
    if [ "$got" -ne 0 ]; then bad "$name: the run without a fault exited $got: $(errors)"; return; fi
    if [ "$(state)" = "$before" ]; then bad "$name: the run without a fault changed nothing"; return; fi
    if [ -n "$(find w -name '*.tmp-*')" ]; then bad "$name: the run without a fault left $(find w -name '*.tmp-*')"; return; fi
    if [ "$steps" -lt "$outputs" ]; then bad "$name: $steps renames and links for $outputs outputs"; return; fi
    ok
    for n in $(seq "$steps"); do
        $setup
        shimmed OB_FAULT_RENAME_FAIL="$n" -- "$@"
        got=$?
        if [ "$got" -ne 4 ]; then bad "$name, step $n of $steps failing: exit $got, want 4: $(errors)"
        elif [ "$(errors | wc -l)" -ne 1 ] || ! errors | grep -q '^obscura: '; then bad "$name, step $n failing: not one line: $(errors)"
        elif [ "$(state)" != "$before" ]; then bad "$name, step $n of $steps failing ($(sed -n "${n}p" steps.log)) changed w:" \
            "$(diff <(echo "$before") <(state) | grep '^[<>]' | tr '\n' ' ')"
        else ok; fi
        local sig=${signals[$((n % 3))]}
        $setup
        shimmed OB_FAULT_RENAME_SIGNAL="$n:$sig" -- "$@"
        got=$?
        if [ "$got" -ne $((128 + ${signum[$sig]})) ]; then bad "$name, SIG$sig before step $n of $steps: exit $got, want $((128 + ${signum[$sig]})): $(errors)"
        elif [ "$(state)" != "$before" ]; then bad "$name, SIG$sig before step $n of $steps ($(sed -n "${n}p" steps.log)) changed w:" \
            "$(diff <(echo "$before") <(state) | grep '^[<>]' | tr '\n' ' ')"
        else ok; fi
        # The same sent to the process (kill), not to the thread: any thread that does not block
        # it may take it (llvmpipe's workers).
        sig=${signals[$((n % 2 + 1))]}
        $setup
        shimmed OB_FAULT_RENAME_KILL="$n:$sig" -- "$@"
        got=$?
        if [ "$got" -ne $((128 + ${signum[$sig]})) ]; then bad "$name, kill -$sig before step $n of $steps: exit $got, want $((128 + ${signum[$sig]})): $(errors)"
        elif [ "$(state)" != "$before" ]; then bad "$name, kill -$sig before step $n of $steps ($(sed -n "${n}p" steps.log)) changed w:" \
            "$(diff <(echo "$before") <(state) | grep '^[<>]' | tr '\n' ' ')"
        else ok; fi
    done
}

skip="$XDG_CACHE_HOME/*"
faults=()
R=(render --size 32x24 --method ssao --filter none)
# Two outputs that exist; three, the third new.
old_pair() { rm -rf w && mkdir w && echo old-png >w/X.png && echo old-pfm >w/X_ao.pfm; }
transaction "render --out --ao-out" old_pair 2 -- "${R[@]}" --out X.png --ao-out X_ao.pfm
transaction "render --out --ao-out --depth-out" old_pair 3 -- "${R[@]}" --out X.png --ao-out X_ao.pfm --depth-out X_d.pfm
# A file system without hard links: the old files are moved aside instead, and back.
faults=(OB_FAULT_NO_LINK=1)
transaction "render --out --ao-out --depth-out, no hard links" old_pair 3 -- "${R[@]}" --out X.png --ao-out X_ao.pfm \
    --depth-out X_d.pfm
faults=()
old_sheet() { rm -rf w && mkdir w && echo old-sheet >w/s.png; }
transaction "sheet" old_sheet 1 -- sheet --scene corner --size 32x24 --methods ssao --out s.png
old_bench() { rm -rf w && mkdir w && echo old-json >w/b.json && echo old-csv >w/b.csv; }
transaction "bench --json --csv" old_bench 2 -- bench --scene corner --size 32x24 --frames 2 --warmup 0 --methods ssao \
    --samples 12 --radius 4 --cameras default --json b.json --csv b.csv
old_tune() { rm -rf w && mkdir w && echo old-tune >w/t.json; }
transaction "tune" old_tune 1 -- tune --method hbao --params hbao.noise --train corner:diagonal --size 32x24 --spp 8 \
    --passes 1 --steps 2 --out t.json
# compare: an earlier report of its own (another method, so that a replaced one differs), and a new
# one. The files it writes into its temporary report are not the commit's steps.
C=(compare --scene corner --size 32x24 --spp 8 --filters none --report rep)
rm -rf w && mkdir w
if (cd w && "$OBSCURA" "${C[@]}" --methods hbao >/dev/null 2>&1); then
    mv w/rep rep.earlier
    old_report() { rm -rf w && mkdir w && cp -a rep.earlier w/rep; }
    no_report() { rm -rf w && mkdir w; }
    skip="$XDG_CACHE_HOME/*:rep.tmp-*/*"
    transaction "compare --report (an earlier report)" old_report 1 -- "${C[@]}" --methods ssao
    transaction "compare --report (a new one)" no_report 1 -- "${C[@]}" --methods ssao
else
    bad "compare could not write the earlier report"
fi

# ---- a target that turns into a directory during the run ---------------------------------------------
# Before the commit (at the first write), and between two of the commit's renames (before the last
# step): either way exit 4, X.png as it was, the directory left alone, nothing temporary left.
skip="$XDG_CACHE_HOME/*"
old_pair
rm -f steps.log
shimmed OB_FAULT_LOG="$dir/steps.log" -- "${R[@]}" --out X.png --ao-out X_ao.pfm
last=$(wc -l <steps.log)
for n in 1 "$last"; do
    old_pair
    shimmed OB_FAULT_RENAME_DIR="$n:X_ao.pfm" -- "${R[@]}" --out X.png --ao-out X_ao.pfm
    got=$?
    if [ "$got" -eq 4 ] && echo old-png | cmp -s - w/X.png && [ -d w/X_ao.pfm ] && [ -z "$(find w -name '*.tmp-*')" ] &&
        errors | grep -q '^obscura: --ao-out X_ao.pfm: .*[Dd]irectory'; then
        ok
    else
        bad "X_ao.pfm made a directory before step $n of $last: exit $got, X.png '$(head -c 20 w/X.png | tr -c '[:print:]' .)'," \
            "left $(ls w | tr '\n' ' '): $(errors)"
    fi
done

# ---- a file of the user's that comes into the old report during the run (class 5) -------------------
# At the first file compare writes (the check at the commit finds it), and just before the commit's
# exchange (the old report, once swapped out, is checked again and swapped back): exit 4, the old
# report and the file as they were.
if [ -d rep.earlier ]; then
    for skip in "$XDG_CACHE_HOME/*" "$XDG_CACHE_HOME/*:rep.tmp-*/*"; do
        old_report
        shimmed OB_FAULT_RENAME_FILE="1:rep/notes.txt" -- "${C[@]}" --methods ssao
        got=$?
        if [ "$got" -eq 4 ] && [ "$(cat w/rep/notes.txt 2>/dev/null)" = mine ] && rm w/rep/notes.txt &&
            diff -r rep.earlier w/rep >/dev/null && [ -z "$(find w -name '*.tmp-*')" ] &&
            errors | grep -q '^obscura: --report rep: holds notes.txt, which obscura did not write'; then
            ok
        else
            bad "a file that came into --report (skipping $skip): exit $got, $(ls -A w w/rep | tr '\n' ' '): $(errors)"
        fi
    done
fi

echo "transaction: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
