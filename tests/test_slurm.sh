#!/usr/bin/env bash
# compare on a real Slurm (issue 49, item 4): a single-node cluster from Debian's packages (munge,
# slurmctld, slurmd) on localhost, with its configuration, state and sockets in a scratch folder
# and ports the kernel picks, takes scripts/slurm/submit.sh's job array of 4 shards over a small
# sweep and its dependent merge; the merged report must be the unsharded run's
# (tests/report_same.py). Everything it started is stopped at the end. When Slurm cannot start
# here the test says why and fails: it is never skipped.
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

echo "slurm: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
