#!/bin/sh
# cli_verilog_full.sh - test_verilog's whole matrix (TST_VERILOG_FULL=1):
# every unit and schedule at 16 and 24 bits and three rounding/overflow
# pairs in Icarus, every schedule linted by Verilator and synthesized by
# Yosys. Minutes of the tools' time: `make test-long` runs it; make test
# runs test_verilog's part of the matrix.
. tests/lib_cli.sh
PREFIX=cli_verilog_full.
b=${TST_BUILD:-build}
case $b in
*-asan) echo "skip cli_verilog_full: the tools run in the plain build only"; exit 0 ;;
esac
if [ ! -x "$b/tests/test_verilog" ]; then fail run "no $b/tests/test_verilog"; else
    TST_VERILOG_FULL=1 "$b/tests/test_verilog" >"$T/out" 2>&1; rc=$?
    if [ "$rc" -eq 0 ] && ! grep -q '^FAIL' "$T/out"; then ok matrix
    else fail matrix "$(grep -v '^ok' "$T/out" | head -12 | tr '\n' ' ')"; fi
fi
