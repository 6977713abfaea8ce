#!/usr/bin/env bash
# tune --shard K/N --exchange DIR (issue 49, item 1): one tuning run as 2 and as 3 processes run at
# once, sharing an exchange folder, gives the unsharded run's result: shard 0's settings file
# equal in every value but the timing (seconds) and its record of the split, and every shard's
# table equal. Each shard loads only its own views: each traces its references into a cache of its
# own, which then holds exactly its views' references. Errors are one line: --shard without
# --exchange (exit 2), a shard that never comes (exit 3 after --exchange-timeout, naming it), a
# shard that fails (the others stop at once naming it, exit 3), a corrupt or foreign record (exit
# 3, naming the file), and a rerun into a folder that holds the finished run's records (exit 4).
# usage: test_tune_shards.sh OBSCURA
set -u
OBSCURA=$1
dir=$(mktemp -d)
pids=()
cleanup() {
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
    rm -rf "$dir"
}
trap cleanup EXIT
# One shader cache for every process; the references' caches are set per run below.
export MESA_SHADER_CACHE_DIR="$dir/mesa" XDG_CACHE_HOME="$dir/cache"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }

# Two training views, a validation and a check view: 13 evaluations, both parameters move.
run=(tune --size 64x48 --method hbao --params hbao.radius_scale,hbao.intensity=0:3 --spp 16 --passes 1 --steps 3
    --train corner:diagonal,cornell:front --validate sphere-on-plane:front --check sphere-on-plane:contact)
"$OBSCURA" "${run[@]}" --out "$dir/whole.json" >"$dir/whole.out" 2>"$dir/err" && ok ||
    bad "unsharded: $(tail -1 "$dir/err")"

# shards NAME N [OPTION...]: shards 0..N-1 of the run at once, each with its own reference cache,
# every one given the same --out; each one's exit status into NAME-K.rc.
shards() {
    local name=$1 n=$2
    shift 2
    local mine=()
    for ((k = 0; k < n; ++k)); do
        XDG_CACHE_HOME="$dir/cache-$name-$k" "$OBSCURA" "${run[@]}" --shard "$k/$n" --exchange "$dir/ex-$name" \
            --out "$dir/$name.json" "$@" >"$dir/$name-$k.out" 2>"$dir/$name-$k.err" &
        mine+=($!)
        pids+=($!)
    done
    for ((k = 0; k < n; ++k)); do
        wait "${mine[$k]}"
        echo $? >"$dir/$name-$k.rc"
    done
}

# same WHOLE SHARDED: every value of the settings file equal but tuned.seconds (a timing) and
# tuned.shard (the split, which the unsharded file has not); the files are whole and hold what a
# tuning run finds (a comparison of two empty files would pass).
same() {
    python3 - "$1" "$2" <<'PY'
import json, sys
whole, sharded = (json.load(open(p)) for p in sys.argv[1:])
t = whole["tuned"]
# Not vacuous: both parameters left their defaults (1 and 1), and every view has its numbers.
assert whole["params"]["radius_scale"] != 1 and whole["params"]["intensity"] != 1, whole["params"]
assert [len(t[k]) for k in ("training", "validation", "check")] == [2, 1, 1], t
assert all(v["rmse_default"] > 0 and v["rmse_tuned"] > 0 for k in ("training", "validation", "check") for v in t[k]), t
assert t["training_rmse_tuned"] < t["training_rmse_default"] and t["evaluations"] == 13, t
shard = sharded["tuned"].pop("shard")
assert shard["index"] == 0, shard
for d in (whole, sharded):
    d["tuned"].pop("seconds")
assert whole == sharded, (whole, sharded)
PY
}
# The table a shard printed, as the unsharded run printed it: without its own first line (which
# views it loads), the last ("wrote", or "shard 0 writes"), and the seconds.
table() { grep -v -e '^tune: shard' -e '^wrote ' -e '^shard .* done' "$1" | sed 's/ evaluations in [0-9]* s:/ evaluations:/'; }

for n in 2 3; do
    shards "s$n" "$n"
    for ((k = 0; k < n; ++k)); do
        [ "$(cat "$dir/s$n-$k.rc")" = 0 ] && ok || bad "shard $k/$n exited $(cat "$dir/s$n-$k.rc"): $(tail -1 "$dir/s$n-$k.err")"
        [ "$(table "$dir/s$n-$k.out")" = "$(table "$dir/whole.out")" ] && ok ||
            bad "shard $k/$n's table differs: $(diff <(table "$dir/whole.out") <(table "$dir/s$n-$k.out"))"
    done
    same "$dir/whole.json" "$dir/s$n.json" && ok || bad "$n shards' settings differ from the unsharded run's"
    grep -qx "shard 1/$n done: shard 0 writes the settings" "$dir/s$n-1.out" && ok || bad "shard 1/$n: $(tail -1 "$dir/s$n-1.out")"
    # A finished run leaves its last evaluation's records (14 evaluations: 0..13), one per shard.
    [ "$(cd "$dir/ex-s$n"/* && ls | tr '\n' ' ')" = "$(for ((k = 0; k < n; ++k)); do printf 'eval-13.shard-%d ' $k; done)" ] &&
        ok || bad "$n shards left $(ls -a "$dir/ex-s$n"/*)"
done

# The split: views of equal cost in turn (2 shards: 0 1 0 1; 3 shards: 0 1 2 0), as the file records
# it, as each shard says, and as its reference cache shows (one entry per view it loaded).
split() { # N SHARD-OF-EACH-VIEW...
    local n=$1
    shift
    python3 - "$dir/s$n.json" "$n" "$@" <<'PY' || return 1
import json, sys
d = json.load(open(sys.argv[1]))
n, owners = int(sys.argv[2]), [int(a) for a in sys.argv[3:]]
views = ["corner:diagonal", "cornell:front", "sphere-on-plane:front", "sphere-on-plane:contact"]
want = {"index": 0, "count": n, "views": [{"view": v, "shard": s} for v, s in zip(views, owners)]}
assert d["tuned"]["shard"] == want, d["tuned"]["shard"]
PY
    local views=(corner:diagonal cornell:front sphere-on-plane:front sphere-on-plane:contact)
    for ((k = 0; k < n; ++k)); do
        local mine=() i
        for i in 0 1 2 3; do
            [ "${@:$((i + 1)):1}" = "$k" ] && mine+=("${views[$i]}")
        done
        local said
        said=$(head -1 "$dir/s$n-$k.out")
        local list
        list=$(printf '%s, ' "${mine[@]}")
        [ "$said" = "tune: shard $k/$n loads ${#mine[@]} of 4 views (${list%, }); records in $(echo "$dir/ex-s$n"/*)" ] ||
            { echo "shard $k/$n said: $said"; return 1; }
        local traced
        traced=$(find "$dir/cache-s$n-$k/obscura" -name 'reference-*' -type f | wc -l)
        [ "$traced" -eq "${#mine[@]}" ] || { echo "shard $k/$n traced $traced references for ${#mine[@]} views"; return 1; }
    done
}
split 2 0 1 0 1 && ok || bad "the 2 shards' split"
split 3 0 1 2 0 && ok || bad "the 3 shards' split"

# expect CODE PATTERN ARGS...: exit CODE and one error line, the last on stderr (progress comes
# before it), matching PATTERN.
expect() {
    local code=$1 pattern=$2
    shift 2
    "$OBSCURA" "$@" >"$dir/stdout" 2>"$dir/stderr"
    local got=$?
    if [ $got -ne "$code" ] || [ "$(grep -c '^obscura: ' "$dir/stderr")" -ne 1 ] ||
        ! tail -1 "$dir/stderr" | grep -qE -e "$pattern"; then
        bad "$* exited $got: $(tail -2 "$dir/stderr") (want $code and /$pattern/)"
    else ok; fi
}
# A rerun into the folder of the finished run: refused, the folder named (the same command makes
# the same records, so an earlier attempt's could not be told from this one's).
shards s2 2
for k in 0 1; do
    [ "$(cat "$dir/s2-$k.rc")" = 4 ] && grep -q "^obscura: --exchange: $dir/ex-s2/[0-9a-f]\{16\} holds an earlier run's records (eval-13.shard-[01]); remove it$" "$dir/s2-$k.err" &&
        ok || bad "a rerun of shard $k/2 into the finished run's folder: exit $(cat "$dir/s2-$k.rc"), $(tail -1 "$dir/s2-$k.err")"
done

small=(tune --size 64x48 --method hbao --params hbao.radius_scale --spp 16 --passes 1 --steps 3 --train corner:diagonal)
expect 2 "^obscura: --shard 1/2: .*give --exchange DIR" "${small[@]}" --shard 1/2 --out "$dir/x.json"
expect 2 "^obscura: --exchange: without --shard K/N" "${small[@]}" --exchange "$dir/ex" --out "$dir/x.json"
for s in 2/2 -1/2 1/0 x; do
    expect 2 "^obscura: --shard: expected K/N" "${small[@]}" --shard "$s" --exchange "$dir/ex" --out "$dir/x.json"
done
expect 2 "^obscura: --exchange-timeout: expected a positive number" "${small[@]}" --shard 0/2 --exchange "$dir/ex" \
    --exchange-timeout 0 --out "$dir/x.json"
expect 2 "^obscura: --out FILE.json is required" "${small[@]}" --shard 0/2 --exchange "$dir/ex"
[ ! -e "$dir/ex" ] && [ ! -e "$dir/x.json" ] && ok || bad "a refused command left $(ls "$dir")"
"$OBSCURA" tune --help >"$dir/help" && grep -q -- "--shard K/N" "$dir/help" && grep -q -- "--exchange DIR" "$dir/help" &&
    grep -q -- "--exchange-timeout S" "$dir/help" && ok || bad "tune --help does not document the shards' options"

# Shard 1 never comes: shard 0 waits --exchange-timeout at the first evaluation, then names it.
start=$SECONDS
expect 3 "^obscura: shard 1/2 never wrote evaluation 0 within --exchange-timeout 1.5 s \(no $dir/ex-alone/[0-9a-f]{16}/eval-0.shard-1\)$" \
    "${small[@]}" --shard 0/2 --exchange "$dir/ex-alone" --exchange-timeout 1.5 --out "$dir/x.json"
[ $((SECONDS - start)) -ge 1 ] && ok || bad "shard 0 gave up before --exchange-timeout"
expect 3 "^obscura: shards 0/4, 2/4, 3/4 never wrote evaluation 0" "${small[@]}" --shard 1/4 --exchange "$dir/ex-four" \
    --exchange-timeout 0.2
[ ! -e "$dir/x.json" ] && ok || bad "a shard that timed out wrote --out"

# A shard that fails (its view cannot be read): it stops with its own error, and shard 0 at once
# with one naming shard 1 and why, long before the timeout. Shard 1 takes no --out.
failing=(tune --size 64x48 --method hbao --params hbao.radius_scale --spp 16 --passes 1 --steps 3
    --train "corner:diagonal,$dir/missing.obj")
start=$SECONDS
"$OBSCURA" "${failing[@]}" --shard 1/2 --exchange "$dir/ex-fail" >"$dir/f1.out" 2>"$dir/f1.err" &
pids+=($!)
expect 3 "^obscura: shard 1/2 failed: cannot read model '$dir/missing.obj': no such file \($dir/ex-fail/[0-9a-f]{16}/failed.shard-1\)$" \
    "${failing[@]}" --shard 0/2 --exchange "$dir/ex-fail" --exchange-timeout 60 --out "$dir/x.json"
[ $((SECONDS - start)) -lt 30 ] && ok || bad "shard 0 waited $((SECONDS - start)) s for the failed shard"
wait "${pids[-1]}"
rc=$?
[ $rc -eq 3 ] && tail -1 "$dir/f1.err" | grep -q "^obscura: cannot read model '$dir/missing.obj'" && ok ||
    bad "the failing shard exited $rc: $(tail -1 "$dir/f1.err")"

# Records that are not this run's shard 1's at evaluation 0: exit 3, the file named. Made from the
# record shard 0 left in ex-alone (the same run: the same command line but for the options that
# differ between shards).
id=$(basename "$(echo "$dir/ex-alone"/*)")
rec="$dir/ex-alone/$id/eval-0.shard-0"
grep -q "^view 0 0x" "$rec" && ok || bad "shard 0's record: $(cat "$rec")"
corrupt() { # PATTERN: shard 0 against the record on stdin as shard 1's
    rm -rf "$dir/ex-bad"
    mkdir -p "$dir/ex-bad/$id"
    cat >"$dir/ex-bad/$id/eval-0.shard-1"
    expect 3 "^obscura: $dir/ex-bad/$id/eval-0.shard-1: $1" "${small[@]}" --shard 0/2 --exchange "$dir/ex-bad" \
        --exchange-timeout 30 --out "$dir/x.json"
}
echo "hello" | corrupt "not a tune exchange record"
sed 's/^shard 0\/2$/shard 1\/2/' "$rec" | corrupt "holds views that are not that shard's in this evaluation"
sed -e 's/^shard 0\/2$/shard 1\/2/' -e 's/^run .*/run 0123456789abcdef/' "$rec" | corrupt "a record of another run \(0123456789abcdef; this run is $id\)"
sed 's/^shard 0\/2$/shard 1\/3/' "$rec" | corrupt "shard 1/3's record where shard 1/2's belongs"
sed -e 's/^shard 0\/2$/shard 1\/2/' -e 's/^version .*/version 0.0.1/' "$rec" | corrupt "written by obscura 0.0.1"
head -3 "$rec" | corrupt "not whole \(no shard line\)"
[ ! -e "$dir/x.json" ] && ok || bad "a failed shard 0 wrote --out"

echo "tune_shards: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
