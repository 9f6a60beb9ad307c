#!/bin/sh
# Command-line contract of shadesim scene: the JSON fields, the output
# folder's files (PNGs checked by pngcheck when installed), one-line errors
# naming FILE:LINE for bad scene files, exit 2 for a bad --set, exit 1 for
# a missed --max-nmse, and the same bytes for -j 1 and -j 2. Small images.
PREFIX=cli_scene.
. tests/lib_cli.sh

R="--set resolution=64x64"
expect help 0 "$S" scene --help
grep -q -- '--target-nmse' "$T/out" && grep -q -- '--sweep' "$T/out" && grep -q -- '--heldout' "$T/out" \
    && ok help_options || fail help_options "--help misses an option"

# A render: every JSON field, every file of the folder.
expect json 0 "$S" scene face $R --json -o "$T/face"
for k in mesh resolution view policy L terms series width unit schedule formats round overflow covered nmse \
         nmse8 psnr max_abs_err max_err8 diff8_share err_scale clocks pixels clocks_per_pixel area_ge overflows spans \
         intervals intervals_deg2 deg2_share nodes_shaded ops_ref ops_hw cost_ref cost_hw speedup; do
    grep -q "^  \"$k\": " "$T/out" && ok "json_$k" || fail "json_$k" "field $k missing"
done
cmp -s "$T/out" "$T/face/scene.json" && ok json_is_scene_json || fail json_is_scene_json "stdout differs from scene.json"
# formats lists the built signals only: the default cubic uses node set N1,
# so N2's own elements (i1x13, ucx3) are not built and not listed.
grep '"formats"' "$T/out" | grep -q '"i1x7"' && ! grep '"formats"' "$T/out" | grep -q '"i1x13"\|"ucx3"\|u0\.0' \
    && ok json_formats_built_only || fail json_formats_built_only "formats lists a signal the unit does not build"
if command -v python3 >/dev/null 2>&1; then
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["covered"]>0 and d["nmse"]>0 and d["speedup"]>1 and d["resolution"]=="64x64" and set(d["ops_ref"])=={"add","mul","div","sqrt","pow"}' "$T/out" \
        && ok json_parses || fail json_parses "python3 could not read the JSON or a figure is off"
else
    echo "skip cli_scene.json_parses: python3 not installed"
fi
# The maps' key in scene.json against the images' own pixels (python3
# inflates and unfilters the PNGs): degree.png and region.png use exactly
# the listed colours and the background; the error key names the heat map
# written and full white is 1/err_scale.
if command -v python3 >/dev/null 2>&1; then
    cat >"$T/key.py" <<'PY'
import json, struct, sys, zlib
def pixels(path):
    b = open(path, 'rb').read(); o, z = 8, b''
    while o < len(b):
        n, = struct.unpack('>I', b[o:o+4]); t = b[o+4:o+8]
        if t == b'IHDR': w, h, bd, ct = struct.unpack('>IIBB', b[o+8:o+18])
        if t == b'IDAT': z += b[o+8:o+8+n]
        o += 12 + n
    r = zlib.decompress(z); bpp = 3 if ct == 2 else 1; rb = w * bpp; up = bytearray(rb); px = set()
    for y in range(h):
        f = r[y*(rb+1)]; cur = bytearray(r[y*(rb+1)+1:(y+1)*(rb+1)])
        for i in range(rb):
            a = cur[i-bpp] if i >= bpp else 0; u = up[i]; c = up[i-bpp] if i >= bpp else 0
            p = a + u - c; pa, pb, pc = abs(p - a), abs(p - u), abs(p - c)
            q = [0, a, u, (a + u) // 2, a if pa <= pb and pa <= pc else (u if pb <= pc else c)][f]
            cur[i] = (cur[i] + q) & 255
        px |= {'#%02x%02x%02x' % tuple(cur[i:i+3]) for i in range(0, rb, 3)}
        up = cur
    return px
d = json.load(open(sys.argv[1] + '/scene.json')); L = d['legend']
deg, reg = pixels(sys.argv[1] + '/degree.png'), pixels(sys.argv[1] + '/region.png')
assert L['background'] == '#000000'
assert deg - {L['background']} <= set(L['degree'].values()) and len(deg) >= 2, deg
assert reg == set(L['region'].values()) | {L['background']}, (reg, L['region'])
assert L['error']['file'] == 'err-x%d.png' % d['err_scale'] and abs(L['error']['white'] * d['err_scale'] - 1) < 1e-15
assert [s[0] for s in L['error']['stops']] == [L['error']['white'] * k / 4 for k in range(5)]
assert L['error']['stops'][-1][1] == '#ffffff' and L['error']['stops'][0][1] == '#000000'
# the key images beside the maps: the same colours, each with its label
import re, xml.dom.minidom as X
def swatches(name):
    doc = X.parse(sys.argv[1] + '/' + name)
    fills = [r.getAttribute('fill') for r in doc.getElementsByTagName('rect')][1:]
    texts = [t.firstChild.data for t in doc.getElementsByTagName('text')]
    return texts[0], list(zip(fills, texts[1:]))
t, s = swatches('degree-key.svg')
assert t == 'degree.png: degree' and s[:3] == [(L['degree'][str(g)], '%d (%s)' % (g, n)) for g, n in ((1, 'linear'), (2, 'quadratic'), (3, 'cubic'))] and s[3] == ('#000000', 'not covered'), s
t, s = swatches('region-key.svg')
assert s[:-1] == [(c, 'region ' + k) for k, c in L['region'].items()] and s[-1] == ('#000000', 'not covered'), s
t, s = swatches('err-key.svg')
assert t == L['error']['file'] + ': |hw - ref|' and [c for c, _ in s] == [c for _, c in L['error']['stops']], s
assert [float(x.replace('>= ', '')) for _, x in s] == [v for v, _ in L['error']['stops']], s
PY
    python3 "$T/key.py" "$T/face" 2>"$T/err" && ok json_legend_matches_images || fail json_legend_matches_images "$(tail -1 "$T/err")"
else
    echo "skip cli_scene.json_legend_matches_images: python3 not installed"
fi
k=$(sed -n 's/^  "err_scale": \([0-9]*\),$/\1/p' "$T/out")
for f in ref.png hw.png "err-x$k.png" degree.png region.png ref-hw.png hw-nodes.png scene.json \
         degree-key.svg region-key.svg err-key.svg; do
    [ -s "$T/face/$f" ] && ok "file_$f" || fail "file_$f" "missing in the output folder"
done
[ "$(ls "$T/face" | wc -l)" -eq 11 ] && ok files_only || fail files_only "$(ls "$T/face")"
# NMSE 8-bit from the PNG files' pixels, decoded here (chunks, zlib,
# filter bytes), against scene.json's nmse8; uncovered pixels are 0 in both
# images, so the sums over every pixel are those over the covered ones.
if command -v python3 >/dev/null 2>&1; then
    python3 - "$T/face" <<'PY' && ok nmse8_from_pngs || fail nmse8_from_pngs "scene.json's nmse8 is not that of ref.png/hw.png"
import json, struct, sys, zlib
def gray(path):
    b = open(path, 'rb').read()
    assert b[:8] == b'\x89PNG\r\n\x1a\n'
    i, idat, w, h = 8, b'', 0, 0
    while i < len(b):
        n, t = struct.unpack('>I4s', b[i:i + 8])
        d = b[i + 8:i + 8 + n]
        if t == b'IHDR':
            w, h, depth, ctype = struct.unpack('>IIBB', d[:10])
            assert depth == 8 and ctype == 0
        elif t == b'IDAT':
            idat += d
        i += 12 + n
    raw, px, prev = zlib.decompress(idat), [], [0] * w
    for y in range(h):
        f, row = raw[y * (w + 1)], list(raw[y * (w + 1) + 1:(y + 1) * (w + 1)])
        for x in range(w):
            # the five PNG filters (one byte a pixel): none, sub, up,
            # average, Paeth
            a = row[x - 1] if x else 0
            u = prev[x]
            c = prev[x - 1] if x else 0
            if f == 1: row[x] = (row[x] + a) & 255
            elif f == 2: row[x] = (row[x] + u) & 255
            elif f == 3: row[x] = (row[x] + (a + u) // 2) & 255
            elif f == 4:
                p = a + u - c
                pa, pb, pc = abs(p - a), abs(p - u), abs(p - c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else (u if pb <= pc else c))) & 255
            else: assert f == 0
        px += row
        prev = row
    return px
d = sys.argv[1]
ref, hw = gray(d + '/ref.png'), gray(d + '/hw.png')
se = sum((a - b) ** 2 for a, b in zip(hw, ref))
sr = sum(a * a for a in ref)
got = json.load(open(d + '/scene.json'))
assert sr > 0 and se > 0, (se, sr)
assert abs(got['nmse8'] - se / sr) <= 1e-12 * (se / sr), (got['nmse8'], se / sr)
assert got['nmse8'] != got['nmse']
PY
else
    echo "skip cli_scene.nmse8_from_pngs: python3 not installed"
fi
if command -v pngcheck >/dev/null 2>&1; then
    for f in "$T"/face/*.png; do
        pngcheck -q "$f" >/dev/null 2>&1 && ok "pngcheck_$(basename "$f")" || fail "pngcheck_$(basename "$f")" "$(pngcheck "$f" 2>&1 | head -2)"
    done
else
    echo "skip cli_scene.pngcheck: pngcheck not installed"
fi

# The table, --max-nmse.
expect table 0 "$S" scene face $R -o "$T/t"
grep -q '^  NMSE ' "$T/out" && grep -q 'speed-up' "$T/out" && ok table_rows || fail table_rows "$(cat "$T/out")"
expect max_nmse_met 0 "$S" scene face $R -o "$T/t" --max-nmse 1
grep -q 'meets your target' "$T/out" && ok max_nmse_says_meets || fail max_nmse_says_meets "$(cat "$T/out")"
expect max_nmse_tiny 1 "$S" scene face $R -o "$T/t" --max-nmse 1e-30
grep -q 'does NOT meet your target' "$T/out" && ok max_nmse_says_misses || fail max_nmse_says_misses "$(cat "$T/out")"

# Same bytes for any -j.
"$S" scene face $R --set policy=adaptive-auto -o "$T/j1" -j 1 --json >"$T/j1.json" 2>/dev/null
"$S" scene face $R --set policy=adaptive-auto -o "$T/j2" -j 2 --json >"$T/j2.json" 2>/dev/null
same=1
for f in j1.json j1/ref.png j1/hw.png j1/degree.png j1/region.png j1/scene.json; do
    g=$(echo "$f" | sed 's/j1/j2/')
    cmp -s "$T/$f" "$T/$g" || same=0
done
[ $same -eq 1 ] && ok jobs_same_bytes || fail jobs_same_bytes "-j 1 and -j 2 differ"

# The batch mode (default) and the kernel alone (--no-batch) give the same
# bytes, on a configuration that overflows (its lanes fall back) too.
for n in auto overflowing; do
    c="--set policy=adaptive-auto"
    [ $n = overflowing ] && c="--set policy=cubic-n2 --set fmt=a=s3.13"   # A in s3.13 overflows
    "$S" scene face $R $c -o "$T/b1" --json >"$T/b1.json" 2>/dev/null
    "$S" scene face $R $c -o "$T/b0" --json --no-batch >"$T/b0.json" 2>/dev/null
    same=1
    for f in b1.json b1/ref.png b1/hw.png b1/scene.json; do
        g=$(echo "$f" | sed 's/b1/b0/')
        cmp -s "$T/$f" "$T/$g" || same=0
    done
    [ -s "$T/b1.json" ] || same=0
    [ $same -eq 1 ] && ok "no_batch_same_bytes_$n" || fail "no_batch_same_bytes_$n" "--no-batch differs ($c)"
done

# Other built-ins, a scene file, the held-out view.
expect sphere 0 "$S" scene sphere $R -o "$T/s"
printf 'shadesim-scene 1\n# a small face\nmesh face\nresolution 48x40\npolicy cubic-n2\nL 6\n' >"$T/small.scene"
expect scene_file 0 "$S" scene "$T/small.scene" --json -o "$T/sf"
grep -q '"resolution": "48x40"' "$T/out" && grep -q '"policy": "cubic-n2"' "$T/out" && ok scene_file_read || fail scene_file_read "$(head -5 "$T/out")"
expect heldout 0 "$S" scene face $R --heldout --json -o "$T/h"
grep -q '"view": "heldout"' "$T/out" && ok heldout_view || fail heldout_view "view not heldout"

# Bad scene files: exit 2, one line naming FILE:LINE:.
bad() {   # bad NAME CONTENT LINE
    printf "$2" >"$T/$1.scene"
    if expect "$1" 2 "$S" scene "$T/$1.scene" -o "$T/bad"; then
        grep -q "$T/$1.scene:$3:" "$T/err" && ok "$1_line" || fail "$1_line" "$(cat "$T/err")"
    fi
}
bad bad_key 'shadesim-scene 1\nresolution 64x64\nfrobnicate 3\n' 3
bad bad_number 'shadesim-scene 1\nL eight\n' 2
bad bad_version 'shadesim-scene 99\n' 1
[ ! -e "$T/bad" ] && ok bad_no_output || fail bad_no_output "output folder made for a bad scene"
expect no_file 2 "$S" scene "$T/nosuch.scene"
printf 'v 0 0 0\nv 1 0 0\nf 1 2 7\n' >"$T/bad.obj"
printf 'shadesim-scene 1\nmesh %s\n' "$T/bad.obj" >"$T/obj.scene"
expect bad_obj 2 "$S" scene "$T/obj.scene"
grep -q "bad.obj:3:" "$T/err" && ok bad_obj_line || fail bad_obj_line "$(cat "$T/err")"

# Bad usage.
expect set_unknown_key 2 "$S" scene face --set frobnicate=1
expect set_no_eq 2 "$S" scene face --set L
expect set_bad_value 2 "$S" scene face --set L=eight
expect set_bad_fmt 2 "$S" scene face --set fmt=nosig=s2.14
# L and terms are the unit's parameters: their ranges are its (2..64,
# 1..20), named at the line that set them
expect set_bad_L 2 "$S" scene face --set L=65
grep -q '^shadesim: --set L: .*2\.\.64' "$T/err" && ok set_bad_L_range || fail set_bad_L_range "$(cat "$T/err")"
printf 'shadesim-scene 1\nL 4\nterms 21\npolicy linear\n' >"$T/terms.scene"
expect file_bad_terms 2 "$S" scene "$T/terms.scene" -o "$T/terms"
grep -q "terms.scene:3: .*terms.*1\.\.20" "$T/err" && ok file_bad_terms_line || fail file_bad_terms_line "$(cat "$T/err")"
expect bad_option 2 "$S" scene face --bogus
expect bad_jobs 2 "$S" scene face -j 0
expect max_nmse_bad 2 "$S" scene face --max-nmse abc
expect two_scenes 2 "$S" scene face sphere
expect bad_camera 2 "$S" scene face $R --set "eye=0 0 -5" --set "target=0 100 -5" -o "$T/cam"
if [ -w /dev/full ]; then
    expect stdout_full 2 sh -c "\"$S\" scene face $R -o \"$T/full\" >/dev/full"
fi

# --compare: three configurations, a table row and a folder each.
expect compare 0 "$S" scene face $R --compare -o "$T/cmp"
# (and a row each in the second table, both pipelines: "config method ...")
[ "$(grep -cE '^(paper|corrected|auto)  *adaptive-' "$T/out")" -eq 3 ] && ok compare_rows || fail compare_rows "$(cat "$T/out")"
[ "$(grep -cE '^(paper|corrected|auto)  *node\+span ' "$T/out")" -ge 3 ] && ok compare_pipes_rows || fail compare_pipes_rows "$(cat "$T/out")"
[ -s "$T/cmp/paper/scene.json" ] && [ -s "$T/cmp/corrected/hw.png" ] && [ -s "$T/cmp/auto/degree.png" ] \
    && ok compare_files || fail compare_files "$(ls -R "$T/cmp")"
grep -q '"terms": 3,' "$T/cmp/paper/scene.json" && grep -q '"policy": "adaptive-auto"' "$T/cmp/auto/scene.json" \
    && ok compare_configs || fail compare_configs "paper or auto configuration not as named"
