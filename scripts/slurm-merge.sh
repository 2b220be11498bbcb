#!/usr/bin/env bash
# Merge the shards of a Slurm search (scripts/slurm-search.sh) into OUT/all; submit from the
# checkout after the array:
#
#   sbatch --dependency=afterany:$jid scripts/slurm-merge.sh OUT
#
# The binary is found as the search tasks find it (scripts/find-wingcheck.sh: $WINGCHECK, else
# `wingcheck` on PATH, else the checkout's target/release/wingcheck), so the merge runs without
# an install too. Exit status: wingcheck merge's (0 every point ok, 3 merged with some points
# failed, 1 an error such as a missing shard, 2 a usage error).
#SBATCH --job-name=wingcheck-merge
#SBATCH --cpus-per-task=1
#SBATCH --output=slurm-merge-%j.out
set -euo pipefail
if [ $# -ne 1 ]; then
    echo "usage: sbatch --dependency=afterany:JOBID $0 OUT" >&2
    exit 2
fi
out=$1
helper=$(dirname "${BASH_SOURCE[0]}")/find-wingcheck.sh
[ -f "$helper" ] || helper=${SLURM_SUBMIT_DIR:-.}/scripts/find-wingcheck.sh
source "$helper"
exec "$wingcheck" merge "$out"/shard-* --out "$out/all"
