#!/bin/sh
# cosim --rtl: the user's own RTL against shadesim. tests/rtl/horner3_hand.v
# (written by hand from the paper's datapath, not by the exporter) is
# bit-exact on the default vectors; horner3_bug.v (bit 8 of D stuck at 0)
# fails naming the first item whose quantized D has that bit set, found
# here from the vector file with awk, with y short by exactly 0x100 at
# clock 6 K + 6 (six clocks an item); horner3_width.v (t 12 bits wide) and
# other port mismatches are exit 2 before simulating. Needs iverilog (plain
# build only); one check in Verilator when it is installed. --match items
# on a re-timed copy (one more register stage) and a broken one.
PREFIX=cli_rtl.
. tests/lib_cli.sh
R=tests/rtl

expect rtl_missing_file 2 "$S" cosim horner3 --rtl "$T/nosuch.v"
expect top_without_rtl 2 "$S" cosim horner3 --top horner3_hand
case "${TST_BUILD:-}" in *-asan) echo "skip ${PREFIX}tools: runs in the plain build only"; exit 0 ;; esac
if ! command -v iverilog >/dev/null 2>&1; then echo "skip ${PREFIX}icarus: iverilog not installed"; exit 0; fi

# bit-exact on the unit's default vectors: every item, 6 clocks each and
# one more for the last beat (the paper's six-step sequence)
items=$(grep -vc '^#' vectors/horner3.vec)
if expect hand_exact 0 "$S" cosim horner3 --rtl $R/horner3_hand.v; then
    want="bit-exact, $items items, $((6 * items + 1)) clocks (icarus)"
    [ "$(cat "$T/out")" = "$want" ] && ok hand_counts || fail hand_counts "got '$(cat "$T/out")', expected '$want'"
fi
expect hand_top_n 0 "$S" cosim horner3 --rtl $R/horner3_hand.v --top horner3_hand -n 20
grep -q '^bit-exact, 20 items, 121 clocks' "$T/out" && ok hand_n_items || fail hand_n_items "$(cat "$T/out")"

# the broken copy: the item, its inputs, expected and actual y, the clock
k=$(grep -v '^#' vectors/horner3.vec | awk '{ r = int($4 * 512); if (int(r / 256) % 2) { print NR - 1; exit } }')
if expect bug_fails 1 "$S" cosim horner3 --rtl $R/horner3_bug.v; then
    line=$(cat "$T/out")
    case "$line" in "MISMATCH at item $k (inputs a="*" t="*"): expected y="*" at clock $((6 * k + 6)), icarus gave y="*" at clock $((6 * k + 6))")
        ok bug_names_item ;;
    *) fail bug_names_item "item $k expected: $line" ;; esac
    e=$(echo "$line" | sed -n 's/.*expected y=\([0-9a-f]*\) .*/\1/p')
    g=$(echo "$line" | sed -n 's/.*gave y=\([0-9a-f]*\) .*/\1/p')
    [ -n "$e" ] && [ -n "$g" ] && [ $(( (0x$e - 0x$g + 65536) % 65536 )) -eq 256 ] && ok bug_off_by_half \
        || fail bug_off_by_half "expected $e, got $g"
fi

# a design that never says out_valid: stopped, the first item reported
sed "s/out_valid <= step\[5\];/out_valid <= 1'b0;/" $R/horner3_hand.v >"$T/stuck.v"
expect stuck_fails 1 "$S" cosim horner3 --rtl "$T/stuck.v" -n 20
grep -q '^MISMATCH at item 0 (inputs .*): expected y=.* at clock 6, icarus gave nothing' "$T/out" \
    && ok stuck_reported || fail stuck_reported "$(cat "$T/out")"

# ports: a width, a missing port, an extra input, the reset choice
expect width_refused 2 "$S" cosim horner3 --rtl $R/horner3_width.v
grep -q 'port t has 12 bits, expected 16' "$T/err" && ok width_names_port || fail width_names_port "$(cat "$T/err")"
# without rst: registers start from initial blocks (what --reset none means)
sed -e 's/^    input  wire        rst,$//' -e 's/if (rst)/if (1'"'"'b0)/' \
    -e 's/^    reg  \[15:0\] rg;$/    reg  [15:0] rg = 16'"'"'d0;\n    initial begin step = 6'"'"'b000001; out_valid = 1'"'"'b0; end/' \
    $R/horner3_hand.v >"$T/norst.v"
expect no_rst_refused 2 "$S" cosim horner3 --rtl "$T/norst.v"
grep -q 'has no port rst' "$T/err" && ok no_rst_named || fail no_rst_named "$(cat "$T/err")"
expect no_rst_reset_none 0 "$S" cosim horner3 --rtl "$T/norst.v" --reset none -n 20
expect extra_rst_refused 2 "$S" cosim horner3 --rtl $R/horner3_hand.v --reset none
sed 's/input  wire \[15:0\] d,/input  wire [15:0] d, input wire [15:0] e,/' $R/horner3_hand.v >"$T/extra.v"
expect extra_input_refused 2 "$S" cosim horner3 --rtl "$T/extra.v"
grep -q 'input port e' "$T/err" && ok extra_input_named || fail extra_input_named "$(cat "$T/err")"
expect width_at_other_width 2 "$S" cosim horner3 --rtl $R/horner3_hand.v --width 12
grep -q 'port a has 16 bits, expected 12' "$T/err" && ok width_follows_options || fail width_follows_options "$(cat "$T/err")"
# two top-level modules: ask which, or take the one asked for
expect two_tops 2 "$S" cosim horner3 --rtl $R/horner3_hand.v --rtl $R/horner3_bug.v
grep -q 'top-level modules in the RTL (.*horner3_hand.*): choose one with --top' "$T/err" && ok two_tops_named || fail two_tops_named "$(cat "$T/err")"
expect two_tops_chosen 1 "$S" cosim horner3 --rtl $R/horner3_hand.v --rtl $R/horner3_bug.v --top horner3_bug
expect no_such_top 2 "$S" cosim horner3 --rtl $R/horner3_hand.v --top nosuch
printf 'module broken(input wire clk);\n  assign = ;\nendmodule\n' >"$T/broken.v"
expect syntax_error 2 "$S" cosim horner3 --rtl "$T/broken.v"

# --match items: tests/rtl/horner3_late.v (horner3_hand.v with one more
# register stage: y and out_valid a clock later) fails clock by clock, as
# before, and passes item by item with its latency one clock more than
# shadesim's and the same six clocks an item; the broken core behind the
# same stage still fails at item k, a clock after the model's beat.
sed 's/horner3_hand core/horner3_bug core/' $R/horner3_late.v >"$T/late_bug.v"
late="--rtl $R/horner3_hand.v --rtl $R/horner3_late.v --top horner3_late"
expect late_by_clocks_fails 1 "$S" cosim horner3 $late
grep -q '^MISMATCH at item 0 .*: expected y=0000 at clock 6, icarus gave y=0000 at clock 7$' "$T/out" &&
    ok late_by_clocks_named || fail late_by_clocks_named "$(cat "$T/out")"
expect late_by_items 0 "$S" cosim horner3 $late --match items
want="bit-exact item by item, $items items (icarus): RTL latency 7 clocks, 0.1667 items per clock; shadesim latency 6 clocks, 0.1667 items per clock"
[ "$(cat "$T/out")" = "$want" ] && ok late_latency || fail late_latency "got '$(cat "$T/out")', expected '$want'"
expect late_bug_by_items 1 "$S" cosim horner3 --rtl $R/horner3_bug.v --rtl "$T/late_bug.v" --top horner3_late --match items
grep -q "^MISMATCH at item $k (inputs .*): expected y=.* at clock $((6 * k + 6)), icarus gave y=.* at clock $((6 * k + 7))\$" "$T/out" &&
    ok late_bug_named || fail late_bug_named "item $k: $(cat "$T/out")"
expect match_bad_value 2 "$S" cosim horner3 --match beats

# The top module among many (more than 16 top-level modules: the one named
# like the unit was not found, and the count was wrong), a name of 150
# characters (over 127 it was "the RTL has no module"), an escaped name
# (`module \horner3! (...)`: the testbench instantiated it unescaped).
{ i=1; while [ $i -le 20 ]; do echo "module extra$i(input x); endmodule"; i=$((i + 1)); done; } >"$T/extras.v"
{ cat "$T/extras.v"; sed 's/module horner3_hand/module horner3/' $R/horner3_hand.v; } >"$T/many.v"
expect many_tops_unit_named 0 "$S" cosim horner3 --rtl "$T/many.v" -n 5
{ cat "$T/extras.v" $R/horner3_hand.v; } >"$T/many2.v"
expect many_tops_refused 2 "$S" cosim horner3 --rtl "$T/many2.v" -n 5
grep -q '^shadesim: cosim: 21 top-level modules in the RTL (extra1, .*horner3_hand): choose one' "$T/err" \
    && ok many_tops_counted || fail many_tops_counted "$(cat "$T/err")"
long=hhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhhh
sed "s/module horner3_hand/module $long/" $R/horner3_hand.v >"$T/long.v"
expect long_top_name 0 "$S" cosim horner3 --rtl "$T/long.v" -n 5
sed 's/module horner3_hand/module \\horner3! /' $R/horner3_hand.v >"$T/esc.v"
expect escaped_top_name 0 "$S" cosim horner3 --rtl "$T/esc.v" -n 5

# The user's RTL is untrusted input: a zero-delay loop stops at --timeout
# (it hung for ever: the clock limit counts clocks, which never come), an
# RTL printing without end at the file cap (its log reached 540 MB in
# 11 s), a FIFO or a folder named by --rtl is refused at once (a FIFO
# blocked iverilog's reader for ever).
sed 's/^endmodule/reg osc = 0; always @(osc) osc <= ~osc;\nendmodule/' $R/horner3_hand.v >"$T/osc.v"
sed 's/^endmodule/initial forever $display("spam spam spam spam spam spam");\nendmodule/' $R/horner3_hand.v >"$T/spam.v"
expect osc_stops 1 "$S" cosim horner3 --rtl "$T/osc.v" -n 5 --timeout 3
grep -q '^shadesim: cosim: icarus stopped after its time limit of 3 s (a zero-delay loop' "$T/err" \
    && ok osc_named || fail osc_named "$(cat "$T/err")"
expect spam_stops 1 "$S" cosim horner3 --rtl "$T/spam.v" -n 5 --timeout 120
grep -q '^shadesim: cosim: icarus stopped: a file it wrote reached 64 MiB' "$T/err" \
    && ok spam_named || fail spam_named "$(cat "$T/err")"
mkfifo "$T/fifo.v"
expect fifo_refused 2 "$S" cosim horner3 --rtl "$T/fifo.v"
grep -q 'fifo.v: not a regular file (a FIFO)' "$T/err" && ok fifo_named || fail fifo_named "$(cat "$T/err")"
expect folder_refused 2 "$S" cosim horner3 --rtl "$T"
grep -q "rtl $T: not a regular file (a folder)" "$T/err" && ok folder_named || fail folder_named "$(cat "$T/err")"
expect timeout_zero 2 "$S" cosim horner3 --timeout 0
# SIGTERM at any moment (shadesim simulating, writing the stimulus, Icarus
# compiling or running): no simulator left running, no temporary folder
# left in TMPDIR (it was, 3 of 3), death by the signal
mkdir "$T/tmp"
# d: seconds after the start, or "tool": once the folder is in TMPDIR and
# a simulator runs in it (polled, up to 60 s: a loaded machine takes
# longer to get there)
for d in 0.2 0.6 1.2 tool; do
    TMPDIR="$T/tmp" "$S" cosim horner3 -n 400000 >/dev/null 2>&1 &
    pid=$!
    if [ "$d" = tool ]; then
        n=0
        while [ $n -lt 600 ] && ! ls "$T"/tmp/*/*.vvp >/dev/null 2>&1; do sleep 0.1; n=$((n + 1)); done
    else sleep $d; fi
    made=$(ls -A "$T/tmp")
    kill -TERM $pid
    wait $pid 2>/dev/null
    st=$?
    sleep 0.3
    left=$(ls -A "$T/tmp")
    if [ $st -eq 143 ] && [ -z "$left" ]; then ok "sigterm_clean_$d"
    else fail "sigterm_clean_$d" "exit $st, left: $left"; fi
done
# (the last one killed while its folder was there: in TMPDIR, not /tmp)
[ -n "$made" ] && ok sigterm_folder_in_tmpdir || fail sigterm_folder_in_tmpdir "no folder with a compiled design in TMPDIR"

if command -v verilator >/dev/null 2>&1; then
    expect verilator_width 2 "$S" cosim horner3 --rtl $R/horner3_width.v --sim verilator
    grep -q 'port t has 12 bits, expected 16' "$T/err" && ok verilator_width_named || fail verilator_width_named "$(cat "$T/err")"
    expect verilator_hand 0 "$S" cosim horner3 --rtl $R/horner3_hand.v --sim verilator -n 12
    # a packed struct port's width from its members (it was read as -1 bits):
    # 8 + 4 bits, refused by its width, before any compile
    { echo 'typedef struct packed { logic [7:0] hi; logic [3:0] lo; } pair_t;'
      sed 's/    input  wire \[15:0\] a,/    input  pair_t a,/' $R/horner3_hand.v; } >"$T/st.sv"
    expect verilator_struct_port 2 "$S" cosim horner3 --rtl "$T/st.sv" --sim verilator
    grep -q 'port a has 12 bits, expected 16' "$T/err" && ok verilator_struct_width || fail verilator_struct_width "$(cat "$T/err")"
else
    echo "skip ${PREFIX}verilator: verilator not installed"
fi
