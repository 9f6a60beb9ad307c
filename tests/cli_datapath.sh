#!/bin/sh
# Datapath files (docs/datapaths.md): a design of one's own in text, run by
# every verb with no C. The hand-written Horner datapath with the paper's
# schedule reports what the built-in horner3 reports, byte for byte (text,
# JSON with the kernel's counters, VCD); the FIR's golden vectors, bound
# and width rules are held to values computed here independently (awk);
# sweep's target search runs on it; and malformed files are each refused
# with their one line "FILE:LINE: what", exit 2.
PREFIX=cli_datapath.
. tests/lib_cli.sh
H=examples/horner3.dp F=examples/fir4.dp

# same NAME A B: files A and B hold the same bytes.
same() { if cmp -s "$2" "$3"; then ok "$1"; else fail "$1" "$(diff "$2" "$3" 2>&1 | head -c 300)"; fi; }

# --- the Horner datapath against the built-in unit ----------------------
"$S" run horner3 --json >"$T/a.json"
"$S" run "$H" --vectors vectors/horner3.vec --json >"$T/b.json"
same horner_json_is_builtins "$T/a.json" "$T/b.json"
"$S" run horner3 >"$T/a.txt"
"$S" run "$H" --vectors vectors/horner3.vec >"$T/b.txt"
same horner_report_is_builtins "$T/a.txt" "$T/b.txt"
mkdir -p "$T/A" "$T/B"
top=$(pwd)
case $S in /*) ;; */*) S=$top/$S ;; esac
(cd "$T/A" && "$S" run horner3 --kernel --json --vcd h.vcd >k.json)
(cd "$T/B" && "$S" run "$top/$H" --vectors "$top/vectors/horner3.vec" --kernel --json --vcd h.vcd >k.json)
sed -i "s#$T/[AB]/##" "$T"/A/h.vcd.gtkw "$T"/B/h.vcd.gtkw 2>/dev/null
same horner_kernel_json_is_builtins "$T/A/k.json" "$T/B/k.json"
same horner_vcd_is_builtins "$T/A/h.vcd" "$T/B/h.vcd"
# another width: the rules s7.(W-7) and u1.(W-1) follow it as horner3's do
"$S" run horner3 --width 12 --json >"$T/a12.json"
"$S" run "$H" --vectors vectors/horner3.vec --width 12 --json >"$T/b12.json"
same horner_width12_is_builtins "$T/a12.json" "$T/b12.json"

# A second schedule in the file (B loaded twice, seven clocks): the same
# results and bound as the paper's, one clock more an item.
sed 's/^ctl bk_pass .*/&\nschedule slow clocks=7 "B loaded twice"\nctl mx1_sel 1 1 0 1 1 1 1\nctl mx2_sel 1 1 0 0 2 0 3\nctl bk_pass 0 0 1 0 1 0 1/' \
    "$H" >"$T/h2.dp"
"$S" run "$T/h2.dp" --vectors vectors/horner3.vec --schedule slow --json >"$T/s.json"
check second_schedule_clocks grep -q '"cycles_per_item": 7,' "$T/s.json"
grep -E '"(max_abs_err|bound|verdict)"' "$T/s.json" >"$T/s.lines"
grep -E '"(max_abs_err|bound|verdict)"' "$T/a.json" >"$T/a.lines"
same second_schedule_same_results "$T/a.lines" "$T/s.lines"

# A long schedule: the paper's first clock (RG <= B) repeated, 250 clocks
# an item in all (a row on one line; the counter's 8 bits): the same
# results and bound, 250 clocks an item; 257 clocks are refused.
awk '/^schedule paper/ { sub(/clocks=6/, "clocks=250") }
     /^ctl / { r = ""; for (i = 0; i < 245; i++) r = r " " $3; $0 = $1 " " $2 r substr($0, length($1 " " $2 " " $3) + 1) }
     { print }' "$H" >"$T/long.dp"
"$S" run "$T/long.dp" --vectors vectors/horner3.vec --json >"$T/l.json"
check long_schedule_clocks grep -q '"cycles_per_item": 250,' "$T/l.json"
grep -E '"(max_abs_err|bound|verdict)"' "$T/l.json" >"$T/l.lines"
same long_schedule_same_results "$T/a.lines" "$T/l.lines"
sed 's/clocks=250/clocks=257/' "$T/long.dp" >"$T/long2.dp"
expect long_schedule_257 2 "$S" run "$T/long2.dp"
check long_schedule_257_says grep -q 'long2.dp:[0-9]*: clocks=257: expected a whole number of clocks per item 2..256' "$T/err"

# --- the FIR: vectors, bound, width rules, against awk ---------------------
expect fir_vectors 0 "$S" vectors "$F"
# every expected output is 0.125 x0 + 0.375 x1 + 0.375 x2 + 0.125 x3 (to
# the double's rounding) and every input lies in its range [-1, 1]
awk '!/^#/ { if ($5 != "|") bad++; y = 0.125 * $1 + 0.375 * $2 + 0.375 * $3 + 0.125 * $4; d = y - $6;
             if (d < 0) d = -d; if (d > 1e-15) bad++;
             for (i = 1; i <= 4; i++) if ($i < -1 || $i >= 1) bad++; n++ }
     END { exit !(n == 1000 && bad == 0) }' "$T/out" && ok fir_vectors_are_the_expression \
    || fail fir_vectors_are_the_expression "$(head -6 "$T/out")"
"$S" vectors "$F" >"$T/v2"
same fir_vectors_deterministic "$T/out" "$T/v2"
expect fir_run 0 "$S" run "$F" --json
# the bound at width W: four products truncated from 2(W-1) to W-1
# fraction bits (an LSB less 2^-2(W-1) each), the sums exact, y cut by one
# bit (half an LSB of s01's, 2^-(W-1)): 5 * 2^-(W-1) - 4 * 2^-2(W-1)
for w in 12 16; do
    "$S" run "$F" --width $w --json >"$T/f$w.json"
    awk -v w=$w -F'"bound": ' 'NF > 1 { split($2, a, /[,}]/); b = a[1] }
         END { e = 5 * 2 ^ -(w - 1) - 4 * 2 ^ -(2 * (w - 1)); d = b - e; if (d < 0) d = -d; exit !(b != "" && d <= 1e-18) }' \
        "$T/f$w.json" && ok fir_bound_w$w || fail fir_bound_w$w "$(grep -o '"bound": [^,]*' "$T/f$w.json" | head -2)"
done
# the dot product on one multiply-add: three clocks an item; its bound,
# three products truncated to W-1 fraction bits (an LSB less 2^-2(W-1)),
# each sum to W-3 (2^-(W-3) - 2^-(W-1)): 3 (2^-(W-3) - 2^-2(W-1))
D=examples/dot3.dp
for w in 12 16; do
    "$S" run "$D" --width $w --json >"$T/d$w.json"
    awk -v w=$w -F'"bound": ' 'NF > 1 { split($2, a, /[,}]/); b = a[1] }
         END { e = 3 * (2 ^ -(w - 3) - 2 ^ -(2 * (w - 1))); d = b - e; if (d < 0) d = -d; exit !(b != "" && d <= 1e-18) }' \
        "$T/d$w.json" && ok dot3_bound_w$w || fail dot3_bound_w$w "$(grep -o '"bound": [^,]*' "$T/d$w.json" | head -2)"
done
check dot3_three_clocks grep -q '"cycles_per_item": 3,' "$T/d16.json"
check dot3_verdict_ok grep -q '"verdict": "ok"' "$T/d12.json"
check fir_verdict_ok grep -q '"verdict": "ok"' "$T/f12.json"
check fir_formats_follow_w grep -q '"formats": {"x0": "s1.15", "x1": "s1.15", "x2": "s1.15", "x3": "s1.15", "y": "s2.14",' "$T/f16.json"
check fir_combinational grep -q '"cycles_per_item": 1,' "$T/f16.json"
# the same filter as a two-stage pipeline: an item a clock, the result two
# clocks later, the same values and bound
"$S" run examples/fir4_pipe.dp --width 16 --json >"$T/p16.json"
check pipe_latency grep -q '"cycles_per_item": 1,.*' "$T/p16.json"
check pipe_latency_2 grep -q '"latency": 2,' "$T/p16.json"
grep -E '"(max_abs_err|mean_err|rms_err|bound|verdict)"' "$T/f16.json" >"$T/f.lines"
grep -E '"(max_abs_err|mean_err|rms_err|bound|verdict)"' "$T/p16.json" >"$T/p.lines"
same pipe_same_results "$T/f.lines" "$T/p.lines"
# a width where a rule gives no bits: one line naming the file's rule
expect fir_width_too_narrow 2 "$S" run "$F" --width 1
# sweep with a target: a design meeting it, checked on held-out vectors
# (under the sanitizers, the plain build's: a search is some 150 runs)
if [ -z "$ASAN" ]; then
    expect fir_sweep_target 0 "$S" sweep "$F" --widths 10:14 --target-error 0.001 -o "$T/sw"
    check fir_sweep_met grep -q 'held-out check .*: passed' "$T/out"
fi
# Without a bound (a logic element the walk does not know): run's verdict
# needs a target, which then decides alone; sweep's search takes it too.
sed 's/^\(add y .*\)/\1\nconst one u1.0 raw=1\nlogic z u1.0 in=one area=1 table=01/' "$F" >"$T/nb.dp"
expect no_bound_fails 1 "$S" run "$T/nb.dp"
check no_bound_says grep -q '^verdict: NO BOUND: .*(a target, --max-error, --max-nmse or --max-lsb, decides instead)' "$T/out"
expect no_bound_target_met 0 "$S" run "$T/nb.dp" --max-error 0.003
check no_bound_target_met_says grep -q '^verdict: ok: meets your target (no bound derived)$' "$T/out"
expect no_bound_target_missed 1 "$S" run "$T/nb.dp" --max-error 0.002
check no_bound_target_missed_says grep -q '^verdict: MISSES YOUR TARGET (no bound derived)$' "$T/out"
if [ -z "$ASAN" ]; then
    expect no_bound_sweep_target 0 "$S" sweep "$T/nb.dp" --widths 10:14 --target-error 0.001 -o "$T/sw2"
    check no_bound_sweep_column grep -q '^   14  .* none   \*$' "$T/out"
    check no_bound_sweep_met grep -q 'held-out check .*: passed' "$T/out"
fi
expect list_file 0 "$S" list "$F"
check list_names_file grep -q '^fir4 — 4-tap FIR' "$T/out"
# a netlist of a built-in unit is run's alone
"$S" netlist horner3 -o "$T/h3.net"
expect netlist_file_not_datapath 2 "$S" vectors "$T/h3.net"
check netlist_file_says grep -q 'a netlist of a built-in unit, which only run takes' "$T/err"
expect datapath_not_netlisted 2 "$S" netlist "$F" --width 12
check datapath_not_netlisted_says grep -q "netlist: $F is a datapath file, already the design's text" "$T/err"

# --- netlist --datapath: a built-in unit as a datapath file --------------
# run FILE reports what run UNIT reports (JSON with the kernel's counters)
# for a unit of each form: the control as schedule rows (horner3 paper and
# mac), the unit's own counter and handshake written out (span1, whose
# rows a counter of its own decodes), wide logic as its Verilog text's
# function (div, fn=verilog), a pipeline (dot3);
# every unit and schedule at two widths: tests/cli_datapath_units.sh.
for us in horner3:paper horner3:mac span1:paper div:restoring dot3:pipe; do
    u=${us%:*} s=${us#*:}
    "$S" netlist $u --schedule $s --datapath -o "$T/$u.$s.dp"
    "$S" run $u --schedule $s --kernel --json >"$T/u.json"
    "$S" run "$T/$u.$s.dp" --kernel --json >"$T/f.json"
    same "written_${u}_${s}_is_builtins" "$T/u.json" "$T/f.json"
done
W=$T/horner3.paper.dp
# the Horner unit's file is the hand-written example's design: the same
# rows and the same rules of W
grep '^ctl ' "$H" >"$T/ctl.a"; grep '^ctl ' "$W" >"$T/ctl.b"
same written_rows_are_the_papers "$T/ctl.a" "$T/ctl.b"
check written_rules grep -q '^mul mul s7.(W-7) a=mx1 b=t$' "$W"
check written_names_unit grep -q '^ideal unit=horner3$' "$W"
# its rules follow --width as the unit's formats do, and sweep runs on it
"$S" run horner3 --width 12 --json >"$T/u12.json"
"$S" run "$W" --width 12 --json >"$T/f12.json"
same written_width12_is_builtins "$T/u12.json" "$T/f12.json"
"$S" sweep horner3 --widths 12:14 -o "$T/swu" >/dev/null
"$S" sweep "$W" --widths 12:14 -o "$T/swf" >/dev/null
same written_sweep_is_builtins "$T/swu/sweep.csv" "$T/swf/sweep.csv"
# what the file cannot follow: another width of a file written at one,
# fn=unit (the unit's function at the file's width), another schedule
expect written_fixed_width 2 "$S" run "$T/span1.paper.dp" --width 12
check written_fixed_width_says grep -q 'span1.paper.dp: its formats are written for width 16 alone (no rule of W): not 12' "$T/err"
sed 's/ fn=verilog$/ fn=unit/' "$T/div.restoring.dp" >"$T/div_unit.dp"
"$S" run div --json >"$T/u.json"
"$S" run "$T/div_unit.dp" --json >"$T/f.json"
same written_fn_unit_is_builtins "$T/u.json" "$T/f.json"
expect written_fn_unit_width 2 "$S" run "$T/div_unit.dp" --width 12
check written_fn_unit_width_says grep -q "div_unit.dp:[0-9]*: logic [a-z_0-9]*: fn=unit is unit div's function at the file's width 16, not 12" "$T/err"
expect written_other_schedule 2 "$S" run "$T/span1.paper.dp" --schedule mac
check written_other_schedule_says grep -q "span1.paper.dp: schedule mac: the file's control is that of unit span1's schedule paper" "$T/err"
expect written_no_rows 2 "$S" run "$W" --schedule mac
check written_no_rows_says grep -q "horner3.paper.dp: schedule mac: the file has no rows for it (its first: paper, line [0-9]*)" "$T/err"

# A sweep of a file in shards, merged: the whole sweep's CSV
"$S" sweep "$F" --widths 10:13 -o "$T/mw" >/dev/null
"$S" sweep "$F" --widths 10:13 --shard 1/2 -o "$T/m1" >/dev/null
"$S" sweep "$F" --widths 10:13 --shard 2/2 -o "$T/m2" >/dev/null
"$S" merge "$T/m1/sweep-1-of-2.csv" "$T/m2/sweep-2-of-2.csv" -o "$T/m.csv"
same merge_shards_of_file "$T/mw/sweep.csv" "$T/m.csv"

# A scene through a file for its span unit (scene --set unit=FILE): span3's
# own file renders the very bytes of the built-in unit (images and
# scene.json); an edited one (the multiplier rounding half-up) renders
# through the edit; a file for another unit than the policy's is refused.
"$S" netlist span3 --datapath -o "$T/s3.dp"
R="face --set resolution=64x64"
"$S" scene $R -o "$T/sc1" >/dev/null
"$S" scene $R --set unit="$T/s3.dp" -o "$T/sc2" >/dev/null
diff -r "$T/sc1" "$T/sc2" >"$T/scd" 2>&1 && ok scene_unit_file_is_builtins || fail scene_unit_file_is_builtins "$(head -c 300 "$T/scd")"
sed 's/^\(mul horner\.mul s7\.9\) /\1:half-up /' "$T/s3.dp" >"$T/s3h.dp"
"$S" scene $R --set unit="$T/s3h.dp" -o "$T/sc3" >/dev/null
grep '"nmse"' "$T/sc1/scene.json" >"$T/n1"; grep '"nmse"' "$T/sc3/scene.json" >"$T/n3"
cmp -s "$T/n1" "$T/n3" && fail scene_unit_file_edit_renders "the same NMSE" || ok scene_unit_file_edit_renders
printf 'shadesim-scene 1\nmesh face\nresolution 64x64\nunit s3.dp\n' >"$T/f.scene"
"$S" scene "$T/f.scene" -o "$T/sc4" >/dev/null
grep '"nmse"' "$T/sc4/scene.json" >"$T/n4"
same scene_unit_key_relative "$T/n1" "$T/n4"
expect scene_unit_other_policy 2 "$S" scene $R --set policy=linear --set unit="$T/s3.dp"
check scene_unit_other_policy_says grep -q "^shadesim: --set unit: unit: .*s3.dp: the policy's unit is span1, and the file's ideal line does not name it (ideal unit=span1)$" "$T/err"
printf 'shadesim-scene 1\nmesh face\nunit nosuch.dp\n' >"$T/g.scene"
expect scene_unit_missing 2 "$S" scene "$T/g.scene"
check scene_unit_missing_says grep -q "^shadesim: .*g.scene:3: unit: .*nosuch.dp: No such file or directory$" "$T/err"

# --- malformed files: each one line, FILE:LINE: what, exit 2 ------------
# bad NAME BASE 'SED SCRIPT' 'EXPECTED TEXT': BASE edited by the script.
# Under the sanitizers the first eight (tests/test_dp_fuzz.c reads
# thousands of malformed files in process there).
nbad=1000; [ -n "$ASAN" ] && nbad=8
bad() {
    nbad=$((nbad - 1)); [ $nbad -lt 0 ] && return
    sed "$3" "$2" >"$T/bad_$1.dp"
    expect "bad_$1" 2 "$S" run "$T/bad_$1.dp"
    grep -qF -- "bad_$1.dp:$4" "$T/err" || fail "bad_$1_says" "expected '$4', got: $(cat "$T/err")"
}
l() { grep -n "$1" "$2" | head -1 | cut -d: -f1; }
bad undeclared   $H 's/^add sm s7.(W-7) a=mx2 b=bk/add sm s7.(W-7) a=mx9 b=bk/' "$(l '^add sm' $H): add sm: a=mx9 is not declared"
bad duplicate    $H 's/^bk bk /bk mx1 /' "$(l '^bk bk' $H): mx1: declared twice (first at line $(l '^mux mx1' $H))"
bad loop         $H 's/^mul mul s7.(W-7) a=mx1 b=t/mul mul s7.(W-7) a=sm b=t/' "$(l '^mul mul' $H): a combinational loop: mul -> mx2 -> sm -> mul"
bad loop_fir     $F 's/^add s01 s2.(W-1) a=p0 b=p1/add s01 s2.(W-1) a=p0 b=y/' "$(l '^add s01' $F): a combinational loop: s01 -> y -> s01"
bad self         $F 's/^add s01 s2.(W-1) a=p0 b=p1/add s01 s2.(W-1) a=s01 b=p1/' "$(l '^add s01' $F): add s01: a=s01 names itself"
bad sel_kind     $H 's/^mux mx1 s7.(W-7) sel=mx1_sel/mux mx1 s7.(W-7) sel=t/' "$(l '^mux mx1' $H): mux mx1: sel=t is a number of format u1.(W-1)"
bad rule_no_bits $F 's/^add y s2.(W-2)/add y s2.(W-13)/' "$(l '^add y' $F): add y: format rule s2.(W-13) gives a negative count of bits at width 12"
bad rule_zero    $F 's/^add y s2.(W-2)/add y u0.(W-12)/' "$(l '^add y' $F): add y: format rule u0.(W-12) gives no bits at width 12"
bad rule_syntax  $F 's/^add y s2.(W-2)/add y s2.(W-2/' "$(l '^add y' $F): format s2.(W-2: expected sI.F or uI.F"
bad row_short    $H 's/^ctl mx2_sel 1 0 0 2 0 3/ctl mx2_sel 1 0 0 2 0/' "$(l '^ctl mx2_sel' $H): ctl mx2_sel: 5 values; schedule paper has 6 clocks per item"
bad row_value    $H 's/^ctl mx1_sel 1 0 1 1 1 1/ctl mx1_sel 1 0 1 1 1 x/' "$(l '^ctl mx1_sel' $H): ctl mx1_sel: x at clock 5: expected a whole number 0..255"
bad row_outside  $H 's/^ctl mx1_sel/reg zz u1.0 d=t clk=clk\nctl mx1_sel/' "$(($(l '^ctl mx1_sel' $H) + 1)): ctl: a control signal's row belongs right after its schedule"
bad sched_twice  $H 's/^\(ctl bk_pass .*\)/\1\nschedule paper clocks=6/' "$(($(l '^ctl bk_pass' $H) + 1)): schedule paper given twice (first at line $(l '^schedule' $H))"
bad ctl_missing  $H 's/^\(ctl bk_pass .*\)/\1\nschedule fast clocks=6\nctl mx1_sel 1 0 1 1 1 1\nctl mx2_sel 1 0 0 2 0 3/' "$(($(l '^ctl bk_pass' $H) + 1)): schedule fast: no row for ctl bk_pass"
bad ctl_unknown  $H 's/^\(ctl bk_pass .*\)/\1\nschedule fast clocks=6\nctl mx3_sel 1 0 1 1 1 1/' "$(($(l '^ctl bk_pass' $H) + 2)): ctl mx3_sel: not a control signal of schedule paper"
bad clocks       $H 's/clocks=6/clocks=1/' "$(l '^schedule' $H): clocks=1: expected a whole number of clocks per item 2..256"
bad expr_op      $F 's/^ideal y .*/ideal y 0.125 * x0 + * x1/' "$(l '^ideal' $F): ideal y: column 14: '*' where a number, an input or '(' belongs"
bad expr_paren   $F 's/^ideal y .*/ideal y (0.125 * x0 + x1/' "$(l '^ideal' $F): ideal y: column 17: ')' expected"
bad expr_name    $F 's/^ideal y .*/ideal y 0.125 * x9/' "$(l '^ideal' $F): ideal y: column 9: x9 is not an input"
bad expr_fn      $F 's/^ideal y .*/ideal y cos(x0)/' "$(l '^ideal' $F): ideal y: column 1: cos(: no such function (sqrt, abs, min, max)"
bad expr_args    $F 's/^ideal y .*/ideal y min(x0)/' "$(l '^ideal' $F): ideal y: column 7: ',' expected in min() (it takes 2 arguments)"
bad ideal_twice  $F 's/^\(ideal y .*\)/\1\n\1/' "$(($(l '^ideal' $F) + 1)): ideal y given twice"
bad ideal_input  $F 's/^ideal y/ideal x0/' "$(l '^ideal' $F): ideal x0: not an output (port out NAME)"
bad no_ideal     $F '/^ideal y/d' " output y has no ideal line (ideal y EXPRESSION, or ideal unit=NAME)"
bad no_range     $F 's/ range=-1,1 what="sample n"/ what="sample n"/' "$(l 'sample n"' $F): input x0: needs range=LO,HI"
bad range_order  $F 's/range=-1,1 what="sample n"/range=1,-1 what="sample n"/' "$(l 'sample n"' $F): range=1,-1: expected LO,HI, two numbers with LO < HI"
bad const_both   $F 's/value=0.125/value=0.125 raw=3/' "$(l '^const h0' $F): const h0: needs one of raw=RAW and value=NUMBER"
bad reg_no_sched $F 's/^\(add y .*\)/\1\nreg r s2.(W-2) d=y clk=clk/' "$(($(l '^add y' $F) + 1)): reg r: a datapath without a schedule is combinational (add schedule NAME clocks=N and its control rows, or latency N for a pipeline)"
bad handshake    $F 's/^port out y/port out y\nport in_valid x0/' "$(($(l '^port out' $F) + 1)): the file gives its own handshake: it needs port in_valid, port in_ready and port out_valid (no port in_ready)"
bad handshake_sched $H 's/^port out y/port out y\nport in_ready y/' "$(($(l '^port out' $H) + 1)): port in_ready: the handshake is made from the file's schedules (line $(l '^schedule' $H)): port in and port out only"
bad fmt_line     $F 's/^width 12/width 12\nfmt y=s2.10/' "$(($(l '^width' $F) + 1)): fmt: a datapath file gives each element its format (or rule of W)"
bad fn_unit      $F 's/^\(add y .*\)/\1\nlogic q u1.0 in=x0 area=1 fn=unit/' "$(($(l '^add y' $F) + 1)): logic q: fn=unit names a built-in unit's function"
bad unit_and_dp  $F 's/^datapath fir4/unit horner3\ndatapath fir4/' "$(($(l '^datapath' $F) + 1)): datapath: a file has one unit NAME or datapath NAME line"
bad kind         $F 's/^add y /adder y /' "$(l '^add y' $F): adder: not a line of a netlist"
bad vlog_text    $F 's/^\(add y .*\)/\1\nlogic q u1.0 in=x0 area=1 verilog="assign %y = %0 <;" fn=verilog/' "$(($(l '^add y' $F) + 1)): logic q: fn=verilog: verilog text, at character 17: an operand expected"
bad vlog_none    $F 's/^\(add y .*\)/\1\nlogic q u1.0 in=x0 area=1 fn=verilog/' "$(($(l '^add y' $F) + 1)): logic q: fn=verilog needs its verilog=\"TEXT\""
bad ref_unknown  $W 's/^ideal unit=horner3/ideal unit=horner9/' "$(l '^ideal unit' $W): ideal unit=horner9: no such built-in unit"
bad ref_twice    $W 's/^\(ideal unit=.*\)/\1\n\1/' "$(($(l '^ideal unit' $W) + 1)): ideal unit= given twice (first at line $(l '^ideal unit' $W))"
bad ref_expr     $W 's/^port out y/port out y\nideal y a/' "$(($(l '^port out' $W) + 1)): ideal: the file's ideal is unit horner3's (line $(l '^ideal unit' $W)): no expressions beside it"
bad ref_sched    $W 's/^schedule paper clocks=6/schedule quick clocks=6/' "$(l '^schedule' $W): schedule quick: unit horner3 has no such schedule (ideal unit=horner3 runs the unit's)"
bad ref_port     $W 's/^shift y /shift z /; s/^port out y/port out z/' "$(l '^port out' $W): port out z: unit horner3's output 1 is y"
bad ref_param    $F 's/^width 12/width 12\nparam terms 5/' "$(($(l '^width' $F) + 1)): param: a datapath file has parameters only from the unit its ideal line names"
P=examples/fir4_pipe.dp
bad hs_latency   $P 's/^port out y/port out y\nport in_valid x0/' "$(($(l '^port out' $P) + 1)): port in_valid: the handshake is made from the file's latency (line $(l '^latency' $P)): port in and port out only"
bad pipe_stages  $P 's/^add s01 s2.(W-1) a=p0 b=p1/add s01 s2.(W-1) a=p0 b=m1/' "$(l '^add s01' $P): add s01: in a pipeline its operands p0 and m1 come 1 and 0 registers after the inputs"
bad pipe_latency $P 's/^latency 2/latency 3/' "$(l '^port out' $P): port out y: 2 registers after the inputs, where latency says 3"
bad pipe_and_sched $P 's/^latency 2/latency 2\nschedule s clocks=2/' "$(($(l '^latency' $P) + 1)): schedule: the file is a pipeline (latency at line $(l '^latency' $P)): one or the other"
