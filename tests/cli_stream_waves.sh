#!/bin/sh
# cli_stream_waves.sh - `run --vectors FILE|-` on the lanes (docs/batch.md,
# "Streams of any length"): units with long items over several waves (a
# deep pipeline that needs the long warm-up, several beats an item) give
# the kernel's JSON and --out rows; when the lanes stop (an overflow), the
# kernel runs the stream from its first row: handed back from the first
# block of a pipe, read again from a file, refused with one line from a
# pipe read past its first block; a bad row in a later block is the
# reader's FILE:LINE.
. tests/lib_cli.sh
PREFIX=cli_stream_waves.

# several waves of units with long items: norm3's pipeline needs the long
# warm-up, span2 gives several beats an item; the --out rows too
m=40000
[ -n "$ASAN" ] && m=15000
for u in norm3 span2; do
    $S vectors $u -n $m --seed 5 -o "$T/$u.vec" 2>/dev/null
    $S run $u --vectors "$T/$u.vec" --json -j 2 --out "$T/b.csv" >"$T/b.json"; rb=$?
    $S run $u --vectors "$T/$u.vec" --json --kernel --out "$T/k.csv" >"$T/k.json"; rk=$?
    if [ $rb != $rk ]; then fail "waves.$u" "exit $rb on lanes, $rk on the kernel"
    elif ! grep -q '"engine": "batch"' "$T/b.json"; then fail "waves.$u" "not on lanes: $(grep '"sim"' "$T/b.json")"
    elif [ "$(grep -v '"sim"' "$T/b.json")" != "$(grep -v '"sim"' "$T/k.json")" ]; then fail "waves.$u" "JSON differs"
    elif ! cmp -s "$T/b.csv" "$T/k.csv"; then fail "waves.$u" "--out differs: $(cmp "$T/b.csv" "$T/k.csv")"
    else ok "waves.$u"; fi
    rm -f "$T/$u.vec" "$T/b.csv" "$T/k.csv"
done

# an overflow in a pipe's first block: the kernel runs the stream, from
# the rows the lanes handed back
cat vectors/horner3.vec | $S run horner3 --fmt mul=s3.12 --vectors - --json >"$T/b.json"; rb=$?
cat vectors/horner3.vec | $S run horner3 --fmt mul=s3.12 --vectors - >"$T/b.txt"
$S run horner3 --fmt mul=s3.12 --vectors vectors/horner3.vec --json --kernel >"$T/k.json"; rk=$?
if [ $rb = 1 ] && [ $rk = 1 ] && cmp -s "$T/b.json" "$T/k.json" && grep -q '^engine kernel: .*(not on lanes: an overflow' "$T/b.txt"
then ok overflow-first-block; else fail overflow-first-block "exit $rb, $rk: $(grep '^engine' "$T/b.txt")"; fi

# an overflow past the first block (the zero rows before it fill more than
# a block, 4 MiB): a file is read again by the kernel, --out too; a pipe
# cannot be, and says so
{ sed -n '/^#/p' vectors/horner3.vec; yes '0 0 0 0 0 | 0' | head -n 320000; sed '/^#/d' vectors/horner3.vec; } >"$T/late.vec"
$S run horner3 --fmt mul=s3.12 --vectors "$T/late.vec" --out "$T/b.csv" >"$T/b.txt"; rb=$?
$S run horner3 --fmt mul=s3.12 --vectors "$T/late.vec" --kernel --out "$T/k.csv" >"$T/k.txt"; rk=$?
if [ $rb = 1 ] && [ $rk = 1 ] && cmp -s "$T/b.csv" "$T/k.csv" && grep -q '^engine kernel: .*(not on lanes: an overflow' "$T/b.txt" &&
   [ "$(grep -v '^engine' "$T/b.txt")" = "$(grep -v '^engine' "$T/k.txt")" ]
then ok overflow-late-file; else fail overflow-late-file "exit $rb, $rk: $(grep '^engine' "$T/b.txt")"; fi
cat "$T/late.vec" | expect overflow-late-pipe 2 $S run horner3 --fmt mul=s3.12 --vectors - --json
grep -q 'run it with --kernel' "$T/err" || fail overflow-late-pipe.says "$(cat "$T/err")"
[ -s "$T/out" ] && fail overflow-late-pipe.nothing-written "$(head -c 200 "$T/out")"
rm -f "$T/late.vec"

# a bad row in a later block: the reader's FILE:LINE, exit 2, no --out left
{ sed -n '/^#/p' vectors/horner3.vec; yes '0 0 0 0 0 | 0' | head -n 320000; echo '0 0 zero 0 0 | 0'; } >"$T/bad.vec"
expect bad-row 2 $S run horner3 --vectors "$T/bad.vec" --out "$T/bad.csv"
grep -q "bad.vec:320005: " "$T/err" || fail bad-row.line "$(cat "$T/err")"
[ -e "$T/bad.csv" ] && fail bad-row.no-out "$T/bad.csv written"
rm -f "$T/bad.vec"

# -j's range
expect j-zero 2 $S run horner3 -j 0
