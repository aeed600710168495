#!/usr/bin/env bash
# Run time against error: every configuration of scripts/sweep.py through the pipeline,
# against the golden model, as independent jobs run in parallel with xargs -P (one per
# core unless JOBS says otherwise); then the wall times, in a serial pass. Writes
# out/sweep/sweep.csv (one row per run); scripts/plot.sh draws it. On a cluster the same
# shards run as a Slurm job array (docs/benchmarks.md).
# Usage: scripts/sweep.sh [--repeats R] [--no-build] [JOBS]
#   --repeats R  times each run R times (default 5): wall_s the median, with quartiles
#                and extremes; 0 keeps the one time each run had in its shard
#   --no-build   uses build/app/shadetlm as it is (no cmake)
# SHADETLM=path runs that binary instead, as it is (e.g. a copy, while build/ is rebuilt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=5 build=1
while [[ ${1:-} == --* ]]; do
  case $1 in
    --repeats)
      [[ ${2:-} =~ ^[0-9]+$ ]] || { echo "sweep.sh: --repeats takes a count (0: one concurrent time a run)" >&2; exit 2; }
      repeats=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    *) echo "sweep.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
"$root/scripts/setup.sh"
bin=${SHADETLM:-$root/build/app/shadetlm}
((build)) && [[ -z ${SHADETLM:-} ]] && "$root/scripts/build.sh" >/dev/null
jobs=${1:-$(nproc)}
out=$root/out/sweep
mkdir -p "$out"
rm -f "$out"/shard-*.csv "$out/sweep.csv" "$out/errors.csv" "$out/timed.csv"
total=$(python3 "$root/scripts/sweep.py" "$bin" "$root" --list)
export SWEEP_ROOT=$root SWEEP_BIN=$bin SWEEP_JOBS=$jobs SWEEP_OUT=$out
seq 0 $((jobs - 1)) | xargs -P "$jobs" -I{} sh -c \
  'python3 "$SWEEP_ROOT/scripts/sweep.py" "$SWEEP_BIN" "$SWEEP_ROOT" --shard {}/$SWEEP_JOBS > "$SWEEP_OUT/shard-{}.csv"' &
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
{ head -1 "$out/shard-0.csv"; tail -q -n +2 "$out"/shard-*.csv | sort -t, -k1,1n; } >"$out/errors.csv"
rm -f "$out"/shard-*.csv
# The shards' wall times come from runs sharing the cores with each other: the times are
# taken again here, one run at a time (error, cycles and operations do not change).
if ((repeats > 0)); then
  python3 "$root/scripts/sweep.py" "$bin" "$root" --time "$repeats" \
    <"$out/errors.csv" >"$out/timed.csv"
  mv "$out/timed.csv" "$out/sweep.csv"
  rm "$out/errors.csv"
else
  mv "$out/errors.csv" "$out/sweep.csv"
fi
echo "$(($(wc -l <"$out/sweep.csv") - 1)) runs: $out/sweep.csv"
