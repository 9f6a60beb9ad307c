#!/bin/sh
# The verdicts of run and run all (issue 9, cases 1, 2, 3, 4, 8): exit
# statuses, the signal that overflowed named, the golden check, user
# targets. One "ok/FAIL NAME" line per check.
PREFIX=cli_verdict.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)

# st NAME WANT CMD...: exit status only.
st() {
    name=$1; want=$2; shift 2
    "$@" >"$T/out" 2>"$T/err"; got=$?
    [ "$got" -eq "$want" ] && ok "$name" || fail "$name" "exit $got, expected $want: $(tail -1 "$T/out") $(cat "$T/err")"
}

# case 1: wide formats are checked exactly (within_bound only with
# max|e - ideal| <= bound, no slack).
exact() {   # exact NAME ARGS...
    name=$1; shift
    "$S" run horner3 "$@" --json >"$T/w.json" 2>/dev/null
    b=$(sed -n 's/.*"bound": \([^,]*\),*/\1/p' "$T/w.json" | head -1)
    e=$(sed -n 's/.*"max_err_vs_ideal": \([^,]*\),*/\1/p' "$T/w.json" | head -1)
    wb=$(grep -c '"within_bound": true' "$T/w.json")
    awk -v b="$b" -v e="$e" -v w="$wb" 'BEGIN { exit !(b != "" && (w == 1) == (e + 0 <= b + 0)) }' \
        && ok "$name" || fail "$name" "within_bound=$wb, max|e-ideal| $e, bound $b"
}
exact exact_width64 --width 64
exact exact_s8_56 --fmt all=s8.56
# and at those widths horner3 is right: ok, exit 0 (the golden check's
# resolution there is the doubles' of the vector file, not the LSB)
st width64_ok 0 "$S" run horner3 --width 64
st s8_56_ok 0 "$S" run horner3 --fmt all=s8.56

# case 2: input quantization wraps x = 1 - 2^-16 to -1: counted on x, exit 1.
st div3_halfup_overflow 1 "$S" run div3 --round half-up
grep -q '^x  *s1.15  *1 ' "$T/out" && ok div3_names_x || fail div3_names_x "$(grep -A1 '^signal' "$T/out")"
# allowed, it is still reported, and the wrapped value fails the golden check
st div3_halfup_allowed 1 "$S" run div3 --round half-up --allow-overflow
grep -q '^verdict: GOLDEN MISMATCH' "$T/out" && grep -q '^x  *s1.15  *1 ' "$T/out" && ok div3_allowed_golden || fail div3_allowed_golden "$(grep verdict "$T/out")"
# constants that do not fit
st schlick_const_overflow 1 "$S" run schlick --param n=32 --fmt k=u4.0
grep -q '^verdict: OVERFLOW on k:1' "$T/out" && ok schlick_names_k || fail schlick_names_k "$(grep verdict "$T/out")"
"$S" run horner3 --json >"$T/h.json"
grep -q '"signals": \[' "$T/h.json" && grep -q '{"name": "rg", "fmt": "s7.9", "overflows": 0, "min": ' "$T/h.json" \
    && ok json_signals || fail json_signals "no per-signal ranges in --json"
"$S" run horner3 --ranges >"$T/r.txt"
grep -q '^signal (range logging)' "$T/r.txt" && grep -q '^mul ' "$T/r.txt" && ok ranges_table || fail ranges_table

# case 3: no invented bound
st div_w8_no_bound 1 "$S" run div --width 8
grep -q 'no bound' "$T/out" && ! grep -q '2\.996' "$T/out" && ok div_w8_says_no_bound || fail div_w8_says_no_bound "$(grep '^q ' "$T/out")"

# case 8: a wraps (144 inputs with the original vectors); the verdict fails naming a
st horner3_a_wraps 1 "$S" run horner3 --fmt a=s2.9
grep -q '^verdict: OVERFLOW on a:[1-9]' "$T/out" && ok horner3_names_a || fail horner3_names_a "$(grep verdict "$T/out")"
# expected y 28 LSB off on every row: the golden check fails
"$S" vectors horner3 >"$T/h.vec"
awk '/^#/ { print; next } { split($0, p, "|"); printf "%s| %.17g\n", p[1], p[2] + 28 / 512 }' "$T/h.vec" >"$T/h28.vec"
st golden_28lsb 1 "$S" run horner3 --vectors "$T/h28.vec"
grep -q '^verdict: GOLDEN MISMATCH' "$T/out" && ok golden_named || fail golden_named "$(grep verdict "$T/out")"
st golden_true 0 "$S" run horner3 --vectors "$T/h.vec"

# case 4: targets
st nmse_target_missed 1 "$S" run horner3 --width 8 --max-nmse 1e-6
grep -q 'MISSES YOUR TARGET' "$T/out" && ok target_named || fail target_named "$(grep verdict "$T/out")"
st target_met 0 "$S" run horner3 --max-error 0.01
st bad_target 2 "$S" run horner3 --max-error -1
st run_all_default 0 "$S" run all
grep -q 'interp3 (0\.2' "$T/out" && ok run_all_says_interp3_far || fail run_all_says_interp3_far "$(tail -2 "$T/out")"
st run_all_target 1 "$S" run all --max-error 0.01
grep -q 'MISS your target' "$T/out" && ok run_all_target_summary || fail run_all_target_summary "$(tail -1 "$T/out")"
# run all --json: one object, each unit's member the object run UNIT --json
# prints (checked for two units: its first, a divider), the verdict as the
# exit status says
st run_all_json_target 1 "$S" run all --json --max-error 0.01
grep -q '"verdict": "fail"}$' "$T/out" && ok run_all_json_fail || fail run_all_json_fail "$(tail -1 "$T/out")"
st run_all_json 0 "$S" run all --json
cp "$T/out" "$T/all.json"
if command -v python3 >/dev/null 2>&1; then
    "$S" run horner3 --json >"$T/h3.json" && "$S" run div --json >"$T/div.json" && python3 - "$T" <<'PY' && ok run_all_json_members || fail run_all_json_members "not each unit's run --json"
import json, sys
t = sys.argv[1]
a = json.load(open(t + "/all.json"))
assert a["verdict"] == "ok" and a["failed"] == 0 and len(a["units"]) >= 20
for u in ("h3", "div"):
    b = json.load(open(t + "/" + u + ".json"))
    assert [o for o in a["units"] if o["unit"] == b["unit"]] == [b]
PY
else echo "skip ${PREFIX}run_all_json_members: python3 not found"; fi
