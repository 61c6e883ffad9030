# shellcheck shell=bash
# A throwaway single-node Slurm for tests, sourced by bash test scripts: munged, slurmctld and
# slurmd from the Debian packages (slurm-wlm, munge), listening on 127.0.0.1 only, with every
# file (key, sockets, state, spool, logs, slurm.conf) in one temporary folder.
#
#   source tests/cluster/slurm_local.sh
#   slurm_start "$dir"      # exports SLURM_CONF; fails (exit 1) naming what did not come up
#   sbatch ...; squeue ...
#   slurm_stop              # also run from an EXIT trap, so daemons never outlive the test
#
# The daemons run as the current user (SlurmUser = SlurmdUser), so jobs run as that user too; the
# node has the machine's CPUs and memory so that jobs with no resource options can start.

slurm_pids=()
slurm_dir=""

slurm_fail() {
  echo "slurm_local: error: $*" >&2
  for log in "$slurm_dir"/{munged,slurmctld,slurmd}.{out,log}; do
    [[ -f $log ]] && { echo "--- last lines of $log" >&2; tail -n 15 "$log" >&2; }
  done
  return 1
}

# A TCP port on 127.0.0.1 that nothing listens on, from a range unlikely to be in use.
slurm_free_port() {
  local port
  for ((try = 0; try < 200; ++try)); do
    port=$((20000 + (RANDOM % 20000)))
    if ! (echo >"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
      echo "$port"
      return 0
    fi
  done
  return 1
}

slurm_write_conf() {
  local dir=$1 user cpus memory ctld_port slurmd_port
  user=$(id -un)
  cpus=$(nproc)
  memory=$(awk '/^MemTotal:/ { print int($2 / 1024 / 2) }' /proc/meminfo)
  ctld_port=$(slurm_free_port) && slurmd_port=$(slurm_free_port) || return 1
  cat >"$dir/slurm.conf" <<EOF
ClusterName=corsatest
SlurmctldHost=$(hostname -s)(127.0.0.1)
MailProg=/bin/true
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$dir/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
ReturnToService=2
SchedulerParameters=sched_interval=1,bf_interval=1
MinJobAge=600
KillWait=2
NodeName=corsa-node NodeAddr=127.0.0.1 NodeHostname=$(hostname) CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=corsa-node Default=YES MaxTime=INFINITE State=UP
EOF
}

# Waits up to $2 seconds for command $1 (a string run by bash) to succeed.
slurm_wait_for() {
  local command=$1 seconds=$2 start=$SECONDS
  until eval "$command" >/dev/null 2>&1; do
    ((SECONDS - start < seconds)) || return 1
    slurm_daemons_alive || return 1
    sleep 0.2
  done
}

# Whether every daemon started so far still runs.
slurm_daemons_alive() {
  local pid
  for pid in "${slurm_pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || return 1
  done
}

slurm_start() {
  slurm_dir=$1
  local missing=()
  for program in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
    command -v "$program" >/dev/null || missing+=("$program")
  done
  ((${#missing[@]} == 0)) ||
    slurm_fail "not installed: ${missing[*]} (Debian packages slurm-wlm and munge; scripts/setup installs them)" ||
    return 1
  mkdir -p "$slurm_dir/state" "$slurm_dir/spool"
  chmod 711 "$slurm_dir"  # munged wants its socket folder searchable by all
  slurm_write_conf "$slurm_dir" || slurm_fail "no free TCP port on 127.0.0.1" || return 1
  export SLURM_CONF=$slurm_dir/slurm.conf

  mungekey -c -k "$slurm_dir/munge.key" || slurm_fail "mungekey could not create a key" || return 1
  munged --foreground --force --socket="$slurm_dir/munge.socket" --key-file="$slurm_dir/munge.key" \
    --pid-file="$slurm_dir/munged.pid" --log-file="$slurm_dir/munged.log" \
    --seed-file="$slurm_dir/munged.seed" >"$slurm_dir/munged.out" 2>&1 &
  slurm_pids+=($!)
  slurm_wait_for "[[ -S '$slurm_dir/munge.socket' ]]" 10 ||
    slurm_fail "munged did not start" || return 1

  slurmctld -D -i -f "$SLURM_CONF" >"$slurm_dir/slurmctld.out" 2>&1 &
  slurm_pids+=($!)
  slurmd -D -N corsa-node -f "$SLURM_CONF" >"$slurm_dir/slurmd.out" 2>&1 &
  slurm_pids+=($!)
  slurm_wait_for "sinfo -h -N -o %T | grep -Eq '^(idle|mixed|allocated)'" 40 ||
    slurm_fail "the node did not become idle: $(sinfo -h -N -o '%T %E' 2>&1)" || return 1
}

slurm_stop() {
  local pid
  if [[ -n ${SLURM_CONF:-} && -f ${SLURM_CONF:-} ]]; then
    scancel --quiet --user="$(id -un)" 2>/dev/null || true
  fi
  # Daemons in reverse order of start, each by its own PID.
  for ((i = ${#slurm_pids[@]} - 1; i >= 0; --i)); do
    pid=${slurm_pids[i]}
    kill "$pid" 2>/dev/null || continue
    for ((t = 0; t < 50; ++t)); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  slurm_pids=()
}
