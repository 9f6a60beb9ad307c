#!/bin/sh
# rom_area.sh - the mapped area of hf_lookup's tables as the export writes
# them, one block of the Verilog at a time: the figures behind docs/area.md,
# "Tables as mapped".
#
# usage: [SCRIPT=light|full] [SIGS="l0_rom_t00 ..."] sh scripts/rom_area.sh LIBERTY [W...]
#   LIBERTY  a Liberty file (gzipped or not), e.g. NanGate45's typical one
#   W        widths of hf_lookup (default 8 16 24)
#   SIGS     the signals whose blocks to map (default l0_rom_t00, one read
#            of a texture map, a case statement over its texel address)
#   SCRIPT   light (default: ABC's mapping alone, the script `synth --abc
#            light` runs, without its buffering) or full (ABC's default
#            script for a Liberty, with its restructuring)
# Each block is the export's text from the comment naming the signal to
# the next (`shadesim verilog hf_lookup --width W`), made a module whose
# inputs are the signals it reads and whose output is the signal, through
# `synth; abc -liberty L; opt_clean; stat -liberty L` (lib_map.sh). Prints:
# W, signal, the words its table's address selects (2^ the case items'
# bits), its output bits, mapped GE, and GE a bit (mapped GE / words /
# bits). Seconds of CPU a texture read; the
# reciprocal's block (l0_rec) at 24, minutes.
lib=${1:?usage: sh scripts/rom_area.sh LIBERTY [W...]}
shift
[ $# -gt 0 ] || set -- 8 16 24
me=rom_area.sh
S=${SHADESIM:-$(dirname "$0")/../bin/shadesim}
[ -x "$S" ] || { echo "$me: $S not found (make, or SHADESIM=PATH)" >&2; exit 2; }
. "$(dirname "$0")/lib_map.sh"
case ${SCRIPT:-light} in
light) abc_script='+strash;dretime;&get,-n;&nf;&put' ;;
full) abc_script= ;;
*) echo "$me: SCRIPT=$SCRIPT: light or full" >&2; exit 2 ;;
esac
for w in "$@"; do
    "$S" verilog hf_lookup --width "$w" -o "$d/v" >/dev/null || { echo "$me: shadesim verilog hf_lookup --width $w failed" >&2; exit 2; }
    for s in ${SIGS:-l0_rom_t00}; do
        # the block, and a module around it: the declared signals it reads
        # (declared outside it) are its inputs
        awk -v s="$s" '
            function width(l) { sub(/^[^[]*\[/, "", l); sub(/:.*/, "", l); return l + 1 }
            /^    (input|output)? *(wire|reg) +\[[0-9]+:0\] +[a-z0-9_]+[;,]/ && !/=/ {
                n = $0; sub(/[;,].*/, "", n); sub(/.* /, "", n); w[n] = width($0) }
            /^    \/\/ / { on = ($2 == s ":"); next }
            /^endmodule/ { on = 0 }
            on { body = body $0 "\n"; t = $0
                 while (match(t, /(wire|reg|function) +(signed +)?(\[[^]]*\] *)?[A-Za-z_][A-Za-z0-9_]*/)) {
                     d = substr(t, RSTART, RLENGTH); sub(/.*[] ]/, "", d); own[d] = 1; t = substr(t, RSTART + RLENGTH) }
                 t = $0; gsub(/[0-9]+'"'"'[bhd][0-9a-fA-F_]+/, " ", t); gsub(/[^A-Za-z0-9_]/, " ", t)
                 for (i = split(t, f, " "); i > 0; i--) used[f[i]] = 1 }
            END {
                if (!(s in w) || body == "") exit 1
                ports = ""
                for (n in used) if (n in w && n != s && !(n in own)) ports = ports sprintf("input [%d:0] %s, ", w[n] - 1, n)
                printf "module m(%soutput [%d:0] %s);\n%sendmodule\n", ports, w[s] - 1, s, body
            }' "$d/v/hf_lookup.v" >"$d/m.v" || { echo "$me: no block $s in hf_lookup at $w" >&2; exit 2; }
        # the words its address selects: 2^(the case items' bits)
        words=$(awk '/^ *[0-9]+'"'"'h[0-9a-f]+: / { sub(/^ */, ""); sub(/'"'"'.*/, ""); print 2 ^ $0; exit }' "$d/m.v")
        [ -n "$words" ] || words=0
        bits=$(awk -v s="$s" '/^module/ { l = $0; sub(".*output \\[", "", l); sub(":.*", "", l); print l + 1 }' "$d/m.v")
        area=$(map_area "$s" "$w") || exit 2
        awk -v w="$w" -v s="$s" -v n="$words" -v b="$bits" -v a="$area" -v g="$nand" 'BEGIN {
            printf "%3d %-12s %6d %3d %9.1f %6.3f\n", w, s, n, b, a / g, (n > 0 ? a / g / n / b : 0) }'
    done
done
