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
# folder. Exit status: 0 when every shard and the merge succeeded; the
# first failing shard's status (1 or 2) otherwise, and DIR/sweep.csv is
# not written; 2 on bad usage.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
S=${SHADESIM:-$here/bin/shadesim}
jobs= hosts=
while getopts j:S: opt; do
    case $opt in
        j) jobs=$OPTARG ;;
        S) hosts=$OPTARG ;;
        *) echo "usage: $0 [-j JOBS] [-S HOSTS] N DIR UNIT [SWEEP OPTIONS...]" >&2; exit 2 ;;
    esac
done
shift $((OPTIND - 1))
if [ $# -lt 3 ]; then
    echo "usage: $0 [-j JOBS] [-S HOSTS] N DIR UNIT [SWEEP OPTIONS...]" >&2; exit 2
fi
n=$1 dir=$2; shift 2
case $n in ''|*[!0-9]*|0) echo "sweep-parallel.sh: N must be a positive number, not '$n'" >&2; exit 2 ;; esac
command -v parallel >/dev/null 2>&1 || { echo "sweep-parallel.sh: GNU parallel is not installed (Debian package parallel)" >&2; exit 2; }
[ -x "$S" ] || { echo "sweep-parallel.sh: no shadesim at $S (make, or set SHADESIM)" >&2; exit 2; }
mkdir -p "$dir" || exit 2
# -q: each argument reaches shadesim as it is (no second word splitting);
# --halt now,fail=1: a failing shard stops the others, its status is ours.
set -- parallel --will-cite -q --halt now,fail=1 -j "${jobs:-$n}" ${hosts:+-S "$hosts"} \
    "$S" sweep "$@" --shard "{}/$n" -o "$dir" ::: $(seq 1 "$n")
"$@" || exit $?
set --
k=1
while [ "$k" -le "$n" ]; do set -- "$@" "$dir/sweep-$k-of-$n.csv"; k=$((k + 1)); done
"$S" merge "$@" -o "$dir/sweep.csv"
