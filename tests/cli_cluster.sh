#!/bin/sh
# Sweeps on cluster tools: scripts/sweep-parallel.sh with GNU parallel, and
# scripts/sweep-slurm.sh against a one-node Slurm this test starts (munged,
# slurmctld and slurmd on localhost, in a temporary folder, stopped on
# exit). Each merges 2 shards; the merged CSV must be byte for byte the
# sweep run whole on this machine. Skipped (with the reason) in the ASan
# build, without the tools, when not root, or when Slurm does not come up.
PREFIX=cli_cluster.
. tests/lib_cli.sh

SWEEP="horner3 --widths 8:11 --round trunc,even"
case "${TST_BUILD:-}" in *-asan)
    echo "skip cli_cluster.parallel_merge_equals_whole: runs in the plain build only"
    echo "skip cli_cluster.slurm_merge_equals_whole: runs in the plain build only"
    exit 0 ;;
esac
S=$(cd "$(dirname "$S")" && pwd)/$(basename "$S")
export SHADESIM="$S"
# shellcheck disable=SC2086
"$S" sweep $SWEEP -o "$T/whole" >/dev/null 2>&1 || fail whole_sweep "the single-machine sweep failed"

# --- GNU parallel -----------------------------------------------------------
if ! command -v parallel >/dev/null 2>&1; then
    echo "skip cli_cluster.parallel_merge_equals_whole: parallel not installed (Debian package parallel)"
else
    # shellcheck disable=SC2086
    if timeout 120 scripts/sweep-parallel.sh 2 "$T/par" $SWEEP >"$T/par.log" 2>&1 \
        && [ -f "$T/par/sweep-1-of-2.csv" ] && [ -f "$T/par/sweep-2-of-2.csv" ] \
        && cmp -s "$T/par/sweep.csv" "$T/whole/sweep.csv"; then
        ok parallel_merge_equals_whole
    else fail parallel_merge_equals_whole "$(tail -3 "$T/par.log")"; fi
    # a missed acceptance is data: every shard runs, the merge is written,
    # the same bytes as the whole sweep's CSV, and the status is 1
    # shellcheck disable=SC2086
    "$S" sweep $SWEEP --max-error 0.05 -o "$T/wholeacc" >/dev/null 2>&1
    # shellcheck disable=SC2086
    timeout 120 scripts/sweep-parallel.sh 2 "$T/paracc" $SWEEP --max-error 0.05 >"$T/paracc.log" 2>&1
    rc=$?
    if [ $rc -eq 1 ] && cmp -s "$T/paracc/sweep.csv" "$T/wholeacc/sweep.csv"; then ok parallel_missed_target_is_data
    else fail parallel_missed_target_is_data "exit $rc; $(tail -2 "$T/paracc.log" | tr '\n' ' ')"; fi
    # a failing shard fails the script and leaves no merged CSV
    if scripts/sweep-parallel.sh 2 "$T/parbad" horner3 --widths 8:11 --no-such-option >/dev/null 2>&1; then
        fail parallel_shard_failure "exit 0"
    elif [ -e "$T/parbad/sweep.csv" ]; then fail parallel_shard_failure "sweep.csv written"
    else ok parallel_shard_failure; fi
fi

# Both scripts explain themselves.
for sc in sweep-parallel sweep-slurm; do
    if sh "scripts/$sc.sh" --help >"$T/help" 2>&1 && grep -q "^usage\|^  scripts/$sc.sh" "$T/help" \
        && grep -q "Exit status" "$T/help"; then ok "${sc}_help"
    else fail "${sc}_help" "$(head -2 "$T/help")"; fi
done

# --- Slurm ------------------------------------------------------------------
slurm_skip() { echo "skip cli_cluster.slurm_merge_equals_whole: $1"; exit 0; }
[ "$(id -u)" = 0 ] || slurm_skip "needs root to start slurmctld and slurmd"
for t in munged slurmctld slurmd sbatch sinfo; do
    command -v $t >/dev/null 2>&1 || slurm_skip "$t not installed (Debian packages slurm-wlm and munge)"
done
D=$T/slurm
mkdir -p "$D/state" "$D/spool" "$D/log" && chmod 700 "$D"
pids=
cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null; done
    [ -f "$D/munged.pid" ] && kill "$(cat "$D/munged.pid")" 2>/dev/null
    sleep 0.2
    rm -rf "$T"
}
trap cleanup EXIT
# the munge key: 1 KiB of random bytes (what mungekey makes)
if command -v mungekey >/dev/null 2>&1; then mungekey -c -k "$D/munge.key" -b 1024 >/dev/null 2>&1
else dd if=/dev/urandom of="$D/munge.key" bs=1024 count=1 2>/dev/null; fi
chmod 600 "$D/munge.key"
munged -f --socket="$D/munge.sock" --key-file="$D/munge.key" --log-file="$D/log/munged.log" \
    --pid-file="$D/munged.pid" --seed-file="$D/munged.seed" >/dev/null 2>&1 \
    || slurm_skip "munged did not start: $(tail -1 "$D/log/munged.log" 2>/dev/null)"
# ports of our own (not the standard 6817/6818 a real Slurm may hold)
base=$((20000 + $$ % 20000))
cat >"$D/slurm.conf" <<EOF
ClusterName=shadesimtest
SlurmctldHost=localhost
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge.sock
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=localhost CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$D/slurm.conf"
slurmctld -D -f "$SLURM_CONF" >"$D/log/slurmctld.out" 2>&1 &
pids="$pids $!"
slurmd -D -N localhost -f "$SLURM_CONF" >"$D/log/slurmd.out" 2>&1 &
pids="$pids $!"
up=0 i=0
while [ $i -lt 60 ]; do
    state=$(timeout 5 sinfo -h -o %T 2>/dev/null)
    case $state in idle*|mixed*|alloc*) up=1; break ;; esac
    sleep 0.5; i=$((i + 1))
done
if [ $up -ne 1 ]; then
    slurm_skip "Slurm did not come up in 30 s (sinfo: '$state'); slurmctld log: $(tail -2 "$D/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
fi
start=$(date +%s)
# shellcheck disable=SC2086
if timeout 120 scripts/sweep-slurm.sh -c 1 -t 00:05:00 2 "$D/out" $SWEEP >"$D/submit.log" 2>&1 \
    && [ "$(ls "$D/out/logs" | wc -l)" -eq 2 ] && cmp -s "$D/out/sweep.csv" "$T/whole/sweep.csv"; then
    ok slurm_merge_equals_whole
    echo "  (slurm: 2 array tasks and the merge in $(( $(date +%s) - start )) s)"
else
    fail slurm_merge_equals_whole "$(tail -3 "$D/submit.log" | tr '\n' ' ') logs: $(ls "$D/out/logs" 2>/dev/null | tr '\n' ' ') $(tail -2 "$D/log/slurmd.log" | tr '\n' ' ')"
fi
