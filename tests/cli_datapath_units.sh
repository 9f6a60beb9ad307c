#!/bin/sh
# Every built-in unit as a datapath file (netlist UNIT --datapath,
# docs/datapaths.md): for every unit and schedule at widths 16 and 12, the
# file netlist writes gives, through run FILE, the JSON of run UNIT byte
# for byte (the kernel's counters at 16, the batch's lanes at 12); a file
# whose formats follow the width (rules of W) gives the unit's at the other
# width too. In tests/slow.list (some 200 processes).
PREFIX=cli_datapath_units.
. tests/lib_cli.sh

units_and_schedules >"$T/units"
check units_listed [ "$(wc -l <"$T/units")" -ge 20 ]
case "${TST_BUILD:-}" in *-asan) echo 'horner3: paper mac' >"$T/units" ;; esac

cases=0 rows=0 rules=0 bad=
while IFS=: read -r u scheds; do
    for s in $scheds; do
        for w in 16 12; do
            c=$u-$s-$w
            "$S" run "$u" --schedule "$s" --width $w >/dev/null 2>&1 || continue   # outside the unit's widths
            cases=$((cases + 1))
            "$S" netlist "$u" --schedule "$s" --width $w --datapath -o "$T/$c.dp" 2>"$T/err" \
                || { bad="$bad [$c: netlist: $(cat "$T/err")]"; continue; }
            opt=; [ $w = 16 ] && opt=--kernel
            "$S" run "$u" --schedule "$s" --width $w --json $opt >"$T/a.json" 2>&1
            "$S" run "$T/$c.dp" --json $opt >"$T/b.json" 2>&1
            cmp -s "$T/a.json" "$T/b.json" || bad="$bad [$c: $(diff "$T/a.json" "$T/b.json" | head -c 200)]"
            grep -q '^ctl ' "$T/$c.dp" && rows=$((rows + 1))
            # a file of rules: the other width from the same file
            if grep -q '^[a-z]* [a-z_0-9.]* [su][^ ]*W' "$T/$c.dp"; then
                rules=$((rules + 1))
                o=12; [ $w = 12 ] && o=16
                "$S" run "$u" --schedule "$s" --width $o --json >"$T/a.json" 2>&1
                "$S" run "$T/$c.dp" --width $o --json >"$T/b.json" 2>&1
                cmp -s "$T/a.json" "$T/b.json" || bad="$bad [$c at $o: $(diff "$T/a.json" "$T/b.json" | head -c 200)]"
            fi
        done
    done
done <"$T/units"
check round_trip_every_unit_and_schedule [ -z "$bad" -a $cases -ge 2 ]
[ -n "$bad" ] && echo "  $bad" | head -c 2000 && echo
echo "  $cases designs, $rows with schedule rows, $rules with rules of W"
