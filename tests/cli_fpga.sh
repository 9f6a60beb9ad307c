#!/bin/sh
# cli_fpga.sh - synth --fpga ice40 (docs/timing.md, "Against OpenSTA and
# nextpnr"): the counts it prints are the cells of Yosys's own netlist
# (counted here in the JSON it wrote), its f_max nextpnr's last "Max
# frequency" line for clk (read here from nextpnr's log); a missed --freq
# target is a result, not a failure; a package with too few pins, a bad
# device or family is one line and exit 2; a design without a clocked path
# gets 1 / its longest port-to-port delay. The progress line appears on a
# terminal (script(1) gives one) and nowhere else.
PREFIX=cli_fpga.
. tests/lib_cli.sh

expect bad_family 2 "$S" synth horner3 --fpga xc7
expect bad_device 2 "$S" synth horner3 --fpga ice40 --device hx9k
expect bad_package 2 "$S" synth horner3 --fpga ice40 --package 'ct256;x'
expect device_without_fpga 2 "$S" synth horner3 --device hx8k
expect json_alone 2 "$S" synth horner3 --json
ALL="counts fmax_from_log missed_target too_few_pins combinational progress_on_tty"
skip_all() { for t in $ALL; do echo "skip ${PREFIX}$t: $1"; done; exit 0; }
command -v yosys >/dev/null 2>&1 || skip_all "yosys not installed"
command -v nextpnr-ice40 >/dev/null 2>&1 || skip_all "nextpnr-ice40 not installed"
case "${TST_BUILD:-}" in *-asan) skip_all "runs in the plain build only" ;; esac

"$S" synth horner3 --fpga ice40 --keep "$T/k" --json >"$T/j" 2>"$T/err"
# a figure of the top object (before "model", whose fmax_mhz is the model's)
num() { sed -n "s/.*\"$1\": \\([0-9.]*\\).*\"model\".*/\\1/p" "$T/j"; }
cells() { grep -c "\"type\": \"$1" "$T/k/horner3.json"; }
[ "$(num luts)" = "$(cells SB_LUT4)" ] && [ "$(num ffs)" = "$(cells SB_DFF)" ] && [ "$(num carries)" = "$(cells SB_CARRY)" ] &&
    [ "$(num luts)" -gt 100 ] && [ "$(num ffs)" -gt 0 ] && ok counts ||
    fail counts "luts $(num luts) ffs $(num ffs) carries $(num carries) against the netlist's $(cells SB_LUT4) $(cells SB_DFF) $(cells SB_CARRY): $(cat "$T/err")"
f=$(grep "Max frequency for clock 'clk" "$T/k/nextpnr.log" | tail -1 | sed -n "s/.*': \\([0-9.]*\\) MHz.*/\\1/p")
lc=$(grep 'ICESTORM_LC:' "$T/k/nextpnr.log" | tail -1 | sed -n 's/.*ICESTORM_LC: *\([0-9]*\)\/.*/\1/p')
[ -n "$f" ] && awk -v a="$(num fmax_mhz)" -v b="$f" 'BEGIN { exit !((a - b) ^ 2 < 1e-6) }' && [ "$(num logic_cells)" = "$lc" ] &&
    grep -q '"clocked": true, "met": true' "$T/j" && ok fmax_from_log || fail fmax_from_log "$(cat "$T/j") log: $f MHz, $lc cells"

# a target far above what it reaches: nextpnr fails, synth reports it
"$S" synth horner3 --fpga ice40 --freq 500 >"$T/out" 2>"$T/err"; rc=$?
[ "$rc" = 0 ] && grep -q "^  f_max (clk)  *$f MHz (nextpnr after routing; misses the 500.00 MHz target)$" "$T/out" &&
    ok missed_target || fail missed_target "exit $rc: $(cat "$T/out" "$T/err")"

expect too_few_pins_exit 2 "$S" synth horner3 --fpga ice40 --device up5k --package sg48 &&
    grep -q 'horner3 needs [0-9]* I/O cells, more than the [0-9]* nextpnr finds on the up5k in package sg48' "$T/err" &&
    ok too_few_pins || fail too_few_pins "$(cat "$T/err")"

# div3 is combinational: no clk domain, 1000 / nextpnr's port-to-port ns
"$S" synth div3 --width 8 --fpga ice40 --keep "$T/c" >"$T/out" 2>"$T/err"
ns=$(grep 'Max delay <async> *-> <async>' "$T/c/nextpnr.log" | tail -1 | sed -n 's/.*: *\([0-9.]*\) ns.*/\1/p')
want=$(awk -v n="$ns" 'BEGIN { if (n > 0) printf "%.2f MHz (no clocked path: 1 / nextpnr'"'"'s longest path, %.2f ns)", 1000 / n, n }')
[ -n "$ns" ] && grep '^  f_max (port to port) ' "$T/out" | grep -qF "$want" && ok combinational || fail combinational "want '$want': $(cat "$T/out" "$T/err")"

# the progress line: on a terminal only
if command -v script >/dev/null 2>&1; then
    script -qec "\"$S\" synth div3 --width 8 --fpga ice40 >/dev/null" "$T/tty" >/dev/null 2>&1
    "$S" synth div3 --width 8 --fpga ice40 >/dev/null 2>"$T/err"
    grep -q 'synth: yosys.*, [0-9]* s of at most 600' "$T/tty" && grep -q 'synth: nextpnr, [0-9]* s' "$T/tty" && [ ! -s "$T/err" ] &&
        ok progress_on_tty || fail progress_on_tty "terminal: $(tr '\r' '\n' <"$T/tty" | head -5); not a terminal: $(cat "$T/err")"
else
    echo "skip ${PREFIX}progress_on_tty: script(1) not installed"
fi
