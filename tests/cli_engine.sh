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
# schedule). Overflowing runs on the lanes, against the reference; a file
# over 64 MiB streamed on the lanes. Then the case that must fall back to
# the kernel: --vcd.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_engine.

# every unit and schedule, as `list` names them
$S list >"$T/list" 2>&1
# "UNIT SCHEDULE" per line, from list's "  schedules: NAME (what), ..." lines
awk '/^[a-z0-9_]+ — / { u = $1 }
     /^  schedules: / { s = substr($0, 14)
                        while (match(s, /(^|, )[a-z0-9_-]+ \(/)) {
                            w = substr(s, RSTART, RLENGTH); gsub(/[,( ]/, "", w); print u, w
                            s = substr(s, RSTART + RLENGTH) } }' "$T/list" >"$T/pairs"
[ -s "$T/pairs" ] || fail units "list names no unit"
# lanes against the kernel: the sim lines say which engine ran, the rest of
# the JSON byte for byte, the clocks of the sim line too (one awk: a
# process per check was most of this test's time)
same_json() {
    awk -v P="$PREFIX" -v n="$1" '
        FNR == NR { if (/"sim": /) bs = $0; else b[++nb] = $0; next }
        { if (/"sim": /) ks = $0; else k[++nk] = $0 }
        END {
            if (bs !~ /"sim": \{"engine": "batch", "lanes": [0-9]+, "clocks": [0-9]+\}$/) { print "FAIL " P n ": did not run on lanes: " bs; exit }
            if (ks !~ /"sim": \{"engine": "kernel", "clocks": [0-9]+, "events": [0-9]+, "delta_cycles"/) { print "FAIL " P n ": --kernel: " ks; exit }
            d = 0
            for (i = 1; i <= nb || i <= nk; i++) if (b[i] != k[i]) { d = i; break }
            if (d) { print "FAIL " P n ": JSON differs at line " d ": " b[d] " | " k[d]; exit }
            match(bs, /"clocks": [0-9]+/); cb = substr(bs, RSTART + 10, RLENGTH - 10)
            match(ks, /"clocks": [0-9]+/); ck = substr(ks, RSTART + 10, RLENGTH - 10)
            if (cb != ck) print "FAIL " P n ": clocks " cb " on lanes, " ck " on the kernel"
            else print "ok " P n
        }' "$T/b.json" "$T/k.json"
}
prev= nu=0 nleft=0
while read -r u sc <&3; do
    if [ "$u" != "$prev" ]; then first=1; prev=$u; nu=$((nu + 1)); fi
    n="$u.$sc"
    # under the sanitizers (ASAN=1), each unit's first schedule (the other
    # 22 of the 47 pairs, 44 processes, were a third of its time there): the
    # others run there in test_reference (the kernel and its reference,
    # every schedule, in process), test_schedules and test_batch (the lanes on the Horner, interpolator
    # and span units' schedules, in process) and test_cells (every
    # element kind on the lanes); the plain build compares them all here
    if [ -n "$ASAN" ] && [ $first = 0 ]; then nleft=$((nleft + 1)); continue; fi
    $S run "$u" --schedule "$sc" --json >"$T/b.json" 2>"$T/b.err"; rb=$?
    $S run "$u" --schedule "$sc" --json --kernel >"$T/k.json" 2>"$T/k.err"; rk=$?
    if [ "$rb" -ne "$rk" ]; then fail "$n" "exit $rb on lanes, $rk on the kernel"; continue; fi
    same_json "$n"
    # under the sanitizers (ASAN=1), the reference and the dumps for each
    # unit's first schedule only, in make test-quick for every fourth
    # unit's: make test's plain build checks them all (test_reference, in
    # every suite, holds the reference to the kernel's counters and
    # outputs on every schedule)
    if { [ -n "$ASAN" ] || ! full_only; } && [ $first = 0 ]; then continue; fi
    if ! full_only && [ $((nu % 4)) != 1 ]; then continue; fi
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
    elif ! cmp -s "$T/k.vcd" "$T/r.vcd" || ! sed 's|"r\.vcd|"k.vcd|g; s| r\.vcd\.gtkw$| k.vcd.gtkw|' "$T/r.vcd.gtkw" | cmp -s "$T/k.vcd.gtkw" -; then
        # (the .gtkw names itself and the dump)
        fail "$n.vcd" "dumps differ: $(cmp "$T/k.vcd" "$T/r.vcd"; diff "$T/k.vcd.gtkw" "$T/r.vcd.gtkw" | head -4 | tr '\n' ' ')"
    elif [ "$(grep -v '^engine ' "$T/k.txt")" != "$(grep -v '^engine ' "$T/r.txt")" ] ||
         [ "$(sed -n 's/^engine kernel: //p' "$T/k.txt")" != "$(sed -n 's/^engine reference: //p' "$T/r.txt")" ]; then
        fail "$n.vcd" "tables differ: $(diff "$T/k.txt" "$T/r.txt" | head -4 | tr '\n' ' ')"
    else
        ok "$n.vcd"
    fi
done 3<"$T/pairs"
[ $nleft -gt 0 ] && echo "skip ${PREFIX}other_schedules: $nleft pairs, compared in the plain build"

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

# overflows stay on the lanes, counted as the kernel counts them (used and
# discarded, per signal): for every unit and schedule a format that makes
# its default vectors overflow (hf_lookup aside: its ROM is a process the
# lanes do not take), the lanes' JSON against the reference's (the kernel
# without its fast paths) but for the sim line, and the sim line says
# batch; some saturating ones, and div's quotient past 1 (n > d) besides
# (under the sanitizers, each unit's first pair: the other 22 of the 49,
# 44 processes, are the plain build's; test_batch counts the lanes'
# overflows against the kernel's in process there)
$S vectors div -n 200 --seed 5 -o "$T/d.vec" 2>/dev/null
awk '!/^#/ && NR % 3 == 0 { $1 = $2 * 1.5; if ($1 >= 2) $1 = 1.9 } { print }' "$T/d.vec" >"$T/dn.vec"
prev= nleft=0
while read -r u sc f <&3; do
    n="overflow.$u.$sc.$f"
    if [ -n "$ASAN" ] && [ "$u" = "$prev" ]; then nleft=$((nleft + 1)); continue; fi
    prev=$u
    case $u in div) extra="--vectors $T/dn.vec";; *) extra=;; esac
    $S run "$u" --schedule "$sc" --fmt "$f" $extra --json >"$T/b.json" 2>"$T/b.err"; rb=$?
    $S run "$u" --schedule "$sc" --fmt "$f" $extra --json --reference >"$T/r.json" 2>"$T/r.err"; rr=$?
    if [ "$rb" != "$rr" ]; then fail "$n" "exit $rb on lanes, $rr on the reference: $(head -c 200 "$T/b.err")"
    elif ! grep -q '"sim": {"engine": "batch"' "$T/b.json"; then fail "$n" "not on lanes: $(grep '"sim"' "$T/b.json")"
    elif ! grep -q '^  "overflows": [1-9]' "$T/r.json"; then fail "$n" "no overflow"
    elif [ "$(grep -v '"sim"' "$T/b.json")" != "$(grep -v '"sim"' "$T/r.json")" ]; then
        fail "$n" "$(diff "$T/b.json" "$T/r.json" | head -6 | tr '\n' ' ')"
    else ok "$n"; fi
done 3<<EOF
    coef2 comb a=s3.12
    coef3_n1 comb a=s5.10
    coef3_n2 comb a=s5.10
    d_approx square d=u2.13
    dot3 comb y=s1.14
    dot3 pipe y=s1.14
    horner2 mac mx1=s3.9
    horner2 paper mx1=s3.9
    horner2 pipe sm1=s3.9
    horner3 mac mul=s3.12:sat
    horner3 paper mul=s3.12
    horner3 pipe mul1=s3.9
    interp2 fwd s12=u1.15
    interp2 mac ra=s3.9
    interp2 paper ra=s3.9
    interp2 pipe ra=s3.9
    interp3 fwd i4x8=u2.12
    interp3 mac ra=s3.9
    interp3 paper all=s4.11
    interp3 pipe ra=s3.9
    mschlick restoring f=u0.15
    norm3 pipe uy=s1.14
    norm3 restoring uy=s1.14
    pow_n sqmul y=u0.15
    powg square y=u0.15
    schlick restoring f=u0.15
    shade pipe nn=u0.28
    shade shared nl=u0.18
    shade_cook pipe i=u0.15
    span1 mac ra=s1.14
    span1 paper ra=s1.14
    span1 pipe ra=s1.14
    span2 mac ra=s3.9
    span2 paper ra=s3.9
    span2 pipe ra=s3.9
    span23 mac mx1=s3.9
    span23 paper mx1=s3.9
    span23 pipe mul1=s3.9
    span3 mac ra=s3.9
    span3 paper mul=s1.14
    span3 pipe ra=s3.9
    sqrt pipe y=u0.15
    sqrt restoring y=u0.15
    ward_approx square e=u0.15
    div3 comb t0=u1.16
    horner3 paper mul=s3.12:sat
    span23 mac mx1=s3.9:sat
    div restoring q=u0.16
EOF
[ $nleft -gt 0 ] && echo "skip ${PREFIX}overflow.other_pairs: $nleft pairs, compared in the plain build"
# the table says so too, with the summary's discarded line
$S run horner3 --fmt mul=s0.16 >"$T/o.txt"; rb=$?
$S run horner3 --fmt mul=s0.16 --kernel >"$T/k.txt"; rk=$?
if [ "$rb" = "$rk" ] && grep -q '^engine batch: ' "$T/o.txt" && grep -q 'overflows on values no element took' "$T/o.txt" &&
   [ "$(grep -v '^engine ' "$T/o.txt")" = "$(grep -v '^engine ' "$T/k.txt")" ]; then ok overflow-table; else fail overflow-table; fi

# a vector file over 64 MiB (here mostly comment lines) is streamed on the
# lanes a block at a time, with the same report (tests/cli_stream.sh: a
# pipe of 10^6 items)
{ sed -n '/^#/p' vectors/horner3.vec; yes '# a comment line, to make the file larger than the lanes held once.........' | head -n 900000
  sed '/^#/d' vectors/horner3.vec; } >"$T/big.vec"
$S run horner3 --vectors "$T/big.vec" --json >"$T/b.json"; rb=$?
$S run horner3 --json --kernel >"$T/k.json"
if [ "$rb" = 0 ] && grep -q '"engine": "batch"' "$T/b.json" &&
   [ "$(grep -v '"sim"' "$T/b.json")" = "$(grep -v '"sim"' "$T/k.json")" ]; then ok big-file-streamed; else fail big-file-streamed; fi
rm -f "$T/big.vec"
