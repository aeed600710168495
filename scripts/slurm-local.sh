#!/usr/bin/env bash
# A single-node Slurm on this machine, for testing what the project submits to a cluster
# (testbenches/slurm_test.sh, scripts/cluster-bench.sh): munged, slurmctld and slurmd
# from Debian's slurm-wlm packages (scripts/setup.sh installs them), configured and run
# entirely inside DIR on localhost, on free ports; nothing under /etc is used or changed.
#
#   scripts/slurm-local.sh start DIR [CPUS [NODES]]
#       starts it (CPUS: the node's, default nproc), waits until the node is idle, and
#       prints the line to use it: export SLURM_CONF=DIR/slurm.conf. NODES > 1 declares
#       that many nodes but starts the first only (the others stay down): a partition
#       that looks like a cluster's, for the tests of what must be shared.
#   scripts/slurm-local.sh stop DIR           stops the daemons and removes DIR
set -euo pipefail
command=${1:-} dir=${2:-}
[[ ($command == start || $command == stop) && -n $dir ]] || { sed -n '2,12p' "$0" >&2; exit 2; }
sbin=/usr/sbin

stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    pid=$(cat "$dir/$name.pid" 2>/dev/null || true)
    [[ -n $pid ]] && kill "$pid" 2>/dev/null || true
  done
  for name in slurmd slurmctld munged; do  # at most 10 s each, then killed
    pid=$(cat "$dir/$name.pid" 2>/dev/null || true)
    for _ in $(seq 100); do [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    [[ -n $pid ]] && kill -KILL "$pid" 2>/dev/null || true
  done
  rm -rf "$dir"
}

if [[ $command == stop ]]; then
  [[ -f $dir/slurm.conf ]] || { echo "slurm-local.sh: $dir is not a folder this script started Slurm in" >&2; exit 2; }
  stop
  exit 0
fi

for daemon in munged slurmctld slurmd; do
  [[ -x $sbin/$daemon ]] || { echo "slurm-local.sh: $sbin/$daemon not found: scripts/setup.sh installs slurm-wlm's packages" >&2; exit 2; }
done
[[ -e $dir ]] && { echo "slurm-local.sh: $dir exists: give a new folder" >&2; exit 2; }
[[ $dir != *[[:space:]]* ]] || { echo "slurm-local.sh: '$dir': slurm.conf takes no paths with spaces" >&2; exit 2; }
cpus=${3:-$(nproc)} nodes=${4:-1}
[[ $cpus =~ ^[1-9][0-9]*$ && $nodes =~ ^[1-9][0-9]*$ ]] || { echo "slurm-local.sh: CPUS and NODES are counts" >&2; exit 2; }
mkdir -p "$dir"/{state,spool,log,munge}
dir=$(cd "$dir" && pwd)
chmod 700 "$dir" "$dir/munge"
trap 'echo "slurm-local.sh: Slurm did not start; the end of its logs:" >&2; tail -n 5 "$dir"/log/* >&2; stop' ERR

# munge: a key of our own, its socket in DIR (--force: munged refuses a socket folder
# under /tmp, which is world-writable, without it).
head -c 1024 /dev/urandom >"$dir/munge/munge.key"
chmod 400 "$dir/munge/munge.key"
$sbin/munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed"

# Two free ports on localhost, for the controller and the node.
read -r ctld_port node_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
node=shadetlm-node names=shadetlm-node
((nodes > 1)) && node=shadetlm-node1 names="shadetlm-node[1-$nodes]"
cat >"$dir/slurm.conf" <<CONF
# A single-node Slurm for shadetlm's tests (scripts/slurm-local.sh); everything in $dir.
ClusterName=shadetlm
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$dir/munge/socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MaxArraySize=1001
# The node as declared here, whatever slurmd finds (a 1-CPU machine still runs the tests).
SlurmdParameters=config_overrides
NodeName=$names NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
$sbin/slurmctld -f "$SLURM_CONF"
$sbin/slurmd -f "$SLURM_CONF" -N "$node"
for _ in $(seq 300); do  # up to 30 s for the node to register
  [[ $(sinfo -h -n "$node" -o %t 2>/dev/null) == idle ]] && break
  sleep 0.1
done
[[ $(sinfo -h -n "$node" -o %t 2>/dev/null) == idle ]] || false
trap - ERR
printf 'export SLURM_CONF=%q\n' "$SLURM_CONF"
