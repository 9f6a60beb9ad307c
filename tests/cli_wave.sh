#!/bin/sh
# Waveforms from the command line: the .gtkw names its dump and itself by
# their names (and GTKWave, from another folder, finds the pair, moved
# too), GTKWave itself
# (headless, under xvfb-run) shows the outputs in fixed point with their
# expected values and errors as the --out CSV has them, the item window
# ends where it should, --fst gives a file fst2vcd reads back, and the bad
# uses of the options are one-line errors.
PREFIX=cli_wave.
. tests/lib_cli.sh

expect2() {   # NAME CMD...: exit 2 with one "shadesim: " line
    name=$1; shift
    "$@" >"$T/out" 2>"$T/err"; got=$?
    if [ "$got" -eq 2 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q '^shadesim: ' "$T/err"; then ok "$name"
    else fail "$name" "exit $got: $(head -c 300 "$T/err")"; fi
}

# the runs below change folder: the binary by absolute path
S=$(cd "$(dirname "$S")" && pwd)/$(basename "$S")
mkdir -p "$T/run/sub" "$T/elsewhere"
# written from one folder with a relative path ...
(cd "$T/run" && "$S" run horner3 --vcd sub/h.vcd --out h.csv >/dev/null 2>&1) || fail written "run failed"
g="$T/run/sub/h.vcd.gtkw"
# ... it names the dump and itself by their names alone (they lie side by
# side; no absolute path, so the bytes do not depend on the folder), and
# a second run from another folder writes the same save file
dump=$(sed -n 's/^\[dumpfile\] "\(.*\)"$/\1/p' "$g")
save=$(sed -n 's/^\[savefile\] "\(.*\)"$/\1/p' "$g")
if [ "$dump" = h.vcd ] && [ -f "$(dirname "$g")/$dump" ]; then ok dumpfile_beside
else fail dumpfile_beside "[dumpfile] \"$dump\""; fi
if [ "$save" = h.vcd.gtkw ]; then ok savefile_names_itself
else fail savefile_names_itself "[savefile] \"$save\""; fi
(cd "$T/elsewhere" && "$S" run horner3 --vcd "$T/run/sub/h2.vcd" >/dev/null 2>&1)
if sed 's/h2\.vcd/h.vcd/g' "$T/run/sub/h2.vcd.gtkw" | cmp -s - "$g"; then ok gtkw_same_bytes_anywhere
else fail gtkw_same_bytes_anywhere "$(diff "$g" "$T/run/sub/h2.vcd.gtkw" | head -3)"; fi
# fixed point: y's fraction bits (run --json's format) as the shift count
fy=$("$S" run horner3 --json | sed -n 's/.*"y": *"[su][0-9]*\.\([0-9]*\)".*/\1/p' | head -1)
if [ -n "$fy" ] && grep -A2 '^@40000424$' "$g" | grep -q "^\[fpshift_count\] $fy\$"; then ok fixed_point_y
else fail fixed_point_y "no fixed-point y with $fy fraction bits"; fi
grep -q '^top\.tb\.expected_y$' "$g" && grep -q '^top\.tb\.err_y$' "$g" && ok expected_error_traces \
    || fail expected_error_traces "no tb.expected_y / tb.err_y in the .gtkw"
grep -q '^\$var real 64 [^ ]* expected_y \$end' "$T/run/sub/h.vcd" && ok vcd_real_vars || fail vcd_real_vars "no \$var real expected_y"

if command -v vcd2fst >/dev/null 2>&1; then
    vcd2fst "$T/run/sub/h.vcd" "$T/h_check.fst" >/dev/null 2>&1 && [ -s "$T/h_check.fst" ] && ok vcd2fst_accepts_reals \
        || fail vcd2fst_accepts_reals "vcd2fst rejected a dump with real variables"
else
    echo "skip cli_wave.vcd2fst_accepts_reals: vcd2fst not installed (Debian package gtkwave)"
fi

# GTKWave itself, headless: open the moved pair from / and read the values
# at the middle of item 11's output cycle (cycle c spans 10c-5 .. 10c+5 ns).
case "${TST_BUILD:-}" in *-asan) gw_skip="runs in the plain build only" ;; *) gw_skip= ;; esac
if [ -z "$gw_skip" ] && ! command -v gtkwave >/dev/null 2>&1; then gw_skip="gtkwave not installed"; fi
if [ -z "$gw_skip" ] && ! command -v xvfb-run >/dev/null 2>&1; then gw_skip="xvfb-run not installed (Debian package xvfb)"; fi
if [ -n "$gw_skip" ]; then
    echo "skip cli_wave.gtkwave_opens_moved_pair: $gw_skip"
    echo "skip cli_wave.gtkwave_values: $gw_skip"
else
    mv "$T/run/sub" "$T/moved"
    line=$(sed -n '13p' "$T/run/h.csv")         # item 11: index,cycle,y_raw,y_real,y_expected,y_err
    cyc=$(echo "$line" | cut -d, -f2)
    cat >"$T/probe.tcl" <<EOF
puts "DUMP [gtkwave::getDumpFileName]"
gtkwave::setMarker [expr {10 * $cyc}]
for {set i 0} {\$i < [gtkwave::getTotalNumTraces]} {incr i} {
  puts "TRACE [gtkwave::getTraceNameFromIndex \$i] [gtkwave::getTraceValueAtMarkerFromIndex \$i]"
}
gtkwave::/File/Quit
EOF
    (cd / && timeout 60 xvfb-run -a gtkwave -S "$T/probe.tcl" "$T/moved/h.vcd.gtkw" >"$T/gw.out" 2>&1)
    if grep -q "^DUMP $T/moved/h.vcd\$" "$T/gw.out" || grep -q "^DUMP $(cd "$T/moved" && pwd -P)/h.vcd\$" "$T/gw.out"; then
        ok gtkwave_opens_moved_pair
    else fail gtkwave_opens_moved_pair "$(grep -i 'dump\|error' "$T/gw.out" | head -3)"; fi
    # the first traces: out_valid, y (fixed point), expected_y, err_y
    gy=$(grep '^TRACE y\[' "$T/gw.out" | head -1 | cut -d' ' -f3)
    ge=$(grep '^TRACE expected_y ' "$T/gw.out" | head -1 | cut -d' ' -f3)
    gr=$(grep '^TRACE err_y ' "$T/gw.out" | head -1 | cut -d' ' -f3)
    if awk -v a="$gy" -v b="$(echo "$line" | cut -d, -f4)" -v c="$ge" -v d="$(echo "$line" | cut -d, -f5)" \
           -v e="$gr" -v f="$(echo "$line" | cut -d, -f6)" \
           'function near(x, y) { return (x - y <= 1e-12 * (1 + (y < 0 ? -y : y))) && (y - x <= 1e-12 * (1 + (y < 0 ? -y : y))) }
            BEGIN { exit !(a != "" && c != "" && e != "" && near(a, b) && near(c, d) && near(e, f)) }'; then
        ok gtkwave_values
    else fail gtkwave_values "GTKWave shows y=$gy expected=$ge err=$gr; the CSV has $line"; fi
fi

# the window: items 3..4 end at the edge that samples item 4 (5 + 10 c)
"$S" run horner3 --vcd "$T/w.vcd" --vcd-from 3 --vcd-to 4 >/dev/null 2>&1
c4=$(sed -n '6p' "$T/run/h.csv" | cut -d, -f2)
last=$(grep '^#' "$T/w.vcd" | tail -1 | tr -d '#')
first=$(grep '^#' "$T/w.vcd" | head -1 | tr -d '#')
if [ -n "$c4" ] && [ "$last" = $((5 + 10 * c4)) ] && [ "$first" -gt 0 ] && [ "$first" -lt "$last" ]; then ok window_ends
else fail window_ends "timestamps #$first..#$last, item 4 sampled at #$((5 + 10 * c4))"; fi

expect2 window_reversed "$S" run horner3 --vcd "$T/x.vcd" --vcd-from 4 --vcd-to 3
expect2 window_past_end "$S" run horner3 --vcd "$T/x.vcd" --vcd-to 1000000
expect2 window_needs_vcd "$S" run horner3 --vcd-from 1
expect2 window_not_a_number "$S" run horner3 --vcd "$T/x.vcd" --vcd-from -1
expect2 fst_needs_vcd "$S" run horner3 --fst
expect2 fst_not_stdout "$S" run horner3 --vcd - --fst
# no vcd2fst on PATH: a clear error naming the package, nothing written
if (PATH=/nonexistent "$S" run horner3 --vcd "$T/nofst.fst" --fst >/dev/null 2>"$T/err"); then
    fail fst_without_vcd2fst "exit 0"
else
    rc=$?
    if [ $rc -eq 2 ] && grep -q 'gtkwave' "$T/err" && [ ! -e "$T/nofst.fst" ]; then ok fst_without_vcd2fst
    else fail fst_without_vcd2fst "exit $rc: $(cat "$T/err")"; fi
fi

if command -v vcd2fst >/dev/null 2>&1 && command -v fst2vcd >/dev/null 2>&1; then
    "$S" run horner3 --vcd "$T/h_full.vcd" >/dev/null 2>&1
    "$S" run horner3 --vcd "$T/h.fst" --fst >/dev/null 2>&1; rc=$?
    # the same time stamps as the VCD of the same run
    if [ $rc -eq 0 ] && fst2vcd "$T/h.fst" >"$T/back.vcd" 2>/dev/null \
        && grep -q 'expected_y' "$T/back.vcd" && grep -q ' rg ' "$T/back.vcd" \
        && [ "$(grep '^#' "$T/back.vcd" | md5sum)" = "$(grep '^#' "$T/h_full.vcd" | md5sum)" ]; then
        ok fst_reads_back
    else fail fst_reads_back "exit $rc; fst2vcd gave $(grep -c '^#' "$T/back.vcd" 2>/dev/null) time stamps"; fi
    grep -q "^\[dumpfile\] \"h.fst\"\$" "$T/h.fst.gtkw" && ok fst_gtkw || fail fst_gtkw "the .gtkw does not name h.fst"
    if ls "$T" | grep -q 'tmp'; then fail fst_no_temporaries "$(ls "$T" | grep tmp)"; else ok fst_no_temporaries; fi
    # an FST replacing a file keeps the file's permissions (vcd2fst makes
    # a new file of its own: it never gets the real path)
    : >"$T/keep.fst" && chmod 600 "$T/keep.fst"
    "$S" run horner3 --vcd "$T/keep.fst" --fst >/dev/null 2>&1; rc=$?
    m=$(stat -c %a "$T/keep.fst" 2>/dev/null)
    [ $rc -eq 0 ] && [ "$m" = 600 ] && [ -s "$T/keep.fst" ] && ok fst_keeps_mode || fail fst_keeps_mode "exit $rc, mode $m"
else
    echo "skip cli_wave.fst_reads_back: vcd2fst/fst2vcd not installed (Debian package gtkwave)"
fi

# scene --vcd writes the GTKWave save file beside its dump, as run does:
# it names the dump, opens with the span unit's valid and pixel traces,
# and every trace it names is a variable of the dump.
"$S" scene sphere --set resolution=24x24 --vcd "$T/sc.vcd" -o "$T/sc" >/dev/null 2>&1
rc=$?
if [ $rc -eq 0 ] && grep -q "^\[dumpfile\] \"sc.vcd\"\$" "$T/sc.vcd.gtkw" 2>/dev/null; then ok scene_vcd_gtkw
else fail scene_vcd_gtkw "exit $rc; $(head -3 "$T/sc.vcd.gtkw" 2>&1)"; fi
first=$(grep '^top\.' "$T/sc.vcd.gtkw" | head -2 | sed 's/\[.*//' | tr '\n' ' ')
case $first in "top.span"*".out_valid top.span"*".y ") ok scene_gtkw_leads_with_pixels ;;
    *) fail scene_gtkw_leads_with_pixels "first traces: $first" ;; esac
missing=
for tr in $(grep '^top\.' "$T/sc.vcd.gtkw" | sed 's/\[.*//' | sort -u); do
    v=${tr##*.}
    grep -q " $v \$end\| $v \[" "$T/sc.vcd" || missing="$missing $tr"
done
[ -z "$missing" ] && ok scene_gtkw_traces_in_dump || fail scene_gtkw_traces_in_dump "$missing"
"$S" scene sphere --set resolution=24x24 --vcd - -o "$T/sc2" >/dev/null 2>&1
[ ! -e "./-.gtkw" ] && ok scene_vcd_stdout_no_gtkw || fail scene_vcd_stdout_no_gtkw
