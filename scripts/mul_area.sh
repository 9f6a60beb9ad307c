#!/bin/sh
# mul_area.sh - the mapped area of full products against the area model's
# array (sim_area_mul), the figures behind sim_area_mul_fit
# (docs/area.md, "Products as mapped").
#
# usage: [KINDS="uu su ..."] sh scripts/mul_area.sh LIBERTY [N...]
#   LIBERTY  a Liberty file (gzipped or not), e.g. NanGate45's typical one
#   N        operand widths (default 4 8 16 24)
#   KINDS    the kinds to map (default all five, below)
# Each product is one combinational module, y = a * b at the full width,
# through `synth; abc -liberty L; opt_clean; stat -liberty L` (as `shadesim
# synth --sta` maps a design), in GE of the file's NAND2_X1. The kinds, as
# the export writes them: uu (a * b), su ($signed(a) * $signed({1'b0, b})),
# ss ($signed(a) * $signed(b)), and the squares usq (a * a) and ssq
# ($signed(a) * $signed(a)). Prints: kind, N, mapped GE, array GE, ratio.
# Minutes of CPU: ABC takes long over the signed x unsigned products of 16
# and 24 bits.
lib=${1:?usage: sh scripts/mul_area.sh LIBERTY [N...]}
shift
[ $# -gt 0 ] || set -- 4 8 16 24
me=mul_area.sh
. "$(dirname "$0")/lib_map.sh"
for n in "$@"; do
    for k in ${KINDS:-uu su ss usq ssq}; do
        case $k in
        uu) e='a * b' ;;
        su) e="\$signed(a) * \$signed({1'b0, b})" ;;
        ss) e='$signed(a) * $signed(b)' ;;
        usq) e='a * a' ;;
        ssq) e='$signed(a) * $signed(a)' ;;
        esac
        printf 'module m(input [%d:0] a, input [%d:0] b, output [%d:0] y);\n  assign y = %s;\nendmodule\n' \
            $((n - 1)) $((n - 1)) $((2 * n)) "$e" >"$d/m.v"
        area=$(map_area $k $n) || exit 2
        # the model's array: n^2 AND2 (1.33 GE) and (n-1) n full adders (5.33 GE)
        awk -v k=$k -v n=$n -v a="$area" -v g="$nand" 'BEGIN {
            m = n * n * 1.33 + (n - 1) * n * 5.33
            printf "%-4s %3d %9.1f %9.1f %6.3f\n", k, n, a / g, m, a / g / m }'
    done
done
