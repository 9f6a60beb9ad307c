#!/bin/sh
# cmul_area.sh - the mapped area of products by a constant against the
# area model's rows (sim_area_cmul): the figures behind docs/area.md,
# "Constant products as mapped".
#
# usage: [KS="31 123 ..."] sh scripts/cmul_area.sh LIBERTY [N...]
#   LIBERTY  a Liberty file (gzipped or not), e.g. NanGate45's typical one
#   N        widths of x (default 8 16 24)
#   KS       the constants (default those the units multiply by: schlick's
#            31, mschlick's 123, d_approx's and ward_approx's 23 and 25
#            (184 and 200 without their trailing zeros), shade_cook's 9329
#            and 22755 at width 8)
# Each is one combinational module, y = x * K at the full width in the
# export's form ($signed({1'b0, x}) * $signed({1'b0, k}), k a wire tied to
# K), through `synth; abc -liberty L; opt_clean; stat -liberty L` (as
# scripts/mul_area.sh maps a product), in GE of the file's NAND2_X1.
# Prints: N, K, the ones of K, mapped GE, and that GE over N bits of each
# row after the first (the model charges each the GE a bit of a mapped
# N-bit adder, docs/area.md's "Adders as mapped": 6.125 at 8, 7.111 at 24).
# Seconds of CPU a product.
lib=${1:?usage: sh scripts/cmul_area.sh LIBERTY [N...]}
shift
[ $# -gt 0 ] || set -- 8 16 24
me=cmul_area.sh
. "$(dirname "$0")/lib_map.sh"
for n in "$@"; do
    for k in ${KS:-31 123 23 25 9329 22755}; do
        kw=$(awk -v k="$k" 'BEGIN { w = 0; for (v = k; v >= 1; v = int(v / 2)) w++; print w }')
        printf 'module m(input [%d:0] a, output [%d:0] y);\n  wire [%d:0] k = %d'"'"'d%d;\n  assign y = $signed({1'"'"'b0, a}) * $signed({1'"'"'b0, k});\nendmodule\n' \
            $((n - 1)) $((n + kw)) $((kw - 1)) "$kw" "$k" >"$d/m.v"
        area=$(map_area "x$k" $n) || exit 2
        awk -v k="$k" -v n=$n -v a="$area" -v g="$nand" 'BEGIN {
            m = 0; for (v = k; v >= 1; v = int(v / 2)) m += v % 2
            printf "%3d %6d %2d %8.1f %6.3f\n", n, k, m, a / g, (m > 1 ? a / g / (m - 1) / n : 0) }'
    done
done
