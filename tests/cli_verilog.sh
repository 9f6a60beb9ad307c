#!/bin/sh
# Command-line contract of verilog, cosim and synth: help, bad input (exit
# 2, one line, nothing written), missing tools named by their Debian
# package, the export's files, --stimulus-hex, and `cosim horner3 --width
# 16` bit-exact. The tool-driven checks run in the plain build only.
PREFIX=cli_verilog.
. tests/lib_cli.sh

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

for v in verilog cosim synth; do expect "help_$v" 0 "$S" $v --help; done
expect no_unit 2 "$S" verilog -o "$T/x"
expect unknown_unit 2 "$S" verilog nosuch -o "$T/x"
expect no_dir 2 "$S" verilog horner3
expect bad_schedule 2 "$S" verilog horner3 --schedule nosuch -o "$T/x"
expect bad_fmt 2 "$S" verilog horner3 --fmt y=q1.2 -o "$T/x"
expect bad_param 2 "$S" verilog div3 --param terms=999 -o "$T/x"
check nothing_written [ ! -e "$T/x" ]
expect dir_unwritable 2 "$S" verilog horner3 -o /dev/null/x
: >"$T/file"
expect dir_is_file 2 "$S" verilog horner3 -o "$T/file"
expect bad_reset 2 "$S" verilog horner3 --reset later -o "$T/x"
check nothing_written_reset [ ! -e "$T/x" ]
expect cosim_bad_reset 2 "$S" cosim horner3 --reset
expect cosim_bad_sim 2 "$S" cosim horner3 --sim modelsim
expect cosim_bad_n 2 "$S" cosim horner3 -n 0

# A missing tool: an empty PATH apart from the shell's own tools.
mkdir "$T/bin"
for t in sh rm; do ln -s "$(command -v $t)" "$T/bin/$t"; done
ENV=$(command -v env)
expect cosim_no_iverilog 2 "$ENV" PATH="$T/bin" "$S" cosim horner3
grep -q "Debian package iverilog" "$T/err" && ok cosim_names_package || fail cosim_names_package "$(cat "$T/err")"
expect cosim_no_verilator 2 "$ENV" PATH="$T/bin" "$S" cosim horner3 --sim verilator
grep -q "Debian package verilator" "$T/err" && ok cosim_names_verilator || fail cosim_names_verilator "$(cat "$T/err")"
expect synth_no_yosys 2 "$ENV" PATH="$T/bin" "$S" synth horner3
grep -q "Debian package yosys" "$T/err" && ok synth_names_package || fail synth_names_package "$(cat "$T/err")"

# The export: the module with the ports of `list`, the testbench, the stimulus.
expect export 0 "$S" verilog horner3 --width 12 -o "$T/rtl" --stimulus-hex "$T/rtl/s.hex"
missing=
for p in "input  wire [11:0] a" "input  wire [11:0] t" "output wire [11:0] y" "in_valid" "in_ready" "out_valid"; do
    grep -qF -- "$p" "$T/rtl/horner3.v" || missing="$missing '$p'"
done
if [ -z "$missing" ]; then ok export_ports; else fail export_ports "missing$missing"; fi
check export_tb [ -s "$T/rtl/horner3_tb.v" ]
# what it wrote, a line a file
printf 'wrote %s\n' "$T/rtl/horner3.v" "$T/rtl/horner3_tb.v" >"$T/want"
n=$(grep -vc '^#' vectors/horner3.vec)
printf 'wrote %s (%s items: +items=%s)\nwrote %s\n' "$T/rtl/s.hex" "$n" "$n" "$T/rtl/s.hex.expect" >>"$T/want"
cmp -s "$T/want" "$T/out" && ok export_says_files || fail export_says_files "$(cat "$T/out")"
# the reset: a port after clk (sync, async), a register reset; initial
# blocks only without it
for r in sync async none; do "$S" verilog horner3 --width 12 --reset $r -o "$T/r$r" >/dev/null 2>&1; done
grep -q '^    input  wire rst,$' "$T/rsync/horner3.v" && ! grep -q 'initial' "$T/rsync/horner3.v" \
    && grep -q '^        if (rst) rg <= 12.h0;$' "$T/rsync/horner3.v" && ok reset_sync || fail reset_sync
grep -q '^    always @(posedge clk or posedge rst)$' "$T/rasync/horner3.v" && ! grep -q 'initial' "$T/rasync/horner3.v" \
    && ok reset_async || fail reset_async
! grep -q 'rst' "$T/rnone/horner3.v" && grep -q '^    initial rg = 12.h0;$' "$T/rnone/horner3.v" && ok reset_none || fail reset_none
cmp -s "$T/rsync/horner3.v" "$T/rtl/horner3.v" && ok reset_default_sync || fail reset_default_sync
# stimulus: 5 hex fields of 3 digits a line, an expected line per item
check stimulus_lines [ "$(wc -l <"$T/rtl/s.hex")" -ge 1 ]
check stimulus_fields [ "$(awk '{ if (NF != 5 || length($1) != 3) bad = 1 } END { print bad + 0 }' "$T/rtl/s.hex")" = 0 ]
check expect_lines [ "$(wc -l <"$T/rtl/s.hex.expect")" = "$(wc -l <"$T/rtl/s.hex")" ]
# the same bytes again (deterministic)
"$S" verilog horner3 --width 12 -o "$T/rtl2" >/dev/null 2>&1
cmp -s "$T/rtl/horner3.v" "$T/rtl2/horner3.v" && ok deterministic || fail deterministic

case "${TST_BUILD:-}" in *-asan) echo "skip ${PREFIX}tools: runs in the plain build only"; exit 0 ;; esac
if command -v iverilog >/dev/null 2>&1; then
    "$S" cosim horner3 --width 16 >"$T/out" 2>"$T/err"
    grep -q '^bit-exact, 50 items, 301 clocks (icarus)$' "$T/out" && ok cosim_horner3 || fail cosim_horner3 "$(cat "$T/out" "$T/err")"
    # the user's own rerun from the exported files, as docs/verilog.md shows
    n=$(wc -l <"$T/rtl/s.hex")
    (cd "$T/rtl" && iverilog -g2005 -o tb.vvp horner3_tb.v horner3.v && vvp -n tb.vvp +in=s.hex +items="$n" +out=out.txt) >/dev/null 2>&1
    cmp -s "$T/rtl/s.hex.expect" "$T/rtl/out.txt" && ok rerun_by_hand || fail rerun_by_hand "results differ"
    # --keep with a folder named like an option, or "-": the tools run in
    # that folder (it ran `cd -x`, exit 1 blaming the RTL, and `cd -`)
    case $S in /*) SA=$S ;; *) SA=$(pwd)/$S ;; esac
    (cd "$T" && "$SA" cosim horner3 --keep -x >"$T/kx" 2>&1 && "$SA" cosim horner3 --keep - >"$T/kd" 2>&1) &&
        grep -q '^bit-exact' "$T/kx" && [ -s "$T/-x/horner3_tb.v" ] && [ -s "$T/-/horner3_tb.v" ] && ok keep_dash_folder \
        || fail keep_dash_folder "$(tail -1 "$T/kx") $(tail -1 "$T/kd" 2>/dev/null)"
else
    echo "skip ${PREFIX}cosim_horner3: iverilog not installed"
fi
if command -v yosys >/dev/null 2>&1; then
    "$S" synth div3 --width 8 >"$T/out" 2>"$T/err"
    grep -q '^  cells  *[1-9]' "$T/out" && grep -q 'GE (area model)' "$T/out" && ok synth_div3 || fail synth_div3 "$(cat "$T/out" "$T/err")"
else
    echo "skip ${PREFIX}synth_div3: yosys not installed"
fi
