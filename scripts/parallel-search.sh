#!/usr/bin/env bash
# Run a wingcheck search as N shards with GNU parallel (one thread per shard), then merge.
#
#   scripts/parallel-search.sh N OUT SEARCH-ARGS...
#   e.g. scripts/parallel-search.sh 8 runs/ab --over control.a=1e-4..10:log:32 --over control.b=1e-2..1e4:log:32
#
# Shard K writes OUT/shard-K; the merged results go to OUT/all. JOBS (default N) sets how
# many shards run at once; WINGCHECK (default `wingcheck`) is the binary. Exit status: that
# of `wingcheck merge` (0: every point ok, 2: complete but some points failed — see
# OUT/all/failures.csv, 1: an error, e.g. a shard that did not finish: its chunks are
# missing). A failed shard can simply be rerun; it resumes from its completed chunks.
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 N OUT SEARCH-ARGS..." >&2
    exit 1
fi
n=$1
out=$2
shift 2
wingcheck=${WINGCHECK:-wingcheck}
mkdir -p "$out"
# A shard exits 2 when some of its points failed (still complete); merge decides the outcome.
parallel --quote --halt never --joblog "$out/parallel-joblog.txt" -j "${JOBS:-$n}" \
    "$wingcheck" search "$@" --threads 1 --shard "{}/$n" --out "$out/shard-{}" ::: $(seq "$n") || true
shards=()
for k in $(seq "$n"); do shards+=("$out/shard-$k"); done
exec "$wingcheck" merge "${shards[@]}" --out "$out/all"
