# Sourced by the Slurm tests: start_cluster DIR starts munge, slurmctld and slurmd as a one-node
# cluster of this machine's CPUs with everything in DIR (its key, sockets, ports, state, spool, pid
# files and logs); stop_cluster stops exactly the daemons it started, by their pids. The clients
# (sbatch, srun, sinfo, scontrol) find it through SLURM_CONF, which start_cluster exports.

cluster_pids=()

# start_cluster DIR: returns 1 (with the logs' last lines on stdout) when the node is not idle
# within 60 s.
start_cluster() {
  local dir=$1 ports node host
  for program in munged slurmctld slurmd sbatch; do
    command -v "$program" >/dev/null || { echo "no $program: run scripts/setup.sh (slurm-wlm, munge)"; return 1; }
  done
  mkdir -p "$dir/munge" "$dir/socket" "$dir/state" "$dir/spool"
  # munged refuses a key, seed or log that others may read and a socket folder they cannot search.
  chmod 711 "$dir"
  chmod 700 "$dir/munge"
  chmod 755 "$dir/socket"
  head -c 1024 /dev/urandom >"$dir/munge/munge.key"
  chmod 400 "$dir/munge/munge.key"
  munged --foreground --key-file="$dir/munge/munge.key" --socket="$dir/socket/munge.sock" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" \
    >"$dir/munged.out" 2>&1 &
  cluster_pids+=($!)
  # Two free ports of this machine's, for slurmctld and slurmd.
  ports=$(/usr/bin/python3 -c 'import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
  set -- $ports
  host=$(hostname -s)
  node=$(slurmd -C | head -1)  # NodeName=HOST CPUs=... RealMemory=...: this machine as it is
  local user
  user=$(id -un)
  cat >"$dir/slurm.conf" <<CONF
# A one-node cluster of this machine for the tests (tests/slurm/one_node_cluster.sh).
ClusterName=workbench-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$1
SlurmdPort=$2
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/socket/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
# No cgroups (a container): processes tracked through /proc, tasks not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# Slurm's default: the profile asks for PMIx itself (srun --mpi=pmix).
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  for _ in $(seq 100); do [ -S "$dir/socket/munge.sock" ] && break; sleep 0.1; done
  slurmctld -D -f "$SLURM_CONF" >"$dir/slurmctld.out" 2>&1 &
  cluster_pids+=($!)
  slurmd -D -f "$SLURM_CONF" >"$dir/slurmd.out" 2>&1 &
  cluster_pids+=($!)
  for _ in $(seq 600); do
    [ "$(sinfo -h -N -o %T 2>/dev/null)" = idle ] && return 0
    sleep 0.1
  done
  tail -n 3 "$dir/munged.out" "$dir/slurmctld.log" "$dir/slurmd.log" 2>&1
  return 1
}

# stop_cluster: SIGTERM to each daemon started here (slurmd first), waited for; SIGKILL after 10 s.
stop_cluster() {
  local i pid
  for ((i = ${#cluster_pids[@]} - 1; i >= 0; i--)); do
    pid=${cluster_pids[i]}
    kill -TERM "$pid" 2>/dev/null || continue
    for _ in $(seq 100); do
      [ "$(cut -d' ' -f3 "/proc/$pid/stat" 2>/dev/null)" = Z ] || [ ! -e "/proc/$pid" ] && break  # ended (a zombie until waited for)
      sleep 0.1
    done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
  done
  cluster_pids=()
}
