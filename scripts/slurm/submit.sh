#!/bin/bash
# Submit an obscura compare run to Slurm as N shards and their merge:
#   scripts/slurm/submit.sh N OUT COMPARE-OPTIONS...
# queues a job array of N tasks (compare-array.sbatch: task K runs --shard K/N into OUT/shard-K)
# and a merge job that starts when every task has succeeded (merge.sbatch: OUT/report). Prints
# the two job ids ("ARRAY_ID MERGE_ID"). Extra sbatch options go in $SBATCH_OPTIONS (e.g.
# "--partition=gpu --time=2:00:00"); $OBSCURA names the binary the jobs run. docs/scale.md.
# With SHARD_UNIT=row the shards take single rows of views (compare --shard-unit row), for more
# shards than views: an array of N tasks traces the references into the shared reference cache
# first (references-array.sbatch), the rows' array starts when it has succeeded, and the ids are
# three ("REFERENCES_ID ARRAY_ID MERGE_ID").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
n=${1:?usage: submit.sh N OUT COMPARE-OPTIONS...}
out=${2:?usage: submit.sh N OUT COMPARE-OPTIONS...}
shift 2
case $n in '' | *[!0-9]*) echo "submit.sh: N must be a whole number, got '$n'" >&2; exit 2 ;; esac
[ "$n" -ge 1 ] || { echo "submit.sh: N must be at least 1" >&2; exit 2; }
case ${SHARD_UNIT:-view} in view | row) ;; *) echo "submit.sh: SHARD_UNIT must be view or row, got '$SHARD_UNIT'" >&2; exit 2 ;; esac
mkdir -p "$out/slurm"
out=$(cd "$out" && pwd)
after=() references=
if [ "${SHARD_UNIT:-view}" = row ]; then
    # shellcheck disable=SC2086 # SBATCH_OPTIONS is a list of options
    references=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="0-$((n - 1))" --output="$out/slurm/references-%a.log" \
        "$here/references-array.sbatch" "$@")
    references=${references%%;*}
    after=(--dependency="afterok:$references")
    set -- "$@" --shard-unit row
fi
# shellcheck disable=SC2086 # SBATCH_OPTIONS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} "${after[@]}" --array="0-$((n - 1))" --output="$out/slurm/shard-%a.log" \
    "$here/compare-array.sbatch" "$out" "$@")
array=${array%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterok:$array" --output="$out/slurm/merge.log" \
    "$here/merge.sbatch" "$out")
echo "${references:+$references }${array} ${merge%%;*}"
