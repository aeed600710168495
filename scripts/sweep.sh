#!/usr/bin/env bash
# Run time against error: every configuration of scripts/sweep.py through the pipeline,
# against the golden model, as independent shards run in parallel with xargs -P (one per
# core unless JOBS says otherwise); then the wall times, in a serial pass. Writes
# RESULTS/sweep.csv (one row per run; RESULTS is out/sweep unless --results says
# otherwise); scripts/plot.sh draws it. On a Slurm cluster, scripts/slurm.py submit sweep
# runs the same shards as a job array (docs/benchmarks.md).
# Usage: scripts/sweep.sh [--repeats R] [--no-build] [--results DIR] [--match REGEX]
#                         [--resolution W,H] [--map-cache DIR | --no-map-cache] [JOBS]
#   --repeats R  times each run R times (default 5): wall_s the median, with quartiles
#                and extremes; 0 keeps the one time each run had in its shard
#   --no-build   uses build/app/shadetlm as it is (no cmake)
#   --match, --resolution, --map-cache, --no-map-cache: as scripts/sweep.py takes them
# SHADETLM=path runs that binary instead, as it is (e.g. a copy, while build/ is rebuilt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=5 build=1 results=$root/out/sweep
filters=()
while [[ ${1:-} == --* ]]; do
  case $1 in
    --repeats)
      [[ ${2:-} =~ ^[0-9]+$ ]] || { echo "sweep.sh: --repeats takes a count (0: one concurrent time a run)" >&2; exit 2; }
      repeats=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    --results) [[ -n ${2:-} ]] || { echo "sweep.sh: --results takes a folder" >&2; exit 2; }
      results=$2; shift 2 ;;
    --match|--resolution|--map-cache) (($# > 1)) || { echo "sweep.sh: $1 takes a value" >&2; exit 2; }
      filters+=("$1" "$2"); shift 2 ;;
    --no-map-cache) filters+=("$1"); shift ;;
    *) echo "sweep.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
"$root/scripts/setup.sh"
bin=${SHADETLM:-$root/build/app/shadetlm}
((build)) && [[ -z ${SHADETLM:-} ]] && "$root/scripts/build.sh" >/dev/null
jobs=${1:-$(nproc)}
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "sweep.sh: JOBS is a count of parallel shards, not '$jobs'" >&2; exit 2; }
sweep=(python3 "$root/scripts/sweep.py" "$bin" "$root")
mkdir -p "$results"
total=$("${sweep[@]}" --list "${filters[@]}")  # (a bad option stops here, the last results kept)
((total > 0)) || { echo "sweep.sh: no run matches ${filters[*]}" >&2; exit 2; }
rm -rf "$results/shards" "$results/sweep.csv"
"${sweep[@]}" --plan "$results" --shards "$jobs" "${filters[@]}" >/dev/null
export SWEEP_ROOT=$root SWEEP_BIN=$bin SWEEP_JOBS=$jobs SWEEP_RESULTS=$results
SECONDS=0  # (each pass's time, printed at the end)
seq 0 $((jobs - 1)) | xargs -P "$jobs" -I{} sh -c \
  'exec python3 "$SWEEP_ROOT/scripts/sweep.py" "$SWEEP_BIN" "$SWEEP_ROOT" --shard {}/$SWEEP_JOBS --results "$SWEEP_RESULTS" "$@"' \
  sh "${filters[@]}" &
runs=$!
# One progress bar for all shards, from the runs each has done so far (only on a terminal).
while [[ -t 2 ]] && kill -0 $runs 2>/dev/null; do
  done_rows=$(( $(cat "$results"/shards/*.progress 2>/dev/null | wc -l) +
                $(cat "$results"/shards/*.csv 2>/dev/null | grep -c '^[0-9]' || true) ))
  filled=$((30 * done_rows / total))
  printf '\rsweep [%-30s] %d/%d' "$(printf '%*s' $filled '' | tr ' ' '#')" "$done_rows" "$total" >&2
  sleep 0.5
done
[[ -t 2 ]] && printf '\r%60s\r' '' >&2
wait $runs || { echo "sweep.sh: a shard failed (its message is above): nothing merged" >&2; exit 1; }
rm -f "$results"/shards/*.progress
# The shards' wall times come from runs sharing the cores with each other: the merge
# times every run again, one at a time (error, cycles and operations do not change).
error_pass=$SECONDS
"${sweep[@]}" --merge "$results" --repeats "$repeats" "${filters[@]}"
timing="the merge and timing pass, $repeats rounds one run at a time"
((repeats > 0)) || timing="the merge"
echo "$(($(wc -l <"$results/sweep.csv") - 1)) runs: $results/sweep.csv (the error pass, $jobs shards at a time:" \
  "$error_pass s; $timing: $((SECONDS - error_pass)) s)"
