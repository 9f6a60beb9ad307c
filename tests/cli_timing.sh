#!/bin/sh
# cli_timing.sh - the critical path against Yosys (docs/timing.md): over
# every unit at widths 8, 16 and 24 (default schedule and parameters),
# Yosys's longest topological path (`ltp -noff` after the same `synth; abc
# -g ...; flatten` as `shadesim synth`) and shadesim's critical-path gate
# levels order the designs alike (Spearman rank correlation >= 0.8) and
# their ratio stays in the band docs/timing.md states (0.8 to 2.0).
# `shadesim synth` runs two at a time (one per core); hf_lookup, whose
# ROMs take ABC far too long for a test, is left out. TIMING_TABLE=FILE also
# writes the comparison table (markdown) to FILE: docs/timing.md's is made
# so, with TIMING_DESIGNS=all.
#
# The designs: TIMING_DESIGNS=all is every unit at widths 8, 16 and 24
# (about four minutes of CPU: `make test-long` runs it, through
# tests/cli_timing_full.sh); otherwise (make test) the run --json fields
# and `synth`'s lines on one design, the rank and band checks left to
# make test-long.
PREFIX=cli_timing.
[ "${TIMING_DESIGNS:-}" = all ] && PREFIX=cli_timing_full.
. tests/lib_cli.sh

# run --json: f_max is 1e6 / ps and items/s f_max / cycles per item;
# the streamed run (a vector file) and the in-memory one (with a dump)
# give the same path
"$S" run horner3 --json >"$T/j1" 2>"$T/err"
"$S" run horner3 --json --vcd "$T/h.vcd" >"$T/j2" 2>>"$T/err"
awk '/"critical_path"/ { n = split($0, a, /[:,]/); lv = a[3] + 0; ps = a[5] + 0; cp = $0 }
     /"cycles_per_item"/ { split($0, a, ":"); cpi = a[2] + 0 }
     /"fmax_mhz"/ { split($0, a, ":"); f = a[2] + 0 }
     /"items_per_s"/ { split($0, a, ":"); ips = a[2] + 0 }
     END { ok = lv > 0 && ps > 0 && cp ~ /"signals": \["[a-z]/ && f > 0 && (f - 1e6 / ps) ^ 2 < 1e-12 * f * f &&
                (ips - f * 1e6 / cpi) ^ 2 < 1e-12 * ips * ips
           exit ok ? 0 : 1 }' "$T/j1" && ok run_json_fields || fail run_json_fields "$(grep -A3 critical_path "$T/j1") $(cat "$T/err")"
[ "$(grep '"critical_path"' "$T/j1")" = "$(grep '"critical_path"' "$T/j2")" ] && [ -n "$(grep '"critical_path"' "$T/j1")" ] &&
    ok run_stream_same_path || fail run_stream_same_path "$(grep critical_path "$T/j1" "$T/j2")"
"$S" run horner3 >"$T/out" 2>"$T/err"
grep -q '^critical path [1-9][0-9]* levels, [0-9]* ps (.* -> .*), f_max [0-9]* MHz, .* M items/s$' "$T/out" &&
    ok run_table_line || fail run_table_line "$(sed -n 1,5p "$T/out")"

command -v yosys >/dev/null 2>&1 || { for t in synth_paths yosys_rank yosys_ratio_band; do echo "skip ${PREFIX}$t: yosys not installed"; done; exit 0; }
case "${TST_BUILD:-}" in *-asan) echo "skip ${PREFIX}yosys_rank: runs in the plain build only"; exit 0 ;; esac

# synth prints both path lengths and their ratio
"$S" synth div3 --width 8 >"$T/out" 2>"$T/err"
grep -q '^  Yosys  *[1-9][0-9]* gates$' "$T/out" && grep -q '^  shadesim  *[1-9][0-9]* levels, [0-9]* ps' "$T/out" &&
    grep -q '^  ratio  .*shadesim levels / Yosys gates' "$T/out" && ok synth_paths || fail synth_paths "$(cat "$T/out" "$T/err")"

# The rank and band checks over the designs: 19 syntheses, half a minute
# of Yosys's CPU (a tenth of make test's whole budget), so make test-long
# alone, which runs them over every unit at widths 8, 16 and 24
# (tests/cli_timing_full.sh: width 8's designs among them).
if [ "${TIMING_DESIGNS:-}" != all ]; then
    for t in yosys_rank yosys_ratio_band; do echo "skip ${PREFIX}$t: make test-long runs it (cli_timing_full: every unit at widths 8, 16, 24)"; done
    exit 0
fi

units=$("$S" list 2>/dev/null | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p')
: >"$T/designs"
widths=8
[ "${TIMING_DESIGNS:-}" = all ] && widths="8 16 24"
for w in $widths; do
    mkdir -p "$T/w$w"
    for u in $units; do
        # hf_lookup is left out: its reciprocal ROMs (2^(W/2+1) + 1 entries
        # a lookup) keep ABC for minutes at width 8 and far longer at 16
        # and 24; a design the export refuses would be too
        [ "$u" = hf_lookup ] && continue
        # horner2 at 24: ABC's gate mapping (abc -g, Yosys 0.23) ran past
        # `synth`'s 600 s limit (seven CPU minutes and on, three times on
        # this machine); OpenSTA's flow (abc -liberty) maps it in seconds
        [ "$u $w" = "horner2 24" ] && continue
        # shade_cook: 38 s of CPU at width 8 (a 70 000 GE pipeline), out
        # of make test; make test-long runs it at 8 only (16 and 24, of
        # 156 000 and 291 000 GE, are not measured)
        [ "$u" = shade_cook ] && { [ "${TIMING_DESIGNS:-}" != all ] || [ "$w" != 8 ]; } && continue
        "$S" verilog "$u" --width "$w" -o "$T/w$w" >/dev/null 2>&1 && echo "$u $w" >>"$T/designs"
    done
done
# `shadesim synth` itself, two at a time (one per core): it prints both
# path lengths, Yosys's exactly as a user's `synth` run gets it.
xargs -P 2 -L 1 sh -c '"$0" synth "$2" --width "$3" >"$1/s_$2_$3.txt" 2>&1' "$S" "$T" <"$T/designs"
: >"$T/pairs"
while read -r u w; do
    f="$T/s_${u}_$w.txt"
    y=$(sed -n 's/^  Yosys  *\([0-9]*\) gates$/\1/p' "$f")
    l=$(sed -n 's/^  shadesim  *\([0-9]*\) levels, \([0-9]*\) ps.*/\1 \2/p' "$f")
    echo "$u $w ${y:-?} ${l:-? ?}" >>"$T/pairs"
done <"$T/designs"

# Spearman's rho (ranks with ties averaged) and the ratio's range
awk -v pre="$PREFIX" -v table="${TIMING_TABLE:-}" '
function rank(v, r, n,   i, j, k, t, idx) {
    for (i = 1; i <= n; i++) idx[i] = i
    for (i = 2; i <= n; i++) for (j = i; j > 1 && v[idx[j - 1]] > v[idx[j]]; j--) { t = idx[j]; idx[j] = idx[j - 1]; idx[j - 1] = t }
    for (i = 1; i <= n; i = j + 1) {
        for (j = i; j < n && v[idx[j + 1]] == v[idx[i]]; j++) ;
        for (k = i; k <= j; k++) r[idx[k]] = (i + j) / 2
    }
}
$3 !~ /^[0-9]+$/ || $4 !~ /^[0-9]+$/ { bad = bad " " $1 "@" $2; next }
{ n++; u[n] = $1; w[n] = $2; y[n] = $3; s[n] = $4; ps[n] = $5; q = $4 / $3
  if (n == 1 || q < lo) lo = q; if (n == 1 || q > hi) hi = q }
END {
    if (bad != "" || n < 3) { printf "FAIL " pre "yosys_rank: no figures for%s\n", bad; exit }
    rank(y, ry, n); rank(s, rs, n)
    for (i = 1; i <= n; i++) { my += ry[i] / n; ms += rs[i] / n }
    for (i = 1; i <= n; i++) { c += (ry[i] - my) * (rs[i] - ms); a += (ry[i] - my) ^ 2; b += (rs[i] - ms) ^ 2 }
    rho = c / sqrt(a * b)
    if (table != "") {
        printf "| unit | width | Yosys ltp | shadesim levels | shadesim ps | levels / ltp |\n|---|---:|---:|---:|---:|---:|\n" >table
        for (i = 1; i <= n; i++) printf "| %s | %d | %d | %d | %d | %.2f |\n", u[i], w[i], y[i], s[i], ps[i], s[i] / y[i] >table
        printf "\n%d designs: Spearman rank correlation %.3f, levels / ltp %.2f to %.2f\n", n, rho, lo, hi >table
    }
    if (rho >= 0.8) printf "ok " pre "yosys_rank\n"
    else printf "FAIL " pre "yosys_rank: Spearman %.3f over %d designs (needs >= 0.8)\n", rho, n
    if (lo >= 0.8 && hi <= 2.0) printf "ok " pre "yosys_ratio_band\n"
    else printf "FAIL " pre "yosys_ratio_band: levels / ltp %.2f to %.2f, outside 0.8 to 2.0\n", lo, hi
}' "$T/pairs"
