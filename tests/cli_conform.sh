#!/bin/sh
# cli_conform.sh - every unit `shadesim list` names (the registry:
# unit_count / unit_at) conforms through the command line, with nothing to
# add here for a new unit: run on the head of its default vectors exits 0
# (verdict ok) and its VCD is one GTKWave's vcd2fst accepts (plain build
# only), an unknown --fmt name exits 2 with one line, and its entry in
# docs/units.md is the one `list --markdown` writes today.
# tests/test_conform.c checks the descriptors, builds and bounds in C.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_conform.

units=$("$S" list | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p')
check units_listed [ "$(echo $units | wc -w)" -ge 20 ]

plain=1
case "${TST_BUILD:-}" in *-asan) plain=0 ;; esac
have_fst=0
command -v vcd2fst >/dev/null 2>&1 && have_fst=1

"$S" list --markdown >"$T/units.md" 2>"$T/err" || fail list_markdown "$(cat "$T/err")"

# vcd2fst converts the dump (its messages kept out of the log).
fst_ok() { vcd2fst "$1" "$2" >/dev/null 2>&1 && [ -s "$2" ]; }

# A unit's section of a units.md: from its heading to the next one.
section() { awk -v h="## $1" '/^## / { on = ($0 == h) } on' "$2"; }

for u in $units; do
    # The head of the default vectors: the 4 header lines and 12 items.
    head -n 16 "vectors/$u.vec" >"$T/$u.vec"
    expect "${u}_runs_within_bound" 0 "$S" run "$u" --vectors "$T/$u.vec" --vcd "$T/$u.vcd"
    if [ $plain = 0 ]; then
        echo "skip ${PREFIX}${u}_vcd2fst: runs in the plain build only"
    elif [ $have_fst = 0 ]; then
        echo "skip ${PREFIX}${u}_vcd2fst: vcd2fst not installed"
    else
        check "${u}_vcd2fst" fst_ok "$T/$u.vcd" "$T/$u.fst"
    fi
    expect "${u}_fmt_unknown_name" 2 "$S" run "$u" --vectors "$T/$u.vec" --fmt no_such_signal=s4.8
    # The docs entry: its section of docs/units.md is today's.
    section "$u" docs/units.md >"$T/doc_$u"
    section "$u" "$T/units.md" >"$T/new_$u"
    if [ -s "$T/new_$u" ] && cmp -s "$T/doc_$u" "$T/new_$u"; then ok "${u}_docs_current"
    else fail "${u}_docs_current" "docs/units.md's entry differs from shadesim list --markdown (make docs)"; fi
    rm -f "$T/$u.vcd" "$T/$u.vcd.gtkw" "$T/$u.fst"
done
