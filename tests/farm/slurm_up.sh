#!/usr/bin/env bash
# Starts a throw-away single-node Slurm cluster on localhost (2 CPUs) for the farm tests.
#
#   eval "$(tests/farm/slurm_up.sh DIR)"     # prints `export SLURM_CONF=...`; DIR holds all state
#   tests/farm/slurm_down.sh DIR             # stops the daemons started here, by their pid files
#
# Everything lives under DIR: the munge key and socket, slurm.conf, state, spool and logs, so
# nothing on the machine is touched and the daemons of another run cannot be reached by mistake.
# Runs as root (SlurmUser=root); no cgroups (proctrack/linuxproc, task/none) so it works in
# containers. Ports default to 16817/16818 (override with ILLUME_SLURM_PORT_BASE).
set -euo pipefail

dir=${1:?usage: slurm_up.sh STATE_DIR}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
base=${ILLUME_SLURM_PORT_BASE:-16817}
cpus=${ILLUME_SLURM_CPUS:-2}
for tool in munged mungekey slurmctld slurmd sbatch; do
  command -v "$tool" >/dev/null 2>&1 || { echo "slurm_up: $tool not found (apt-get install slurm-wlm munge)" >&2; exit 2; }
done

# munge: its own key, socket and logs. munged refuses group/world-writable paths.
mkdir -p "$dir/munge" "$dir/ctld" "$dir/spool"
chmod 700 "$dir/munge"
[ -f "$dir/munge/munge.key" ] || mungekey --create --keyfile="$dir/munge/munge.key" >/dev/null 2>&1 \
  || dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$dir/munge/munge.key"
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
  --seed-file="$dir/munge/munged.seed"

cat >"$dir/slurm.conf" <<CONF
ClusterName=illume
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# cred_expire is also how long a requeued job waits before it may start again (default 120 s).
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
SlurmctldPort=$base
SlurmdPort=$((base + 1))
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
JobRequeue=1
MinJobAge=600
MaxArraySize=1001
# Look at pending jobs every second (default 60 s; 1 s is the least), so requeued tasks restart
# and jobs whose dependencies completed start promptly; schedule a submitted batch job at once
# (batch_sched_delay=0) with no rate limit: submit to running ≈ 0.7 s instead of ≈ 1.9 s
# (tests/farm/overhead.sh).
SchedulerParameters=sched_interval=1,sched_min_interval=0,batch_sched_delay=0
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"

slurmctld -i -f "$SLURM_CONF"
slurmd -N localhost -f "$SLURM_CONF"

# Wait until the node takes jobs (idle), at most 30 s.
for _ in $(seq 60); do
  state=$(sinfo -h -n localhost -o %t 2>/dev/null || true)
  case "$state" in
    idle*|mix*|alloc*) echo "export SLURM_CONF=$SLURM_CONF"; exit 0 ;;
  esac
  sleep 0.5
done
echo "slurm_up: node never became idle (state '${state:-?}'); logs in $dir:" >&2
tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" "$dir/munge/munged.log" >&2 2>/dev/null || true
exit 1
