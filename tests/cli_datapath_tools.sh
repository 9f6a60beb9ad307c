#!/bin/sh
# Datapath files through the external tools (docs/datapaths.md): the
# export of each example co-simulated in Icarus bit-exact at two widths
# and on 1000 items, built-in units' files with fn=verilog logic likewise,
# and synthesized by Yosys. In tests/slow.list.
PREFIX=cli_datapath_tools.
. tests/lib_cli.sh
case "${TST_BUILD:-}" in *-asan) echo "skip ${PREFIX}tools: runs in the plain build only"; exit 0 ;; esac
if ! command -v iverilog >/dev/null 2>&1; then echo "skip ${PREFIX}icarus: iverilog not installed"
else
    for f in examples/fir4.dp examples/horner3.dp examples/dot3.dp examples/fir4_pipe.dp; do
        n=$(basename "$f" .dp)
        for w in 12 16; do
            expect "cosim_${n}_w$w" 0 "$S" cosim "$f" --width $w -n 1000
            check "cosim_${n}_w${w}_bit_exact" grep -q '^bit-exact, 1000 items' "$T/out"
        done
    done
    # the export is the file's: another schedule of rows, another design
    sed 's/^ctl bk_pass .*/&\nschedule slow clocks=7 "B loaded twice"\nctl mx1_sel 1 1 0 1 1 1 1\nctl mx2_sel 1 1 0 0 2 0 3\nctl bk_pass 0 0 1 0 1 0 1/' \
        examples/horner3.dp >"$T/h2.dp"
    expect cosim_second_schedule 0 "$S" cosim "$T/h2.dp" --schedule slow -n 200
    check cosim_second_schedule_bit_exact grep -q '^bit-exact, 200 items, 1401 clocks' "$T/out"
    # built-in units as datapath files whose wide logic is fn=verilog: the
    # simulator evaluates the texts Icarus compiles, bit for bit (every
    # unit with such elements, each of their kinds: compares, zero tests,
    # clamps, shifters, a priority encoder, the ROMs)
    for u in div schlick mschlick d_approx hf_lookup norm3 shade shade_cook; do
        "$S" netlist $u --datapath -o "$T/$u.dp"
        expect "cosim_written_$u" 0 "$S" cosim "$T/$u.dp" -n 200
        check "cosim_written_${u}_bit_exact" grep -q '^bit-exact, 200 items' "$T/out"
    done
fi
if ! command -v yosys >/dev/null 2>&1; then echo "skip ${PREFIX}synth: yosys not installed"
else
    expect synth_fir4 0 "$S" synth examples/fir4.dp
    check synth_fir4_cells grep -q '^  cells  *[0-9][0-9]* *= [0-9.]* GE' "$T/out"
fi
