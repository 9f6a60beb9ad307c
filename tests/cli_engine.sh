#!/bin/sh
# cli_engine.sh - `run` on the batch's lanes (the default) gives the same
# report as on the event-driven kernel (--kernel), for every unit and
# schedule: the JSON, byte for byte but for its "sim" line (the engine,
# and the kernel's own counters, printed only when the kernel ran), the
# text table but for its engine line, the --out CSV. The kernel and its
# reference (--reference: no fast path) give the same JSON byte for byte
# but for the engine's name, so every counter (events, delta cycles,
# process runs, clocks) and overflow count, and the same --vcd dump and
# .gtkw byte for byte (under the sanitizers, for each unit's first
# schedule). Then the cases that must fall back to the kernel:
# --vcd, an overflow.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_engine.

# every unit and schedule, as `list` names them
$S list >"$T/list" 2>&1
units=$(sed -n 's/^\([a-z0-9_]*\) — .*/\1/p' "$T/list")
[ -n "$units" ] || fail units "list names no unit"
for u in $units; do
    scheds=$($S list "$u" | sed -n 's/^  schedules: //p' | grep -oE '(^|, )[a-z0-9_-]+ \(' | tr -d ',( ')
    first=1
    for sc in $scheds; do
        n="$u.$sc"
        $S run "$u" --schedule "$sc" --json >"$T/b.json" 2>"$T/b.err"; rb=$?
        $S run "$u" --schedule "$sc" --json --kernel >"$T/k.json" 2>"$T/k.err"; rk=$?
        if [ "$rb" -ne "$rk" ]; then fail "$n" "exit $rb on lanes, $rk on the kernel"; continue; fi
        if ! grep -q '"sim": {"engine": "batch", "lanes": [0-9]*, "clocks": [0-9]*}$' "$T/b.json"; then
            fail "$n" "did not run on lanes: $(grep '"sim"' "$T/b.json")"; continue
        fi
        if ! grep -q '"sim": {"engine": "kernel", "clocks": [0-9]*, "events": [0-9]*, "delta_cycles"' "$T/k.json"; then
            fail "$n" "--kernel: $(grep '"sim"' "$T/k.json")"; continue
        fi
        grep -v '"sim": ' "$T/b.json" >"$T/b.rest"
        grep -v '"sim": ' "$T/k.json" >"$T/k.rest"
        # the clocks of the sim line too
        cb=$(sed -n 's/.*"clocks": \([0-9]*\).*/\1/p' "$T/b.json")
        ck=$(sed -n 's/.*"sim".*"clocks": \([0-9]*\),.*/\1/p' "$T/k.json")
        if ! cmp -s "$T/b.rest" "$T/k.rest"; then
            fail "$n" "JSON differs: $(diff "$T/b.rest" "$T/k.rest" | head -4 | tr '\n' ' ')"
        elif [ "$cb" != "$ck" ]; then
            fail "$n" "clocks $cb on lanes, $ck on the kernel"
        else
            ok "$n"
        fi
        # under the sanitizers (ASAN=1), the reference and the dumps for
        # each unit's first schedule only: the plain build checks them all
        if [ -n "$ASAN" ] && [ $first = 0 ]; then continue; fi
        first=0
        # the reference: the whole JSON, the sim line's counters included
        $S run "$u" --schedule "$sc" --json --reference >"$T/r.json" 2>"$T/r.err"; rr=$?
        sed 's/^\(  "sim": {"engine": \)"reference"/\1"kernel"/' "$T/r.json" >"$T/r.as-k"
        if [ "$rr" -ne "$rk" ]; then
            fail "$n.reference" "exit $rr on the reference, $rk on the kernel"
        elif ! grep -q '"sim": {"engine": "reference", "clocks": [0-9]*, "events": [0-9]*, "delta_cycles"' "$T/r.json"; then
            fail "$n.reference" "$(grep '"sim"' "$T/r.json")"
        elif ! cmp -s "$T/k.json" "$T/r.as-k"; then
            fail "$n.reference" "JSON differs: $(diff "$T/k.json" "$T/r.as-k" | head -4 | tr '\n' ' ')"
        else
            ok "$n.reference"
        fi
        # and the dump (through tb_run, where the JSON above was streamed)
        $S run "$u" --schedule "$sc" --kernel --vcd "$T/k.vcd" >"$T/k.txt" 2>&1; rk=$?
        $S run "$u" --schedule "$sc" --reference --vcd "$T/r.vcd" >"$T/r.txt" 2>&1; rr=$?
        if [ "$rk" -ne "$rr" ] || [ ! -s "$T/k.vcd" ]; then
            fail "$n.vcd" "exit $rk on the kernel, $rr on the reference: $(head -c 200 "$T/r.txt")"
        elif ! cmp -s "$T/k.vcd" "$T/r.vcd" || ! sed "s|$T/r\.vcd|$T/k.vcd|g" "$T/r.vcd.gtkw" | cmp -s "$T/k.vcd.gtkw" -; then
            # (the .gtkw names its own path and the dump's)
            fail "$n.vcd" "dumps differ: $(cmp "$T/k.vcd" "$T/r.vcd"; diff "$T/k.vcd.gtkw" "$T/r.vcd.gtkw" | head -4 | tr '\n' ' ')"
        elif [ "$(grep -v '^engine ' "$T/k.txt")" != "$(grep -v '^engine ' "$T/r.txt")" ] ||
             [ "$(sed -n 's/^engine kernel: //p' "$T/k.txt")" != "$(sed -n 's/^engine reference: //p' "$T/r.txt")" ]; then
            fail "$n.vcd" "tables differ: $(diff "$T/k.txt" "$T/r.txt" | head -4 | tr '\n' ' ')"
        else
            ok "$n.vcd"
        fi
    done
done

# the text table: one engine line each, the rest the same
$S run horner3 >"$T/b.txt"; $S run horner3 --no-batch >"$T/k.txt"
if grep -q '^engine batch: [0-9]* lanes' "$T/b.txt" && grep -q '^engine kernel: [0-9]* events, [0-9]* delta cycles' "$T/k.txt" &&
   [ "$(grep -v '^engine ' "$T/b.txt")" = "$(grep -v '^engine ' "$T/k.txt")" ]; then ok table; else fail table "$(diff "$T/b.txt" "$T/k.txt" | head -6 | tr '\n' ' ')"; fi
# the reference's table: its engine line names it, with the kernel's counts
$S run horner3 --reference >"$T/r.txt"
if grep -q '^engine reference: [0-9]* events, [0-9]* delta cycles' "$T/r.txt" &&
   [ "$(sed 's/^engine reference: /engine kernel: /' "$T/r.txt")" = "$(cat "$T/k.txt")" ]; then ok table-reference
else fail table-reference "$(diff "$T/k.txt" "$T/r.txt" | head -6 | tr '\n' ' ')"; fi

# a longer file (several items a lane, 64 lanes) and its --out rows
$S vectors span23 -n 5000 --seed 3 -o "$T/s.vec" 2>/dev/null
$S run span23 --schedule mac --vectors "$T/s.vec" --json --out "$T/b.csv" >"$T/b.json"; rb=$?
$S run span23 --schedule mac --vectors "$T/s.vec" --json --kernel --out "$T/k.csv" >"$T/k.json"; rk=$?
if [ "$rb" = "$rk" ] && grep -q '"engine": "batch", "lanes": 64' "$T/b.json" && cmp -s "$T/b.csv" "$T/k.csv" &&
   [ "$(grep -v '"sim"' "$T/b.json")" = "$(grep -v '"sim"' "$T/k.json")" ]; then ok long-csv; else fail long-csv; fi

# --vcd runs the kernel
$S run horner3 --vcd "$T/h.vcd" >"$T/v.txt"
if grep -q '^engine kernel: ' "$T/v.txt"; then ok vcd-kernel; else fail vcd-kernel "$(grep engine "$T/v.txt")"; fi

# an overflow: the kernel counts it, and says why it ran
$S run horner3 --fmt mul=s3.12 --json >"$T/b.json"; rb=$?
$S run horner3 --fmt mul=s3.12 --json --kernel >"$T/k.json"; rk=$?
$S run horner3 --fmt mul=s3.12 >"$T/o.txt"
if [ "$rb" = 1 ] && [ "$rk" = 1 ] && cmp -s "$T/b.json" "$T/k.json" && grep -q '"overflows": [1-9]' "$T/k.json" &&
   grep -q '^engine kernel: .*(not on lanes: an overflow' "$T/o.txt"; then ok overflow; else fail overflow; fi

# a vector file over 64 MiB (here mostly comment lines) is streamed on the
# kernel, with the same report
{ sed -n '/^#/p' vectors/horner3.vec; yes '# a comment line, to make the file larger than the lanes hold..............' | head -n 900000
  sed '/^#/d' vectors/horner3.vec; } >"$T/big.vec"
$S run horner3 --vectors "$T/big.vec" --json >"$T/b.json"; rb=$?
$S run horner3 --vectors "$T/big.vec" >"$T/b.txt"
$S run horner3 --json --kernel >"$T/k.json"
if [ "$rb" = 0 ] && grep -q '"engine": "kernel"' "$T/b.json" && grep -q '(not on lanes: a vector file over 64 MiB' "$T/b.txt" &&
   cmp -s "$T/b.json" "$T/k.json"; then ok big-file-streamed; else fail big-file-streamed; fi
rm -f "$T/big.vec"
