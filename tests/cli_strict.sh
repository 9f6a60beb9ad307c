#!/bin/sh
# cli_strict.sh - option values are taken whole or refused: every number an
# option takes is checked to its last character and against its range, and
# a refused value is exit 2 with one line on stderr naming the option.
PREFIX=cli_strict.
. tests/lib_cli.sh

# refused NAME ARGS...: exit 2, nothing on stdout, one stderr line
# "shadesim: ..." (the option's message, not a crash or a usage dump).
refused() {
    name=$1; shift
    "$S" "$@" >"$T/out" 2>"$T/err"; rc=$?
    lines=$(wc -l <"$T/err")
    if [ $rc -ne 2 ]; then fail "$name" "exit $rc, expected 2"
    elif [ "$lines" -ne 1 ]; then fail "$name" "$lines lines on stderr"
    elif ! grep -q '^shadesim: ' "$T/err"; then fail "$name" "stderr: $(cat "$T/err")"
    elif [ -s "$T/out" ]; then fail "$name" "wrote to stdout"
    else ok "$name"; fi
}
# taken NAME ARGS...: exit 0 (the same options with a proper value).
taken() {
    name=$1; shift
    if "$S" "$@" >"$T/out" 2>"$T/err"; then ok "$name"; else fail "$name" "exit $?: $(head -1 "$T/err")"; fi
}

# The issue's examples: a value cut at 31 characters, a seed past 2^64-1,
# an empty count, hex and spaces in a parameter.
refused shard_junk_after_31_chars sweep horner3 --widths 8:8 --shard 0000000000000000000000000000001junk/2 -o "$T/s"
refused widths_junk_after_31_chars sweep horner3 --widths 0000000000000000000000000000008junk:9 -o "$T/s"
refused seed_past_2_64 vectors horner3 -n 1 --seed 18446744073709551616
refused sweep_seed_past_2_64 sweep horner3 --widths 8:8 --seed 18446744073709551616 -o "$T/s"
refused n_empty vectors horner3 -n ""
refused param_hex vectors div3 -n 1 --param terms=0x3
refused param_leading_space vectors div3 -n 1 --param "terms= 3"
refused param_trailing_space vectors div3 -n 1 --param "terms=3 "
refused param_plus vectors div3 -n 1 --param terms=+3
refused param_inf vectors div3 -n 1 --param terms=inf
# a whole-number parameter takes digits only (docs/cli.md; issue 26: 3e0
# used to be taken)
refused param_real_form vectors div3 -n 1 --param terms=3e0
refused param_fraction_form vectors div3 -n 1 --param terms=3.0
refused width_leading_space run horner3 --width " 16"
refused width_plus run horner3 --width +16
refused list_width_junk list horner3 --width 16x
refused n_hex vectors horner3 -n 0x10
refused n_negative vectors horner3 -n -1
refused seed_negative vectors horner3 -n 1 --seed -1
refused sweep_n_space sweep horner3 --widths 8:8 -n " 5" -o "$T/s"
refused sweep_j_trailing sweep horner3 --widths 8:8 -j "2 " -o "$T/s"
refused sweep_margin_hex sweep horner3 --widths 8:8 --target-error 1e-3 --margin 0x1 -o "$T/s"
refused sweep_max_error_nan sweep horner3 --widths 8:8 --max-error nan -o "$T/s"
refused run_max_error_hex run horner3 --max-error 0x1p-3
refused run_vcd_from_plus run horner3 --vcd-from +1 --vcd "$T/v.vcd"
refused scene_j_space scene sphere -j " 2" -o "$T/sc"
refused scene_max_nmse_inf scene sphere --max-nmse inf -o "$T/sc"

# The same options with well-formed values are taken (the edges of range).
taken seed_2_64_minus_1 vectors horner3 -n 1 --seed 18446744073709551615
taken param_whole vectors div3 -n 1 --param terms=3
taken list_width list horner3 --width 64

# Messages. message NAME EXPECTED ARGS...: exit 2 and stderr is exactly
# the line EXPECTED.
message() {
    name=$1 want=$2; shift 2
    "$S" "$@" >"$T/out" 2>"$T/err"; rc=$?
    if [ $rc -ne 2 ]; then fail "$name" "exit $rc, expected 2"
    elif [ "$(cat "$T/err")" != "$want" ]; then fail "$name" "stderr: $(cat "$T/err")"
    else ok "$name"; fi
}
message list_schedule_without_value "shadesim: --schedule needs a value" list horner3 --schedule
message vectors_o_without_value "shadesim: -o needs a FILE" vectors horner3 -o
message vectors_o_empty "shadesim: empty output path" vectors horner3 -o ""
# A raw byte 0xff and an escape character in user text are echoed as \xNN.
bad=$(printf 'hor\377ner\033[31m')
message raw_bytes_escaped "shadesim: unknown unit 'hor\\xffner\\x1b[31m' (shadesim list shows the units)" run "$bad"
message raw_bytes_in_value "shadesim: --width 1\\xff: expected a whole number 1..64" run horner3 --width "$(printf '1\377')"
# a scene file's text too: valid UTF-8 kept, other bytes \xNN (each was a "?")
printf 'shadesim-scene 1\nlumi\303\250re 1\n' >"$T/u8.scene"
printf 'shadesim-scene 1\nx\377y 1\n' >"$T/ff.scene"
message scene_utf8_kept "shadesim: $T/u8.scene:2: unknown key \"$(printf 'lumi\303\250re')\"" scene "$T/u8.scene"
message scene_bytes_escaped "shadesim: $T/ff.scene:2: unknown key \"x\\xffy\"" scene "$T/ff.scene"

# One spelling of not-a-number. Expected outputs of 1e200 make every error
# about 1e200: the squared errors and references overflow to inf, and the
# NMSE, inf/inf, is NaN (IEEE 754). Text and CSV say nan, JSON null.
printf '# shadesim vectors 1\n# unit: horner3\n# inputs: a b c d t\n# outputs: y\n0 0 0 0 0 | 1e200\n0 0 0 0 0.5 | 1e200\n' >"$T/nan.vec"
"$S" run horner3 --vectors "$T/nan.vec" >"$T/t.txt" 2>/dev/null
"$S" run horner3 --vectors "$T/nan.vec" --json >"$T/t.json" 2>/dev/null
"$S" sweep horner3 --widths 16:16 --vectors "$T/nan.vec" -o "$T/sw" >/dev/null 2>&1
check nan_table_spelling sh -c 'grep -q "^y .* nan " "$1" && ! grep -q -- "-nan" "$1"' sh "$T/t.txt"
check nan_json_null grep -q '^  "nmse": null,' "$T/t.json"
check nan_sweep_summary sh -c 'grep -q " nan " "$1/summary.txt" && ! grep -q -- "-nan" "$1/summary.txt" "$1/sweep.csv"' sh "$T/sw"
