#!/bin/sh
# cli_cells_full.sh - test_cells's full table: every element kind against
# sim_elem_eval for every format of widths 1 to 4 (the quick table, in
# test_cells itself, stops at 2 and 3 bits). About three minutes of CPU on
# the plain build; the sanitizer flavour runs the quick table only.
. tests/lib_cli.sh
PREFIX=cli_cells_full.
b=${TST_BUILD:-build}
case $b in
*-asan) echo "skip cli_cells_full: the plain build runs the full table (hours under the sanitizers)"; exit 0 ;;
esac
if [ ! -x "$b/tests/test_cells" ]; then fail run "no $b/tests/test_cells"; else
    TST_CELLS_FULL=1 "$b/tests/test_cells" >"$T/out" 2>&1; rc=$?
    if [ "$rc" -eq 0 ] && ! grep -q '^FAIL' "$T/out"; then ok widths4
    else fail widths4 "$(grep -v '^ok' "$T/out" | head -12 | tr '\n' ' ')"; fi
fi

