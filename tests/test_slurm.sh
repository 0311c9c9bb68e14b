#!/usr/bin/env bash
# test_slurm — a split render on a real Slurm cluster: the test starts a single-node cluster
# from Debian's packages (munged, slurmctld and slurmd for localhost, configured in a temporary
# directory), submits tools/slurm/submit.sh's array job of 4 parts and the dependent merge job,
# waits for them, and compares the merged files with a single-process render, byte for byte.
# It also checks that the tasks' cache directories on the node's disk (one per task) are gone
# when the jobs are, and renders a 2-frame animation as 2 tasks (whole frames, no merge) that
# share one kept node cache (ATMO_NODE_CACHE_SHARED=1). The daemons are stopped on every exit (trap). Exit 77 (skipped) where the
# packages are missing or the daemons cannot be started (not root, ports taken, no munge).
# labels: cli slow
#
# Oracle: the single-process render of the same scene and seed on the same device (bitwise:
# the parts hold each pixel's sums in sample order, atmo/part.h; each frame against a render at
# its interpolated zenith, 40 and 60 deg, exact in binary), and the Slurm job states
# (COMPLETED) that scontrol reports.
set -u
atmo=$1
src=${ATMO_SOURCE_DIR:-$(cd "$(dirname "$0")/.." && pwd)}
for c in munged slurmctld slurmd sbatch scontrol sinfo; do
    command -v "$c" >/dev/null || { echo "skip: $c not installed (slurm-wlm, munge)"; exit 77; }
done
[ "$(id -u)" -eq 0 ] || { echo "skip: slurmd needs root"; exit 77; }
work=$(mktemp -d /tmp/atmo-slurm.XXXXXX)
chmod 755 "$work"
stop() {
    local f
    for f in "$work"/slurmd.pid "$work"/slurmctld.pid "$work"/munge/munged.pid; do
        [ -s "$f" ] && kill "$(cat "$f")" 2>/dev/null
    done
    sleep 1
    rm -rf "$work"
}
trap stop EXIT
cd "$work"
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAIL: $*" >&2; }
skip() {
    echo "skip: $*"
    for f in "$work"/log/*.log "$work"/munge/munged.log; do [ -f "$f" ] && tail -n 5 "$f"; done
    exit 77
}

# munge: a fresh key and a socket of our own
mkdir -p "$work"/munge "$work"/spool "$work"/state "$work"/log "$work"/out "$work"/node
chmod 700 "$work"/munge
dd if=/dev/urandom of="$work"/munge/munge.key bs=1024 count=1 2>/dev/null
chmod 400 "$work"/munge/munge.key
munged --force --key-file="$work"/munge/munge.key --socket="$work"/munge/munge.socket \
    --pid-file="$work"/munge/munged.pid --log-file="$work"/munge/munged.log \
    --seed-file="$work"/munge/munged.seed || skip "munged did not start"

# slurm: one node (this host, all its CPUs), one partition, ports of this test
host=$(hostname -s)
port=$((20000 + $$ % 20000))
cat >"$work"/slurm.conf <<EOF
ClusterName=atmotest
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=600
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=atmo Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
slurmctld -c -i || skip "slurmctld did not start"
slurmd -c || skip "slurmd did not start"
for ((i = 0; i < 40; i++)); do
    sinfo -h -o %T 2>/dev/null | grep -qx idle && break
    sleep 0.5
done
sinfo -h -o %T 2>/dev/null | grep -qx idle || skip "the node did not come up"

# the single-process render, then the same scene in 4 parts through Slurm
scene=(--preset sky-sunset --width 64 --height 64 --samples 4 --set sun.zenith_deg=80 --set camera.pitch_deg=5)
"$atmo" render "${scene[@]}" --quiet --output "$work"/single.exr --output "$work"/single.pfm ||
    bad "single render failed"
export ATMO=$atmo ATMO_NODE_CACHE=$work/node
ids=$("$src"/tools/slurm/submit.sh 4 "$work"/out merged.exr,merged.pfm "${scene[@]}") ||
    bad "submit.sh failed"
read -r array merge <<<"$ids"
state() { scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sort -u | tr '\n' ' '; }
# until no task of the job is still waiting or running (an array job lists one state a task)
wait_job() {
    local i s
    for ((i = 0; i < 480; i++)); do
        s=$(state "$1")
        case $s in *PENDING* | *RUNNING* | *CONFIGURING* | *COMPLETING* | *SUSPENDED* | "") ;;
        *) return ;; esac
        sleep 0.5
    done
}
wait_job "$array"
wait_job "$merge"
[ "$(state "$array")" = "JobState=COMPLETED " ] && ok ||
    { bad "array job $array: $(state "$array")"; cat "$work"/out/part.*.log >&2; }
[ "$(state "$merge")" = "JobState=COMPLETED " ] && ok ||
    { bad "merge job $merge: $(state "$merge")"; cat "$work"/out/merge.log >&2; }
n=$(ls "$work"/out/part.*.exr 2>/dev/null | wc -l)
[ "$n" -eq 4 ] && ok || bad "$n part files, want 4"
# the jobs run in the submission directory ($work): the merged files land there
cmp -s single.exr merged.exr && ok || bad "merged .exr differs from the single render"
cmp -s single.pfm merged.pfm && ok || bad "merged .pfm differs from the single render"
[ -z "$(ls -A "$work"/node)" ] && ok || bad "tasks left cache directories: $(ls "$work"/node)"

# an animation: 2 tasks render frames 1 and 2 whole, sharing one kept cache on the node
anim=(--preset sky-sunset --width 32 --height 16 --samples 2 --frames 1..2 --animate sun.zenith_deg=40..60)
ids=$(ATMO_NODE_CACHE_SHARED=1 "$src"/tools/slurm/submit.sh 2 "$work"/frames sky.pfm "${anim[@]}") ||
    bad "submit.sh --frames failed"
read -r array merge <<<"$ids"
wait_job "$array"
[ "$(state "$array")" = "JobState=COMPLETED " ] && ok ||
    { bad "frames job $array: $(state "$array")"; cat "$work"/frames/frames.*.log >&2; }
[ "$merge" = - ] && ok || bad "a merge job ($merge) for an animation"
for f in 1 2; do
    "$atmo" render --preset sky-sunset --width 32 --height 16 --samples 2 --set sun.zenith_deg=$((20 + 20 * f)) \
        --quiet --output ref$f.pfm
    cmp -s ref$f.pfm "$work"/frames/sky.000$f.pfm && ok || bad "Slurm frame $f differs"
done
[ -d "$work"/node/atmo-cache ] && ok || bad "the shared node cache is not kept"

echo "test_slurm: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
