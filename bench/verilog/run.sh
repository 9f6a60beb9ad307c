#!/bin/sh
# bench/verilog/run.sh - shadesim against Verilator and Icarus Verilog on the
# Verilog that `shadesim verilog` exports (generated, not hand-written):
# horner3 (paper schedule, 200,000 pixels, 1.2M clocks) and interp3 (paper
# schedule, L = 8: 5,000 intervals, 240k clocks), same stimulus.
#
# `shadesim cosim --keep` exports, builds and checks each design bit- and
# cycle-exact first; then each simulator's whole process is timed from
# outside (best of 3; Icarus once): shadesim reads and quantizes the vector
# text and simulates; the Verilog testbenches read the pre-quantized hex
# stimulus. Called by `make bench`; says "skipped" without verilator.
#
# For horner3 also what a user who wants speed writes: a C++ main
# (bench/verilog/harness.cpp) driving the Verilated model from the same
# text vector file with std::from_chars, built -O3, checked against the
# same expected lines and timed whole-process the same way; and the
# simulation alone: the harness's eval loop (the file already parsed)
# against the batch mode's lanes (bench_batch clocks, when built).
#
#   sh bench/verilog/run.sh
cd "$(dirname "$0")/../.." || exit 2
if ! command -v verilator >/dev/null 2>&1; then
    echo "verilog  generated RTL vs Verilator: skipped: verilator not installed"
    exit 0
fi
SHADESIM=${SHADESIM:-bin/shadesim}
tmp=$(mktemp -d /tmp/shadesim_verilog.XXXXXX) || exit 2
trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
# best CMD...: best of 3 wall-clock seconds of CMD (output discarded).
best() {
    b=
    for k in 1 2 3; do
        t0=$(now); "$@" >/dev/null 2>&1 || { echo "verilog: '$*' failed" >&2; return 1; }; t1=$(now)
        b=$(echo "$t0 $t1 ${b:-999}" | awk '{d = $2 - $1; print (d < $3 ? d : $3)}')
    done
    echo "$b"
}
fail=0
for spec in "horner3 200000" "interp3 5000"; do
    set -- $spec
    u=$1 n=$2 D=$tmp/$u
    "$SHADESIM" vectors "$u" -n "$n" --seed 7 -o "$tmp/$u.vec" || exit 1
    v=$("$SHADESIM" cosim "$u" --width 16 --vectors "$tmp/$u.vec" --sim verilator --keep "$D") || { echo "verilog  $u: $v"; fail=1; continue; }
    clocks=$(echo "$v" | sed 's/.* items, \([0-9]*\) clocks.*/\1/')
    ts=$(best "$SHADESIM" run "$u" --width 16 --vectors "$tmp/$u.vec" --json) || exit 1
    tv=$(best "$D/obj_verilator/${u}_vtb" +in="$D/stimulus.hex" +items="$n" +out="$tmp/v.out") || exit 1
    # Icarus is slow: a tenth of the items, one run, checked against the
    # same expected lines, its time scaled up by ten.
    ni=$((n / 10))
    (cd "$D" && iverilog -g2005 -P "${u}_tb.MAXWORDS=$((n * 8))" -o "${u}_tb.vvp" "${u}_tb.v" "$u.v") || exit 1
    t0=$(now); vvp -n "$D/${u}_tb.vvp" +in="$D/stimulus.hex" +items="$ni" +out="$tmp/i.out" >/dev/null 2>&1; t1=$(now)
    lines=$(wc -l <"$tmp/i.out")
    if head -n "$lines" "$D/stimulus.hex.expect" | cmp -s - "$tmp/i.out" && [ "$lines" -gt 0 ]; then i="bit-exact ($lines beats)"; else i=DIFFER; fail=1; fi
    echo "verilog  $u (generated RTL, --width 16): $n items, $clocks clocks; verilator: $v; icarus on $ni items: $i"
    echo "$ts $tv $t0 $t1 $clocks" | awk '{ti = 10 * ($4 - $3);
        printf "verilog    shadesim  %.3f s   (%.2f M clocks/s)\n", $1, $5 / $1 / 1e6;
        printf "verilog    verilator %.3f s   (--binary, timed testbench; shadesim / verilator = %.2f)\n", $2, $1 / $2;
        printf "verilog    icarus    %.3f s   (a tenth of the items times ten; icarus / shadesim = %.1f)\n", ti, ti / $1}'
    [ "$u" = horner3 ] || continue
    # the C++ harness on the same .vec text
    H=$D/objh/horner3_harness
    if ! verilator --cc --exe --build -O3 --x-assign fast --x-initial fast --noassert -Wno-fatal \
            -CFLAGS "-O3 -std=c++17" -MAKEFLAGS "OPT_FAST=-O3 OPT_SLOW=-O3 OPT_GLOBAL=-O3" \
            --top-module horner3 -Mdir "$D/objh" -o horner3_harness "$D/horner3.v" "$PWD/bench/verilog/harness.cpp" \
            >"$tmp/harness.log" 2>&1; then
        echo "verilog  horner3 C++ harness: build failed: $(tail -3 "$tmp/harness.log")"; fail=1; continue
    fi
    "$H" "$tmp/$u.vec" "$tmp/h.out" 2>"$tmp/h.err" || { echo "verilog  horner3 C++ harness failed"; fail=1; continue; }
    if ! cmp -s "$tmp/h.out" "$D/stimulus.hex.expect"; then echo "verilog  horner3 C++ harness: DIFFERS from shadesim"; fail=1; continue; fi
    # whole process, interleaved with shadesim (best of 5 each), and its eval loop alone
    bs=999 bh=999 be=999
    for k in 1 2 3 4 5; do
        t0=$(now); "$SHADESIM" run "$u" --width 16 --vectors "$tmp/$u.vec" --json >/dev/null 2>&1; t1=$(now)
        "$H" "$tmp/$u.vec" "$tmp/h.out" 2>"$tmp/h.err"; t2=$(now)
        set -- $(echo "$t0 $t1 $t2 $bs $bh $be $(cat "$tmp/h.err")" | awk '{s = $2 - $1; h = $3 - $2;
            print (s < $4 ? s : $4), (h < $5 ? h : $5), ($8 < $6 ? $8 : $6), $9}')
        bs=$1 bh=$2 be=$3 ec=$4
    done
    B=${BENCH_BATCH:-build/bench/bench_batch}
    bb=; [ -x "$B" ] && bb=$("$B" clocks 2>/dev/null)
    # the load average the interleaved runs shared the cores with
    load=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || uptime | sed 's/.*average[s]*: *//; s/,//g')
    echo "$bs $bh $be $ec $ts $tv $bb" | awk -v load="$load" '{
        printf "verilog    harness   %.3f s   (C++ main, std::from_chars on the same .vec, -O3, bit-exact; shadesim %.3f s: shadesim / verilator = %.2f, target <= 0.5; load average %s)\n", $2, $1, $1 / $2, load;
        printf "verilog    ratios    shadesim / verilator: %.2f against the C++ harness, %.2f against the --binary testbench\n", $1 / $2, $5 / $6;
        printf "verilog    eval loop %.1f M clocks/s (%d clocks in %.4f s, file parsed before)", $4 / $3 / 1e6, $4, $3;
        if (NF >= 8) printf "; batch lanes (bench_batch clocks, 64 lanes) %.1f M clocks/s: batch / eval loop = %.2f", $8 / $7 / 1e6, ($8 / $7) / ($4 / $3);
        printf "\n"}'
done
exit $fail
