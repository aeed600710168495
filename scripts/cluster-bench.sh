#!/usr/bin/env bash
# Sweep throughput here and through Slurm (docs/benchmarks.md, "On a cluster"), all
# measured in one run of this script:
#  1. the same runs (the sweep's error pass) with 1 shard at a time and with 2 (xargs -P):
#     runs per second and their ratio;
#  2. the same through a single-node Slurm started here (scripts/slurm-local.sh), the
#     array throttled to 1 task at a time and to 2, from submission to merged CSV;
#  3. the scheduler's overhead per shard: an array of empty tasks, one at a time;
#  4. the merge's time against the number of shards: the rows of step 1 cut into 1 to
#     512 shard files and merged.
# Usage: scripts/cluster-bench.sh [--match REGEX]   (default: every run of the sweep)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
match=''
[[ ${1:-} == --match ]] && match=${2:?--match takes a regular expression}
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

# 1. Locally (scripts/sweep.sh --repeats 0: the error pass and the merge). One warm-up
# pass first (page cache, map cache).
"$root/scripts/sweep.sh" --no-build --repeats 0 --results "$tmp/warm" "${filters[@]}" 2 >/dev/null
declare -A local_s
for jobs in 1 2; do
  start=$(now)
  "$root/scripts/sweep.sh" --no-build --repeats 0 --results "$tmp/local-$jobs" "${filters[@]}" "$jobs" >/dev/null
  local_s[$jobs]=$(python3 -c "print($(now) - $start)")
done
echo "local, $runs runs: 1 shard at a time $(printf %.1f "${local_s[1]}") s ($(ratio "$runs" "${local_s[1]}") runs/s)," \
  "2 at a time $(printf %.1f "${local_s[2]}") s ($(ratio "$runs" "${local_s[2]}") runs/s): throughput x$(ratio "${local_s[1]}" "${local_s[2]}") (goal >= 1.8)"

# 2. Through Slurm, the shards the script chooses (4 per CPU), 1 and then 2 at a time.
conf=$("$root/scripts/slurm-local.sh" start "$tmp/cluster" 2) || exit 1
eval "$conf"
declare -A slurm_s
for jobs in 1 2; do
  start=$(now)
  python3 "$root/scripts/slurm.py" submit sweep "$tmp/slurm-$jobs" "${filters[@]}" --max-parallel "$jobs" --wait >/dev/null
  slurm_s[$jobs]=$(python3 -c "print($(now) - $start)")
done
shards=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["shards"])' "$tmp/slurm-1/manifest.json")
echo "Slurm, $runs runs in $shards shards: 1 task at a time $(printf %.1f "${slurm_s[1]}") s ($(ratio "$runs" "${slurm_s[1]}") runs/s)," \
  "2 at a time $(printf %.1f "${slurm_s[2]}") s ($(ratio "$runs" "${slurm_s[2]}") runs/s): throughput x$(ratio "${slurm_s[1]}" "${slurm_s[2]}") (goal >= 1.8)"
echo "Slurm against local, 2 at a time: $(printf %.1f "${slurm_s[2]}") s / $(printf %.1f "${local_s[2]}") s = $(ratio "${slurm_s[2]}" "${local_s[2]}")"

# 3. The scheduler's own cost: K empty tasks, one at a time, submission to the last one's end.
tasks=16
start=$(now)
job=$(sbatch --parsable --array="0-$((tasks - 1))%1" --output=/dev/null --wrap=true)
while [[ -n $(squeue -h -j "$job") ]]; do sleep 0.2; done
empty_s=$(python3 -c "print($(now) - $start)")
echo "scheduler overhead: $tasks empty tasks one at a time in $(printf %.1f "$empty_s") s: $(ratio "$empty_s" "$tasks") s per shard"

# 4. The merge against the number of shards: the local rows cut into N shard files.
rows=$tmp/local-1/sweep.csv
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
