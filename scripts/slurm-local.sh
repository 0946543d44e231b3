#!/usr/bin/env bash
# A single-node Slurm on localhost inside one private folder (docs/verification-at-scale.md, "A Slurm
# of one's own"): munged with its own key and socket, slurmctld and slurmd reading DIR/slurm.conf,
# every state, spool, log and pid file under DIR. Needs root (SlurmUser=root; slurmd starts jobs as
# their user); installs Debian's slurm-wlm and munge when missing.
#
#   scripts/slurm-local.sh start DIR   # prints `export SLURM_CONF=DIR/slurm.conf` once the node is idle
#   scripts/slurm-local.sh stop DIR
#
# Exit code 3: not root, or Slurm is not installed and cannot be (apt-get failed).
#
# Clients (sbatch, squeue, sinfo, scontrol) find the cluster through SLURM_CONF=DIR/slurm.conf, and
# munge's socket through the AuthInfo line of that file. Ports: SLURM_LOCAL_PORT (default 6817) for
# slurmctld and the next one for slurmd.
set -euo pipefail

usage() {
  echo "usage: $0 start|stop DIR" >&2
  exit 2
}
[ $# -eq 2 ] || usage
action=$1
if [ "$action" = start ]; then mkdir -p "$2"; fi
[ -d "$2" ] || exit 0 # stop: nothing was started there
dir=$(cd "$2" && pwd)
conf=$dir/slurm.conf
export SLURM_CONF=$conf

# The pid in pid file $1 if that process is still $2 (a stale file's pid may belong to another
# process by now).
daemon_pid() {
  [ -s "$1" ] || return 0
  local pid
  pid=$(cat "$1")
  if [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$2" ]; then echo "$pid"; fi
}

# Stops the three daemons together (each takes about 2 s to leave after SIGTERM), SIGKILL after 10 s.
stop() {
  local pids
  pids="$(daemon_pid "$dir/run/slurmd.pid" slurmd) $(daemon_pid "$dir/run/slurmctld.pid" slurmctld) \
    $(daemon_pid "$dir/munge/munged.pid" munged)"
  for pid in $pids; do kill "$pid" 2>/dev/null || true; done
  for pid in $pids; do
    for _ in $(seq 100); do
      kill -0 "$pid" 2>/dev/null || continue 2
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
  done
  rm -f "$dir/run/slurmd.pid" "$dir/run/slurmctld.pid" "$dir/munge/munged.pid"
}

install() {
  command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v sbatch >/dev/null \
    && command -v munged >/dev/null && return 0
  [ "$(id -u)" -eq 0 ] || { echo "$0: slurm-wlm and munge are missing and only root installs them" >&2; exit 3; }
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y -q --no-install-recommends -o DPkg::Lock::Timeout=900 slurm-wlm munge \
    || { apt-get -q update && apt-get install -y -q --no-install-recommends slurm-wlm munge; } \
    || { echo "$0: cannot install slurm-wlm and munge" >&2; exit 3; }
}

# munged with its own key, socket, pid, seed and log (no systemd: started by hand, forks itself).
start_munge() {
  mkdir -p "$dir/munge"
  # Every user must reach the socket: the folder is 755 (munged refuses 700).
  chmod 755 "$dir/munge"
  [ -s "$dir/munge/munge.key" ] || mungekey --create --keyfile="$dir/munge/munge.key"
  chmod 600 "$dir/munge/munge.key"
  munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/munged.seed" \
    --log-file="$dir/munge/munged.log"
}

# slurm.conf: this machine's CPUs and memory as `slurmd -C` reports them, one partition.
write_conf() {
  local port=${SLURM_LOCAL_PORT:-6817}
  local node
  node=$(slurmd -C | head -1 | sed -e 's/^NodeName=[^ ]* //')
  mkdir -p "$dir/state" "$dir/spool" "$dir/log" "$dir/run"
  cat >"$conf" <<EOF
# Written by scripts/slurm-local.sh: a single-node Slurm on localhost, everything under $dir.
ClusterName=local
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
# No cgroups in a container: processes tracked through /proc, tasks not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
# No mail server: the default MailProg (/bin/mail) is missing.
MailProg=/bin/true
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
# Finished jobs stay in slurmctld's memory (scontrol show job) for 10 min.
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 $node State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "$0: needs root (SlurmUser=root: slurmd starts jobs as their user)" >&2; exit 3; }
  install
  stop
  start_munge
  write_conf
  slurmctld -f "$conf" -c
  slurmd -f "$conf" -N localhost
  for _ in $(seq 300); do
    if [ "$(sinfo -h -N -o %t 2>/dev/null)" = idle ]; then
      echo "export SLURM_CONF=$conf"
      return 0
    fi
    sleep 0.1
  done
  echo "$0: the node did not become idle within 30 s; sinfo says:" >&2
  sinfo -N >&2 || true
  tail -n 30 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" "$dir/munge/munged.log" >&2 || true
  stop
  exit 1
}

case $action in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
