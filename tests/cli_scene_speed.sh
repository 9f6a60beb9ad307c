#!/bin/sh
# cli_scene_speed.sh - a scene's speed and energy in hardware terms: the
# span unit's f_max, pixels per second and energy per pixel in scene.json
# and the table, each checked against its definition; the reference's
# bound recomputed from an independent `run` of the div unit on the same
# vectors; --compare's columns equal each configuration's scene.json; and
# scene --sweep's speed and energy columns and fronts recomputed from its
# CSV.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)
PREFIX=cli_scene_speed.

"$S" scene sphere --set resolution=96x96 -o "$T/s" >"$T/s.out" 2>"$T/s.err"
check render_runs [ $? -eq 0 ]
j=$T/s/scene.json
num() { sed -n "s/.*\"$1\": \\([-0-9.e+]*\\).*/\\1/p" "$j" | head -1; }
ps=$(sed -n 's/.*"critical_path": {"levels": [0-9]*, "ps": \([-0-9.e+]*\).*/\1/p' "$j")
fmax=$(num fmax_mhz); pps=$(num pixels_per_s); cpp=$(num clocks_per_pixel); epp=$(num energy_pj_per_pixel)
check json_has_speed [ -n "$ps" -a -n "$fmax" -a -n "$pps" -a -n "$epp" ]
# f_max is 1e6 / the critical path in ps, pixels/s f_max / clocks per pixel (the same doubles, the same order)
awk -v ps="$ps" -v f="$fmax" -v p="$pps" -v c="$cpp" 'BEGIN {
    exit !(sprintf("%.17g", 1e6 / ps) == sprintf("%.17g", f) && sprintf("%.17g", f * 1e6 / c) == sprintf("%.17g", p)) }' \
    && ok json_fmax_and_pixels_per_s_exact || fail json_fmax_and_pixels_per_s_exact "ps $ps fmax $fmax pps $pps cpp $cpp"
awk -v e="$epp" 'BEGIN { exit !(e > 0) }' && ok energy_per_pixel_positive || fail energy_per_pixel_positive "$epp"
# The table shows the same figures.
grep -q "^  f_max  *$(awk -v f="$fmax" 'BEGIN { printf "%.0f", f }') MHz" "$T/s.out" && ok table_fmax || fail table_fmax
grep -q "^  pixels / s  *$(awk -v p="$pps" 'BEGIN { printf "%.4g", p / 1e6 }') M" "$T/s.out" && ok table_pixels_per_s \
    || fail table_pixels_per_s "$(grep 'pixels / s' "$T/s.out")"

# The reference's bound: the div unit at the scene's width, run on its own
# vectors (64, seed 1), divisions per second over divides per pixel.
"$S" vectors div -n 64 --seed 1 -o "$T/div.vec" >/dev/null 2>&1
"$S" run div --width 16 --vectors "$T/div.vec" --json >"$T/div.json" 2>/dev/null
df=$(sed -n 's/^  "fmax_mhz": \(.*\),$/\1/p' "$T/div.json"); dc=$(sed -n 's/^  "cycles_per_item": \(.*\),$/\1/p' "$T/div.json")
de=$(sed -n 's/^  "energy_pj_per_item": \(.*\),$/\1/p' "$T/div.json")
rb=$(sed -n 's/.*"reference_bound": {\(.*\)}.*/\1/p' "$j")
nd=$(echo "$rb" | sed -n 's/.*"divides_per_pixel": \([-0-9.e+]*\).*/\1/p')
rmax=$(echo "$rb" | sed -n 's/.*"pixels_per_s_max": \([-0-9.e+]*\).*/\1/p')
rmin=$(echo "$rb" | sed -n 's/.*"energy_pj_per_pixel_min": \([-0-9.e+]*\).*/\1/p')
awk -v f="$df" -v c="$dc" -v n="$nd" -v m="$rmax" -v e="$de" -v r="$rmin" 'BEGIN {
    exit !(n > 0 && sprintf("%.17g", f * 1e6 / c / n) == sprintf("%.17g", m) && sprintf("%.17g", e * n) == sprintf("%.17g", r)) }' \
    && ok reference_bound_from_run_div || fail reference_bound_from_run_div "div fmax $df clocks $dc energy $de; scene: $rb"

# --compare: each row's f_max, Mpx/s and pJ/px are its scene.json's.
"$S" scene sphere --set resolution=64x64 --compare -o "$T/c" >"$T/c.out" 2>&1
check compare_runs [ $? -eq 0 ]
bad=
for cfg in paper corrected auto; do
    jj=$T/c/$cfg/scene.json
    f=$(sed -n 's/^  "fmax_mhz": \(.*\),$/\1/p' "$jj"); p=$(sed -n 's/^  "pixels_per_s": \(.*\),$/\1/p' "$jj")
    e=$(sed -n 's/^  "energy_pj_per_pixel": \(.*\),$/\1/p' "$jj")
    want=$(awk -v f="$f" -v p="$p" -v e="$e" 'BEGIN { printf "%4.0f MHz %9.4g %7.3g", f, p / 1e6, e }')
    grep "^$cfg " "$T/c.out" | grep -qF -- "$want" || bad="$bad $cfg"
done
[ -z "$bad" ] && ok compare_columns_match_json || fail compare_columns_match_json "$bad"
# The reference: measured on the shade unit where the lighting fits it
# (a row of the second table), else the divider's bound line.
if grep -q '"available": true' "$T/c/paper/scene.json"; then
    grep -q "^-  *per-pixel " "$T/c.out" && ! grep -q "^reference: <=" "$T/c.out"
else
    grep -q "^reference: <= .* M pixels/s, >= .* pJ/pixel" "$T/c.out"
fi && ok compare_reference_line || fail compare_reference_line

# --sweep: the speed and energy columns and their fronts, recomputed.
"$S" scene sphere --set resolution=48x48 --sweep 'L=4,8;policy=linear,cubic-n1;terms=3' -o "$T/w" >"$T/w.out" 2>&1
check sweep_runs [ $? -eq 0 ]
csv=$T/w/sweep.csv
col() { head -1 "$csv" | tr ',' '\n' | grep -n -x "$1" | cut -d: -f1; }
cn=$(col nmse); cc=$(col clocks_per_pixel); cf=$(col fmax_mhz); cp=$(col pixels_per_s); ce=$(col energy_pj_per_pixel)
cs=$(col front_speed); cfe=$(col front_energy); csa=$(col same_as); co=$(col overflows); cst=$(col status)
# The CSV prints 9 significant digits, so f_max and pixels/s as printed
# each carry a relative rounding of at most 5e-9: the recomputation must
# agree within their sum, relative (no absolute slack).
bad=$(tail -n +2 "$csv" | awk -F, -v cc="$cc" -v cf="$cf" -v cp="$cp" '$cf != "" {
    w = $cf * 1e6 / $cc; d = w - $cp; if (d < 0) d = -d; if (!(d <= 1e-8 * $cp)) print NR }')
[ -z "$bad" ] && ok sweep_pixels_per_s || fail sweep_pixels_per_s "rows $bad"
for pair in "speed $cp $cs max" "energy $ce $cfe min"; do
    set -- $pair
    want=$(awk -F, -v x="$2" -v n="$cn" -v sa="$csa" -v o="$co" -v st="$cst" -v dir="$4" 'NR > 1 && $sa == "" && $st == "ok" && $o == 0 {
        k++; r[k] = NR - 2; v[k] = (dir == "max" ? -$x : $x); e[k] = $n }
        END { for (i = 1; i <= k; i++) { on = 1
            for (j = 1; j <= k && on; j++) if (j != i && v[j] <= v[i] && e[j] <= e[i] && (v[j] < v[i] || e[j] < e[i])) on = 0
            if (on) print r[i] } }' "$csv" | sort -n | tr '\n' ' ')
    got=$(awk -F, -v f="$3" 'NR > 1 && $f == 1 { print NR - 2 }' "$csv" | sort -n | tr '\n' ' ')
    [ -n "$want" ] && [ "$want" = "$got" ] && ok "sweep_front_$1" || fail "sweep_front_$1" "want '$want' got '$got'"
done
check sweep_speed_chart [ -s "$T/w/sweep_speed.svg" -a -s "$T/w/sweep_energy.svg" ]
