#!/bin/sh
# make_gold.sh - the event-driven kernel's counters, one line per run, on
# stdout: every unit and schedule on its default vectors (as `list` names
# them), then a few configurations that overflow, so that the overflow
# counts are pinned too. Each line:
#   NAME events=E deltas=D runs=P clocks=C overflows=O discarded=X
# (NAME is UNIT.SCHEDULE[.what], E/D/P the kernel's signal value changes,
# delta cycles and process runs, C the rising clock edges, O and X the
# overflows on used and on discarded values; `run --json` has them all).
#
# usage: sh tests/gold/make_gold.sh SHADESIM ENGINE [overflows]
#   ENGINE --reference: `make gold` writes tests/gold/counters.txt so, from
#   the kernel's reference (no fast path); --kernel: tests/cli_gold.sh
#   holds the fast kernel to that file. A third word, overflows, makes the
#   overflowing runs alone (tests/cli_gold.sh holds the reference to them:
#   tests/cli_engine.sh compares it with the kernel on the others).
S=${1:?usage: make_gold.sh SHADESIM --reference|--kernel}
E=${2:-"--reference"}
case $E in --reference|--kernel) ;; *) echo "make_gold.sh: ENGINE is --reference or --kernel" >&2; exit 2;; esac
ONLY=${3:-}
case $ONLY in ''|overflows) ;; *) echo "make_gold.sh: the third word is overflows or nothing" >&2; exit 2;; esac

# NAME ARGS... per run
runs() {
    [ "${ONLY:-}" = overflows ] || every_schedule
    # overflows: wrapped, saturated, and some on values nobody takes
    echo "horner3.paper.mul=s3.12 horner3 --fmt mul=s3.12"
    echo "horner3.paper.mul=s3.12.sat horner3 --fmt mul=s3.12 --overflow sat"
    echo "interp3.paper.all=s4.11 interp3 --fmt all=s4.11"
}
every_schedule() {
    units=$("$S" list | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p')
    [ -n "$units" ] || { echo "make_gold.sh: $S list names no unit" >&2; exit 2; }
    for u in $units; do
        for sc in $("$S" list "$u" | sed -n 's/^  schedules: //p' | grep -oE '(^|, )[a-z0-9_-]+ \(' | tr -d ',( '); do
            echo "$u.$sc $u --schedule $sc"
        done
    done
}

echo "# The kernel's counters for every unit and schedule on its default vectors,"
echo "# and a few runs that overflow (tests/gold/make_gold.sh says what each field is)."
echo "# Made by \`make gold\` from the kernel's reference (run --reference: no fast"
echo "# path); tests/cli_gold.sh holds the fast kernel (run --kernel) to it."
runs | while read -r name args; do
    # shellcheck disable=SC2086  # args are words
    out=$("$S" run $args --json "$E" 2>&1); rc=$?
    if [ "$rc" -gt 1 ]; then echo "make_gold.sh: $name: exit $rc: $out" >&2; exit 2; fi
    # the counters, one awk a run (a sed per field made this test's time)
    printf '%s\n' "$out" | awk -v name="$name" '
        function field(line, key,   m) {
            if (!match(line, "\"" key "\": [0-9]+")) return ""
            m = substr(line, RSTART, RLENGTH); sub(/.*: /, "", m); return m
        }
        /^  "sim": / { sim = $0; ev = field($0, "events"); dc = field($0, "delta_cycles")
                       pr = field($0, "process_runs"); ck = field($0, "clocks") }
        /^  "overflows": [0-9]+,$/ { ov = field($0, "overflows") }
        /^  "overflows_discarded": [0-9]+,$/ { ox = field($0, "overflows_discarded") }
        END {
            if (ev == "" || dc == "" || pr == "" || ck == "" || ov == "" || ox == "") {
                print "make_gold.sh: " name ": no kernel counters in: " sim > "/dev/stderr"; exit 2
            }
            print name " events=" ev " deltas=" dc " runs=" pr " clocks=" ck " overflows=" ov " discarded=" ox
        }' || exit 2
done
