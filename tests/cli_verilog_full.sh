#!/bin/sh
# cli_verilog_full.sh - test_verilog's whole matrix (TST_VERILOG_FULL=1):
# every unit and schedule at 16 and 24 bits and three rounding/overflow
# pairs in Icarus, every schedule linted by Verilator and synthesized by
# Yosys. Minutes of the tools' time: `make test-long` runs it; make test
# runs test_verilog's part of the matrix.
. tests/lib_cli.sh
PREFIX=cli_verilog_full.
run_full test_verilog matrix TST_VERILOG_FULL
