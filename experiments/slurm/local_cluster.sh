#!/bin/bash
# A private single-node Slurm cluster on this machine, for trying sweep_array.sh for real: munged, slurmctld
# and slurmd (Debian 12's munge, slurmctld, slurmd and slurm-client packages), started without systemd,
# with their configuration, key, sockets, state and logs in DIR and their own ports, so nothing of the
# system's (an /etc/slurm, a running munged) is read or touched. Run as root: slurmd starts jobs as their
# submitting user.
#
#   experiments/slurm/local_cluster.sh start DIR    # then: export SLURM_CONF=DIR/slurm.conf; sbatch ...
#   experiments/slurm/local_cluster.sh stop DIR
#
# Exit status of start: 0 when the node is idle and takes jobs; 77 when this machine cannot run the
# daemons (packages missing, not root), with the reason on stderr; 1 when they were started and failed.
set -euo pipefail
action=${1:?usage: local_cluster.sh start|stop DIR}
dir=$(realpath -m "${2:?usage: local_cluster.sh start|stop DIR}")

stop() {
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [ -f "$pidfile" ] && kill "$(cat "$pidfile")" 2>/dev/null || true
  done
  sleep 1
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [ -f "$pidfile" ] && kill -9 "$(cat "$pidfile")" 2>/dev/null || true
    rm -f "$pidfile"
  done
}

if [ "$action" = stop ]; then
  stop
  exit 0
fi
[ "$action" = start ] || { echo "local_cluster.sh: unknown action '$action' (start or stop)" >&2; exit 2; }

for program in munged slurmctld slurmd sbatch sinfo; do
  command -v "$program" >/dev/null || {
    echo "local_cluster.sh: $program is not installed (Debian: apt install munge slurmctld slurmd slurm-client)" >&2
    exit 77
  }
done
[ "$(id -u)" = 0 ] || { echo "local_cluster.sh: slurmd must run as root to start jobs" >&2; exit 77; }

mkdir -p "$dir/state" "$dir/spool" "$dir/log"
chmod 700 "$dir"
node=$(hostname -s)
cpus=$(nproc)
memory_mb=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))
# Ports from the directory's name, so two clusters (two test runs) on one machine do not collide.
port=$(( 20000 + $(printf '%s' "$dir" | cksum | cut -d' ' -f1) % 20000 ))

# munged insists on a key only its user can read and on a socket directory of its own.
dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge.key"
cat > "$dir/slurm.conf" <<EOF
ClusterName=arbor-local
SlurmctldHost=$node
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$node CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$dir/slurm.conf

trap 'stop; echo "local_cluster.sh: the daemons did not come up; logs in $dir/log" >&2; exit 1' ERR
munged --force --socket="$dir/munge.socket" --key-file="$dir/munge.key" --pid-file="$dir/munged.pid" \
  --log-file="$dir/log/munged.log" --seed-file="$dir/munged.seed"
slurmctld -f "$SLURM_CONF" -i
slurmd -f "$SLURM_CONF"
# The node is ready when sinfo shows it idle (a minute at most).
for _ in $(seq 60); do
  state=$(sinfo --noheader --format=%t 2>/dev/null || true)
  [ "$state" = idle ] && exit 0
  sleep 1
done
echo "local_cluster.sh: the node did not become idle (sinfo: '${state:-no answer}')" >&2
false
