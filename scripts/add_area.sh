#!/bin/sh
# add_area.sh - the mapped area of adders, subtractors, incrementers and
# carry-only adders per bit, the figures behind sim_area_add_fit
# (docs/area.md, "Adders as mapped").
#
# usage: [KINDS="add sub ..."] sh scripts/add_area.sh LIBERTY [N...]
#   LIBERTY  a Liberty file (gzipped or not), e.g. NanGate45's typical one
#   N        operand widths (default 4 8 16 24)
#   KINDS    the kinds to map (default all four, below)
# Each is one combinational module of n-bit operands through `synth; abc
# -liberty L; opt_clean; stat -liberty L` (as scripts/mul_area.sh maps a
# product), in GE of the file's NAND2_X1. The kinds: add (y = a + b, n
# bits), sub (y = a - b), inc (y = a + c, c one bit: an incrementer) and
# carry (the carry out of a + b alone). Prints: kind, N, mapped GE, GE a bit.
# Seconds of CPU.
lib=${1:?usage: sh scripts/add_area.sh LIBERTY [N...]}
shift
[ $# -gt 0 ] || set -- 4 8 16 24
me=add_area.sh
. "$(dirname "$0")/lib_map.sh"
for n in "$@"; do
    for k in ${KINDS:-add sub inc carry}; do
        case $k in
        add) e="wire [$((n - 1)):0] s = a + b; assign y = s;" ;;
        sub) e="wire [$((n - 1)):0] s = a - b; assign y = s;" ;;
        inc) e="wire [$((n - 1)):0] s = a + c; assign y = s;" ;;
        carry) e="wire [$n:0] s = a + b; assign y = s[$n];" ;;
        esac
        printf 'module m(input [%d:0] a, input [%d:0] b, input c, output [%d:0] y);\n  %s\nendmodule\n' \
            $((n - 1)) $((n - 1)) $((n - 1)) "$e" >"$d/m.v"
        area=$(map_area $k $n) || exit 2
        awk -v k=$k -v n=$n -v a="$area" -v g="$nand" 'BEGIN { printf "%-5s %3d %8.1f %6.3f\n", k, n, a / g, a / g / n }'
    done
done
