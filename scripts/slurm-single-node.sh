#!/usr/bin/env bash
# A private single-node Slurm (munged + slurmctld + slurmd from Debian's packages) for testing
# `lantern farm`: its configuration, state, logs and munge key all live in one folder under
# /tmp, the daemons are started by hand and stopped by the PIDs in their PID files, and `stop`
# leaves no process and no file behind. Needs root (slurmd starts jobs as their owner).
#
# Usage: scripts/slurm-single-node.sh COMMAND
#   install             install slurm-wlm slurmctld slurmd slurm-client munge (apt, root or sudo)
#   probe               check, starting nothing, that this machine can run the cluster (root,
#                       the programs, the loopback interface, a free port pair); rc 1 and the
#                       reason on stderr when it cannot (the farm tests then skip with it)
#   start [--watch PID] start the cluster; with --watch, a watchdog stops it when PID exits
#                       (so a test that crashes or is killed leaves nothing running)
#   env                 print `export SLURM_CONF=...` (eval it to use sbatch/squeue/scancel)
#   wait JOBID [SECS]   wait until every task of JOBID has ended; rc 0 only if all COMPLETED
#   status              the daemons and the node state
#   stop                cancel every job, stop the daemons, delete the folder
#
# Knobs (environment):
#   LANTERN_SLURM_DIR        the cluster's folder, under /tmp (default /tmp/lantern-slurm);
#                            two clusters at once need two folders
#   LANTERN_SLURM_PORT       slurmctld's port; slurmd uses the next one (default: the first
#                            free pair from 6817 up, chosen under a lock)
#   LANTERN_SLURM_CPUS       CPUs the node advertises (default: what `slurmd -C` finds)
#   LANTERN_SLURM_SAVE_LOGS  copy the daemons' logs to this folder on stop
#
# What was learnt setting this up (wrong turns included) is in docs/farm.md.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
self="$here/$(basename "${BASH_SOURCE[0]}")"
D=${LANTERN_SLURM_DIR:-/tmp/lantern-slurm}
D=${D%/}
CONF=$D/etc/slurm.conf
MARKER=$D/.lantern-slurm-single-node

die() {
    echo "slurm-single-node: $*" >&2
    exit 1
}
say() { echo "slurm-single-node: $*" >&2; }

check_dir() {
    case "$D" in
    /tmp/?*) ;;
    *) die "LANTERN_SLURM_DIR must be a folder under /tmp/ (it is deleted on stop): $D" ;;
    esac
    case "$D" in *[[:space:]]* | *..*) die "LANTERN_SLURM_DIR may hold no spaces or '..': $D" ;; esac
}

need_root() {
    [ "$(id -u)" = 0 ] || die "needs root: slurmd starts each job as the user who submitted it"
}

# pid_of NAME: the PID in NAME's PID file when that process is alive and is NAME.
pid_of() {
    local f=$D/run/$1.pid pid
    [ -r "$f" ] || return 1
    pid=$(tr -dc 0-9 <"$f")
    [ -n "$pid" ] || return 1
    [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$1" ] || return 1
    echo "$pid"
}

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

# Waits up to $2 tenths of a second for the command in $3... to succeed, failing at once when
# daemon $1 has died. A daemon writes its PID file a moment after it forks (longer on a busy
# machine), so a missing file only counts as death after 5 s.
wait_for() {
    local daemon=$1 tenths=$2
    shift 2
    for ((i = 0; i < tenths; i++)); do
        "$@" >/dev/null 2>&1 && return 0
        if ! pid_of "$daemon" >/dev/null && { [ -s "$D/run/$daemon.pid" ] || [ $i -ge 50 ]; }; then
            say "$daemon died while starting"
            return 1
        fi
        sleep 0.1
    done
    say "$daemon did not come up in $((tenths / 10)) s"
    return 1
}

show_logs() {
    for f in "$D"/log/*.log; do
        [ -f "$f" ] || continue
        echo "--- last lines of $f" >&2
        tail -n 15 "$f" >&2
    done
}

write_conf() {
    local host cpus mem
    host=$(hostname -s)
    # What slurmd itself detects: a RealMemory above it would drain the node ("Low RealMemory").
    local hw
    hw=$(slurmd -C | head -n 1)
    cpus=$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$hw")
    mem=$(sed -n 's/.* RealMemory=\([0-9]*\).*/\1/p' <<<"$hw")
    [ -n "$cpus" ] && [ -n "$mem" ] || die "cannot read CPUs and RealMemory from 'slurmd -C': $hw"
    local overrides=""
    if [ -n "${LANTERN_SLURM_CPUS:-}" ]; then
        # Advertising more CPUs than exist makes the node INVALID unless slurmd is told to trust
        # the configuration.
        [ "$LANTERN_SLURM_CPUS" -gt "$cpus" ] && overrides="SlurmdParameters=config_overrides"
        cpus=$LANTERN_SLURM_CPUS
    fi
    cat >"$CONF" <<EOF
# Single-node Slurm written by scripts/slurm-single-node.sh; everything under $D.
ClusterName=lantern
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/run/munge.socket
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/run/slurmctld.pid
SlurmdPidFile=$D/run/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$D/log/jobcomp.txt
MpiDefault=none
# The default batch_sched_delay=3 starts array tasks in waves 3 s apart.
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
# CPUs are the consumable; memory is not, so tasks without --mem still share the node.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
$overrides
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=lantern Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

# Closes every descriptor above stderr that this script inherited (a test's pipe, say), so the
# daemons started from here cannot hold a caller's pipe open. 255 is bash's own script file.
close_inherited_fds() {
    local fd
    for fd in /proc/$$/fd/*; do
        fd=${fd##*/}
        if [ "$fd" -gt 2 ] && [ "$fd" -lt 255 ]; then eval "exec $fd>&-" 2>/dev/null || true; fi
    done
}

cmd_install() { exec "$here/install-deps.sh" slurm; }

# free_port_pair: the first port P from 6817 up (or LANTERN_SLURM_PORT) with P and P+1 free.
free_port_pair() {
    local port
    if [ -n "${LANTERN_SLURM_PORT:-}" ]; then
        port=$LANTERN_SLURM_PORT
        port_free "$port" && port_free $((port + 1)) && echo "$port"
        return
    fi
    for ((port = 6817; port < 7017; port += 2)); do
        if port_free "$port" && port_free $((port + 1)); then
            echo "$port"
            return 0
        fi
    done
    return 1
}

need_tools() {
    local tool
    for tool in munged mungekey munge unmunge slurmctld slurmd scontrol sinfo; do
        command -v "$tool" >/dev/null || die "$tool not found: run '$0 install' first"
    done
}

# What a machine may lack that start needs, checked without starting anything.
cmd_probe() {
    need_root
    need_tools
    # The daemons talk over 127.0.0.1; in a network namespace without networking (a container
    # run with --network none, say) lo is down and a connection there is "unreachable".
    local answer
    answer=$(LC_ALL=C bash -c 'exec 3<>/dev/tcp/127.0.0.1/6817' 2>&1 || true)
    case "$answer" in
    *unreachable* | *"Cannot assign"*)
        die "no loopback network (127.0.0.1: ${answer##*: }): the daemons talk over it" ;;
    esac
    if [ -n "${LANTERN_SLURM_PORT:-}" ]; then
        free_port_pair >/dev/null ||
            die "TCP port $LANTERN_SLURM_PORT or $((LANTERN_SLURM_PORT + 1)) is in use (LANTERN_SLURM_PORT)"
    else
        free_port_pair >/dev/null || die "no free TCP port pair in 6817-7016 for slurmctld and slurmd"
    fi
    hostname -s >/dev/null 2>&1 || die "'hostname -s' fails: the node needs a host name"
}

cmd_start() {
    local watch=""
    if [ "${1:-}" = "--watch" ]; then
        watch=${2:?--watch needs a PID}
        [[ "$watch" =~ ^[0-9]+$ ]] || die "--watch needs a PID: $watch"
    fi
    need_root
    check_dir
    close_inherited_fds
    need_tools
    if pid_of slurmctld >/dev/null || pid_of slurmd >/dev/null || pid_of munged >/dev/null; then
        die "a cluster is already running in $D: '$0 stop' first (or set LANTERN_SLURM_DIR)"
    fi
    if [ -e "$D" ] && [ ! -e "$MARKER" ] && [ -n "$(ls -A "$D" 2>/dev/null)" ]; then
        die "$D exists, is not empty and was not made by this script: refusing to wipe it"
    fi
    rm -rf "$D"
    mkdir -p "$D"/{etc,state,spool,log,run,munge}
    touch "$MARKER"
    # munged refuses a socket folder that not everyone may enter, and a key folder others may.
    chmod 0755 "$D" "$D/run"
    chmod 0700 "$D/munge"
    # From here on, a failure stops whatever did start.
    trap 'rc=$?; if [ $rc -ne 0 ]; then show_logs; "$self" stop || true; fi' EXIT

    mungekey --create --keyfile="$D/munge/munge.key"
    # Daemons get no terminal and none of our pipes: a caller reading our output (a test)
    # must see end-of-file when this script ends, not when the cluster stops.
    munged --key-file="$D/munge/munge.key" --socket="$D/run/munge.socket" \
        --pid-file="$D/run/munged.pid" --log-file="$D/log/munged.log" \
        --seed-file="$D/munge/munge.seed" </dev/null >>"$D/log/start.log" 2>&1
    wait_for munged 50 bash -c "munge -n -S '$D/run/munge.socket' | unmunge -S '$D/run/munge.socket'"

    # Choose the ports and bind them under a lock, so clusters started at once (from any
    # checkout) do not collide. The lock is on /tmp itself, so that nothing is left behind.
    exec 9</tmp
    flock -w 60 9 || die "could not lock /tmp to choose the ports"
    if [ -n "${LANTERN_SLURM_PORT:-}" ]; then
        CTLD_PORT=$(free_port_pair) ||
            die "port $LANTERN_SLURM_PORT or $((LANTERN_SLURM_PORT + 1)) is in use (LANTERN_SLURM_PORT)"
    else
        CTLD_PORT=$(free_port_pair) || die "no free port pair in 6817-7016 (set LANTERN_SLURM_PORT)"
    fi
    SLURMD_PORT=$((CTLD_PORT + 1))
    write_conf
    export SLURM_CONF=$CONF
    slurmctld -f "$CONF" </dev/null >>"$D/log/start.log" 2>&1
    wait_for slurmctld 150 bash -c "scontrol ping | grep -q 'is UP'"
    slurmd -f "$CONF" -N "$(hostname -s)" </dev/null >>"$D/log/start.log" 2>&1
    wait_for slurmd 150 bash -c "sinfo -h -o %T | grep -qx idle"
    flock -u 9
    exec 9>&-

    if [ -n "$watch" ]; then
        LANTERN_SLURM_DIR=$D setsid "$self" _watch "$watch" </dev/null >>"$D/log/watch.log" 2>&1 &
        echo $! >"$D/run/watch.pid"
    fi
    trap - EXIT
    say "up in $D (slurmctld port $CTLD_PORT, slurmd port $SLURMD_PORT); eval \"\$($0 env)\""
}

# The watchdog: stops the cluster once the watched process has gone.
cmd_watch() {
    local pid=$1
    while kill -0 "$pid" 2>/dev/null && [ -e "$MARKER" ]; do sleep 1; done
    [ -e "$MARKER" ] || exit 0
    echo "watched process $pid is gone: stopping the cluster" >&2
    exec "$self" stop
}

cmd_env() {
    check_dir
    [ -f "$CONF" ] || die "no cluster in $D ('$0 start' first)"
    echo "export SLURM_CONF=$CONF"
}

cmd_wait() {
    local job=${1:?wait needs a job id} secs=${2:-600}
    check_dir
    # A missing configuration makes every Slurm client retry for 60 s; check first.
    [ -f "$CONF" ] && pid_of slurmctld >/dev/null || die "no running cluster in $D"
    export SLURM_CONF=$CONF
    local deadline=$((SECONDS + secs)) states
    while :; do
        states=$(squeue -h -r -j "$job" -t all -o '%K %T') || die "squeue failed for job $job"
        if ! grep -qvE ' (COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|PREEMPTED|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE)$' <<<"$states"; then
            break
        fi
        if sinfo -h -o %T | grep -qE 'down|drain|invalid|fail'; then
            die "the node is $(sinfo -h -o %T); see $D/log/slurmd.log"
        fi
        if [ $SECONDS -ge $deadline ]; then
            scancel "$job" || true
            die "job $job still running after $secs s: cancelled"
        fi
        sleep 0.2
    done
    echo "$states" | sort -n
    ! grep -qv ' COMPLETED$' <<<"$states"
}

cmd_status() {
    check_dir
    local d
    for d in munged slurmctld slurmd; do
        if pid_of "$d" >/dev/null; then echo "$d: running, PID $(pid_of "$d")"; else echo "$d: not running"; fi
    done
    if pid_of slurmctld >/dev/null; then SLURM_CONF=$CONF sinfo; fi
}

# stop_pid NAME...: TERM each daemon by its PID file, then wait for all (up to 15 s; then KILL).
stop_daemons() {
    local pids=() name pid
    for name in "$@"; do
        pid=$(pid_of "$name") && kill -TERM "$pid" 2>/dev/null && pids+=("$pid")
    done
    for pid in "${pids[@]}"; do
        for ((i = 0; i < 150; i++)); do
            kill -0 "$pid" 2>/dev/null || break
            sleep 0.1
        done
        if kill -0 "$pid" 2>/dev/null; then
            say "PID $pid ignored TERM for 15 s: KILL"
            kill -KILL "$pid" 2>/dev/null || true
        fi
    done
}

cmd_stop() {
    check_dir
    [ -e "$D" ] || return 0
    [ -e "$MARKER" ] || die "$D was not made by this script: not touching it"
    export SLURM_CONF=$CONF
    if pid_of slurmctld >/dev/null && [ -f "$CONF" ]; then
        # Cancel every job of this cluster (this SLURM_CONF), then let the queue drain.
        scancel --user="$(id -un)" 2>/dev/null || true
        for ((i = 0; i < 50; i++)); do
            [ -z "$(squeue -h -t PENDING,RUNNING,CONFIGURING,COMPLETING,SUSPENDED 2>/dev/null)" ] && break
            sleep 0.1
        done
    fi
    # Job steps still alive (slurmd gone first, say): those started for this cluster only.
    local p
    for p in $(pgrep -x slurmstepd || true); do
        if { tr '\0' '\n' <"/proc/$p/environ"; } 2>/dev/null | grep -qx "SLURM_CONF=$CONF"; then
            kill -TERM "$p" 2>/dev/null || true
        fi
    done
    stop_daemons slurmd slurmctld munged
    # The watchdog, unless it is what runs this stop.
    if [ -r "$D/run/watch.pid" ]; then
        p=$(tr -dc 0-9 <"$D/run/watch.pid")
        if [ -n "$p" ] && [ "$p" != "$$" ] && { tr '\0' ' ' <"/proc/$p/cmdline"; } 2>/dev/null | grep -q "_watch"; then
            kill -TERM "$p" 2>/dev/null || true
        fi
    fi
    if [ -n "${LANTERN_SLURM_SAVE_LOGS:-}" ]; then
        mkdir -p "$LANTERN_SLURM_SAVE_LOGS"
        cp -r "$D/log/." "$LANTERN_SLURM_SAVE_LOGS/" 2>/dev/null || true
    fi
    rm -rf "$D"
}

case "${1:-}" in
install) cmd_install ;;
probe) cmd_probe ;;
start) cmd_start "${@:2}" ;;
_watch) cmd_watch "${2:?}" ;;
env) cmd_env ;;
wait) cmd_wait "${@:2}" ;;
status) cmd_status ;;
stop) cmd_stop ;;
*)
    sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
    exit 2
    ;;
esac
