#!/bin/sh
# sweep-parallel.sh - run one `shadesim sweep` as N shards with GNU parallel
# (on this machine, or over ssh hosts with -S) and merge the shards' rows
# into DIR/sweep.csv, the same bytes as the sweep run whole.
#
#   scripts/sweep-parallel.sh [-j JOBS] [-S HOSTS] N DIR UNIT [SWEEP OPTIONS...]
#
#   N      shards (shadesim sweep --shard K/N, K = 1..N)
#   DIR    output folder (on a file system every host shares, with -S)
#   -j     shards at once per host (default: N)
#   -S     GNU parallel's host list, e.g. host1,host2 (ssh; shadesim must
#          be at the same path there)
# The shadesim run is $SHADESIM, else bin/shadesim beside this script's
# folder. Exit status: 0 when every shard and the merge succeeded; 1 when
# some shard exited 1 (a row missed --max-error/--max-nmse/--max-lsb, or a
# configuration's simulation failed: data, in its rows) and the merge
# succeeded; a shard's status 2 or worse (bad usage, a crash) stops the
# others and is ours, and DIR/sweep.csv is not written; 2 on bad usage.
set -u
usage="usage: $0 [-j JOBS] [-S HOSTS] N DIR UNIT [SWEEP OPTIONS...]"
case ${1:-} in -h|--help)
    sed -n '2,/^set -u/p' "$0" | sed -e '/^set -u/d' -e 's/^# \{0,1\}//'
    exit 0 ;;
esac
here=$(cd "$(dirname "$0")/.." && pwd)
S=${SHADESIM:-$here/bin/shadesim}
jobs= hosts=
while getopts j:S: opt; do
    case $opt in
        j) jobs=$OPTARG ;;
        S) hosts=$OPTARG ;;
        *) echo "$usage" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 3 ]; then
    echo "$usage" >&2; exit 2
fi
n=$1 dir=$2; shift 2
case $n in ''|*[!0-9]*|0) echo "sweep-parallel.sh: N must be a positive number, not '$n'" >&2; exit 2 ;; esac
command -v parallel >/dev/null 2>&1 || { echo "sweep-parallel.sh: GNU parallel is not installed (Debian package parallel)" >&2; exit 2; }
[ -x "$S" ] || { echo "sweep-parallel.sh: no shadesim at $S (make, or set SHADESIM)" >&2; exit 2; }
mkdir -p "$dir" || exit 2
# -q: each argument reaches shadesim as it is (no second word splitting);
# --halt now,fail=1 is not used: a shard's exit 1 is data (a missed
# acceptance), so the others go on; the job log tells 1 from worse, and a
# status of 2 or more (or a signal) is ours, without a merge.
log=$dir/.parallel-joblog
set -- parallel --will-cite -q --joblog "$log" -j "${jobs:-$n}" ${hosts:+-S "$hosts"} \
    "$S" sweep "$@" --shard "{}/$n" -o "$dir" ::: $(seq 1 "$n")
"$@"
worst=$(awk 'NR > 1 { s = $7 + 0; if ($8 + 0) s = 128 + $8; if (s > w) w = s } END { print w + 0 }' "$log" 2>/dev/null)
rm -f "$log"
[ -n "$worst" ] || worst=2
[ "$worst" -ge 2 ] && exit "$worst"
set --
k=1
while [ "$k" -le "$n" ]; do set -- "$@" "$dir/sweep-$k-of-$n.csv"; k=$((k + 1)); done
"$S" merge "$@" -o "$dir/sweep.csv" || exit $?
exit "$worst"
