#!/usr/bin/env bash
# One shard of a wingcheck search per task of a Slurm job array; submit from the checkout.
#
#   jid=$(sbatch --parsable --array=1-16 scripts/slurm-search.sh OUT SEARCH-ARGS...)
#   sbatch --dependency=afterany:$jid scripts/slurm-merge.sh OUT      # merges into OUT/all
#
# The array must be numbered 1..N (task K runs shard K/N, N = SLURM_ARRAY_TASK_COUNT) and
# writes OUT/shard-K, with SLURM_CPUS_PER_TASK threads (default 1). The binary: $WINGCHECK,
# else `wingcheck` on PATH (`cargo install --locked --path .`), else the checkout's
# target/release/wingcheck (scripts/find-wingcheck.sh). A task exits 0 when its shard is
# complete — also when some of its points failed (wingcheck's status 3: they are answered,
# and merge reports them) — and with wingcheck's own status otherwise, so Slurm shows it
# FAILED: 2 a usage error (e.g. a misspelt option), 1 an error. A failed task can be
# resubmitted alone with the shard count given explicitly,
# `SHARDS=16 sbatch --array=K --export=ALL,SHARDS scripts/slurm-search.sh ...`; it resumes
# from its completed chunks.
#SBATCH --job-name=wingcheck-search
#SBATCH --cpus-per-task=1
#SBATCH --output=slurm-search-%A_%a.out
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: sbatch --array=1-N $0 OUT SEARCH-ARGS..." >&2
    exit 2
fi
out=$1
shift
k=${SLURM_ARRAY_TASK_ID:?submit as a job array: sbatch --array=1-N}
n=${SHARDS:-${SLURM_ARRAY_TASK_COUNT:?submit as a job array: sbatch --array=1-N}}
if [ -z "${SHARDS:-}" ] && { [ "${SLURM_ARRAY_TASK_MIN:-1}" != 1 ] || [ "${SLURM_ARRAY_TASK_MAX:-$n}" != "$n" ]; }; then
    echo "the array must be numbered 1..N (got ${SLURM_ARRAY_TASK_MIN}..${SLURM_ARRAY_TASK_MAX})" >&2
    exit 2
fi
# Slurm runs a copy of this script: the helper is found beside the original (the submit
# directory is the checkout) or beside this file when run directly.
helper=$(dirname "${BASH_SOURCE[0]}")/find-wingcheck.sh
[ -f "$helper" ] || helper=${SLURM_SUBMIT_DIR:-.}/scripts/find-wingcheck.sh
source "$helper"
mkdir -p "$out"
status=0
"$wingcheck" search "$@" --threads "${SLURM_CPUS_PER_TASK:-1}" --shard "$k/$n" --out "$out/shard-$k" || status=$?
# 3 = the shard is complete and some of its points failed (reported by merge): the task did its job
if [ "$status" -eq 3 ]; then status=0; fi
exit "$status"
