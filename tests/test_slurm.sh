#!/usr/bin/env bash
# compare and tune on a real Slurm (issue 49, items 1 and 4): a single-node cluster from Debian's
# packages (munge, slurmctld, slurmd) on localhost, with its configuration, state and sockets in a
# scratch folder and ports the kernel picks, takes scripts/slurm/submit.sh's job array of 4 shards
# over a small sweep and its dependent merge; the merged report must be the unsharded run's
# (tests/report_same.py); the same with SHARD_UNIT=row (a references array, the rows' array after
# it, the merge). Then scripts/slurm/tune.sbatch runs a tune as one job of 2 tasks, which
# must run at once and exchange their evaluations; shard 0's settings must be the unsharded run's.
# Everything it started is stopped at the end. When Slurm cannot start here the test says why and
# fails: it is never skipped.
# usage: test_slurm.sh OBSCURA
set -u
OBSCURA=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
here=$(cd "$(dirname "$0")" && pwd)
scripts=$here/../scripts/slurm
dir=$(mktemp -d)
S=$dir/slurm
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
stop() {
    for p in "$S/slurmd.pid" "$S/slurmctld.pid" "$S/munge/pid"; do
        [ -f "$p" ] && kill "$(cat "$p")" 2>/dev/null
    done
    sleep 1
    for p in "$S/slurmd.pid" "$S/slurmctld.pid" "$S/munge/pid"; do
        [ -f "$p" ] && kill -9 "$(cat "$p")" 2>/dev/null
    done
    rm -rf "$dir"
}
trap stop EXIT
cannot() {
    echo "FAIL: Slurm cannot start on this machine: $*" >&2
    for f in "$S"/log/*.log; do [ -f "$f" ] && { echo "--- $f" >&2; tail -5 "$f" >&2; }; done
    echo "slurm: 0 passed, 1 failed"
    exit 1
}
for b in munged slurmctld slurmd sbatch squeue; do
    command -v "$b" >/dev/null || cannot "$b is not installed (Debian: munge, slurmctld, slurmd, slurm-client; scripts/install-deps.sh)"
done

# munge: its own key and socket (the key 0600, as munged demands; --force lets root run it).
mkdir -p "$S/munge" "$S/state" "$S/spool" "$S/log"
chmod 700 "$S/munge"
head -c 1024 /dev/urandom >"$S/munge/key"
chmod 600 "$S/munge/key"
munged --force --socket="$S/munge/sock" --key-file="$S/munge/key" --pid-file="$S/munge/pid" \
    --log-file="$S/log/munged.log" --seed-file="$S/munge/seed" || cannot "munged did not start"

# Two free ports, one node named as this host answers to, the daemons as the current user.
read -r ctld_port d_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
host=$(hostname -s)
user=$(id -un)
cat >"$S/slurm.conf" <<EOF
ClusterName=obscura-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
AuthInfo=socket=$S/munge/sock
CredType=cred/munge
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
PlugStackConfig=$S/plugstack.conf
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=obscura Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
EOF
: >"$S/plugstack.conf"
export SLURM_CONF=$S/slurm.conf
slurmctld -f "$SLURM_CONF" -i || cannot "slurmctld did not start"
slurmd -f "$SLURM_CONF" -N "$host" || cannot "slurmd did not start"
up=0
for _ in $(seq 1 30); do
    if sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then up=1; break; fi
    sleep 1
done
[ $up -eq 1 ] || cannot "the node never came up ($(sinfo -h -o '%T %E' 2>&1 | head -1))"
ok

# The sweep, unsharded, here; then the same through Slurm as 4 shards and a merge.
export OBSCURA XDG_CACHE_HOME="$dir/cache"
run=(--scene corner:diagonal --scene cornell:front --scene sphere-on-plane:contact --scene grille:front
    --methods ssao,vbao --size 48x36 --spp 16)
"$OBSCURA" compare "${run[@]}" --report "$dir/whole" >/dev/null 2>"$dir/err" && ok || bad "unsharded: $(tail -1 "$dir/err")"
if ids=$("$scripts/submit.sh" 4 "$dir/sweep" "${run[@]}" 2>"$dir/err"); then ok
else cannot "sbatch refused the job array: $(cat "$dir/err")"; fi
read -r array merge <<<"$ids"
# Wait for the merge job to leave the queue (it starts only after all four shards succeeded).
for _ in $(seq 1 300); do
    squeue -h -j "$array,$merge" 2>/dev/null | grep -q . || break
    sleep 1
done
squeue -h -j "$array,$merge" 2>/dev/null | grep -q . && bad "jobs $array and $merge still queued after 300 s: $(squeue 2>&1)"
for k in 0 1 2 3; do
    [ -f "$dir/sweep/shard-$k/results.json" ] && ok || bad "shard $k wrote no report: $(cat "$dir/sweep/slurm/shard-$k.log" 2>&1)"
done
if [ -f "$dir/sweep/report/index.html" ]; then ok; else bad "no merged report: $(cat "$dir/sweep/slurm/merge.log" 2>&1)"; fi
python3 "$here/report_same.py" "$dir/whole" "$dir/sweep/report" && ok || bad "the merged report differs from the unsharded run"
# One view per shard (four views of equal cost over four shards).
for k in 0 1 2 3; do
    [ "$(find "$dir/sweep/shard-$k" -mindepth 1 -maxdepth 1 -type d | wc -l)" -eq 1 ] && ok ||
        bad "shard $k ran $(ls "$dir/sweep/shard-$k")"
done

# Split by rows (SHARD_UNIT=row): an array tracing the references into the cache, the rows' array
# after it, and the merge; three jobs, in order, a fresh cache so that the first traces them.
export XDG_CACHE_HOME="$dir/cache-rows"
rows=(--scene corner:diagonal --scene cornell:front --methods ssao,gtao,vbao --size 48x36 --spp 16)
if ids=$(SHARD_UNIT=row "$scripts/submit.sh" 4 "$dir/rows" "${rows[@]}" 2>"$dir/err"); then ok
else cannot "sbatch refused the row arrays: $(cat "$dir/err")"; fi
read -r references array merge <<<"$ids"
[ -n "$merge" ] && ok || bad "submit.sh with SHARD_UNIT=row printed '$ids', not three job ids"
for _ in $(seq 1 300); do
    squeue -h -j "$references,$array,$merge" 2>/dev/null | grep -q . || break
    sleep 1
done
grep -h 'traced into the cache' "$dir"/rows/slurm/references-*.log | wc -l | grep -qx 2 && ok ||
    bad "the references array: $(cat "$dir"/rows/slurm/references-*.log 2>&1)"
python3 -c '
import json, sys
for k in range(4):
    d = json.load(open(sys.argv[1] + "/shard-%d/results.json" % k))
    assert all(v["reference"]["cached"] is True for v in d["views"]), k  # traced by the first array
' "$dir/rows" && ok || bad "a row shard did not find its reference in the cache"
"$OBSCURA" compare "${rows[@]}" --report "$dir/rows-whole" >/dev/null 2>"$dir/err" || bad "rows unsharded: $(tail -1 "$dir/err")"
python3 "$here/report_same.py" "$dir/rows-whole" "$dir/rows/report" && ok ||
    bad "the row shards' merged report differs from the unsharded run: $(cat "$dir/rows/slurm/merge.log" 2>&1)"
export XDG_CACHE_HOME="$dir/cache"

# tune as one job step of 2 tasks (the node has CPUs=$(nproc): 2 on the test machine, or the tasks
# share a CPU with --overcommit); both shards must run at once, or they time out.
tune=(--size 64x48 --method hbao --params hbao.radius_scale,hbao.intensity=0:3 --spp 16 --passes 1 --steps 3
    --train corner:diagonal,cornell:front --validate sphere-on-plane:front)
"$OBSCURA" tune "${tune[@]}" --out "$dir/tune-whole.json" >/dev/null 2>"$dir/err" && ok || bad "unsharded tune: $(tail -1 "$dir/err")"
over=()
[ "$(nproc)" -ge 2 ] || over=(--overcommit)
if job=$(sbatch --parsable --ntasks=2 "${over[@]}" --output="$dir/tune.log" "$scripts/tune.sbatch" "$dir/exchange" \
    "${tune[@]}" --exchange-timeout 60 --out "$dir/tune-slurm.json" 2>"$dir/err"); then ok
else cannot "sbatch refused the tune job: $(cat "$dir/err")"; fi
job=${job%%;*}
for _ in $(seq 1 120); do
    squeue -h -j "$job" 2>/dev/null | grep -q . || break
    sleep 1
done
squeue -h -j "$job" 2>/dev/null | grep -q . && bad "tune job $job still queued after 120 s: $(squeue 2>&1)"
# Each task said which views it loads (srun --label: "K: "), both in the job's one folder.
grep -q "^0: tune: shard 0/2 loads 2 of 3 views (corner:diagonal, sphere-on-plane:front); records in $dir/exchange/job-$job-0/" \
    "$dir/tune.log" && grep -q "^1: tune: shard 1/2 loads 1 of 3 views (cornell:front)" "$dir/tune.log" &&
    grep -q "^1: shard 1/2 done" "$dir/tune.log" && ok || bad "the tune job's tasks: $(cat "$dir/tune.log")"
python3 - "$dir/tune-whole.json" "$dir/tune-slurm.json" <<'PY' && ok || bad "the tune job's settings differ from the unsharded run's"
import json, sys
whole, sharded = (json.load(open(p)) for p in sys.argv[1:])
assert whole["params"]["radius_scale"] != 1 and len(whole["tuned"]["training"]) == 2, whole
assert sharded["tuned"].pop("shard")["count"] == 2, sharded
for d in (whole, sharded):
    d["tuned"].pop("seconds")
assert whole == sharded, (whole, sharded)
PY

echo "slurm: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
