#!/bin/sh
# cli_stream_waves.sh - `run --vectors FILE|-` on the lanes (docs/batch.md,
# "Streams of any length"): units with long items over several waves (a
# deep pipeline that needs the long warm-up, several beats an item) give
# the kernel's JSON and --out rows; when the lanes stop (an item that
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
if [ $rb = $rk ] && cmp -s "$T/b.json" "$T/k.json" && grep -q '^engine kernel: .*(not on lanes: item [0-9]* depends on more than the 128 items' "$T/b.txt"
then ok history-first-block; else fail history-first-block "exit $rb, $rk: $(grep '^engine' "$T/b.txt")"; fi

# past the first block (zero rows before the sum moves fill more than a
# block, 4 MiB): a file is read again by the kernel, --out written again;
# a pipe cannot be, and says so
{ hdr; yes '0.0000000000000000 | 0' | head -n 200000; yes '0.01 | 0.01' | head -n 3000; } >"$T/late.vec"
$S run "$T/acc.dp" --vectors "$T/late.vec" --out "$T/b.csv" >"$T/b.txt"; rb=$?
$S run "$T/acc.dp" --vectors "$T/late.vec" --kernel --out "$T/k.csv" >"$T/k.txt"; rk=$?
if [ $rb = $rk ] && cmp -s "$T/b.csv" "$T/k.csv" && grep -q '^engine kernel: .*(not on lanes: item 2002[0-9]* depends' "$T/b.txt" &&
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
