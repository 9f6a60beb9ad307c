#!/bin/sh
# bench/verilog/run.sh - shadesim against Verilator (and Icarus Verilog) on
# the same design and the same vector file: horner3 (bench/verilog/horner3.v,
# the RTL of units/unit_horner.c) over 200,000 pixels, 1.2M clocks.
#
# Each simulator's whole process is timed from outside (best of 3): reading
# and parsing the vector text, quantizing, simulating, writing results.
# The outputs are compared raw for raw. Called by `make bench`; prints
# "skipped: verilator not installed" when there is no verilator.
#
#   sh bench/verilog/run.sh [VECTORS]     (default: generated, 200k pixels)
cd "$(dirname "$0")/../.." || exit 2
if ! command -v verilator >/dev/null 2>&1; then
    echo "verilog  horner3 vs Verilator: skipped: verilator not installed"
    exit 0
fi
SHADESIM=${SHADESIM:-bin/shadesim}
B=build/verilog
OBJ=$B/obj16
TB=$OBJ/horner3_tb
mkdir -p "$B"
tmp=$(mktemp -d /tmp/shadesim_verilog.XXXXXX) || exit 2
trap 'rm -rf "$tmp"' EXIT

# Build the Verilator model when its sources changed.
if [ ! -x "$TB" ] || [ bench/verilog/horner3.v -nt "$TB" ] || [ bench/verilog/horner3_tb.cpp -nt "$TB" ]; then
    rm -rf "$OBJ"
    # The model's C++ at -O3 (Verilator's makefile default is -Os, slower here).
    if ! verilator -O3 --x-assign fast --x-initial fast --noassert -Wno-fatal \
            --cc --exe --build -j 2 -CFLAGS -O2 -MAKEFLAGS "OPT_FAST=-O3 OPT_GLOBAL=-O2" \
            --Mdir "$OBJ" --top-module horner3 \
            -o horner3_tb "$PWD/bench/verilog/horner3.v" "$PWD/bench/verilog/horner3_tb.cpp" \
            >"$B/verilator.log" 2>&1; then
        echo "verilog: verilator build failed, see $B/verilator.log"
        exit 1
    fi
fi

VEC=${1:-$tmp/h3.vec}
if [ -z "$1" ]; then
    "$SHADESIM" vectors horner3 -n 200000 --seed 7 -o "$VEC" || exit 1
fi
now() { date +%s.%N; }
# best CMD...: best of 3 wall-clock seconds of CMD (stdout discarded).
best() {
    b=
    for k in 1 2 3; do
        t0=$(now); "$@" >/dev/null 2>&1 || { echo "verilog: '$*' failed" >&2; return 1; }; t1=$(now)
        b=$(echo "$t0 $t1 ${b:-999}" | awk '{d = $2 - $1; print (d < $3 ? d : $3)}')
    done
    echo "$b"
}
ts=$(best "$SHADESIM" run horner3 --vectors "$VEC" --json) || exit 1
tv=$(best "$TB" "$VEC" -) || exit 1

# Same outputs: shadesim's y_raw column against the Verilator model's.
"$SHADESIM" run horner3 --vectors "$VEC" --out "$tmp/s.csv" >/dev/null || exit 1
"$TB" "$VEC" "$tmp/v.txt" --raw-in "$tmp/in.hex" 2>/dev/null || exit 1
tail -n +2 "$tmp/s.csv" | cut -d, -f3 >"$tmp/s.txt"
n=$(wc -l <"$tmp/s.txt")
if cmp -s "$tmp/s.txt" "$tmp/v.txt"; then same="identical ($n values)"; else same="DIFFER"; fi

echo "verilog  horner3 $n pixels, 1.2M clocks, whole process (parse + quantize + simulate + output), best of 3:"
echo "$ts $tv" | awk '{printf "verilog    shadesim  %.3f s\nverilog    verilator %.3f s   (-O3 --x-assign fast, C++ -O3)\nverilog    shadesim / verilator = %.2f\n", $1, $2, $1 / $2}'
echo "verilog    outputs shadesim vs verilator: $same"

if command -v iverilog >/dev/null 2>&1 && [ -z "$NO_ICARUS" ]; then
    if iverilog -g2005 -o "$tmp/tb.vvp" bench/verilog/horner3_tb.v bench/verilog/horner3.v 2>"$tmp/iv.log"; then
        # One run: Icarus reads the quantized inputs (hex), not the text.
        t0=$(now); vvp -n "$tmp/tb.vvp" +in="$tmp/in.hex" +out="$tmp/i.txt" >/dev/null 2>&1; t1=$(now)
        cut -d' ' -f2 "$tmp/i.txt" | cmp -s - "$tmp/v.txt" && isame=identical || isame=DIFFER
        echo "$t0 $t1 $ts" | awk '{d = $2 - $1; printf "verilog    icarus    %.3f s   (one run, from pre-quantized hex; %.2f M clocks/s; %.0fx shadesim)\n", d, 1.2 / d, d / $3}'
        echo "verilog    outputs icarus vs verilator: $isame"
    else
        echo "verilog    icarus: compile failed: $(head -1 "$tmp/iv.log")"
    fi
fi
[ "$same" != DIFFER ]
