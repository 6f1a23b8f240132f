# shellcheck shell=bash
# A throwaway Slurm cluster on this machine, for tests/farm/slurm_test.sh:
# munged, slurmctld and slurmd (Debian's munge and slurm-wlm) as root, one
# node (this host, `nproc` CPUs), everything (key, sockets, state, spool,
# pid and log files, slurm.conf) in one temporary folder, on free ports.
# Nothing of a system Slurm or munge is read or touched: the clients find
# this cluster through SLURM_CONF, slurm.conf names this munged's socket
# (AuthInfo=socket=...), and no daemon forks away from this shell.
#
#   source tests/farm/slurm_cluster.sh
#   cluster_start DIR        # DIR: an empty folder; exports SLURM_CONF
#   cluster_env              # prints VAR=VALUE for the jobs' marker (see below)
#   cluster_logs             # prints the daemons' logs
#   cluster_stop             # cancels the jobs, stops every daemon (idempotent)
#
# Every process the cluster starts carries STRATA_SLURM_TEST=DIR in its
# environment (the daemons directly, the jobs through `env "$(cluster_env)"
# sbatch ...`), so that cluster_stop can end any that outlives a daemon
# (a job's slurmstepd or a job's own processes) by its id.

CLUSTER_DIR=""
CLUSTER_PIDS=()

cluster_fail() { echo "slurm cluster: $*" >&2; return 1; }

# cluster_require: fails with a clear message when a package is missing.
cluster_require() {
  local missing=() c
  for c in munged mungekey munge unmunge slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
    command -v "$c" >/dev/null 2>&1 || missing+=("$c")
  done
  [ ${#missing[@]} -eq 0 ] ||
    cluster_fail "not installed: ${missing[*]} (Debian packages slurm-wlm and munge, in scripts/debian-packages.txt; make test installs them)" || return 1
  [ "$(id -u)" -eq 0 ] || cluster_fail "must run as root (slurmd starts jobs as their user)"
}

cluster_port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

# _cluster_wait SECONDS COMMAND...: runs COMMAND each 0.2 s until it succeeds.
_cluster_wait() {
  local end=$((SECONDS + $1)); shift
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $end ] || return 1
    sleep 0.2
  done
}

# _cluster_up SECONDS COMMAND...: as _cluster_wait, failing at once when a
# daemon has ended.
_cluster_up() {
  local end=$((SECONDS + $1)) p; shift
  until "$@" >/dev/null 2>&1; do
    for p in "${CLUSTER_PIDS[@]}"; do
      _cluster_gone "$p" && { cluster_fail "a daemon ended ($(tr '\0' ' ' </proc/"$p"/cmdline 2>/dev/null))"; return 1; }
    done
    [ $SECONDS -lt $end ] || return 1
    sleep 0.2
  done
}

_cluster_alive() { kill -0 "$1" 2>/dev/null; }

cluster_env() { echo "STRATA_SLURM_TEST=$CLUSTER_DIR"; }

cluster_start() {
  local d=$1 node cpus port i
  cluster_require || return 1
  CLUSTER_DIR=$d
  node=$(hostname -s)
  cpus=$(nproc)
  # Munge refuses key, seed and log folders that others can read or write,
  # and a socket folder others cannot enter (DIR's parents included).
  mkdir -p "$d" && chmod 755 "$d" || return 1
  mkdir -m 700 "$d/munge-etc" "$d/munge-lib" "$d/log"
  mkdir -m 755 "$d/munge-run"
  mkdir -p "$d/state" "$d/spool" "$d/run"
  local sock=$d/munge-run/munge.socket
  [ ${#sock} -lt 100 ] || cluster_fail "the folder's path is too long for a socket: $sock" || return 1
  mungekey --create --keyfile="$d/munge-etc/munge.key" || return 1
  env "$(cluster_env)" munged --foreground --socket="$sock" --key-file="$d/munge-etc/munge.key" \
    --pid-file="$d/munge-run/munged.pid" --log-file="$d/log/munged.log" \
    --seed-file="$d/munge-lib/munged.seed" >"$d/log/munged.out" 2>&1 &
  CLUSTER_PIDS+=($!)
  _cluster_up 20 sh -c "munge --socket='$sock' -n | unmunge --socket='$sock'" ||
    cluster_fail "munged did not start (log follows)" || { cluster_logs; return 1; }

  port=""
  for ((i = 0; i < 100; i++)); do
    local p=$((20000 + RANDOM % 30000))
    if cluster_port_free "$p" && cluster_port_free $((p + 1)); then port=$p; break; fi
  done
  [ -n "$port" ] || cluster_fail "no two free TCP ports" || return 1

  : >"$d/plugstack.conf"  # no SPANK plugins (not /etc/slurm/plugstack.conf)
  cat >"$d/slurm.conf" <<EOF
# Written by tests/farm/slurm_cluster.sh for one test run.
ClusterName=strata$$
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/run/slurmctld.pid
SlurmdPidFile=$d/run/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$d/plugstack.conf
MailProg=/bin/true
# No cgroups (a container has none of its own): processes tracked by their
# parent ids, tasks not bound.
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
# Finished jobs stay visible to scontrol show job for 10 minutes.
MinJobAge=600
KillWait=5
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$d/slurm.conf
  env "$(cluster_env)" slurmctld -D -f "$SLURM_CONF" >"$d/log/slurmctld.out" 2>&1 &
  CLUSTER_PIDS+=($!)
  env "$(cluster_env)" slurmd -D -f "$SLURM_CONF" >"$d/log/slurmd.out" 2>&1 &
  CLUSTER_PIDS+=($!)
  _cluster_up 30 scontrol ping ||
    cluster_fail "slurmctld did not answer scontrol ping (logs follow)" || { cluster_logs; return 1; }
  _cluster_up 30 sh -c "sinfo -h -n '$node' -o %T | grep -qx idle" ||
    cluster_fail "node $node did not come up idle (logs follow)" || { sinfo; cluster_logs; return 1; }
  # The clients talk to this controller, not to a system one.
  local name
  name=$(scontrol show config | awk '$1 == "ClusterName" {print $3}')
  [ "$name" = "strata$$" ] ||
    cluster_fail "scontrol reached cluster '$name', not strata$$ (SLURM_CONF=$SLURM_CONF)" || return 1
  echo "slurm cluster strata$$ up: node $node, $cpus CPUs, ports $port/$((port + 1)), in $d"
}

cluster_logs() {
  local n f
  [ -n "$CLUSTER_DIR" ] || return 0
  for n in munged slurmctld slurmd; do
    # NAME.log, or the daemon's own output when it died before opening it.
    f=$CLUSTER_DIR/log/$n.log
    [ -s "$f" ] || f=$CLUSTER_DIR/log/$n.out
    [ -s "$f" ] || continue
    echo "----- $f (last 100 lines)"
    tail -n 100 "$f"
  done
}

# The ids of the processes still carrying this cluster's marker, but this shell.
_cluster_marked() {
  local e p
  for e in /proc/[0-9]*/environ; do
    p=${e#/proc/}; p=${p%/environ}
    [ "$p" != "$$" ] || continue
    tr '\0' '\n' 2>/dev/null <"$e" | grep -qxF "$(cluster_env)" && echo "$p"
  done
  return 0
}

# _cluster_gone PID: the process has ended (a zombie child counts as ended).
_cluster_gone() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 0
  stat=${stat##*) }
  [ "${stat:0:1}" = Z ]
}

_cluster_all_gone() {
  local p
  for p in "$@"; do _cluster_gone "$p" || return 1; done
}

_cluster_no_jobs() { [ -z "$(squeue -h -o %i 2>/dev/null)" ]; }

cluster_stop() {
  local p pids
  [ -n "$CLUSTER_DIR" ] || return 0
  set +e
  if [ -n "${SLURM_CONF:-}" ] && timeout 5 scontrol ping >/dev/null 2>&1; then
    timeout 10 scancel --user="$(id -un)" >/dev/null 2>&1
    _cluster_wait 15 _cluster_no_jobs
    timeout 10 scontrol shutdown >/dev/null 2>&1
  fi
  # slurmctld and slurmd end on shutdown (munged, the first, does not).
  _cluster_wait 10 _cluster_all_gone "${CLUSTER_PIDS[@]:1}"
  for p in "${CLUSTER_PIDS[@]}"; do _cluster_gone "$p" || kill -TERM "$p" 2>/dev/null; done
  _cluster_wait 5 _cluster_all_gone "${CLUSTER_PIDS[@]}"
  for p in "${CLUSTER_PIDS[@]}"; do
    _cluster_gone "$p" || kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  # Whatever outlived them (a job step's slurmstepd, a job's processes).
  pids=$(_cluster_marked)
  if [ -n "$pids" ]; then
    echo "slurm cluster: ending leftover processes ${pids//$'\n'/ }" >&2
    # shellcheck disable=SC2086
    kill -KILL $pids 2>/dev/null
  fi
  CLUSTER_PIDS=()
  CLUSTER_DIR=""
  return 0
}
