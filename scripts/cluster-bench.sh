#!/usr/bin/env bash
# Sweep throughput here and through Slurm (docs/benchmarks.md, "On a cluster"), all
# measured in one run of this script:
#  1. the same runs (the sweep's error pass) with 1 shard at a time and with 2 (xargs -P):
#     runs per second and their ratio;
#  2. the same through a single-node Slurm started here (scripts/slurm-local.sh), the
#     array throttled to 1 task at a time and to 2, from submission to merged CSV;
#     1 and 2 in rounds, the best of each;
#  3. the scheduler's overhead per shard: an array of empty tasks, one at a time;
#  4. the merge's time against the number of shards: the rows of step 1 cut into 1 to
#     512 shard files and merged.
# Usage: scripts/cluster-bench.sh [--match REGEX]   (default: every run of the sweep)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
match=''
if (($#)); then
  [[ $1 == --match && $# == 2 ]] || { echo "usage: scripts/cluster-bench.sh [--match REGEX]" >&2; exit 2; }
  match=$2
fi
"$root/scripts/setup.sh" slurmctld slurmd slurm-client munge
"$root/scripts/build.sh" >/dev/null
export SHADETLM=$root/build/app/shadetlm
tmp=$(mktemp -d)
cleanup() { [[ -f $tmp/cluster/slurm.conf ]] && "$root/scripts/slurm-local.sh" stop "$tmp/cluster"; rm -rf "$tmp"; }
trap cleanup EXIT
now() { date +%s.%N; }
ratio() { python3 -c "import sys; print('%.3g' % (float(sys.argv[1]) / float(sys.argv[2])))" "$@"; }
filters=(--match "$match")
runs=$(python3 "$root/scripts/sweep.py" "$SHADETLM" "$root" --list "${filters[@]}")

# 1, 2. Local and Slurm, 1 and 2 at a time, in rounds that take each in turn (this
# machine's speed drifts by tens of per cent over minutes: a configuration measured only
# after the others would carry the drift); each one's best round is taken. One warm-up
# pass first (page cache, map cache). Locally: scripts/sweep.sh --repeats 0 (the error
# pass and the merge); through Slurm: submit --wait, the shards the script chooses.
"$root/scripts/sweep.sh" --no-build --repeats 0 --results "$tmp/warm" "${filters[@]}" 2 >/dev/null
conf=$("$root/scripts/slurm-local.sh" start "$tmp/cluster" 2) || exit 1
eval "$conf"
declare -A best samples
run() {  # run WHERE JOBS ROUND: one sweep, its time into best[WHERE JOBS] and samples
  local start seconds
  start=$(now)
  if [[ $1 == local ]]; then
    "$root/scripts/sweep.sh" --no-build --repeats 0 --results "$tmp/local-$2-$3" "${filters[@]}" "$2" >/dev/null
  else
    python3 "$root/scripts/slurm.py" submit sweep "$tmp/slurm-$2-$3" "${filters[@]}" --max-parallel "$2" --wait >/dev/null
  fi
  seconds=$(python3 -c "print('%.1f' % ($(now) - $start))")
  samples[$1 $2]+=" $seconds"
  if [[ -z ${best[$1 $2]:-} ]] || python3 -c "import sys; sys.exit(not $seconds < ${best[$1 $2]})"; then
    best[$1 $2]=$seconds
  fi
}
rounds=2
for round in $(seq $rounds); do
  for where in local slurm; do for jobs in 1 2; do run $where $jobs "$round"; done; done
done
shards=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["shards"])' "$tmp/slurm-1-1/manifest.json")
for where in local slurm; do
  what=$([[ $where == local ]] && echo "local, $runs runs" || echo "Slurm, $runs runs in $shards shards")
  echo "$what: 1 at a time ${best[$where 1]} s ($(ratio "$runs" "${best[$where 1]}") runs/s), 2 at a time" \
    "${best[$where 2]} s ($(ratio "$runs" "${best[$where 2]}") runs/s): throughput x$(ratio "${best[$where 1]}" "${best[$where 2]}")" \
    "(goal >= 1.8; best of $rounds rounds: 1 at a time${samples[$where 1]} s, 2 at a time${samples[$where 2]} s)"
done
echo "Slurm against local, 2 at a time: ${best[slurm 2]} s / ${best[local 2]} s = $(ratio "${best[slurm 2]}" "${best[local 2]}")"

# 3. The scheduler's own cost: K empty tasks, one at a time, submission to the last one's end.
tasks=16
start=$(now)
job=$(sbatch --parsable --array="0-$((tasks - 1))%1" --output=/dev/null --wrap=true)
while [[ -n $(squeue -h -j "$job") ]]; do sleep 0.2; done
empty_s=$(python3 -c "print($(now) - $start)")
echo "scheduler overhead: $tasks empty tasks one at a time in $(printf %.1f "$empty_s") s: $(ratio "$empty_s" "$tasks") s per shard"

# 4. The merge against the number of shards: the local rows cut into N shard files.
rows=$tmp/local-1-1/sweep.csv
line="merge (--repeats 0) of $runs rows:"
for n in 1 8 64 512; do
  dir=$tmp/merge-$n
  mkdir -p "$dir/shards"
  python3 - "$rows" "$dir" "$n" <<'PY'
import csv, json, sys
rows, folder, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
with open(rows) as f:
    reader = csv.reader(f)
    header, body = next(reader), list(reader)
for i in range(n):
    with open("%s/shards/sweep-%d-of-%d.csv" % (folder, i, n), "w") as f:
        csv.writer(f).writerows([header] + body[i::n])
json.dump({"kind": "sweep", "shards": n, "args": []}, open(folder + "/manifest.json", "w"))
PY
  start=$(now)
  python3 "$root/scripts/sweep.py" "$SHADETLM" "$root" --merge "$dir" --repeats 0
  line+=" $n shards $(python3 -c "print('%.3f' % ($(now) - $start))") s,"
  cmp -s <(sort "$rows") <(sort "$dir/sweep.csv") || { echo "the merge of $n shards changed the rows" >&2; exit 1; }
done
echo "${line%,}"
