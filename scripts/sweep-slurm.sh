#!/bin/sh
# sweep-slurm.sh - submit one `shadesim sweep` as a Slurm job array of N
# shards (scripts/sweep.slurm), wait for it, and merge the shards into
# DIR/sweep.csv: the same bytes as the sweep run whole.
#
#   scripts/sweep-slurm.sh [-c CPUS] [-t TIME] [-p PARTITION] N DIR UNIT [SWEEP OPTIONS...]
#
#   -c  CPUs per task (default 2; each shard runs with -j CPUS)
#   -t  time limit per task (default 00:10:00)
#   -p  partition (default: the cluster's default)
# DIR must be on a file system the nodes share; task logs go to
# DIR/logs/. Exit status: 0 when every task and the merge succeeded; 1
# when some task exited 1 (a row missed --max-error/--max-nmse/--max-lsb,
# or a configuration's simulation failed: data, in its rows) and the merge
# of every shard succeeded; a task's status 2 or worse (sbatch --wait
# gives the highest of the array) is ours, and DIR/sweep.csv is not
# written; 2 on bad usage.
set -u
usage="usage: $0 [-c CPUS] [-t TIME] [-p PARTITION] N DIR UNIT [SWEEP OPTIONS...]"
case ${1:-} in -h|--help)
    sed -n '2,/^set -u/p' "$0" | sed -e '/^set -u/d' -e 's/^# \{0,1\}//'
    exit 0 ;;
esac
here=$(cd "$(dirname "$0")/.." && pwd)
S=${SHADESIM:-$here/bin/shadesim}
cpus=2 tlim=00:10:00 part=
while getopts c:t:p: opt; do
    case $opt in
        c) cpus=$OPTARG ;;
        t) tlim=$OPTARG ;;
        p) part=$OPTARG ;;
        *) echo "$usage" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 3 ]; then
    echo "$usage" >&2; exit 2
fi
n=$1 dir=$2; shift 2
case $n in ''|*[!0-9]*|0) echo "sweep-slurm.sh: N must be a positive number, not '$n'" >&2; exit 2 ;; esac
command -v sbatch >/dev/null 2>&1 || { echo "sweep-slurm.sh: sbatch not found (Debian package slurm-client)" >&2; exit 2; }
[ -x "$S" ] || { echo "sweep-slurm.sh: no shadesim at $S (make, or set SHADESIM)" >&2; exit 2; }
mkdir -p "$dir/logs" || exit 2
dir=$(cd "$dir" && pwd)
SHADESIM=$S sbatch --wait --array="1-$n" --cpus-per-task="$cpus" --time="$tlim" ${part:+--partition="$part"} \
    --output="$dir/logs/sweep-%A_%a.log" --export=ALL,SHADESIM="$S" \
    "$here/scripts/sweep.slurm" "$n" "$dir" "$@" >/dev/null
worst=$?
[ "$worst" -ge 2 ] && exit "$worst"
set --
k=1
while [ "$k" -le "$n" ]; do set -- "$@" "$dir/sweep-$k-of-$n.csv"; k=$((k + 1)); done
# A task that died (a signal gives 1 too) left no shard: merge says so.
"$S" merge "$@" -o "$dir/sweep.csv" || exit $?
exit "$worst"
