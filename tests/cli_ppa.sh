#!/bin/sh
# cli_ppa.sh - speed and energy where sweeps show them: the sweep CSV's
# derived columns recomputed from its own figures, the Pareto front over
# (max |e|, area, pixels per second) recomputed independently, and the
# target search's --min-throughput and --max-energy limits honoured by the
# design it chooses (and refused when no design can meet them).
# One line per check: "ok NAME", "FAIL NAME" or "skip NAME: why".
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_ppa.

"$S" sweep horner3 --widths 8:20 --schedule paper,pipe -o "$T/sw" >"$T/sw.out" 2>"$T/sw.err"
check sweep_runs [ $? -eq 0 ]
csv=$T/sw/sweep.csv

# Column numbers by name.
col() { head -1 "$csv" | tr ',' '\n' | grep -n -x "$1" | cut -d: -f1; }
cf=$(col fmax_mhz); cc=$(col crit_ps); ci=$(col items_per_s); cp=$(col pixels_per_s)
ccpi=$(col cycles_per_item); ccpb=$(col cycles_per_beat)
ce=$(col energy_pj_per_item); cep=$(col energy_pj_per_pixel); cb=$(col beats_per_item)
ca=$(col area_ge); cm=$(col max_abs_err); cw=$(col width); cs=$(col schedule)
check csv_has_speed_and_energy_columns [ -n "$cf" -a -n "$cc" -a -n "$ci" -a -n "$cp" -a -n "$ce" -a -n "$cep" ]

# Every row has a critical path and energy, and the derived figures are
# what their definitions give from the row's own columns, to the last bit
# (awk computes in the same doubles, in the same order).
bad=$(tail -n +2 "$csv" | awk -F, -v cf="$cf" -v cc="$cc" -v ci="$ci" -v cp="$cp" -v ccpi="$ccpi" \
    -v ccpb="$ccpb" -v ce="$ce" -v cep="$cep" -v cb="$cb" '
    !($cc > 0 && $cf > 0 && $ce > 0) { print "row " NR ": no timing or energy"; next }
    sprintf("%.17g", 1e6 / $cc) != sprintf("%.17g", $cf) { print "row " NR ": fmax " $cf " != 1e6/" $cc }
    sprintf("%.17g", $cf * 1e6 / $ccpi) != sprintf("%.17g", $ci) { print "row " NR ": items/s " $ci }
    sprintf("%.17g", $cf * 1e6 / $ccpb) != sprintf("%.17g", $cp) { print "row " NR ": pixels/s " $cp }
    sprintf("%.17g", $ce / $cb) != sprintf("%.17g", $cep) { print "row " NR ": pJ/pixel " $cep }')
check derived_columns_exact [ -z "$bad" ] || echo "  $bad"

# A wider design is slower: f_max falls (or stays) with the width, per schedule.
bad=$(tail -n +2 "$csv" | sort -t, -k"$cs,$cs" -k"$cw,${cw}n" | awk -F, -v cs="$cs" -v cf="$cf" -v cw="$cw" '
    $cs == s && $cf > f { print $cs " width " $cw " faster than width " w } { s = $cs; f = $cf; w = $cw }')
check fmax_falls_with_width [ -z "$bad" ] || echo "  $bad"
# The pipelined schedule has the shorter critical path at every width.
fp=$(awk -F, -v cs="$cs" -v cw="$cw" -v cc="$cc" 'NR > 1 && $cs == "paper" { p[$cw] = $cc }
    NR > 1 && $cs == "pipe" { q[$cw] = $cc } END { for (w in p) if (!(q[w] < p[w])) print w }' "$csv")
check pipe_shorter_path_than_paper [ -z "$fp" ] || echo "  widths: $fp"

# The front, recomputed: a row is on it unless another is no worse in
# max |e|, area and pixels per second and better in one.
awk -F, -v cm="$cm" -v ca="$ca" -v cp="$cp" -v cw="$cw" -v cs="$cs" 'NR > 1 { n++; e[n] = $cm; a[n] = $ca;
    p[n] = $cp; k[n] = $cs " " $cw } END {
    for (i = 1; i <= n; i++) { on = 1
        for (j = 1; j <= n && on; j++) if (j != i && e[j] <= e[i] && a[j] <= a[i] && p[j] >= p[i] &&
            (e[j] < e[i] || a[j] < a[i] || p[j] > p[i])) on = 0
        if (on) print k[i] }
    }' "$csv" | sort >"$T/front.want"
# The summary table marks the front with "*" in its last column.
awk 'NR > 2 && $1 ~ /^[0-9]+$/ && $NF == "*" { print $2 " " $1 }' "$T/sw/summary.txt" | sort >"$T/front.got"
check pareto_front_recomputed [ -s "$T/front.want" ] && check pareto_front_matches cmp -s "$T/front.want" "$T/front.got"
check throughput_chart_written [ -s "$T/sw/throughput_vs_error.svg" ]
check energy_chart_written [ -s "$T/sw/energy_vs_error.svg" ]
"$S" chart "$csv" -o "$T/ch" >/dev/null 2>&1
check chart_verb_same_throughput_chart cmp -s "$T/ch/throughput_vs_error.svg" "$T/sw/throughput_vs_error.svg"

# ---- the target search's limits ----
"$S" sweep horner3 --widths 8:24 --target-error 1e-3 --margin 1 -o "$T/t0" >/dev/null 2>&1
check target_runs [ $? -eq 0 ]
tc=$T/t0/target.csv
tcol() { head -1 "$tc" | tr ',' '\n' | grep -n -x "$1" | cut -d: -f1; }
cu=$(tcol uniform_items_per_s); cx=$(tcol chosen_items_per_s); cue=$(tcol chosen_energy_pj_per_item)
ips=$(sed -n 2p "$tc" | cut -d, -f"$cx")
epi=$(sed -n 2p "$tc" | cut -d, -f"$cue")
# A limit just above what the unconstrained choice reaches: the search must
# choose another design, one that meets it, or none.
lim=$(awk -v v="$ips" 'BEGIN { printf "%.17g", v * 1.02 }')
"$S" sweep horner3 --widths 8:24 --target-error 1e-3 --margin 1 --min-throughput "$lim" -o "$T/t1" >"$T/t1.out" 2>&1
rc=$?
met=$(sed -n 2p "$T/t1/target.csv" | cut -d, -f"$(head -1 "$T/t1/target.csv" | tr ',' '\n' | grep -n -x met | cut -d: -f1)")
got=$(sed -n 2p "$T/t1/target.csv" | cut -d, -f"$cx")
check min_throughput_honoured [ "$rc" -le 1 ] && { [ "$met" = false ] || awk -v g="$got" -v l="$lim" 'BEGIN { exit !(g >= l) }'; } \
    && ok min_throughput_chosen_meets_it || fail min_throughput_chosen_meets_it "met=$met items/s=$got limit=$lim"
jl=$(sed -n 's/.*"limits": {"min_items_per_s": \([^,]*\),.*/\1/p' "$T/t1/target.json")
awk -v a="$jl" -v b="$lim" 'BEGIN { exit !(a == b) }' && grep -q '"rule": ".*at least .* items per second' "$T/t1/target.json" \
    && ok min_throughput_in_json || fail min_throughput_in_json "limits: '$jl', asked $lim"
grep -q '"limits": {"min_items_per_s": null, "max_energy_pj_per_item": null}' "$T/t0/target.json" \
    && ok no_limits_null_in_json || fail no_limits_null_in_json
# An impossible limit: nothing meets it, and the output says which limit.
"$S" sweep horner3 --widths 8:24 --target-error 1e-3 --min-throughput 1e15 -o "$T/t2" >"$T/t2.out" 2>&1
check min_throughput_impossible_none_met grep -q "meet it miss the limits: .* items/s < 1e+15" "$T/t2.out"
# A limit between the uniform start's rate and the unconstrained choice's:
# the start misses it, the search goes on below it and must end meeting it.
uips=$(sed -n 2p "$tc" | cut -d, -f"$cu")
mid=$(awk -v a="$uips" -v b="$ips" 'BEGIN { printf "%.17g", (a + b) / 2 }')
if awk -v a="$uips" -v b="$ips" 'BEGIN { exit !(a < b) }'; then
    "$S" sweep horner3 --widths 8:24 --target-error 1e-3 --margin 1 --min-throughput "$mid" -o "$T/t4" >/dev/null 2>&1
    got=$(sed -n 2p "$T/t4/target.csv" | cut -d, -f"$cx")
    awk -v g="$got" -v l="$mid" 'BEGIN { exit !(g >= l) }' && ok min_throughput_met_below_start \
        || fail min_throughput_met_below_start "items/s '$got', limit $mid (start $uips)"
else
    echo "skip cli_ppa.min_throughput_met_below_start: the choice is not faster than its start here"
fi
lim=$(awk -v v="$epi" 'BEGIN { printf "%.17g", v * 0.98 }')
"$S" sweep horner3 --widths 8:24 --target-error 1e-3 --margin 1 --max-energy "$lim" -o "$T/t3" >/dev/null 2>&1
met=$(sed -n 2p "$T/t3/target.csv" | cut -d, -f"$(head -1 "$T/t3/target.csv" | tr ',' '\n' | grep -n -x met | cut -d: -f1)")
got=$(sed -n 2p "$T/t3/target.csv" | cut -d, -f"$cue")
{ [ "$met" = false ] || awk -v g="$got" -v l="$lim" 'BEGIN { exit !(g <= l) }'; } \
    && ok max_energy_chosen_meets_it || fail max_energy_chosen_meets_it "met=$met pJ=$got limit=$lim"

# Bad values: exit 2, one line.
expect min_throughput_zero 2 "$S" sweep horner3 --widths 8:9 --target-error 1e-3 --min-throughput 0
expect min_throughput_junk 2 "$S" sweep horner3 --widths 8:9 --target-error 1e-3 --min-throughput fast
expect max_energy_negative 2 "$S" sweep horner3 --widths 8:9 --target-error 1e-3 --max-energy -1
expect limits_need_target 2 "$S" sweep horner3 --widths 8:9 --max-energy 3
