#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine (Debian 12's slurm-wlm 22.05 and munge),
# for trying the batch files in scripts/slurm/ and for scripts/test-slurm.sh.
#
#   scripts/slurm/local-cluster.sh start    # install what is missing, configure, start, wait
#   scripts/slurm/local-cluster.sh status   # the daemons and `sinfo`
#   scripts/slurm/local-cluster.sh stop     # stop the daemons it started
#   scripts/slurm/local-cluster.sh env      # the line to paste: export SLURM_CONF=...
#
# Everything it writes lives in one folder, $SSRT_SLURM_DIR (default /var/tmp/ssrt-slurm):
# slurm.conf, the munge key and socket, the controller's state, slurmd's spool, the pid files
# and the logs (log/). It never touches /etc/slurm or the system's munged, so the Slurm
# commands need SLURM_CONF pointed at its slurm.conf (`eval "$(... env)"`). The ports are
# Slurm's usual 6817 and 6818 (SSRT_SLURM_CTLD_PORT, SSRT_SLURM_SLURMD_PORT: other ones where
# the machine runs a Slurm of its own); SSRT_SLURM_WAIT_S bounds the wait for the node (60).
#
# It runs the daemons directly as root, without systemd (a container need not have it):
# munged with its own key and socket, slurmctld and slurmd daemonized. The configuration
# needs no cgroups: processes are tracked through /proc (proctrack/linuxproc), tasks are not
# bound (task/none), no accounting (jobacct_gather/none, accounting_storage/none). The node
# is what `slurmd -C` sees (CPUs, sockets, cores, threads, memory); cores are scheduled one
# by one (select/cons_tres with CR_CPU), memory is not a consumable, so an array task with
# --cpus-per-task=1 takes one CPU and a 2-CPU machine runs two at once.
#
# Exit status of `start`: 0 when the node is idle in `sinfo`; 3 when Slurm cannot start here
# (the packages cannot be installed, a daemon dies or the node never comes up: the reason is
# printed with the end of its log); 1 for any other error.
set -euo pipefail

dir="${SSRT_SLURM_DIR:-/var/tmp/ssrt-slurm}"
ctld_port="${SSRT_SLURM_CTLD_PORT:-6817}"
slurmd_port="${SSRT_SLURM_SLURMD_PORT:-6818}"
wait_s="${SSRT_SLURM_WAIT_S:-60}"
conf="$dir/slurm.conf"
socket="$dir/munge/munge.socket"
packages=(munge slurm-wlm slurmctld slurmd slurm-client)

say() { echo "local-cluster: $*" >&2; }
starting=0
cannot_start() {
    say "CANNOT START: $*"
    # Leave no half-started cluster behind: stop whichever of our daemons did start.
    [ "$starting" = 0 ] || cmd_stop
    exit 3
}
# The last error a daemon logged, for the reason cannot_start prints.
last_error() { grep -E 'fatal|error' "$dir/log/$1.log" 2>/dev/null | grep -v pmix | tail -n 1 | cut -c 27- || true; }
# Whether the daemon a pid file names runs: the pid alive and its command the file's name
# (slurmd.pid: slurmd), so a stale file from before a reboot, its pid reused, does not count.
alive() {
    local pid
    pid="$(cat "$1" 2>/dev/null)" || return 1
    [ -n "$pid" ] && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$(basename "$1" .pid)" ]
}

install_missing() {
    local missing=() p
    for p in "${packages[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' ||
            missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    say "installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    # The packages' postinst scripts try to start the system's services; without systemd
    # (or with a policy-rc.d that denies it) that is skipped, which is what we want.
    if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >"$dir/log/apt.log" 2>&1; }; then
        tail -n 20 "$dir/log/apt.log" >&2 || true
        cannot_start "apt-get could not install ${missing[*]} (log: $dir/log/apt.log)"
    fi
}

write_conf() {
    # The node as slurmd detects it: "NodeName=vm CPUs=2 Boards=1 ... RealMemory=24105".
    local node_line node
    node_line="$(slurmd -C 2>&1 | head -n 1)" || true
    node="$(sed -n 's/^NodeName=\([^ ]*\).*/\1/p' <<<"$node_line")"
    [ -n "$node" ] || cannot_start "slurmd -C printed no node line: $node_line"
    echo "$node" >"$dir/nodename"
    cat >"$conf" <<EOF
# Written by scripts/slurm/local-cluster.sh: a single node on this machine. Do not edit;
# \`local-cluster.sh start\` rewrites it.
ClusterName=ssrt
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/ctld
SlurmdSpoolDir=$dir/slurmd
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups needed: a container may have none, or read-only ones.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
MinJobAge=300
KillWait=10
MaxArraySize=10001
# No mail on this node (the default /bin/mail is missing: an error at every start).
MailProg=/bin/true
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=ssrt Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
    # Drop the UpTime=... that `slurmd -C` may print on the node line's own line.
    sed -i '/^UpTime=/d' "$conf"
}

start_munge() {
    if alive "$dir/munge/munged.pid"; then return 0; fi
    mkdir -p "$dir/munge"
    chmod 755 "$dir/munge" # the socket must be reachable; the key stays 0600
    if [ ! -s "$dir/munge/munge.key" ]; then
        mungekey --create --keyfile="$dir/munge/munge.key" 2>/dev/null ||
            dd if=/dev/urandom of="$dir/munge/munge.key" bs=128 count=1 status=none
    fi
    chmod 600 "$dir/munge/munge.key"
    if ! munged --force --key-file="$dir/munge/munge.key" --socket="$socket" \
        --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
        --seed-file="$dir/munge/munged.seed" 2>>"$dir/log/munged.log"; then
        tail -n 5 "$dir/log/munged.log" >&2 || true
        cannot_start "munged could not start (log: $dir/log/munged.log)"
    fi
    # A credential encoded and decoded through our socket proves munged works.
    munge --socket="$socket" -n </dev/null | unmunge --socket="$socket" >/dev/null 2>&1 ||
        cannot_start "munged started but does not encode/decode credentials"
}

start_daemon() { # name, pid file, command...
    local name="$1" pid="$2"
    shift 2
    if alive "$pid"; then return 0; fi
    if ! "$@" >>"$dir/log/$name.out" 2>&1; then
        tail -n 10 "$dir/log/$name.log" "$dir/log/$name.out" >&2 2>/dev/null || true
        cannot_start "$name exited at start: $(last_error "$name") (log: $dir/log/$name.log)"
    fi
}

node_state() { sinfo -h -n "$(cat "$dir/nodename")" -o '%t' 2>/dev/null | head -n 1; }

cmd_start() {
    # SlurmUser and SlurmdUser are root: the daemons run jobs as whoever submits them.
    [ "$(id -u)" -eq 0 ] || cannot_start "the daemons need root (run it as root)"
    mkdir -p "$dir/log" "$dir/ctld" "$dir/slurmd"
    install_missing
    starting=1
    local t0=$SECONDS
    if alive "$dir/slurmctld.pid" && alive "$dir/slurmd.pid"; then
        say "already running"
    else
        write_conf
        start_munge
        # -i: start even if the saved state cannot be read (an earlier, killed cluster).
        start_daemon slurmctld "$dir/slurmctld.pid" slurmctld -f "$conf" -i
        start_daemon slurmd "$dir/slurmd.pid" slurmd -f "$conf" -N "$(cat "$dir/nodename")"
    fi
    export SLURM_CONF="$conf"
    local state=""
    while [ $((SECONDS - t0)) -lt "$wait_s" ]; do
        state="$(node_state)" || state="" # no controller answering yet
        case "$state" in
            idle | mix | alloc) break ;;
            # A node left down or drained by an earlier run comes back.
            down* | drain* | fail*)
                scontrol update nodename="$(cat "$dir/nodename")" state=resume 2>/dev/null || true ;;
        esac
        # The daemons fork and write their pid files after: give them a moment to appear.
        for d in slurmctld slurmd; do
            [ $((SECONDS - t0)) -lt 3 ] || alive "$dir/$d.pid" || {
                tail -n 10 "$dir/log/$d.log" >&2 2>/dev/null || true
                cannot_start "$d died while starting: $(last_error "$d") (log: $dir/log/$d.log)"
            }
        done
        sleep 1
    done
    case "$state" in
        idle | mix | alloc) ;;
        *)
            tail -n 10 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 2>/dev/null || true
            cannot_start "the node is '${state:-not listed}' after ${wait_s}s, not idle"
            ;;
    esac
    say "node $(cat "$dir/nodename") is $state after $((SECONDS - t0))s; run: export SLURM_CONF=$conf"
}

cmd_stop() {
    local d pid
    if [ -f "$conf" ] && alive "$dir/slurmctld.pid"; then
        SLURM_CONF="$conf" scancel --quiet --user="$(id -un)" 2>/dev/null || true
    fi
    for d in slurmd slurmctld munge/munged; do
        alive "$dir/$d.pid" || continue
        pid="$(cat "$dir/$d.pid")"
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
        kill -9 "$pid" 2>/dev/null || true
        rm -f "$dir/$d.pid"
        say "stopped ${d#munge/} (pid $pid)"
    done
}

cmd_status() {
    local d running=0
    for d in munge/munged slurmctld slurmd; do
        if alive "$dir/$d.pid"; then
            echo "${d#munge/}: running (pid $(cat "$dir/$d.pid"))"
        else
            echo "${d#munge/}: stopped"
            running=1
        fi
    done
    # sinfo retries for seconds when no controller answers: only ask a running one.
    if [ -f "$conf" ] && alive "$dir/slurmctld.pid"; then SLURM_CONF="$conf" sinfo || true; fi
    return $running
}

case "${1:-}" in
    start) cmd_start ;;
    stop) cmd_stop ;;
    status) cmd_status ;;
    env) echo "export SLURM_CONF=$conf" ;;
    *)
        echo "usage: $0 start|stop|status|env" >&2
        exit 2
        ;;
esac
