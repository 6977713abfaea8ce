#!/usr/bin/env bash
# Runs the libFuzzer targets of an OB_FUZZ build: `make fuzz` (long) and `make test-fuzz` (smoke,
# part of `make test`).
#
# usage: tests/fuzz/run.sh BUILD_DIR SECONDS [smoke]
#   long:  each target for SECONDS on its corpus BUILD_DIR/corpus-NAME, which keeps what the runs
#          found; crashes land in BUILD_DIR/crash-* and the run stops at the first.
#   smoke: each target from its committed seeds alone (a scratch corpus), with a fixed seed and a
#          fixed number of runs, SECONDS at most, so a failure is a regression in the code rather
#          than the luck of the draw. The report of a crash is printed and its input kept in
#          BUILD_DIR; keep it in the target's seeds once fixed. fuzz_model only runs its seeds
#          (real models of every format and the inputs that once crashed it), no mutations:
#          mutating Assimp 5.2.5 finds a bug of Assimp's own within seconds to minutes, and its
#          hash tables (keyed by pointers) make even a fixed seed take another path each run, so
#          `make test` would fail by chance. Those runs belong to `make fuzz`.
#
# Targets and seeds: fuzz_model (assimp-testmodels and the hostile corpus through
# seed_model_corpus.py, plus tests/fuzz/corpus_model), fuzz_sidecar (scenes/), fuzz_path,
# fuzz_settings and fuzz_cli (tests/fuzz/corpus_NAME).
set -u
build=$(realpath "$1")
seconds=$2
mode=${3:-long}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

python3 "$here/seed_model_corpus.py" "$build/seeds-model" >/dev/null || exit 1

# name, smoke runs (about 12 s each on 2 cores with ASan; 0: the seeds alone), seed directories
targets=(
    "model 0 $build/seeds-model $here/corpus_model"
    "sidecar 15000 $root/scenes"
    "path 15000 $here/corpus_path"
    "settings 30000 $here/corpus_settings"
    "cli 60000 $here/corpus_cli"
)
status=0
for t in "${targets[@]}"; do
    read -r name runs seeds <<<"$t"
    flags=(-rss_limit_mb=2048 -timeout=60 -artifact_prefix="$build/")
    env=()
    case $name in
    # Assimp 5.2.5 leaks on some malformed ASCII STL files (its error path, not ours), which would
    # stop the run at the first one, and LeakSanitizer's report at exit (Assimp's objects only)
    # would fail it; our C code's leaks show in make test-asan.
    model) flags+=(-detect_leaks=0 -max_len=65536); env=(ASAN_OPTIONS=detect_leaks=0) ;;
    # Their parsers print the one-line error of each bad input: libFuzzer's own lines are enough.
    settings | cli) flags+=(-close_fd_mask=2) ;;
    esac
    if [ "$mode" = smoke ]; then
        corpus=$(mktemp -d "$build/smoke-$name.XXXXXX")
        log=$build/smoke-$name.log
        # shellcheck disable=SC2086 # seeds: a list of directories without blanks
        env "${env[@]}" "$build/fuzz_$name" "${flags[@]}" -seed=1 -runs="$runs" -max_total_time="$seconds" \
            "$corpus" $seeds >"$log" 2>&1
        rc=$?
        rm -rf "$corpus"
        done_line=$(grep -a '^Done ' "$log" | tail -n 1)
        if [ "$rc" -ne 0 ]; then
            echo "fuzz_$name: FAILED (exit $rc); the end of $log:" >&2
            tail -n 40 "$log" >&2
            status=1
        else
            echo "fuzz_$name: ${done_line:-no summary}"
        fi
    else
        mkdir -p "$build/corpus-$name"
        # shellcheck disable=SC2086
        (cd "$build" && env "${env[@]}" "./fuzz_$name" "${flags[@]}" -max_total_time="$seconds" "corpus-$name" $seeds) || exit 1
    fi
done
exit $status
