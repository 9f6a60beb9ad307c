#!/bin/sh
# Command-line contract of list, vectors and run (docs/cli.md): exit statuses,
# one-line errors naming file and line, no output left behind on bad input,
# the JSON fields and the CSV columns. One "ok/FAIL NAME" line per check.
PREFIX=cli_run.
. tests/lib_cli.sh

# expect NAME STATUS CMD...: exit status, and for status 2 exactly one
# stderr line starting "shadesim: ".
expect() {
    name=$1; want=$2; shift 2
    "$@" >"$T/out" 2>"$T/err"; got=$?
    if [ "$got" -ne "$want" ]; then fail "$name" "exit $got, expected $want: $(head -c 300 "$T/err")"; return; fi
    if [ "$want" -eq 2 ]; then
        n=$(wc -l <"$T/err")
        if [ "$n" -ne 1 ] || ! grep -q '^shadesim: ' "$T/err"; then fail "$name" "stderr not one 'shadesim:' line: $(cat "$T/err")"; return; fi
    fi
    ok "$name"
}

expect help 0 "$S" --help
expect no_verb 2 "$S"
expect bad_verb 2 "$S" frobnicate
for v in list vectors run; do expect "help_$v" 0 "$S" $v --help; done
expect list 0 "$S" list
for u in $("$S" list | grep -E '^[a-z0-9_]+ — ' | cut -d' ' -f1); do
    "$S" list "$u" >/dev/null 2>&1 && ok "list_$u" || fail "list_$u" "list $u failed"
done
expect list_unknown 2 "$S" list nosuch

# Bad usage.
expect run_no_unit 2 "$S" run
expect run_unknown 2 "$S" run nosuch
expect fmt_s0.0 2 "$S" run horner3 --fmt all=s0.0
expect fmt_s70.3 2 "$S" run horner3 --fmt all=s70.3
expect fmt_q1.15 2 "$S" run horner3 --fmt mul=q1.15
expect fmt_no_signal 2 "$S" run horner3 --fmt nosig=s2.14
expect fmt_no_eq 2 "$S" run horner3 --fmt s2.14
expect width_65 2 "$S" run horner3 --width 65
expect width_abc 2 "$S" run horner3 --width abc
expect round_bad 2 "$S" run horner3 --round up
expect overflow_bad 2 "$S" run horner3 --overflow clip
expect schedule_bad 2 "$S" run horner3 --schedule nosuch
expect param_bad 2 "$S" run horner3 --param nosuch=3
expect unknown_opt 2 "$S" run horner3 --bogus
expect vcd_no_file 2 "$S" run horner3 --vcd

# A good run, its JSON and CSV.
expect run_horner3 0 "$S" run horner3
"$S" run horner3 --json >"$T/r.json" 2>&1
for k in unit schedule formats round overflow vectors cycles cycles_per_item latency max_abs_err mean_err rms_err nmse max_err_lsb overflows area_ge; do
    grep -q "^  \"$k\": " "$T/r.json" && ok "json_$k" || fail "json_$k" "field $k missing"
done
if command -v python3 >/dev/null 2>&1; then
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["unit"]=="horner3" and d["cycles_per_item"]==6 and d["formats"]["mul"]' "$T/r.json" \
        && ok json_parses || fail json_parses "python3 could not read the JSON"
else
    echo "skip cli_run.json_parses: python3 not installed"
fi
"$S" run horner3 --out "$T/r.csv" >/dev/null 2>&1
head -1 "$T/r.csv" | grep -qx 'index,cycle,y_raw,y_real,y_expected,y_err' && ok csv_header || fail csv_header "$(head -1 "$T/r.csv")"
rows=$(($(wc -l <"$T/r.csv") - 1))
nvec=$(grep '"vectors"' "$T/r.json" | tr -dc 0-9)
[ "$rows" -eq "$nvec" ] && ok csv_rows || fail csv_rows "$rows rows for $nvec vectors"
# cycle column: pixel k appears at clock 6(k+1)
awk -F, 'NR>1 && $2 != 6*($1+1) {bad=1} END {exit bad}' "$T/r.csv" && ok csv_cycles || fail csv_cycles "cycle column is not 6(k+1)"

# The error bound: formats too narrow for the coefficients overflow, and
# the testbench says so with exit 1.
expect bound_exceeded 1 "$S" run horner3 --fmt all=s2.14

# Bad vector files: exit 2, the file and line named, no CSV left behind.
hdr='# shadesim vectors 1
# unit: horner3
# inputs: a b c d t
# outputs: y'
badfile() {   # badfile NAME LINE CONTENT
    printf '%s\n' "$3" >"$T/$1.vec"
    rm -f "$T/$1.csv"
    "$S" run horner3 --vectors "$T/$1.vec" --out "$T/$1.csv" >/dev/null 2>"$T/err"; st=$?
    if [ $st -ne 2 ]; then fail "badvec_$1" "exit $st"; return; fi
    if ! grep -q "$T/$1.vec:$2:" "$T/err" || [ "$(wc -l <"$T/err")" -ne 1 ]; then fail "badvec_$1" "message: $(cat "$T/err")"; return; fi
    if ls "$T" | grep -q "^$1.csv"; then fail "badvec_$1" "output file left behind"; return; fi
    ok "badvec_$1"
}
badfile columns 5 "$hdr
0.1 0.2 0.3 0.4 | 0.5"
badfile nonnumeric 6 "$hdr
0.1 0.2 0.3 0.4 0.5 | 0.5
0.1 zz 0.3 0.4 0.5 | 0.5"
badfile nan 5 "$hdr
0.1 nan 0.3 0.4 0.5 | 0.5"
badfile inf 5 "$hdr
0.1 0.2 0.3 inf 0.5 | 0.5"
badfile otherunit 2 '# shadesim vectors 1
# unit: div3
# inputs: x
# outputs: y
0.5 | 0.1666'
badfile empty 4 "$hdr"
printf '# shadesim vectors 1\n# unit: horner3\n\001\002\377binary\n' >"$T/junk.vec"
"$S" run horner3 --vectors "$T/junk.vec" >/dev/null 2>"$T/err"; st=$?
[ $st -eq 2 ] && grep -q "junk.vec:3:" "$T/err" && ok badvec_binary || fail badvec_binary "exit $st: $(cat "$T/err")"
expect badvec_missing 2 "$S" run horner3 --vectors "$T/does-not-exist.vec"

# Unwritable outputs: exit 2, nothing half-written.
expect csv_unwritable 2 "$S" run horner3 --out /nonexistent/dir/x.csv
expect vcd_unwritable 2 "$S" run horner3 --vcd /nonexistent/dir/x.vcd

# VCD and its GTKWave save file.
"$S" run horner3 --vcd "$T/h.vcd" >/dev/null 2>&1 && [ -s "$T/h.vcd" ] && [ -s "$T/h.vcd.gtkw" ] && ok vcd_written || fail vcd_written "no VCD or .gtkw"
grep -q '^\$var wire [0-9]* [^ ]* rg ' "$T/h.vcd" && ok vcd_has_rg || fail vcd_has_rg "rg not declared"
if command -v vcd2fst >/dev/null 2>&1; then
    vcd2fst "$T/h.vcd" "$T/h.fst" >/dev/null 2>&1 && ok vcd2fst_accepts || fail vcd2fst_accepts "vcd2fst rejected the dump"
else
    echo "skip cli_run.vcd2fst_accepts: vcd2fst not installed"
fi

# The checked-in default vectors are what the reference generates today.
for f in vectors/*.vec; do
    [ -f "$f" ] || continue
    u=$(basename "$f" .vec)
    "$S" vectors "$u" >"$T/v.vec" 2>"$T/err" && cmp -s "$T/v.vec" "$f" && ok "default_vectors_$u" \
        || fail "default_vectors_$u" "shadesim vectors $u differs from $f (make vectors regenerates)"
done
expect vectors_bad_n 2 "$S" vectors horner3 -n -5
expect vectors_no_unit 2 "$S" vectors
"$S" vectors horner3 -n 10 --seed 3 -o "$T/v10.vec" && [ "$(grep -vc '^#' "$T/v10.vec")" -eq 10 ] && ok vectors_n || fail vectors_n "-n 10 did not give 10 rows"
# run -n N --seed S: the vectors `vectors -n N --seed S` writes, run as if read
# from that file (the same JSON, the file's name being in none of it)
"$S" run horner3 -n 10 --seed 3 --json >"$T/rn.json" 2>"$T/err" \
    && "$S" run horner3 --vectors "$T/v10.vec" --json >"$T/rf.json" 2>>"$T/err" && cmp -s "$T/rn.json" "$T/rf.json" \
    && grep -q '"vectors": 10,' "$T/rn.json" && ok run_n_equals_file || fail run_n_equals_file "$(head -c 300 "$T/err")"
expect run_n_and_vectors 2 "$S" run horner3 -n 10 --vectors "$T/v10.vec"
expect run_seed_without_n 2 "$S" run horner3 --seed 4
expect run_n_zero 2 "$S" run horner3 -n 0

# docs/units.md is generated from the same descriptors (make docs).
"$S" list --markdown >"$T/units.md" 2>&1 && cmp -s "$T/units.md" docs/units.md && ok docs_units_current \
    || fail docs_units_current "docs/units.md differs from shadesim list --markdown (make docs regenerates)"
