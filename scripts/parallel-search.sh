#!/usr/bin/env bash
# Run a wingcheck search as N shards with GNU parallel (one thread per shard), then merge.
#
#   scripts/parallel-search.sh N OUT SEARCH-ARGS...
#   e.g. scripts/parallel-search.sh 8 runs/ab --over control.a=1e-4..10:log:32 --over control.b=1e-2..1e4:log:32
#
# Shard K writes OUT/shard-K; the merged results go to OUT/all. JOBS (default N) sets how
# many shards run at once. The binary: $WINGCHECK, else `wingcheck` on PATH
# (`cargo install --locked --path .`), else the checkout's target/release/wingcheck (see
# scripts/find-wingcheck.sh). Exit status: that of `wingcheck merge` — 0 every point ok, 3
# complete but some points failed (see OUT/all/failures.csv), 1 an error — unless a shard
# failed: then the first such shard's status (2: a usage error, e.g. a misspelt option; 1:
# an error), with the shards' log lines, and nothing is merged. A failed shard can simply be
# rerun; it resumes from its completed chunks.
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 N OUT SEARCH-ARGS..." >&2
    exit 2
fi
n=$1
out=$2
shift 2
source "$(dirname "${BASH_SOURCE[0]}")/find-wingcheck.sh"
mkdir -p "$out"
log="$out/parallel-joblog.txt"
# Every shard runs to its end (--halt never); their statuses are read from the job log below.
# The shards are merged below: tell them so (they then do not ask a person to merge).
export WINGCHECK_MERGED_BY=scripts/parallel-search.sh
parallel --quote --halt never --joblog "$log" -j "${JOBS:-$n}" \
    "$wingcheck" search "$@" --threads 1 --shard "{}/$n" --out "$out/shard-{}" ::: $(seq "$n") || true
# Exitval is column 7 of the job log; 3 = the shard is complete with some failed points.
failed=$(awk -F'\t' 'NR > 1 && $7 != 0 && $7 != 3 { print $7; exit }' "$log")
if [ -n "$failed" ]; then
    echo "error: a shard failed (exit status $failed); nothing merged. Job log $log:" >&2
    cat "$log" >&2
    exit "$failed"
fi
shards=()
for k in $(seq "$n"); do shards+=("$out/shard-$k"); done
exec "$wingcheck" merge "${shards[@]}" --out "$out/all"
