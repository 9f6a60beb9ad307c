#!/bin/sh
# cli_search.sh - verdicts a user can trust, from the outside: no silent
# widening of --width, only built signals exist, searches re-checked on
# held-out stimuli, acceptance flags on sweep, deterministic claims.
# One line per check: "ok NAME", "FAIL NAME" or "skip NAME: why".
PREFIX=cli_search.
. tests/lib_cli.sh

# ---- no silent widening: horner3's datapath is s7.(W-7) ----------------
"$S" run horner3 --width 4 >"$T/o" 2>"$T/e"
check width_below_minimum_exit_2 [ $? -eq 2 -a ! -s "$T/o" -a "$(wc -l <"$T/e")" -eq 1 ]
check width_below_minimum_names_it grep -q 'needs --width >= 8 (signal a.s integer part is s7)' "$T/e"
"$S" run horner3 --width 8 >"$T/o" 2>&1
check width_minimum_is_built_as_said grep -q '^formats: a=s7.1 .* t=u1.7 ' "$T/o"
"$S" sweep horner3 --widths 4:9 -o "$T/sw" >/dev/null 2>"$T/e"
check sweep_below_minimum_runs [ $? -eq 0 ]
check sweep_below_minimum_one_notice [ "$(wc -l <"$T/e")" -eq 1 ] 
check sweep_below_minimum_notice_says_start grep -q 'starting at 8' "$T/e"
check sweep_below_minimum_rows_from_8 [ "$(cut -d, -f6 "$T/sw/sweep.csv" | tail -n +2 | tr '\n' ' ')" = "8 9 " ]
"$S" sweep horner3 --widths 4:6 -o "$T/sw2" >/dev/null 2>"$T/e"
check sweep_all_below_minimum_exit_2 [ $? -eq 2 -a "$(wc -l <"$T/e")" -eq 1 ]

# ---- only built signals exist: div3 with 3 terms builds t0..t3, s1..s3 --
"$S" run div3 >"$T/o" 2>&1
check div3_run_lists_built_terms_only grep -qx 'formats: x=s1.15 y=s1.15 t0=s1.16 t1=s1.17 t2=s1.17 t3=s1.17 s1=s1.17 s2=s1.17 s3=s1.17' "$T/o"
"$S" run div3 --json >"$T/o" 2>&1
check div3_json_has_no_phantom_terms sh -c "! grep -q '\"t4\"' '$T/o'"
"$S" run div3 --fmt t7=s1.3 >"$T/o" 2>"$T/e"
check div3_unbuilt_fmt_exit_2 [ $? -eq 2 -a ! -s "$T/o" -a "$(wc -l <"$T/e")" -eq 1 ]
check div3_unbuilt_fmt_names_built grep -q "does not build signal 't7' (it builds: x y t0 t1 t2 t3 s1 s2 s3)" "$T/e"
"$S" run div3 --param terms=7 --fmt t7=s1.20 >/dev/null 2>&1
check div3_fmt_t7_with_7_terms_accepted [ $? -ne 2 ]
"$S" list div3 >"$T/o" 2>&1
check div3_list_has_no_t4 sh -c "! grep -q '^ *t4 ' '$T/o'"
"$S" run div3 --vcd "$T/d.vcd" >/dev/null 2>&1
check div3_vcd_same_set sh -c "grep -q ' t3 ' '$T/d.vcd' && ! grep -q ' t4 ' '$T/d.vcd'"

# ---- deterministic output: claims has no timings --------------------------
"$S" claims --json >"$T/c1" 2>/dev/null
"$S" claims --json >"$T/c2" 2>/dev/null
check claims_json_twice_same_bytes cmp -s "$T/c1" "$T/c2"
check claims_no_cpu_kind sh -c "! grep -q 'speed_cpu\|on this CPU' '$T/c1'"
