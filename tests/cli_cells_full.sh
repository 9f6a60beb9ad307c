#!/bin/sh
# cli_cells_full.sh - test_cells's full table: every element kind against
# sim_elem_eval for every format of widths 1 to 4 (the quick table, in
# test_cells itself, stops at 2 and 3 bits). About three minutes of CPU on
# the plain build; the sanitizer flavour runs the quick table only.
. tests/lib_cli.sh
PREFIX=cli_cells_full.
run_full test_cells widths4 TST_CELLS_FULL
