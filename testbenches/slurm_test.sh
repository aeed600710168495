#!/usr/bin/env bash
# The sweep and the regression through a real Slurm (docs/benchmarks.md, "On a cluster"):
# a single-node Slurm started here (scripts/slurm-local.sh), a small sweep and a small
# regression submitted as job arrays, their merged results equal to a local run's but for
# wall times; a lost shard refused by the merge, then found and run again by resubmit;
# no Slurm, no controller, and results folders that cannot be written or are not shared
# refused with exit 2 and nothing submitted.
# Usage: slurm_test.sh SHADETLM ROOT
set -uo pipefail
bin=$(realpath "$1") root=$(realpath "$2")
tmp=$(mktemp -d)
slurm=("$root/scripts/slurm.py")
cleanup() {
  for d in "$tmp"/cluster*; do [[ -f $d/slurm.conf ]] && "$root/scripts/slurm-local.sh" stop "$d"; done
  rm -rf "$tmp"
}
trap cleanup EXIT
failures=0
problem() { echo "FAIL: $*"; ((failures++)); }

# Skipped (77) without slurm-wlm's daemons: scripts/test.sh installs them, and CI runs it.
for daemon in munged slurmctld slurmd; do
  [[ -x /usr/sbin/$daemon ]] || { echo "skipped: /usr/sbin/$daemon not installed (scripts/test.sh installs it)"; exit 77; }
done
# Two CPUs, whatever this machine has: the shard count below follows from them.
conf=$("$root/scripts/slurm-local.sh" start "$tmp/cluster" 2) || { echo "FAIL: Slurm did not start"; exit 1; }
eval "$conf"
export SHADETLM=$bin SHADETLM_MAP_CACHE=$tmp/maps
# A few runs of two families (the parallax ones read the map cache), small frames.
filters=(--match '^normal golden/sphere\S* .*mode=(exact|rsqrt1);|^parallax .*max_iterations=16;' --resolution 96,72)

# same_rows A B: two sweep CSVs hold the same rows, wall times aside.
same_rows() {
  python3 - "$1" "$2" <<'PY'
import csv, sys
def rows(path):
    with open(path) as f:
        return [{k: v for k, v in r.items() if not k.startswith("wall_")} for r in csv.DictReader(f)]
a, b = rows(sys.argv[1]), rows(sys.argv[2])
sys.exit(0 if a == b and a else 1)
PY
}

# --- 1. The sweep: locally (2 shards, xargs) and through Slurm (shards chosen by the script).
"$root/scripts/sweep.sh" --no-build --repeats 0 --results "$tmp/local-sweep" "${filters[@]}" 2 >/dev/null ||
  problem "the local sweep failed"
"${slurm[@]}" submit sweep "$tmp/sweep" "${filters[@]}" --wait >"$tmp/out" 2>&1 ||
  { problem "the Slurm sweep failed: $(tail -3 "$tmp/out")"; cat "$tmp"/sweep/logs/* 2>/dev/null | tail -5; }
runs=$(($(wc -l <"$tmp/local-sweep/sweep.csv") - 1))
((runs >= 6)) || problem "the local sweep has $runs rows, expected at least 6"
same_rows "$tmp/local-sweep/sweep.csv" "$tmp/sweep/sweep.csv" || problem "the Slurm sweep's rows differ from the local run's"
shards=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["shards"])' "$tmp/sweep/manifest.json")
# 2 CPUs, 4 shards per CPU, at most one per run.
((shards == (runs < 8 ? runs : 8))) || problem "$shards shards for $runs runs on 2 CPUs, expected $((runs < 8 ? runs : 8))"
ls "$tmp"/maps/*.exr >/dev/null 2>&1 || problem "no map in the map cache"

# --- 2. A lost shard: the merge refuses (exit 2, nothing written), resubmit runs it again.
# (merge.status stays from the first merge: resubmit must not take it for the new one's)
rm "$tmp/sweep/shards/sweep-1-of-$shards.csv" "$tmp/sweep/sweep.csv"
"${slurm[@]}" merge "$tmp/sweep" >"$tmp/out" 2>&1
rc=$?
((rc == 2)) || problem "merge with a shard missing: exit $rc, expected 2"
grep -q "1 of $shards shards missing (1)" "$tmp/out" || problem "merge does not name the missing shard: $(cat "$tmp/out")"
[[ ! -e $tmp/sweep/sweep.csv ]] || problem "merge with a shard missing wrote sweep.csv"
"${slurm[@]}" resubmit "$tmp/sweep" --wait >"$tmp/out" 2>&1 || problem "resubmit failed: $(tail -3 "$tmp/out")"
grep -q "submitted 1 shard as job .* (array 1)" "$tmp/out" || problem "resubmit did not run shard 1 alone: $(cat "$tmp/out")"
same_rows "$tmp/local-sweep/sweep.csv" "$tmp/sweep/sweep.csv" || problem "the resubmitted sweep's rows differ"
"${slurm[@]}" status "$tmp/sweep" >"$tmp/out" 2>&1
grep -q "$shards done, 0 missing" "$tmp/out" || problem "status does not show every shard done: $(cat "$tmp/out")"

# --- 3. The regression of one scene: locally and through Slurm, the same rows.
python3 "$root/scripts/regress.py" "$bin" "$root" "$tmp/local-regress" --scene sphere 2>/dev/null
local_rc=$?
"${slurm[@]}" submit regress "$tmp/regress" --scene sphere --wait >"$tmp/out" 2>&1
rc=$?
((rc == local_rc)) || problem "the Slurm regression exits $rc, the local one $local_rc: $(tail -3 "$tmp/out")"
[[ -s $tmp/regress/index.html ]] || problem "the Slurm regression wrote no report"
python3 - "$tmp/local-regress" "$tmp/regress" <<'PY' || problem "the Slurm regression's rows differ from the local run's"
import json, sys
def rows(folder):
    with open(folder + "/rows.json") as f:
        return json.loads(f.read().replace(folder, "RESULTS"))
sys.exit(0 if rows(sys.argv[1]) == rows(sys.argv[2]) and rows(sys.argv[1]) else 1)
PY

# --- 4. Refused, exit 2, nothing submitted.
refused() {  # refused NAME EXPECTED-TEXT COMMAND...: exit 2, the text on stderr
  local name=$1 text=$2 rc
  shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"
  rc=$?
  ((rc == 2)) || problem "$name: exit $rc, expected 2"
  grep -q -- "$text" "$tmp/err" || problem "$name: stderr lacks '$text': $(cat "$tmp/err")"
}
# python3 itself (not a wrapper script that needs a shell from the PATH), and no Slurm.
mkdir -p "$tmp/nopath" && ln -s "$(python3 -c 'import sys; print(sys.executable)')" "$tmp/nopath/python3"
refused "no Slurm" "no Slurm on this machine" env PATH="$tmp/nopath" python3 "${slurm[@]}" submit sweep "$tmp/r1"
sed 's/^SlurmctldPort=.*/SlurmctldPort=1/' "$SLURM_CONF" >"$tmp/unreachable.conf"
refused "no controller" "controller does not answer" env SLURM_CONF="$tmp/unreachable.conf" "${slurm[@]}" submit sweep "$tmp/r2"
: >"$tmp/a-file"
refused "results under a file" "cannot be made" "${slurm[@]}" submit sweep "$tmp/a-file/results"
refused "results taken" "already holds a submission" "${slurm[@]}" submit sweep "$tmp/sweep"
# Two nodes, the results on this machine's own filesystem: the other node would not see them.
conf=$("$root/scripts/slurm-local.sh" start "$tmp/cluster2" 1 2) && eval "$conf" || problem "the two-node Slurm did not start"
refused "results not shared" "local to this machine, and the partition has 2 nodes" "${slurm[@]}" submit sweep "$tmp/r3"
[[ -z $(squeue -h) ]] || problem "a refused submission queued jobs: $(squeue -h)"
for r in r1 r2 r3; do [[ ! -e $tmp/$r/manifest.json ]] || problem "a refused submission wrote $r/manifest.json"; done

echo "slurm: $runs sweep runs in $shards shards, one scene's regression; $failures failures"
((failures == 0))
