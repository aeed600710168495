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
rm -f "$out"/shard-*.csv "$out/sweep.csv"
total=$(python3 "$root/scripts/sweep.py" "$root/build/app/shadetlm" "$root" --list)
export SWEEP_ROOT=$root SWEEP_JOBS=$jobs SWEEP_OUT=$out
seq 0 $((jobs - 1)) | xargs -P "$jobs" -I{} sh -c \
  'python3 "$SWEEP_ROOT/scripts/sweep.py" "$SWEEP_ROOT/build/app/shadetlm" "$SWEEP_ROOT" --shard {}/$SWEEP_JOBS > "$SWEEP_OUT/shard-{}.csv"' &
runs=$!
# One progress bar for all shards, from their rows so far (only on a terminal).
while kill -0 $runs 2>/dev/null; do
  if [[ -t 2 ]]; then
    done_rows=$(cat "$out"/shard-*.csv 2>/dev/null | grep -c '^[0-9]' || true)
    filled=$((30 * done_rows / total))
    printf '\rsweep [%-30s] %d/%d' "$(printf '%*s' $filled '' | tr ' ' '#')" "$done_rows" "$total" >&2
  fi
  sleep 0.5
done
[[ -t 2 ]] && printf '\r%60s\r' '' >&2
wait $runs
# One header, then every shard's rows in run order.
{ head -1 "$out/shard-0.csv"; tail -q -n +2 "$out"/shard-*.csv | sort -t, -k1,1n; } >"$out/sweep.csv"
rm -f "$out"/shard-*.csv
echo "$(($(wc -l <"$out/sweep.csv") - 1)) runs: $out/sweep.csv"
