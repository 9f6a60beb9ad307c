#!/bin/sh
# cli_stream.sh - `run --vectors FILE|-` streamed on the batch's lanes a
# wave at a time (docs/batch.md, "Streams of any length"): a pipe of 10^6
# items (10^5 under the sanitizers, 2 10^5 in make test-quick) gives the
# kernel's JSON but for its "sim" line, and the same bytes on 1 and 2
# threads. tests/cli_stream_waves.sh: other units over several waves, and
# the fall-backs.
. tests/lib_cli.sh
PREFIX=cli_stream.

n=1000000
if [ -n "$ASAN" ]; then n=100000; elif ! full_only; then n=200000; fi
$S vectors horner3 -n $n --seed 7 -o "$T/h.vec" 2>"$T/err" || fail vectors "$(cat "$T/err")"
cat "$T/h.vec" | $S run horner3 --vectors - --json -j 1 >"$T/j1.json"; r1=$?
cat "$T/h.vec" | $S run horner3 --vectors - --json -j 2 >"$T/j2.json"; r2=$?
$S run horner3 --vectors "$T/h.vec" --json --kernel >"$T/k.json"; rk=$?
if [ $r1 != 0 ] || [ $r2 != 0 ] || [ $rk != 0 ]; then fail pipe "exit $r1, $r2 on lanes, $rk on the kernel"
elif ! grep -q '"sim": {"engine": "batch", "lanes": [0-9]*, "clocks": [0-9]*}' "$T/j1.json"; then fail pipe "not on lanes: $(grep '"sim"' "$T/j1.json")"
elif [ "$(grep -v '"sim"' "$T/j1.json")" != "$(grep -v '"sim"' "$T/k.json")" ]; then
    fail pipe "JSON differs from the kernel's: $(diff "$T/j1.json" "$T/k.json" | head -4 | tr '\n' ' ')"
elif [ "$(sed -n 's/.*"clocks": \([0-9]*\).*/\1/p' "$T/j1.json")" != "$(sed -n 's/.*"sim".*"clocks": \([0-9]*\).*/\1/p' "$T/k.json")" ]; then
    fail pipe "clocks differ"
else ok pipe; fi
if cmp -s "$T/j1.json" "$T/j2.json"; then ok threads; else fail threads "-j 1 and -j 2 differ: $(diff "$T/j1.json" "$T/j2.json" | head -4 | tr '\n' ' ')"; fi
rm -f "$T/h.vec"

