#!/usr/bin/env bash
# Run time against error: every configuration of scripts/sweep.py through the pipeline,
# against the golden model, as independent jobs run in parallel with xargs -P (one per
# core unless JOBS says otherwise). Writes out/sweep/sweep.csv (one row per run);
# scripts/plot.sh draws it. On a cluster the same shards run as a Slurm job array
# (docs/benchmarks.md).
# Usage: scripts/sweep.sh [JOBS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh" >/dev/null
jobs=${1:-$(nproc)}
out=$root/out/sweep
mkdir -p "$out"
rm -f "$out"/shard-*.csv
seq 0 $((jobs - 1)) | xargs -P "$jobs" -I{} sh -c \
  "python3 '$root/scripts/sweep.py' '$root/build/app/shadetlm' '$root' --shard {}/$jobs > '$out/shard-{}.csv'"
# One header, then every shard's rows in run order.
{ head -1 "$out/shard-0.csv"; tail -q -n +2 "$out"/shard-*.csv | sort -t, -k1,1n; } >"$out/sweep.csv"
rm -f "$out"/shard-*.csv
echo "$(($(wc -l <"$out/sweep.csv") - 1)) runs: $out/sweep.csv"
