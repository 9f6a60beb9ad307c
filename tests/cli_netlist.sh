#!/bin/sh
# The netlist text (docs/netlist.md): for every unit and schedule, the
# design `netlist UNIT` writes, built back by `run FILE`, gives the very
# bytes of `run UNIT`: the JSON report with the kernel's counters and the
# VCD at the default width, the batch's JSON at width 12; netlist writes
# the same bytes twice and through -o; and malformed files are each
# refused with their one line "FILE:LINE: what", exit 2.
PREFIX=cli_netlist.
. tests/lib_cli.sh

# The units and their schedules, from list.
units_and_schedules >"$T/units"
check units_listed [ "$(wc -l <"$T/units")" -ge 20 ]
# Under the sanitizers (a process costs ten times as much) the command
# line's round trip takes one design, the malformed files four:
# tests/test_netlist.c runs every unit and schedule, and every malformed
# text, in process there.
widths="16 12" min=80 nbad=1000
case "${TST_BUILD:-}" in
*-asan) widths=16 min=1 nbad=4; echo 'horner3: paper' >"$T/units" ;;
esac
# make test-quick: every unit and schedule at width 16 alone (the kernel's
# counters and the VCD; the batch's width 12 in make test)
full_only || { widths=16; [ $min -gt 40 ] && min=40; }

# same NAME A B: files A and B hold the same bytes.
same() { if cmp -s "$2" "$3"; then ok "$1"; else fail "$1" "$(cmp "$2" "$3" 2>&1 | head -c 200)"; fi; }

# Each side writes into a folder of its own, under the same names (the
# VCD's save file names the dump), and one diff compares them all.
case $S in /*) ;; */*) S=$(pwd)/$S ;; esac
mkdir -p "$T/A" "$T/B"
top=$(pwd)
cases=0 bad=
while IFS=: read -r u scheds; do
    for s in $scheds; do
        for w in $widths; do
            cases=$((cases + 1))
            c=$u-$s-$w
            "$S" netlist "$u" --schedule "$s" --width $w -o "$T/B/$c.net" 2>"$T/err" \
                || { bad="$bad [$c: netlist: $(cat "$T/err")]"; continue; }
            # 16: the kernel (counters) and the VCD; 12: the batch's lanes
            opt=; [ $w = 16 ] && opt="--vcd $c.vcd"
            cd "$T/A" && "$S" run "$u" --schedule "$s" --width $w --json $opt >"$c.json" 2>/dev/null; ra=$?
            cd "$T/B" && "$S" run "$c.net" --json $opt >"$c.json" 2>"$T/err"; rb=$?
            cd "$top" || exit 2
            [ $ra = $rb ] || bad="$bad [$c: exit $ra, from the text $rb: $(cat "$T/err")]"
        done
    done
done <"$T/units"
# the save files name their dump by its full path: the folder aside
for f in "$T"/A/*.gtkw; do [ -f "$f" ] && sed -i "s#$T/[AB]/##" "$T"/A/*.gtkw "$T"/B/*.gtkw; break; done
cd "$T" && diff -r -q -x '*.net' A B >"$T/diff" 2>&1 || bad="$bad $(head -c 600 "$T/diff")"
cd "$top" || exit 2
check round_trip_every_unit_and_schedule [ -z "$bad" -a $cases -ge $min ]
[ -n "$bad" ] && echo "  $bad" | head -c 2000 && echo
check round_trip_wrote_vcd [ -s "$T/B/horner3-paper-16.vcd" -a -s "$T/B/horner3-paper-16.vcd.gtkw" ]

# The counters are there to compare: the kernel's events and deltas.
"$S" netlist horner3 -o "$T/h3.net"
"$S" run "$T/h3.net" --kernel --json >"$T/k.json"
check json_has_kernel_counters grep -q '"engine": "kernel", "clocks": [1-9][0-9]*, "events": [1-9]' "$T/k.json"
# Deterministic bytes: stdout and -o the same, twice.
"$S" netlist span23 --schedule pipe --param terms=5 >"$T/s1.net"
"$S" netlist span23 --schedule pipe --set terms=5 -o "$T/s2.net"
same deterministic_bytes "$T/s1.net" "$T/s2.net"
check param_written grep -qx 'param terms 5' "$T/s1.net"
# A netlist with its own formats and modes runs as the unit with them.
"$S" netlist horner3 --round half-up --fmt mul=s3.12:even:sat -o "$T/f.net"
"$S" run horner3 --round half-up --fmt mul=s3.12:even:sat --kernel --json >"$T/a.json"
"$S" run "$T/f.net" --kernel --json >"$T/b.json"
same fmt_override_round_trip "$T/a.json" "$T/b.json"
# The design is the file's: options that change it are refused.
expect run_file_refuses_width 2 "$S" run "$T/h3.net" --width 12
grep -q 'the netlist is the design' "$T/err" && ok run_file_width_says_why || fail run_file_width_says_why "$(cat "$T/err")"
# A logic element too wide for a table is wiring where its Verilog text
# says so (the square root's shifted remainder), else its Verilog text's
# function (fn=verilog: the divider's operand shifter and zero test); the
# round trip above runs both.
"$S" netlist div -o "$T/div.net"
check wide_logic_fn_verilog grep -q '^logic dz_next u1.0 in=d area=[0-9.]* verilog=".*" fn=verilog$' "$T/div.net"
"$S" netlist sqrt -o "$T/sqrt.net"
check wide_logic_bits grep -q '^logic rt_dq u18.0 in=rt_q_in area=0 depth=0 verilog=".*" bits={%0\[15:0\],2'"'"'h1}$' "$T/sqrt.net"
check narrow_logic_table grep -q ' table=[0-9a-f]*$' "$T/h3.net"
# --help, and bad usage of the verb.
expect help 0 "$S" netlist --help
check help_names_docs grep -q 'docs/netlist.md' "$T/out"
expect no_unit 2 "$S" netlist
expect unknown_unit 2 "$S" netlist hornerx
expect bad_schedule 2 "$S" netlist horner3 --schedule nope
expect out_dir_missing 2 "$S" netlist horner3 -o "$T/nodir/x.net"
"$S" netlist horner3 -o /dev/null && ok out_devnull || fail out_devnull

# --- malformed files: each one line, FILE:LINE: what, exit 2 ------------
# bad NAME 'SED SCRIPT' 'EXPECTED TEXT': horner3's netlist edited by the
# script is refused with the text in its one line.
bad() {
    nbad=$((nbad - 1)); [ $nbad -lt 0 ] && return
    sed "$2" "$T/h3.net" >"$T/bad_$1.net"
    expect "bad_$1" 2 "$S" run "$T/bad_$1.net"
    grep -qF -- "bad_$1.net:$3" "$T/err" || fail "bad_$1_says" "expected '$3', got: $(cat "$T/err")"
}
l() { grep -n "$1" "$T/h3.net" | head -1 | cut -d: -f1; }
bad undeclared   's/^add sm s7.9 a=mx2 b=bk/add sm s7.9 a=mx9 b=bk/' "$(l '^add sm'): add sm: a=mx9 is not declared"
bad duplicate    's/^bk bk /bk mx1 /' "$(l '^bk bk'): mx1: declared twice (first at line $(l '^mux mx1'))"
bad later        's/^mux mx1 s7.9 sel=mx1_sel in=a,rg/mux mx1 s7.9 sel=mx1_sel in=a,sm/' "$(l '^mux mx1'): mux mx1: in=sm is made at line $(l '^add sm'), after it"
bad format       's/^add sm s7.9/add sm s7.99x/' "$(l '^add sm'): format s7.99x"
bad kind         's/^add sm/adder sm/' "$(l '^add sm'): adder: not a line of a netlist"
bad attribute    's/^add sm s7.9 a=mx2 b=bk/add sm s7.9 a=mx2 b=bk sel=rg/' "$(l '^add sm'): sel=: not an attribute of add"
bad missing_b    's/^add sm s7.9 a=mx2 b=bk/add sm s7.9 a=mx2/' "$(l '^add sm'): add sm: needs b=NAME"
bad table_short  's/^\(logic mx1_sel .*table=\)10111100/\11011110/' "$(l '^logic mx1_sel'): logic mx1_sel: table= has 7 hex digits, its 8 rows of 1 need 8"
bad table_digit  's/^\(logic mx1_sel .*table=\)10111100/\11011110g/' "$(l '^logic mx1_sel'): logic mx1_sel: table=: 'g' is not a lower-case hex digit"
bad table_bits   's/^\(logic mx1_sel .*table=\)10111100/\11011110f/' "$(l '^logic mx1_sel'): logic mx1_sel: table= row 7: f has more bits than mx1_sel's 1"
bad unit         's/^unit horner3/unit horner9/' "$(l '^unit'): unit horner9: no such built-in unit"
bad version      's/^netlist 1/netlist 2/' "$(l '^netlist'): netlist 2: this reader knows version 1"
bad no_header    '/^netlist 1/d' "2: expected 'netlist 1' first"
bad scope        's/^add sm /add dp.sm /' "$(l '^add sm'): dp.sm: scope dp is not declared"
bad port_missing '/^port out y/d' " 5 input and 0 output ports; unit horner3 has 5 and 1"
bad port_kind    's/^port in a$/port in sm/' "$(l '^port in a'): port in sm: not an input without from="
bad clock_operand 's/^bk bk s7.9 pass=bk_pass x=rg/bk bk s7.9 pass=clk x=rg/' "$(l '^bk bk'): bk bk: pass=clk is the clock"
bad reg_clock    's/^reg rg s7.9 d=sm clk=clk/reg rg s7.9 d=sm clk=step/' "$(l '^reg rg'): reg rg: clk=step is not the clock"
bad quote        's/^logic in_ready u1.0/logic in_ready u1.0 verilog="assign/' "$(l '^logic in_ready'): a quoted text without its closing"
bad shift_by     's/^shift y s7.9 x=rg by=0/shift y s7.9 x=rg by=65/' "$(l '^shift y'): by=65: expected a whole number -64..64"
bad twice        's/^add sm s7.9 a=mx2 b=bk/add sm s7.9 a=mx2 b=bk a=rg/' "$(l '^add sm'): a= given twice"
bad wide_table   's/^logic mx1_sel u1.0 in=step /logic mx1_sel u1.0 in=step,a /' "$(l '^logic mx1_sel'): logic mx1_sel: inputs of 19 bits in all: a table takes at most 12"
bad fn_unit      's/^\(logic in_ready .*\)/\1\nlogic zz u1.0 in=step area=1 fn=unit/' "$(($(l '^logic in_ready') + 1)): logic zz: fn=unit, but unit horner3 has no logic element zz with this format and inputs"
# not a netlist at all, an empty file, a binary one, a missing one
printf '' >"$T/empty.net"
expect bad_empty 2 "$S" run "$T/empty.net"
grep -qF 'empty.net: empty: not a netlist' "$T/err" || fail bad_empty_says "$(cat "$T/err")"
printf 'netlist 1\n\000\n' >"$T/nul.net"
expect bad_nul 2 "$S" run "$T/nul.net"
grep -qF 'nul.net:2: not a text file (NUL byte)' "$T/err" || fail bad_nul_says "$(cat "$T/err")"
expect bad_vectors_file 2 "$S" run vectors/horner3.vec
grep -qF "horner3.vec:5: expected 'netlist 1' first" "$T/err" || fail bad_vectors_file_says "$(cat "$T/err")"
# A combinational loop through a wire: the simulation says so, no hang.
sed 's/^add sm s7.9 a=mx2 b=bk/wire lp s7.9 from=sm\nadd sm s7.9 a=mx2 b=lp/' "$T/h3.net" >"$T/loop.net"
"$S" run "$T/loop.net" >"$T/out" 2>"$T/err"; rc=$?
if [ $rc -ne 0 ] && [ $rc -le 2 ] && [ "$(wc -l <"$T/err")" -eq 1 ]; then ok loop_refused
else fail loop_refused "exit $rc: $(head -c 300 "$T/err")"; fi
