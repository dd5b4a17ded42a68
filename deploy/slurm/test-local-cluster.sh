#!/usr/bin/env bash
# study-array.sh under a real Slurm: installs Slurm and munge from Debian's
# packages if missing, starts a one-node cluster on this machine (munged,
# slurmctld, slurmd; every CPU of the machine), submits a small study as
# deploy/README.md tells a user to (an array of shards, then the dependent
# report job), waits for both with a bound, and checks that every output
# equals an unsharded study's but for measured times. Everything it starts
# is stopped at exit; its files live in one temporary directory.
#
#   deploy/slurm/test-local-cluster.sh [--skip-if-unavailable]
#
# BIN: the directory of the coordinator executable (default target/debug).
# With --skip-if-unavailable, a machine where the cluster cannot be set up
# (not root, no packages) skips with a message instead of failing.
set -euo pipefail
cd "$(dirname "$0")/../.."
here=$PWD
skip_ok=0
[ "${1:-}" = --skip-if-unavailable ] && skip_ok=1
unavailable() {
    if [ "$skip_ok" = 1 ]; then
        echo "slurm cluster test skipped: $*"
        exit 0
    fi
    echo "error: $*" >&2
    exit 1
}
fail() {
    echo "error: slurm cluster test: $*" >&2
    exit 1
}

[ "$(id -u)" = 0 ] || unavailable "it needs root to start munged, slurmctld and slurmd"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge) \
        >/dev/null 2>&1 || unavailable "Slurm and munge could not be installed (apt-get install slurm-wlm munge)"
fi
coordinator="${BIN:-$here/target/debug}/coordinator"
[ -x "$coordinator" ] || fail "no coordinator at $coordinator (build it, or set BIN)"

work=$(mktemp -d /tmp/adv-slurm.XXXXXX)
chmod 755 "$work"
pids=()
# True while any daemon started here is still running.
any_alive() {
    local pid
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && return 0; done
    return 1
}
# The daemons write their state as they stop: the files go only once they are
# gone (10 s each for SIGTERM, then SIGKILL). Nothing here changes the verdict.
cleanup() {
    local signal pid
    for signal in TERM KILL; do
        for pid in "${pids[@]}"; do kill -s "$signal" "$pid" 2>/dev/null || true; done
        for _ in $(seq 100); do any_alive || break; sleep 0.1; done
    done
    rm -rf "$work" 2>/dev/null || echo "warning: could not remove $work" >&2
}
trap cleanup EXIT

# munge: a key of its own and a daemon on its own socket.
mkdir -p "$work/munge" "$work/munge-key"
dd if=/dev/urandom of="$work/munge-key/munge.key" bs=1024 count=1 status=none
chown -R munge:munge "$work/munge" "$work/munge-key"
chmod 755 "$work/munge" && chmod 700 "$work/munge-key" && chmod 400 "$work/munge-key/munge.key"
socket="$work/munge/munge.socket"
runuser -u munge -- munged --key-file="$work/munge-key/munge.key" --socket="$socket" \
    --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" \
    --seed-file="$work/munge/munged.seed" || fail "munged did not start ($work/munge/munged.log)"
pids+=("$(cat "$work/munge/munged.pid")")

# A one-node cluster on free ports.
node=$(hostname -s)
cpus=$(nproc)
ports=($(python3 -c 'import socket
s=[socket.socket() for _ in range(2)]
[x.bind(("127.0.0.1", 0)) for x in s]
print(*[x.getsockname()[1] for x in s])'))
mkdir -p "$work/state" "$work/spool"
export SLURM_CONF="$work/slurm.conf"
cat > "$SLURM_CONF" <<EOF
ClusterName=adv-test
SlurmctldHost=$node
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start ($work/slurmctld.log)"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start ($work/slurmd.log)"
for f in slurmctld slurmd; do
    for _ in $(seq 50); do [ -s "$work/$f.pid" ] && break; sleep 0.1; done
    pids+=("$(cat "$work/$f.pid" 2>/dev/null)")
done

# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
    local limit=$1 what=$2
    shift 2
    for _ in $(seq "$((limit * 5))"); do
        "$@" >/dev/null 2>&1 && return 0
        sleep 0.2
    done
    fail "$what did not happen within ${limit}s (logs in $work)"
}
wait_for 60 "node $node becoming idle" bash -c "sinfo -h -n $node -o %T | grep -qx idle"

# A small study: two algorithms, four runs each.
cat > "$work/study.toml" <<'EOF'
name = "slurm-test"
runs = 4
episodes = 60
eval_every = 20
eval_episodes = 10
seed = 5
transport = "in-process"
baseline = "no-advice"

[[entry]]
name = "no-advice"
algorithm = "no-advice"

[[entry]]
name = "adhoc-td"
algorithm = "adhoc-td"
EOF

# As deploy/README.md says: the array, then the report job after it.
export COORDINATOR="$coordinator" STUDY_CONFIG=1
script="$here/deploy/slurm/study-array.sh"
array=$(sbatch --parsable --array=1-2 --cpus-per-task=1 --chdir="$work" \
    "$script" "$work/study.toml" "$work/sharded") || fail "sbatch of the array was refused"
report=$(sbatch --parsable --dependency=afterok:"$array" --cpus-per-task=1 --chdir="$work" \
    "$script" "$work/study.toml" "$work/sharded") || fail "sbatch of the report job was refused"
echo "submitted array job $array (2 shards) and report job $report"
wait_for 900 "jobs $array and $report finishing" bash -c "[ -z \"\$(squeue -h -j $array,$report)\" ]"
state=$(scontrol show job "$report" | grep -o 'JobState=[A-Z_]*' || true)
[ "$state" = JobState=COMPLETED ] || fail "the report job ended $state; its log: $(cat "$work"/adv-study-"$report"_*.log 2>/dev/null | tail -5)"
for task in 1 2; do
    state=$(scontrol show job "${array}_$task" | grep -o 'JobState=[A-Z_]*' || true)
    [ "$state" = JobState=COMPLETED ] || fail "array task $task ended $state"
done
[ -f "$work/sharded/REPORT.md" ] || fail "the report job wrote no REPORT.md"

# The same study unsharded, and the two compared.
"$coordinator" study --config "$work/study.toml" --out "$work/unsharded" --threads 1 --quiet
python3 "$here/deploy/slurm/same_results.py" "$work/unsharded" "$work/sharded" ||
    fail "the sharded study's results differ from the unsharded one's"
echo "slurm cluster test passed: 2 array tasks and the report job under slurmctld/slurmd on $node ($cpus CPUs) equal the unsharded study"
