#!/bin/sh
# cli_report.sh - shadesim report from the outside: one HTML page that
# xmllint's HTML parser reads without a complaint, a row for every unit
# `shadesim list` names and for every claim id `shadesim claims --json`
# prints, no script, links that resolve to files beside it, the same bytes
# twice, and a page headless Chromium renders (pngcheck on its screenshot,
# not blank; --dump-dom holds the tables). Bad usage exits 2 with one line.
# The page takes a few seconds (claims render the face scene), the browser
# more: both run in the plain build only.
PREFIX=cli_report.
. tests/lib_cli.sh

expect help 0 "$S" report --help
grep -q -- '-o DIR' "$T/out" && ok help_names_option || fail help_names_option
expect bad_option 2 "$S" report --bogus
expect o_without_folder 2 "$S" report -o
: >"$T/plainfile"
expect o_under_a_file 2 "$S" report -o "$T/plainfile/sub"

case "${TST_BUILD:-}" in
*-asan)
    for n in runs xmllint_html_clean unit_rows claim_rows no_script links_resolve same_bytes chromium_screenshot \
             chromium_dom; do
        echo "skip ${PREFIX}$n: runs in the plain build only"
    done
    exit 0 ;;
esac

expect runs 0 "$S" report -o "$T/r1"
P="$T/r1/report.html"
[ -s "$P" ] || { fail page_written "no $P"; exit 0; }

if command -v xmllint >/dev/null 2>&1; then
    xmllint --html --noout "$P" >"$T/xl" 2>&1 && [ ! -s "$T/xl" ] && ok xmllint_html_clean \
        || fail xmllint_html_clean "$(head -c 300 "$T/xl")"
else
    echo "skip ${PREFIX}xmllint_html_clean: xmllint not installed (Debian: libxml2-utils)"
fi

# A row for every unit, named as list names them.
"$S" list | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p' >"$T/units"
missing=
nu=0
while read -r u; do
    nu=$((nu + 1))
    grep -q "<tr id=\"unit-$u\"><td class=\"id\">$u</td>" "$P" || missing="$missing $u"
done <"$T/units"
[ "$nu" -gt 10 ] && [ -z "$missing" ] && ok unit_rows || fail unit_rows "units: $nu, without a row:$missing"

# A row for every claim id claims --json prints.
"$S" claims --json | sed -n 's/^ *{"id": "\([^"]*\)".*/\1/p' >"$T/ids"
missing=
nc=0
while read -r id; do
    nc=$((nc + 1))
    grep -q "<tr id=\"claim-$id\">" "$P" || missing="$missing $id"
done <"$T/ids"
[ "$nc" -gt 10 ] && [ -z "$missing" ] && ok claim_rows || fail claim_rows "claims: $nc, without a row:$missing"

grep -qi '<script' "$P" && fail no_script "the page has a script" || ok no_script

# Every relative link names a file that is there.
bad=
for h in $(grep -o 'href="[^"#][^"]*"' "$P" | sed 's/^href="//; s/"$//' | sort -u); do
    [ -f "$T/r1/$h" ] || bad="$bad $h"
done
[ -z "$bad" ] && [ -s "$T/r1/horner3.vcd" ] && [ -s "$T/r1/sweep-horner3.csv" ] && ok links_resolve \
    || fail links_resolve "missing:$bad"

"$S" report -o "$T/r2" >/dev/null 2>&1
cmp -s "$P" "$T/r2/report.html" && ok same_bytes || fail same_bytes "two runs differ"

CH=
for c in chromium chromium-browser; do command -v $c >/dev/null 2>&1 && { CH=$c; break; }; done
if [ -z "$CH" ]; then
    echo "skip ${PREFIX}chromium_screenshot: chromium not installed"
    echo "skip ${PREFIX}chromium_dom: chromium not installed"
    exit 0
fi
abs=$(cd "$T/r1" && pwd)/report.html
(cd "$T" && HOME="$T" timeout 120 "$CH" --headless --no-sandbox --disable-gpu --hide-scrollbars \
    --screenshot="$T/shot.png" --window-size=1200,3000 "file://$abs") >/dev/null 2>&1
if [ ! -s "$T/shot.png" ]; then
    fail chromium_screenshot "no screenshot"
elif command -v pngcheck >/dev/null 2>&1; then
    # A blank 1200x3000 page compresses to a few kB; the tables and
    # charts make it some hundred.
    pngcheck "$T/shot.png" >"$T/pc" 2>&1 && grep -q '1200x3000' "$T/pc" && [ "$(wc -c <"$T/shot.png")" -gt 50000 ] \
        && ok chromium_screenshot || fail chromium_screenshot "$(cat "$T/pc"), $(wc -c <"$T/shot.png") bytes"
else
    echo "skip ${PREFIX}chromium_screenshot: pngcheck not installed"
fi
(cd "$T" && HOME="$T" timeout 120 "$CH" --headless --no-sandbox --disable-gpu --dump-dom "file://$abs") \
    >"$T/dom" 2>/dev/null
grep -q '<table' "$T/dom" && grep -q 'id="unit-horner3"' "$T/dom" && grep -q 'id="claim-' "$T/dom" \
    && ok chromium_dom || fail chromium_dom "the DOM lacks the tables"
