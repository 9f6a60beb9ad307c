#!/bin/sh
# cli_widthrange.sh - a unit's range of widths: `list` states it, `run` past
# its top says so (exit 2, one line), and `sweep` reports configurations
# past it as "not buildable" (exit 0), not as failed simulations.
PREFIX=cli_widthrange.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)

# The top, from the divider's rule (units/unit_div.c): the remainder r has
# the divisor's fraction bits plus its integer bits and may be at most 62
# bits wide. div's divisor is u1.(W-1): W <= 62. schlick's divisor is
# uI.(W-1) with I the integer bits of n (n = 32 by default: 6 bits):
# 6 + W - 1 <= 62, W <= 57.
"$S" list div >"$T/div.txt" 2>&1
"$S" list schlick >"$T/schlick.txt" 2>&1
"$S" list horner3 >"$T/horner3.txt" 2>&1
check list_div_range grep -q '^  --width range: [0-9]*\.\.62 (default parameters); wider, ' "$T/div.txt"
check list_schlick_range grep -q '^  --width range: [0-9]*\.\.57 (default parameters); wider, ' "$T/schlick.txt"
check list_horner3_range grep -q '^  --width range: 8\.\.64 (default parameters)$' "$T/horner3.txt"

# run at the top builds; one past it is refused with the range.
oneline() {
    name=$1 want=$2; shift 2
    "$S" "$@" >"$T/out" 2>"$T/err"; rc=$?
    if [ $rc -ne 2 ]; then fail "$name" "exit $rc, expected 2"
    elif [ "$(wc -l <"$T/err")" -ne 1 ] || ! grep -q "$want" "$T/err"; then fail "$name" "stderr: $(cat "$T/err")"
    else ok "$name"; fi
}
oneline run_schlick_58 '^shadesim: --width 58: unit schlick builds with its default formats at widths [0-9]*\.\.57 only' run schlick --width 58
oneline run_div_63 '^shadesim: --width 63: unit div builds with its default formats at widths [0-9]*\.\.62 only' run div --width 63
"$S" vectors div -n 20 -o "$T/div.vec" 2>/dev/null
check run_div_62 sh -c '"$1" run div --width 62 --vectors "$2" >/dev/null' sh "$S" "$T/div.vec"

# sweep across the top: the rows past it say "not buildable"; exit 0.
"$S" sweep div --widths 61:63 -n 20 -o "$T/sw" >"$T/sw.txt" 2>"$T/sw.err"; rc=$?
check sweep_exit_0 [ $rc -eq 0 ]
check sweep_row_63_not_buildable grep -q '^   63  -  *not buildable: ' "$T/sw.txt"
check sweep_row_62_ran sh -c 'grep "^   62 " "$1" | grep -qv "not buildable\|failed"' sh "$T/sw.txt"
check sweep_csv_status sh -c 'grep -q ",div,[a-z]*,63,.*,not_buildable," "$1" && grep -q ",div,[a-z]*,62,.*,ok," "$1"' sh "$T/sw/sweep.csv"
check sweep_no_failed sh -c '! grep -q failed "$1"' sh "$T/sw.txt"

# shade: the square root's recurrence takes at most 57 result bits, and
# shade's root has W + 2 fraction bits after a radicand of 2W - 4 (up to
# W = 25) or W + 21: W + 2 <= 57 and half the radicand's at most the
# root's, so W <= 39. Every verb past the top says the range in one line
# (the shared schedule's program once named the exponent n instead).
"$S" list shade >"$T/shade.txt" 2>&1
check list_shade_range grep -q '^  --width range: 3\.\.39 (default parameters); wider, ' "$T/shade.txt"
shade_range='unit shade builds with its default formats at widths 3\.\.39 only (square root: '
oneline run_shade_40 "^shadesim: --width 40: $shade_range" run shade --width 40
oneline run_shade_pipe_60 "^shadesim: --width 60: $shade_range" run shade --schedule pipe --width 60
oneline verilog_shade_60 "^shadesim: --width 60: $shade_range" verilog shade --width 60 -o "$T/v60"
check verilog_shade_60_no_file [ ! -e "$T/v60" ]
oneline scene_shade_60 "^shadesim: --set width: width 60: $shade_range.*(the per-pixel shader)\$" \
    scene face --set width=60 --set resolution=16x16 -j 1 -o "$T/sc60"
# a scene file's width past a unit the render builds: at the key's line,
# before any work (63 failed in the divider, naming --fmt)
printf 'shadesim-scene 1\nresolution 16x16\nwidth 63\n' >"$T/w63.scene"
oneline scene_file_width_63 "^shadesim: .*w63.scene:3: width 63: $shade_range" scene "$T/w63.scene" -o "$T/sc63"
printf 'shadesim-scene 1\nresolution 16x16\nspecular phong\nwidth 63\n' >"$T/p63.scene"
oneline scene_phong_width_63 "^shadesim: .*p63.scene:4: width 63: unit div builds with its default formats at widths [0-9]*\.\.62 only.*(the reference's divider bound)\$" \
    scene "$T/p63.scene" -o "$T/sp63"
"$S" sweep shade --widths 39:40 -o "$T/swsh" >"$T/swsh.txt" 2>&1; rc=$?
check sweep_shade_exit_0 [ $rc -eq 0 ]
check sweep_shade_40_not_buildable grep -q '^   40  -  *not buildable: square root: ' "$T/swsh.txt"
