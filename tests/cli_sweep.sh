#!/bin/sh
# cli_sweep.sh - the sweep and merge verbs from the outside: the CSV is the
# same bytes for -j 1, -j 2 and merged shards, and for -n's vectors
# streamed and the same rows held; bad arguments exit 2 with one line; the
# files are there and no temporaries are left.
# One line per check: "ok NAME", "FAIL NAME" or "skip NAME: why".
. tests/lib_cli.sh

# Small and quick, but with two axes so that order and shards matter.
ARGS="horner3 --widths 8:20 --round trunc,half-up --overflow wrap,sat"

"$S" sweep $ARGS -j 1 -o "$T/j1" >"$T/j1.out" 2>"$T/j1.err"
check sweep_runs [ $? -eq 0 ]
check sweep_quiet_stderr_when_not_a_tty [ ! -s "$T/j1.err" ]
"$S" sweep $ARGS -j 2 -o "$T/j2" >/dev/null 2>&1
check sweep_j2_same_csv cmp -s "$T/j1/sweep.csv" "$T/j2/sweep.csv"
rows=$(($(wc -l <"$T/j1/sweep.csv") - 1))
check sweep_one_row_per_configuration [ "$rows" -eq 52 ]
check sweep_writes_charts_and_summary \
    [ -s "$T/j1/error_vs_width.svg" -a -s "$T/j1/area_vs_error.svg" -a -s "$T/j1/summary.txt" ]
check sweep_no_cycles_chart_when_cycles_are_constant [ ! -e "$T/j1/cycles_vs_error.svg" ]
check sweep_leaves_no_temporaries [ -z "$(ls "$T/j1" | grep -v -e '\.csv$' -e '\.svg$' -e '\.txt$')" ]

for n in 2 3; do
    k=1
    while [ $k -le $n ]; do
        "$S" sweep $ARGS -j 2 --shard $k/$n -o "$T/sh$n" >/dev/null 2>&1 || fail "sweep_shard_${k}_of_$n"
        k=$((k + 1))
    done
    # Given in reverse order on purpose: merge sorts.
    "$S" merge $(ls "$T/sh$n"/sweep-*-of-$n.csv | sort -r) -o "$T/merged$n.csv" 2>"$T/m.err"
    check "merge_${n}_shards_exit_0" [ $? -eq 0 ]
    check "merge_${n}_shards_same_csv_as_whole_run" cmp -s "$T/merged$n.csv" "$T/j1/sweep.csv"
done

# merge refuses a missing shard, a shard twice, another sweep's shard.
"$S" merge "$T/sh3/sweep-1-of-3.csv" "$T/sh3/sweep-2-of-3.csv" -o "$T/bad.csv" 2>"$T/e"
check merge_missing_shard_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 -a ! -e "$T/bad.csv" ]
"$S" merge "$T/sh3/sweep-1-of-3.csv" "$T/sh3/sweep-1-of-3.csv" "$T/sh3/sweep-2-of-3.csv" "$T/sh3/sweep-3-of-3.csv" \
    -o "$T/bad.csv" 2>"$T/e"
check merge_duplicate_rows_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 -a ! -e "$T/bad.csv" ]
"$S" sweep horner3 --widths 8:20 --shard 2/2 -o "$T/other" >/dev/null 2>&1
"$S" merge "$T/sh2/sweep-1-of-2.csv" "$T/other/sweep-2-of-2.csv" -o "$T/bad.csv" 2>"$T/e"
check merge_other_sweep_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 ]
"$S" merge "$T/j1/summary.txt" -o "$T/bad.csv" 2>"$T/e"
check merge_not_a_sweep_csv_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 ]

# -n streams its vectors (each configuration generates them a block at a
# time: 40000 rows are three blocks), and so does a --vectors file (read a
# block at a time); the same rows held (from stdin, read once) give the
# same CSV and summary, fingerprint included.
"$S" sweep horner3 --widths 12:13 -n 40000 --seed 7 -j 2 -o "$T/st" >/dev/null 2>&1
check sweep_streamed_runs [ $? -eq 0 ]
"$S" vectors horner3 -n 40000 --seed 7 -o "$T/st.vec" 2>/dev/null
"$S" sweep horner3 --widths 12:13 --vectors "$T/st.vec" -j 2 -o "$T/sf" >/dev/null 2>&1
"$S" sweep horner3 --widths 12:13 --vectors - -j 2 -o "$T/held" <"$T/st.vec" >/dev/null 2>&1
check sweep_streamed_same_csv_as_held cmp -s "$T/st/sweep.csv" "$T/held/sweep.csv"
check sweep_streamed_same_summary_as_held cmp -s "$T/st/summary.txt" "$T/held/summary.txt"
check sweep_file_streamed_same_csv_as_held cmp -s "$T/sf/sweep.csv" "$T/held/sweep.csv"
# a bad row far into a streamed file: one line naming it, exit 2, before
# any folder is made
{ cat "$T/st.vec"; echo "1 2 x 4 5 | 6"; } >"$T/bad.vec"
"$S" sweep horner3 --widths 12:13 --vectors "$T/bad.vec" -o "$T/badout" >/dev/null 2>"$T/e"
check sweep_file_streamed_bad_row_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 ]
check sweep_file_streamed_bad_row_named grep -q "bad.vec:40005: " "$T/e"
check sweep_file_streamed_bad_nothing_written [ ! -e "$T/badout" ]

# The target search writes target.json and a summary line (with a margin
# of one bit its result passes the held-out check: exit 0).
"$S" sweep horner3 --widths 8:24 --target-error 1e-2 --margin 1 -j 2 -o "$T/tg" >"$T/tg.out" 2>&1
check sweep_target_exit_0 [ $? -eq 0 ]
check sweep_target_json [ -s "$T/tg/target.json" ]
check sweep_target_summary_line grep -q '^target max |e| <= 0.01: uniform width [0-9]*:.*saving' "$T/tg/summary.txt"
if grep -q '"met": true' "$T/tg/target.json"; then ok sweep_target_met; else fail sweep_target_met; fi
# A later sweep without a target into the same folder removes the stale one.
"$S" sweep horner3 --widths 8:10 -o "$T/tg" >/dev/null 2>&1
check sweep_removes_stale_target_json [ ! -e "$T/tg/target.json" ]

# Bad arguments: exit 2, one line on stderr starting "shadesim: ".
bad() {   # bad NAME ARGS...
    name=$1; shift
    "$S" "$@" >"$T/o" 2>"$T/e"
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$T/e")" -eq 1 ] && grep -q '^shadesim: ' "$T/e" && [ ! -s "$T/o" ]; then
        ok "$name"
    else
        fail "$name" "exit $rc, stderr: $(cat "$T/e")"
    fi
}
bad sweep_bad_widths_reversed sweep horner3 --widths 9:3 -o "$T/x"
bad sweep_bad_widths_text sweep horner3 --widths abc -o "$T/x"
bad sweep_bad_widths_range sweep horner3 --widths 0:70 -o "$T/x"
bad sweep_bad_widths_missing sweep horner3 -o "$T/x"
bad sweep_bad_shard_k_over_n sweep horner3 --widths 8:9 --shard 3/2 -o "$T/x"
bad sweep_bad_shard_zero sweep horner3 --widths 8:9 --shard 0/2 -o "$T/x"
bad sweep_bad_shard_text sweep horner3 --widths 8:9 --shard two -o "$T/x"
bad sweep_bad_unit sweep nosuchunit --widths 8:9 -o "$T/x"
bad sweep_bad_round sweep horner3 --widths 8:9 --round trunc,up -o "$T/x"
bad sweep_bad_threads sweep horner3 --widths 8:9 -j 0 -o "$T/x"
bad sweep_bad_option sweep horner3 --widths 8:9 --frobnicate -o "$T/x"
bad sweep_bad_target sweep horner3 --widths 8:9 --target-error abc -o "$T/x"
bad sweep_target_with_shard sweep horner3 --widths 8:9 --target-error 1e-3 --shard 1/2 -o "$T/x"
check sweep_bad_arguments_write_nothing [ ! -e "$T/x" ]
: >"$T/afile"
bad sweep_unwritable_output_folder sweep horner3 --widths 8:9 -o "$T/afile/sub"
bad merge_no_output merge "$T/j1/sweep.csv"
bad merge_no_input merge -o "$T/x.csv"
bad merge_missing_file merge "$T/nonexistent.csv" -o "$T/x.csv"

"$S" sweep --help >"$T/h" 2>&1
check sweep_help [ $? -eq 0 -a "$(head -1 "$T/h" | cut -c1-21)" = "usage: shadesim sweep" ]
"$S" merge --help >"$T/h" 2>&1
check merge_help [ $? -eq 0 -a "$(head -1 "$T/h" | cut -c1-21)" = "usage: shadesim merge" ]
# A target no width meets: the files are written, target.json says
# "met": false, and the run exits 1 (docs/cli.md's rule for every
# --target-*; it exited 0).
"$S" sweep horner3 --widths 8:10 --target-error 1e-9 -o "$T/miss" >"$T/miss.out" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q '"met": false' "$T/miss/target.json" && [ -s "$T/miss/sweep.csv" ] && ok target_missed_exit_1 \
    || fail target_missed_exit_1 "exit $rc: $(grep -c '"met": false' "$T/miss/target.json" 2>&1) $(tail -2 "$T/miss.out")"
# The price of a halving of the error along the front, against the CSV: two
# widths of div (both on the front) give area difference / log2(error ratio);
# a front whose error hardly falls (an output format of 6 fraction bits
# holds horner3 at about 4) quotes no price: its quotient was billions of GE.
"$S" sweep div --widths 8:9 -o "$T/half" >"$T/half.out" 2>&1
want=$(awk -F, 'NR == 2 { e0 = $16; a0 = $22 } NR == 3 { e1 = $16; a1 = $22 }
    END { printf "halving max |e| costs %.0f GE on average", (a1 - a0) / (log(e0 / e1) / log(2)) }' "$T/half/sweep.csv")
check sweep_price_of_a_halving_from_the_csv grep -qF "$want" "$T/half.out"
"$S" sweep horner3 --widths 14:15 --fmt y=s2.6 -o "$T/flat" >"$T/flat.out" 2>&1
check sweep_no_price_when_error_hardly_falls sh -c "grep -q 'falls only from 4.022 to 4.007 (less than a tenth of a halving)' '$T/flat.out' && ! grep -q 'costs' '$T/flat.out'"
exit 0
