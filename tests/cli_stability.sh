#!/bin/sh
# cli_stability.sh - the stability verb from the outside: exit status, the
# table's header and rows, the same bytes on a second run, the JSON parses
# with a boundary per row, -o DIR writes the charts (well-formed SVG), bad
# arguments exit 2 with one line on stderr and nothing on stdout.
. tests/lib_cli.sh
PREFIX=cli_stability.
bad_args() {
    name=$1; shift
    "$S" stability "$@" >"$T/bad.out" 2>"$T/bad.err"
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$T/bad.err")" -eq 1 ] && [ ! -s "$T/bad.out" ]; then ok "$name"
    else fail "$name" "exit $rc, stderr: $(cat "$T/bad.err")"; fi
}

"$S" stability --help >"$T/help" 2>&1
rc=$?
check help test $rc -eq 0 -a "$(head -c 25 "$T/help")" = "usage: shadesim stability"

"$S" stability >"$T/text" 2>"$T/text.err"
check exit_0 [ $? -eq 0 -a -s "$T/text" ]
check quiet_stderr [ ! -s "$T/text.err" ]
check table_header grep -q '^method | condition | measured | verdict$' "$T/text"
rows=$(grep -c ' | .* | .* | ' "$T/text")
check rows_counted grep -q "^$((rows - 1)) rows$" "$T/text"
check rows_enough [ "$rows" -ge 16 ]
missing=""
for m in 'interp3 fwd' 'coef3_n1' 'coef3_n2' 'interp3 (cubic N1)' 'degree 2 vs 3 vs 1' 'div3 (paper series)' \
         'D16' 'Ward 16th power' 'modified Schlick' 'div (restoring)' 'pow_n (square and multiply)'; do
    grep -qF "$m | " "$T/text" || missing="$missing, $m"
done
check rows_present [ -z "$missing" ]
[ -n "$missing" ] && echo "  missing$missing"


"$S" stability >"$T/text2" 2>/dev/null
check deterministic cmp -s "$T/text" "$T/text2"

"$S" stability --json >"$T/json" 2>"$T/json.err"
check json_exit_0 [ $? -eq 0 -a -s "$T/json" ]
if command -v python3 >/dev/null 2>&1; then
    if python3 -c 'import json,sys; d=json.load(sys.stdin); r=d["rows"]; assert len(r) >= 15
assert all(x["method"] and x["verdict"] for x in r)
assert [x for x in r if x["id"] == "fwd3"][0]["boundary"] > 8' <"$T/json"; then ok json_parses
    else fail json_parses; fi
else echo "skip ${PREFIX}json_parses: python3 not installed"; fi

"$S" stability -o "$T/charts" >"$T/o.out" 2>"$T/o.err"
check charts_exit_0 [ $? -eq 0 ]
n=$(ls "$T/charts"/stability_*.svg 2>/dev/null | wc -l)
check charts_written [ "$n" -ge 8 ]
check charts_listed [ "$(grep -c '^wrote ' "$T/o.out")" -eq "$n" ]
# the charts --help names are the charts written (cli_outset takes a
# chart's name from --help)
grep -o 'stability_[a-z_0-9]*\.svg' "$T/help" | sort -u >"$T/help.names"
(cd "$T/charts" && ls stability_*.svg) | sort >"$T/written.names"
check charts_named_in_help cmp -s "$T/help.names" "$T/written.names"
check charts_no_temporaries [ "$(ls -A "$T/charts" | grep -vc '\.svg$')" -eq 0 ]
if command -v xmllint >/dev/null 2>&1; then
    bad=0
    for f in "$T/charts"/*.svg; do xmllint --noout "$f" 2>/dev/null || bad=1; done
    check charts_well_formed [ $bad -eq 0 ]
else echo "skip ${PREFIX}charts_well_formed: xmllint not installed"; fi
check chart_marks_boundary grep -q 'cubic boundary' "$T/charts/stability_fwd_err.svg"

bad_args bad_option --frobnicate
bad_args o_without_dir -o
: >"$T/afile"
bad_args o_is_a_file -o "$T/afile/sub"
if [ -w /dev/full ]; then
    "$S" stability >/dev/full 2>"$T/full.err"
    check stdout_write_error [ $? -eq 2 ]
fi
