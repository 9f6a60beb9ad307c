#!/bin/sh
# Command-line contract of shadesim factor: help, the output folder's files,
# the claims' verdicts
# (PNGs checked by pngcheck when installed), the same bytes on a rerun, and
# exit 2 with one 'shadesim:' line for bad input. Small maps (R = 8).
PREFIX=cli_factor.
. tests/lib_cli.sh

expect help 0 "$S" factor --help
grep -q -- '--smooth' "$T/out" && grep -q -- '--svd' "$T/out" && ok help_options || fail help_options "--help misses an option"

expect run 0 "$S" factor ward-aniso --res 8 --svd 2 --heldout 2000 -o "$T/a"
for f in lambda.png pi.png factors.f32 report.csv; do
    [ -s "$T/a/$f" ] && ok "file_$f" || fail "file_$f" "missing or empty"
done
[ "$(wc -c <"$T/a/factors.f32")" -eq 512 ] && ok f32_size || fail f32_size "expected 2 * 8 * 8 * 4 bytes"
grep -q '^factor,8,' "$T/a/report.csv" && grep -q '^svd,8,0,2,' "$T/a/report.csv" && ok csv_rows || fail csv_rows "$(cat "$T/a/report.csv")"
# every factorized row: no negative value, exact reciprocity
awk -F, '$1 ~ /^factor/ && ($10 != 0 || $11 != 0) { bad = 1 } END { exit bad }' "$T/a/report.csv" \
    && ok positive_reciprocal || fail positive_reciprocal "$(grep '^factor' "$T/a/report.csv")"
if command -v pngcheck >/dev/null 2>&1; then
    pngcheck -q "$T/a/lambda.png" >/dev/null 2>&1 && pngcheck -q "$T/a/pi.png" >/dev/null 2>&1 \
        && ok pngcheck || fail pngcheck "pngcheck rejects a map"
else
    echo "skip cli_factor.pngcheck: pngcheck not installed"
fi
cp "$T/out" "$T/out1"
expect rerun 0 "$S" factor ward-aniso --res 8 --svd 2 --heldout 2000 -o "$T/b"
for f in lambda.png pi.png factors.f32 report.csv; do
    cmp -s "$T/a/$f" "$T/b/$f" || { fail same_bytes "$f differs"; break; }
done && ok same_bytes

# --claims: every claim measured holds for Ward (exit 0), the Fig. 1 row says it is not measured
expect claims 0 "$S" factor ward --res 8 --heldout 2000 --claims -o "$T/c"
[ "$(grep -c ',holds$' "$T/c/claims.csv")" -eq 4 ] && grep -q ',not measured$' "$T/c/claims.csv" \
    && ok claims_rows || fail claims_rows "$(cat "$T/c/claims.csv")"

# --scene: the three images and both NMSE figures (small image)
expect scene 0 "$S" factor ward --res 8 --heldout 1000 --svd 0 --scene sphere --scene-res 48 -o "$T/s"
for f in vertex.png factorized.png exact.png; do
    [ -s "$T/s/$f" ] || { fail scene_files "$f missing"; break; }
done && ok scene_files
grep -q 'exact at vertices, interpolated   NMSE [0-9]' "$T/out" && grep -q 'factorized per pixel (hf_lookup)  NMSE [0-9]' "$T/out" \
    && ok scene_nmse || fail scene_nmse "$(cat "$T/out")"
expect scene_not_ward 2 "$S" factor ct --res 8 --scene sphere -o "$T/s"
expect scene_bad_res 2 "$S" factor ward --res 12 --scene sphere -o "$T/s"
expect scene_unknown 2 "$S" factor ward --res 8 --svd 0 --scene nowhere -o "$T/s"

expect unknown_brdf 2 "$S" factor phong9 -o "$T/c"
expect res_0 2 "$S" factor ct --res 0 -o "$T/c"
expect res_100000 2 "$S" factor ct --res 100000 -o "$T/c"
expect param_nan 2 "$S" factor ct --param m=nan -o "$T/c"
expect param_inf 2 "$S" factor ward --param alpha=inf -o "$T/c"
expect smooth_neg 2 "$S" factor ct --smooth -1 -o "$T/c"
expect unknown_option 2 "$S" factor ct --bogus 1
expect missing_value 2 "$S" factor ct --res
expect no_brdf 2 "$S" factor
