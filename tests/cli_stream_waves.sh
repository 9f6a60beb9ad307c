#!/bin/sh
# cli_stream_waves.sh - `run --vectors FILE|-` on the lanes (docs/batch.md,
# "Streams of any length"): units with long items over several waves (a
# deep pipeline that needs the long warm-up, several beats an item) give
# the kernel's JSON and --out rows, overflowing ones too (the kernel's
# counts, -j 1 and -j 2 the same bytes); when the lanes stop (an item that
# depends on more than the warm-up), the kernel runs the stream from its
# first row: handed back from the first block of a pipe, read again from a
# file, refused with one line from a pipe read past its first block (or
# with --out on a device); a bad row in a later block is the reader's
# FILE:LINE.
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

# overflows stay on the lanes over several waves (each file more than a
# block of text, 1 MiB: a stream's first wave is its first block alone),
# counted as the kernel counts them:
# horner3 with a product too narrow (used and discarded counts), norm3's
# deep pipeline on inputs scaled past the unit circle (its squares' sum
# wraps), span2's several beats an item with a narrow accumulator. A file
# on 2 threads, the same rows piped on 1: the same bytes, and the JSON the
# kernel's but for the sim line
# (under the sanitizers, fewer rows)
m=40000 h=100000
[ -n "$ASAN" ] && m=15000 h=60000
$S vectors horner3 -n $h --seed 9 -o "$T/horner3.vec" 2>/dev/null
$S vectors norm3 -n $m --seed 5 2>/dev/null |
    awk '!/^#/ { for (i = 1; i <= 3; i++) $i = sprintf("%.17g", $i * 1.6) } { print }' >"$T/norm3.vec"
$S vectors span2 -n $m --seed 5 -o "$T/span2.vec" 2>/dev/null
while read -r u sc f disc <&3; do
    n="ovf-waves.$u"
    $S run $u --schedule $sc --fmt $f --vectors "$T/$u.vec" --json -j 2 >"$T/j2.json"; r2=$?
    cat "$T/$u.vec" | $S run $u --schedule $sc --fmt $f --vectors - --json -j 1 >"$T/j1.json"; r1=$?
    $S run $u --schedule $sc --fmt $f --vectors "$T/$u.vec" --json --kernel >"$T/k.json"; rk=$?
    if [ $r1 != $rk ] || [ $r2 != $rk ]; then fail "$n" "exit $r1, $r2 on lanes, $rk on the kernel"
    elif ! grep -q '"sim": {"engine": "batch", "lanes": [0-9]*,' "$T/j1.json"; then
        fail "$n" "not on lanes: $(grep '"sim"' "$T/j1.json")"
    elif [ "$(wc -c <"$T/$u.vec")" -le 1048576 ]; then fail "$n" "the file is one block: not in waves"
    elif ! grep -q '^  "overflows": [1-9]' "$T/k.json"; then fail "$n" "no overflow"
    elif [ "$disc" = 1 ] && ! grep -q '^  "overflows_discarded": [1-9]' "$T/k.json"; then fail "$n" "no discarded overflow"
    elif [ "$(grep -v '"sim"' "$T/j1.json")" != "$(grep -v '"sim"' "$T/k.json")" ]; then
        fail "$n" "$(diff "$T/j1.json" "$T/k.json" | head -6 | tr '\n' ' ')"
    elif ! cmp -s "$T/j1.json" "$T/j2.json"; then fail "$n" "-j 1 and -j 2 differ: $(diff "$T/j1.json" "$T/j2.json" | head -4 | tr '\n' ' ')"
    else ok "$n"; fi
    rm -f "$T/$u.vec"
done 3<<EOF
    horner3 paper mul=s0.16 1
    norm3 pipe nx=s2.14 0
    span2 pipe ra=s1.9 0
EOF

# When the lanes stop, here because each item depends on every one before
# it (a running sum: no warm-up reaches its state), the kernel runs the
# stream: in a pipe's first block, from the rows the lanes hand back
cat >"$T/acc.dp" <<'EOF'
# y: the running sum of every x so far (twice each: two clocks an item)
netlist 1
datapath acc "running sum"
width 16
round trunc
overflow wrap
clock clk
input x s1.(W-1) range=-1,1
schedule run clocks=2 "x added into acc on each clock"
ctl keep 1 1
bk held s8.(W-8) pass=keep x=acc
add sum s8.(W-8) a=x b=held
reg acc s8.(W-8) d=sum clk=clk
shift y s8.(W-8) x=acc by=0
port in x
port out y
ideal y x
EOF
hdr() { printf '# shadesim vectors 1\n# unit: acc\n# inputs: x\n# outputs: y\n'; }
{ hdr; yes '0.01 | 0.01' | head -n 3000; } >"$T/first.vec"
cat "$T/first.vec" | $S run "$T/acc.dp" --vectors - --json >"$T/b.json"; rb=$?
cat "$T/first.vec" | $S run "$T/acc.dp" --vectors - >"$T/b.txt"
$S run "$T/acc.dp" --vectors "$T/first.vec" --json --kernel >"$T/k.json"; rk=$?
# (the JSON the kernel's but for the sim line's reason, which names it too)
if [ $rb = $rk ] && [ "$(sed 's/, "not_on_lanes": "[^"]*"}$/}/' "$T/b.json")" = "$(cat "$T/k.json")" ] &&
   grep -q '"not_on_lanes": "item [0-9]* depends on more than the 128 items' "$T/b.json" &&
   grep -q '^engine kernel: .*(not on lanes: item [0-9]* depends on more than the 128 items' "$T/b.txt"
then ok history-first-block; else fail history-first-block "exit $rb, $rk: $(grep '^engine' "$T/b.txt")"; fi

# past the first block (zero rows before the sum moves fill more than a
# block, 1 MiB): a file is read again by the kernel, --out written again;
# a pipe cannot be, and says so
{ hdr; yes '0.0000000000000000 | 0' | head -n 200000; yes '0.01 | 0.01' | head -n 3000; } >"$T/late.vec"
$S run "$T/acc.dp" --vectors "$T/late.vec" --out "$T/b.csv" >"$T/b.txt"; rb=$?
$S run "$T/acc.dp" --vectors "$T/late.vec" --kernel --out "$T/k.csv" >"$T/k.txt"; rk=$?
if [ $rb = $rk ] && cmp -s "$T/b.csv" "$T/k.csv" && grep -q '^engine kernel: .*(not on lanes: item 200[1-9][0-9][0-9] depends' "$T/b.txt" &&
   [ "$(grep -v '^engine' "$T/b.txt")" = "$(grep -v '^engine' "$T/k.txt")" ]
then ok history-late-file; else fail history-late-file "exit $rb, $rk: $(grep '^engine' "$T/b.txt")"; fi
cat "$T/late.vec" | expect history-late-pipe 2 $S run "$T/acc.dp" --vectors - --json
grep -q 'first block of stdin, which cannot be read again for the kernel: run it with --kernel' "$T/err" ||
    fail history-late-pipe.says "$(cat "$T/err")"
[ -s "$T/out" ] && fail history-late-pipe.nothing-written "$(head -c 200 "$T/out")"
expect history-late-out-device 2 $S run "$T/acc.dp" --vectors "$T/late.vec" --out /dev/null
rm -f "$T/late.vec"

# a bad row in a later block: the reader's FILE:LINE, exit 2, no --out left
{ sed -n '/^#/p' vectors/horner3.vec; yes '0 0 0 0 0 | 0' | head -n 320000; echo '0 0 zero 0 0 | 0'; } >"$T/bad.vec"
expect bad-row 2 $S run horner3 --vectors "$T/bad.vec" --out "$T/bad.csv"
grep -q "bad.vec:320005: " "$T/err" || fail bad-row.line "$(cat "$T/err")"
[ -e "$T/bad.csv" ] && fail bad-row.no-out "$T/bad.csv written"
rm -f "$T/bad.vec"

# -j's range
expect j-zero 2 $S run horner3 -j 0
