#!/bin/sh
# cli_claims.sh - the claims verb from the outside: exit status, every
# claim in the text and the JSON, the JSON parses, -o DIR writes the
# charts, bad arguments exit 2 with one line on stderr.
# One line per check: "ok NAME", "FAIL NAME" or "skip NAME: why".
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
# bad_args NAME ARGS...: exit 2, one line on stderr, nothing on stdout.
bad_args() {
    name=$1; shift
    "$S" claims "$@" >"$T/bad.out" 2>"$T/bad.err"
    rc=$?
    if [ $rc -eq 2 ] && [ "$(wc -l <"$T/bad.err")" -eq 1 ] && [ ! -s "$T/bad.out" ]; then ok "$name"
    else fail "$name" "exit $rc, stderr: $(cat "$T/bad.err")"; fi
}

# Text, then JSON (no CPU timing: that is make bench's). Under the
# sanitizers (ASAN=1), where each run of every claim takes ten seconds,
# the text is the -o run's below (less its "wrote" lines) and the
# determinism check is the plain build's.
if [ -n "$ASAN" ]; then
    "$S" claims -o "$T/charts/sub" >"$T/o.out" 2>"$T/text.err"
    check claims_exit_0 [ $? -eq 0 -a -s "$T/o.out" ]
    grep -v '^wrote ' "$T/o.out" >"$T/text"
else
    "$S" claims >"$T/text" 2>"$T/text.err"
    check claims_exit_0 [ $? -eq 0 -a -s "$T/text" ]
fi
check claims_quiet_stderr [ ! -s "$T/text.err" ]
check claims_hardware_speed_rows grep -q '^d16_speed_hw (' "$T/text"
check claims_failure_regions grep -q '^Failure regions' "$T/text"

# Under the sanitizers the run above is the one: a second whole run for
# the JSON (ten seconds of CPU there) would sanitize only its printer (a
# few base_json calls, as every verb's JSON), and the factor verb's run
# beside it repeats what cli_factor runs there; the checks against the
# JSON and the factor verb are the plain build's.
if [ -n "$ASAN" ]; then
    echo "skip ${PREFIX}claims_json: the JSON and the factor verb against the text, in the plain build"
    check claims_verdict_words [ "$(grep -c -E '^[a-z0-9_.]+ \(.*\): (holds|holds only for .+|does not hold)$' "$T/text")" -ge 20 ]
else
"$S" claims --json >"$T/json" 2>"$T/json.err"
check claims_json_exit_0 [ $? -eq 0 -a -s "$T/json" ]

# Every claim id of the JSON (which is claims_compute's table plus the
# speed rows; test_units_brdf checks it against claims_compute itself)
# appears in the text with its verdict line.
ids=$(sed -n 's/^ *{"id": "\([^"]*\)".*/\1/p' "$T/json")
n=0; missing=""
for id in $ids; do
    n=$((n + 1))
    grep -q "^$id (" "$T/text" || missing="$missing $id"
done
check claims_every_id_in_text [ "$n" -ge 20 -a -z "$missing" ]
[ -n "$missing" ] && echo "  missing:$missing"
check claims_verdict_words [ "$(grep -c -E '^[a-z0-9_.]+ \(.*\): (holds|holds only for .+|does not hold)$' "$T/text")" -eq "$n" ]

# The factorization paper's claims: rows of the table, and the same
# measurements, word for word, as the factor verb prints for the
# configuration the claims verb states.
for id in positive_factors reciprocity relative_error few_operations fig1_vertex_vs_pixel; do
    grep -q "^$id (Romanyuk et al. (2020)" "$T/text" && grep -q "{\"id\": \"$id\", \"kind\": \"factor\"" "$T/json" \
        && ok "claims_factor_$id" || fail "claims_factor_$id" "no factor row $id"
done
cfg=$(sed -n 's/^ward --claims --scene \([a-z]*\) --scene-res \([0-9]*\)` measures them$/\1 \2/p' "$T/text")
# (exit 1: a claim does not hold, Fig. 1's)
"$S" factor ward --claims --scene ${cfg% *} --scene-res ${cfg#* } -o "$T/fac" >"$T/fac.out" 2>&1
rc=$?
if [ -n "$cfg" ] && [ $rc -le 1 ]; then
    sed -n 's/^  \([a-z0-9_]*\)  *\(holds\|DOES NOT HOLD\)  *\(.*\)$/\1|\3/p' "$T/fac.out" >"$T/fac.rows"
    awk '/^[a-z0-9_]+ \(Romanyuk et al. \(2020\)/ { id = $1 } id && /^  ours: / { sub(/^  ours: +/, ""); print id "|" $0; id = "" }' \
        "$T/text" >"$T/cl.rows"
    [ "$(wc -l <"$T/fac.rows")" -eq 5 ] && cmp -s "$T/fac.rows" "$T/cl.rows" && ok claims_factor_same_as_factor_verb \
        || fail claims_factor_same_as_factor_verb "$(diff "$T/fac.rows" "$T/cl.rows" | head -4)"
else
    fail claims_factor_same_as_factor_verb "factor ward --claims --scene ... failed or no configuration line: $cfg"
fi

if command -v python3 >/dev/null 2>&1; then
    if python3 -c 'import json,sys; d=json.load(sys.stdin); assert len(d["claims"]) >= 20
ok = ("holds", "does not hold")
assert all(c["verdict"] in ok or c["verdict"].startswith("holds only for ") for c in d["claims"])
assert d["hardware"]["units"]["d_approx"]["clocks_per_item"] == 4' <"$T/json" 2>"$T/py.err"; then
        ok claims_json_parses
    else
        fail claims_json_parses "$(tail -1 "$T/py.err")"
    fi
else
    echo "skip claims_json_parses: no python3"
fi
check claims_json_no_cpu_kind sh -c "! grep -q 'speed_cpu\|on this CPU' '$T/json'"
fi   # (the plain build's checks against the JSON and the factor verb)

# No CPU timing in the verdicts: no d16_speed/ward_speed rows (only the
# hardware ones), no CPU kind in the JSON, and two runs are the same bytes
# (the text of the -o run below is the first run's text: each run
# computes every claim, the slowest part of the suite under ASan).
check claims_no_cpu_rows [ "$(grep -c -E '^(d16|ward)_speed \(' "$T/text")" -eq 0 ]

# Charts.
if [ -n "$ASAN" ]; then
    echo "skip ${PREFIX}claims_deterministic: the plain build runs it"
else
    "$S" claims -o "$T/charts/sub" >"$T/o.out" 2>&1
    check claims_o_exit_0 [ $? -eq 0 ]
    grep -v '^wrote ' "$T/o.out" >"$T/text2"
    check claims_deterministic cmp -s "$T/text" "$T/text2"
fi
nsvg=0
for f in claims_d16.svg claims_ward.svg claims_schlick.svg claims_d16_clamp.svg claims_cost.svg; do
    if [ -s "$T/charts/sub/$f" ] && head -c 200 "$T/charts/sub/$f" | grep -q '<svg' && tail -c 20 "$T/charts/sub/$f" | grep -q '</svg>'; then
        nsvg=$((nsvg + 1))
    fi
done
check claims_o_writes_svgs [ "$nsvg" -eq 5 ]
check claims_o_no_temporaries [ "$(ls "$T/charts/sub" | grep -v -c '\.svg$')" -eq 0 ]
check claims_o_lists_files grep -q "wrote $T/charts/sub/claims_cost.svg" "$T/o.out"

# A width where a unit of the speed table derives no error bound says so,
# as run says NO BOUND (claims --width 4 ran without a word); at the
# default width every unit has its bound.
[ -z "$ASAN" ] && check claims_default_bounded grep -q '"no_bound": \[\],' "$T/json"
check claims_default_no_note sh -c '! grep -q "note: at width" "$0"' "$T/text"
if [ -z "$ASAN" ]; then
    "$S" claims --width 8 >"$T/w8" 2>&1
    check claims_w8_note grep -q '^  note: at width 8, div derives no error bound for its formats (run says NO BOUND):$' "$T/w8"
    "$S" run div --width 8 >"$T/div8" 2>&1
    check claims_w8_as_run grep -q '^verdict: NO BOUND' "$T/div8"
fi

"$S" claims --help >"$T/help" 2>&1
rc=$?
check claims_help [ $rc -eq 0 -a "$(grep -c '^usage: shadesim claims' "$T/help")" -eq 1 ]

bad_args claims_bad_option --bogus
bad_args claims_bad_width --width 0
bad_args claims_bad_width_text --width abc
bad_args claims_width_missing --width
bad_args claims_o_missing -o
bad_args claims_cpu_seconds_gone --cpu-seconds 1
bad_args claims_stray_argument extra
touch "$T/afile"
bad_args claims_o_not_a_folder -o "$T/afile/x"
exit 0
