# shellcheck shell=bash disable=SC2034
# A one-node Slurm cluster on this machine for scripts/test_slurm.sh and scripts/bench_slurm.sh
# (sourced, not run). The sourcing script defines log, skip and fail, and sets ROOT.
#
# Installs Debian's slurm-wlm and munge with apt-get if they are missing (skip: not root, or the
# packages cannot be installed), writes a munge key and a one-node slurm.conf (NodeName=localhost
# CPUs=2, proctrack/linuxproc, task/none, select/cons_tres, two free TCP ports) into TMP, starts
# munged, slurmctld and slurmd as daemons with pid files there (no systemd), waits (bounded) for
# the node, and on EXIT cancels the jobs left, stops exactly these daemons and removes TMP
# (KEEP_SLURM_TMP=1 keeps it). Exports SLURM_CONF; defines wait_jobs, job_states,
# expect_completed, parse_submission.

if [ "$(id -u)" != 0 ]; then
    skip "needs root (apt-get install slurm-wlm munge, and slurmd runs as root); run as root to include it"
fi
have_slurm() {
    command -v munged >/dev/null && command -v slurmctld >/dev/null &&
        command -v slurmd >/dev/null && command -v sbatch >/dev/null
}
if ! have_slurm; then
    log "installing slurm-wlm and munge (apt-get)"
    if ! command -v apt-get >/dev/null; then
        skip "slurm-wlm and munge are not installed and there is no apt-get to install them"
    fi
    export DEBIAN_FRONTEND=noninteractive
    if ! { timeout 600 apt-get update -q >/tmp/ehl-slurm-apt.log 2>&1 &&
        timeout 900 apt-get install -y -q slurm-wlm munge >>/tmp/ehl-slurm-apt.log 2>&1; }; then
        tail -5 /tmp/ehl-slurm-apt.log
        skip "apt-get could not install slurm-wlm and munge (log: /tmp/ehl-slurm-apt.log)"
    fi
    have_slurm || skip "slurm-wlm and munge installed but munged/slurmctld/slurmd/sbatch not found"
fi
log "$(slurmctld -V)"

TMP=$(mktemp -d /tmp/ehl-slurm.XXXXXX)
chmod 755 "$TMP"
export SLURM_CONF=$TMP/slurm.conf

stop_pidfile() { # stop the daemon of a pid file (ours only), waiting at most 15 s
    local f=$1 pid
    [ -s "$f" ] || return 0
    pid=$(cat "$f")
    kill "$pid" 2>/dev/null || return 0
    for _ in $(seq 1 150); do
        kill -0 "$pid" 2>/dev/null || return 0
        sleep 0.1
    done
    kill -9 "$pid" 2>/dev/null || true
}
cleanup() {
    local rc=$?
    set +e
    if [ -s "$TMP/slurmctld.pid" ]; then
        timeout 10 scancel --quiet --user="$(id -un)" 2>/dev/null
        for _ in $(seq 1 100); do
            [ -z "$(timeout 5 squeue -h 2>/dev/null)" ] && break
            sleep 0.2
        done
    fi
    if [ "$rc" != 0 ]; then
        echo "--- Slurm stage failed (exit $rc); last lines of the logs in $TMP:" >&2
        for f in "$TMP"/log/*.log "$TMP"/*.slurm/logs/*.out; do
            [ -f "$f" ] && { echo "--- $f" >&2; tail -15 "$f" >&2; }
        done
    fi
    stop_pidfile "$TMP/slurmd.pid"
    stop_pidfile "$TMP/slurmctld.pid"
    stop_pidfile "$TMP/munge/munged.pid"
    if [ "${KEEP_SLURM_TMP:-0}" = 1 ]; then
        echo "kept $TMP" >&2
    else
        rm -rf "$TMP"
    fi
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
PORT=""
for _ in $(seq 1 50); do
    p=$((20000 + RANDOM % 20000))
    if port_free "$p" && port_free $((p + 1)); then
        PORT=$p
        break
    fi
done
[ -n "$PORT" ] || fail "no two free TCP ports found for slurmctld and slurmd"

mkdir -p "$TMP/munge" "$TMP/state" "$TMP/spool" "$TMP/log"
chmod 700 "$TMP/munge"
if ! mungekey --create --keyfile="$TMP/munge/munge.key" --force 2>/dev/null; then
    dd if=/dev/urandom of="$TMP/munge/munge.key" bs=1024 count=1 status=none
fi
chmod 600 "$TMP/munge/munge.key"
munged --force --key-file="$TMP/munge/munge.key" --socket="$TMP/munge/munge.socket" \
    --pid-file="$TMP/munge/munged.pid" --log-file="$TMP/munge/munged.log" \
    --seed-file="$TMP/munge/munge.seed" || fail "munged did not start (log: $TMP/munge/munged.log)"

cat >"$SLURM_CONF" <<EOF
# One-node test cluster written by scripts/test_slurm.sh
ClusterName=ehltest
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
AuthInfo=socket=$TMP/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$TMP/state
SlurmdSpoolDir=$TMP/spool
SlurmctldPidFile=$TMP/slurmctld.pid
SlurmdPidFile=$TMP/slurmd.pid
SlurmctldLogFile=$TMP/log/slurmctld.log
SlurmdLogFile=$TMP/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$TMP/log/jobcomp.log
MpiDefault=none
ReturnToService=2
MinJobAge=3600
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=60 State=UP
EOF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start (log: $TMP/log/slurmctld.log)"
slurmd -f "$SLURM_CONF" -N localhost || fail "slurmd did not start (log: $TMP/log/slurmd.log)"
ready=""
for _ in $(seq 1 150); do
    if [ "$(timeout 5 sinfo -h -N -o %t 2>/dev/null)" = idle ]; then
        ready=1
        break
    fi
    sleep 0.2
done
[ -n "$ready" ] || fail "the node did not come up idle within 30 s (sinfo: $(timeout 5 sinfo -h -N 2>&1))"
log "cluster up: slurmctld port $PORT, slurmd port $((PORT + 1)), node localhost with 2 CPUs"

# ---------------------------------------------------------------- helpers
# wait_jobs TIMEOUT_S ID...: wait until none of the jobs is pending or running.
wait_jobs() {
    local limit=$1
    shift
    local ids
    ids=$(
        IFS=,
        echo "$*"
    )
    local t0=$SECONDS
    while [ -n "$(timeout 10 squeue -h -j "$ids" 2>/dev/null)" ]; do
        if ((SECONDS - t0 > limit)); then
            timeout 5 squeue >&2
            fail "jobs $ids not finished after $limit s"
        fi
        sleep 0.5
    done
}
# job_states ID: the states of a job (every task of an array), one per line.
job_states() {
    timeout 10 scontrol show job "$1" | grep -o 'JobState=[A-Z_]*' | cut -d= -f2
}
expect_completed() { # expect_completed WHAT ID...
    local what=$1 id s
    shift
    for id in "$@"; do
        s=$(job_states "$id" | sort -u | tr '\n' ' ')
        [ "$s" = "COMPLETED " ] || fail "$what: job $id ended in state(s) $s(expected COMPLETED)"
    done
}
# submit OUT_OF_SBATCH_VAR: sets ARRAY_ID, ARRAY_TASKS and MERGE_ID from `study sbatch --submit` output.
parse_submission() {
    local line
    line=$(grep '^submitted array job' <<<"$1") || fail "no submission in: $1"
    ARRAY_ID=$(sed -E 's/^submitted array job ([0-9]+) .*/\1/' <<<"$line")
    ARRAY_TASKS=$(sed -E 's/.*\(tasks ([^)]*)\).*/\1/' <<<"$line")
    MERGE_ID=$(sed -E 's/.* and merge job ([0-9]+) .*/\1/' <<<"$line")
}

