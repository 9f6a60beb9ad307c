#!/bin/sh
# cli_fmtmodes.sh - a format's own rounding and overflow modes on the
# command line: --fmt NAME=sI.F:ROUND:OVERFLOW is taken by run, sweep,
# verilog and scene --set fmt=..., printed back as given, and a bad mode
# text is exit 2 with one line naming the option and the problem.
PREFIX=cli_fmtmodes.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)

# refused NAME WHAT ARGS...: exit 2, one stderr line containing WHAT.
refused() {
    name=$1; what=$2; shift 2
    expect "$name" 2 "$S" "$@" || return
    grep -qF -- "$what" "$T/err" || fail "$name.message" "stderr lacks '$what': $(cat "$T/err")"
}
refused bad_mode "--fmt mul=s7.12:foo: bad format 's7.12:foo': unknown mode 'foo'" run horner3 --fmt mul=s7.12:foo
refused mode_twice "--fmt mul=s7.12:sat:sat: bad format 's7.12:sat:sat': overflow mode given twice" run horner3 --fmt mul=s7.12:sat:sat
refused empty_mode "--fmt mul=s7.12:: bad format 's7.12:': empty mode" run horner3 --fmt mul=s7.12:
refused two_roundings "rounding mode given twice" run horner3 --fmt mul=s7.12:half-up:even
refused sweep_bad_mode "--fmt mul=s7.9:wrapp" sweep horner3 --widths 16 -n 4 --fmt mul=s7.9:wrapp -o "$T/sw"
refused verilog_bad_mode "--fmt y=s7.9:" verilog horner3 --fmt y=s7.9: -o "$T/v"
refused scene_bad_mode 'fmt: "mul=s7.9:foo": unknown mode' scene sphere --set fmt=mul=s7.9:foo -o "$T/sc"
refused own_logic "--fmt rec=u1.15:half-up: unit hf_lookup computes signal rec" run hf_lookup --fmt rec=u1.15:half-up

# Taken, and printed back in the order ROUND then OVERFLOW, whatever the
# order given; the other signals print as plain formats.
expect run_json 0 "$S" run horner3 --round half-up --fmt mul=s7.9:sat:half-up --json
check run_json_fmt grep -q '"mul": "s7.9:half-up:sat", "mx2": "s7.9"' "$T/out"
expect run_text 0 "$S" run horner3 --fmt mul=s7.9:sat
check run_text_fmt grep -q ' mul=s7.9:sat mx2=s7.9 ' "$T/out"

# The table's format column widens to a format with modes: each number
# ends where its header ends (the output row and the overflowed-signal row).
aligned() {   # FILE HEADER_START: the header's max|e| column ends where the next row's 3rd field does
    awk -v h="$2" 'index($0, h) == 1 { e = index($0, "max|e|") + 5; if (e == 5) e = index($0, "overflows") + 8; getline;
        n = split($0, f, " +"); p = index($0, " " f[3] " ") + length(f[3]); ok = p == e } END { exit !ok }' "$1"
}
expect long_fmt_out 1 "$S" run horner3 --fmt y=s7.9:half-up:sat
check long_fmt_out_aligned aligned "$T/out" output
expect long_fmt_ovf 1 "$S" run horner3 --fmt a=s2.9:trunc:sat
check long_fmt_ovf_aligned aligned "$T/out" "signal (overflowed)"

# A rounding mode other than --round on a signal: the unit's bound assumes
# one mode throughout, so none is claimed (exit 1, "NO BOUND"); the same
# mode as --round keeps the bound.
expect no_bound 1 "$S" run horner3 --fmt mul=s7.9:half-up
check no_bound_said grep -q 'NO BOUND' "$T/out"
expect same_mode_bound 0 "$S" run horner3 --round half-up --fmt mul=s7.9:half-up

# Every signal given :half-up under trunc gives the raws of --round half-up.
expect global_csv 0 "$S" run horner3 --round half-up --out "$T/g.csv"
args=""
for s in a b c d y mx1 mul mx2 bk sm rg; do args="$args --fmt $s=s7.9:half-up"; done
expect per_signal_csv 1 "$S" run horner3 $args --fmt t=u1.15:half-up --out "$T/p.csv"
check per_signal_equals_global cmp -s "$T/g.csv" "$T/p.csv"
expect trunc_csv 0 "$S" run horner3 --out "$T/t.csv"
check trunc_differs sh -c "! cmp -s '$T/g.csv' '$T/t.csv'"

# sweep pins the format with its modes; the CSV's format column says so
expect sweep 0 "$S" sweep horner3 --widths 12:13 -n 8 --round half-up --fmt mul=s7.9:half-up:sat -o "$T/sw"
check sweep_csv grep -q ',s7.9:half-up:sat,' "$T/sw/sweep.csv"

# scene files and --set take the same text
expect scene 0 "$S" scene sphere --set resolution=32x32 --set fmt=mul=s7.9:sat -o "$T/sc"
check scene_json grep -q '"mul": "s7.9:sat"' "$T/sc/scene.json"
