#!/usr/bin/env bash
# Starts a single-node Slurm on this machine for the farm tests (crates/cli/tests/slurm.rs):
# installs Debian's slurm-wlm and munge with apt-get if they are missing, writes a slurm.conf
# for one node on localhost, and starts munged, slurmctld and slurmd directly (a container
# has no systemd). Idempotent: installed packages are not reinstalled, a running daemon is
# not restarted, and it ends as soon as `sinfo` shows the node idle.
#
# Runs as root (or with sudo). Environment: REYES_SLURM_CPUS overrides the node's CPU count.
set -euo pipefail

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

if ! command -v sbatch >/dev/null || ! command -v slurmctld >/dev/null \
  || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq slurm-wlm munge >/dev/null
fi

conf_dir=/etc/slurm
host=$(hostname -s)
cpus=${REYES_SLURM_CPUS:-$(nproc)}
mem=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)

# munge: a key, its directories, the daemon.
if [ ! -s /etc/munge/munge.key ]; then
  $sudo mkdir -p /etc/munge
  $sudo dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
fi
$sudo mkdir -p /run/munge /var/lib/munge /var/log/munge
$sudo chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge
$sudo chmod 0700 /etc/munge /var/lib/munge /var/log/munge
$sudo chmod 0755 /run/munge
$sudo chmod 0400 /etc/munge/munge.key
if ! munge -n >/dev/null 2>&1; then
  $sudo runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do munge -n >/dev/null 2>&1 && break; sleep 0.1; done
  munge -n >/dev/null || { echo "slurm-up: munged did not start" >&2; exit 1; }
fi

# slurm.conf: one node, one partition, no accounting daemon, no cgroups.
want=$(cat <<CONF
# Written by tools/slurm/up.sh (reyes-render's farm tests): one node on this machine.
ClusterName=reyes
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=3600
SlurmdTimeout=300
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
)
$sudo mkdir -p "$conf_dir" /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
if [ ! -f "$conf_dir/slurm.conf" ] || [ "$(cat "$conf_dir/slurm.conf")" != "$want" ]; then
  printf '%s\n' "$want" | $sudo tee "$conf_dir/slurm.conf" >/dev/null
  # A running controller reads the new configuration.
  if scontrol ping >/dev/null 2>&1; then $sudo scontrol reconfigure || true; fi
fi

running() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }
running /run/slurmctld.pid || $sudo slurmctld
running /run/slurmd.pid || $sudo slurmd

for _ in $(seq 100); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  case "$state" in
    idle*|mixed*|allocated*) echo "slurm-up: node $host $state"; exit 0 ;;
    down*|drain*) $sudo scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true ;;
  esac
  sleep 0.2
done
echo "slurm-up: the node did not come up (sinfo: ${state:-no answer}); see /var/log/slurm/" >&2
exit 1
