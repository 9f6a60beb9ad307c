#!/bin/sh
# The operation counts shadesim scene prints: the reference's per pixel in
# three lighting/camera configurations against counts derived by hand, and
# both speed-ups as the ratio of the printed counts (text table, scene.json,
# --compare). Small images.
PREFIX=cli_scene_ops.
. tests/lib_cli.sh
no_leak_check   # (lib_cli.sh: the same verbs over and over)

R="--set resolution=64x64"

# The reference per pixel, by hand (the default face: Blinn, ks 0.35, one
# light). Primitives: a dot product 2 add 3 mul; a vector normalized: its
# dot with itself, 1 sqrt, 1 reciprocal (div), 3 mul = 2 add 6 mul 1 div
# 1 sqrt; a vector difference or sum 3 add. Frame constants (L of a
# directional light, V of an orthographic camera, H = normalize(L + V) when
# both are constant, I0 kd, I0 ks) cost nothing per pixel.
#   directional + orthographic: N normalized (2 6 1 1), N.L (2 3),
#     (I0 kd) N.L summed (1 1), (I0 ks) spec added (1 1), N.H (2 3), ^n
#     (1 pow)                                          = 8 add 14 mul 1 1 1
#   point light + orthographic: the above + L = light - P normalized
#     (3 + 2 add, 6 mul, div, sqrt) + H = L + V normalized (the same)
#                                                      = 18 26 3 3 1
#   directional + perspective: the above with V = eye - P for L
#                                                      = 18 26 3 3 1
printf 'shadesim-scene 1\nresolution 64x64\nlight point 1 2 4\n' >"$T/point.scene"
for c in ortho point persp; do
    case $c in
        ortho) hand="8 14 1 1 1"; args="face $R" ;;
        point) hand="18 26 3 3 1"; args="$T/point.scene" ;;
        persp) hand="18 26 3 3 1"; args="face $R --set camera=perspective" ;;
    esac
    # shellcheck disable=SC2086
    expect "table_$c" 0 "$S" scene $args -o "$T/$c" || continue
    cp "$T/out" "$T/$c.txt"
    got=$(awk '$1 == "reference" { printf "%g %g %g %g %g", $2, $3, $4, $5, $6 }' "$T/$c.txt")
    [ "$got" = "$hand" ] && ok "reference_$c" || fail "reference_$c" "printed '$got', by hand '$hand'"
    # The weighted and long columns from the printed counts and weights;
    # the speed-ups as the ratios of the printed columns (to the rounding
    # of the printed digits).
    msg=$(awk '
        function near(a, b, tol) { return (a - b < tol && b - a < tol) }
        $1 == "weight" { for (k = 2; k <= 6; k++) w[k] = $k }
        $1 == "reference" || $1 == "method" { for (k = 2; k <= 8; k++) v[$1, k] = $k }
        /speed-up \(weighted\)/ { sw = $3 + 0 }
        /speed-up \(long ops\)/ { sl = $4 + 0 }
        END {
            split("reference method", who, " ")
            for (i = 1; i <= 2; i++) {
                s = 0; tol = 0
                for (k = 2; k <= 6; k++) { s += v[who[i], k] * w[k]; tol += 0.0005 * w[k] }
                if (!near(s, v[who[i], 7], tol + 0.0005)) print who[i] " weighted " v[who[i], 7] " != " s
                l = v[who[i], 4] + v[who[i], 5] + v[who[i], 6]
                if (!near(l, v[who[i], 8], 0.002)) print who[i] " long " v[who[i], 8] " != " l
            }
            if (!(v["method", 7] > 0 && v["method", 8] > 0)) { print "no method counts"; exit }
            rw = v["reference", 7] / v["method", 7]; rl = v["reference", 8] / v["method", 8]
            if (!near(sw, rw, 0.005 + 0.001 * rw)) print "weighted speed-up " sw " != " rw
            if (!near(sl, rl, 0.005 + 0.001 * rl)) print "long speed-up " sl " != " rl
        }' "$T/$c.txt" | tr '\n' ' ')
    [ -z "$msg" ] && ok "ratios_$c" || fail "ratios_$c" "$msg"
    # scene.json, at full precision.
    msg=$(awk '
        function num(s) { sub(/^[^:]*: */, "", s); sub(/,$/, "", s); return s + 0 }
        function obj(s, a,   n, p, i, kv) { sub(/^[^{]*\{/, "", s); sub(/\}.*$/, "", s); n = split(s, p, ", ")
            for (i = 1; i <= n; i++) { split(p[i], kv, ": "); gsub(/"/, "", kv[1]); a[kv[1]] = kv[2] + 0 } }
        function rel(a, b) { d = a - b; if (d < 0) d = -d; return d <= 1e-12 * (b < 0 ? -b : b) + 1e-300 }
        /^  "ops_ref": / { obj($0, r) }
        /^  "ops_hw": / { obj($0, h) }
        /^  "cost_weights": / { obj($0, w) }
        /^  "cost_ref": / { cr = num($0) }
        /^  "cost_hw": / { ch = num($0) }
        /^  "speedup": / { sp = num($0) }
        /^  "long_ops_ref": / { lr = num($0) }
        /^  "long_ops_hw": / { lh = num($0) }
        /^  "speedup_long": / { sl = num($0) }
        END {
            s = 0; t = 0
            for (k in w) { s += r[k] * w[k]; t += h[k] * w[k] }
            if (!rel(cr, s) || !rel(ch, t)) print "cost_ref/cost_hw " cr "/" ch " != " s "/" t
            if (!rel(lr, r["div"] + r["sqrt"] + r["pow"]) || !rel(lh, h["div"] + h["sqrt"] + h["pow"]))
                print "long_ops " lr "/" lh
            if (!(ch > 0 && lh > 0) || !rel(sp, cr / ch) || !rel(sl, lr / lh)) print "speedup " sp " " sl
        }' "$T/$c/scene.json" | tr '\n' ' ')
    [ -z "$msg" ] && ok "json_$c" || fail "json_$c" "$msg"
done

# --compare: both speed-ups of each configuration, those of its scene.json.
expect compare 0 "$S" scene face $R --compare -o "$T/cmp"
grep -q 'speed-up  long ops' "$T/out" && ok compare_header || fail compare_header "$(head -1 "$T/out")"
bad=""
for c in paper corrected auto; do
    js=$(awk '/^  "speedup": / { sub(/,$/, "", $2); w = $2 } /^  "speedup_long": / { sub(/,$/, "", $2); l = $2 }
                END { printf "%.2fx %.2fx", w, l }' "$T/cmp/$c/scene.json")
    got=$(awk -v c="$c" '$1 == c { for (i = 1; i < NF; i++) if ($i ~ /x$/ && $(i + 1) ~ /x$/) { print $i " " $(i + 1); exit } }' "$T/out")
    [ "$got" = "$js" ] || bad="$bad $c: '$got' != '$js'"
done
[ -z "$bad" ] && ok compare_speedups || fail compare_speedups "$bad"

# All-zero weights: the weighted speed-up is 0 / 0, not defined: "nan" in
# the table and --compare, null in scene.json (docs/cli.md's rule; it was
# printed 0.00x and 0); the long-ops one is still the ratio of its totals.
"$S" scene sphere --set resolution=24x24 --set "cost=add=0 mul=0 div=0 sqrt=0 pow=0" -o "$T/zw" >"$T/zw.out" 2>&1
grep -q '^  speed-up (weighted)  *nan  *weighted cost, reference / method: 0.000 / 0.000$' "$T/zw.out" &&
    grep -q '^  "speedup": null,$' "$T/zw/scene.json" && grep -q '^  "speedup_long": [1-9]' "$T/zw/scene.json" &&
    ok zero_weights_nan || fail zero_weights_nan "$(grep 'speed-up' "$T/zw.out"; grep '"speedup' "$T/zw/scene.json")"
"$S" scene sphere --set resolution=24x24 --set "cost=add=0 mul=0 div=0 sqrt=0 pow=0" --compare -o "$T/zc" >"$T/zc.out" 2>&1
[ "$(awk '$1 == "paper" || $1 == "corrected" || $1 == "auto" { if ($0 ~ / nan  *[0-9.]+x /) n++ } END { print n + 0 }' "$T/zc.out")" = 3 ] &&
    ok zero_weights_compare || fail zero_weights_compare "$(sed -n 1,4p "$T/zc.out")"
