#!/bin/sh
# cli_chart.sh - shadesim chart from the outside: the charts drawn from a
# sweep's CSV, and from the CSV merge joins from its shards, are the same
# bytes as the sweep's own; charts are XML (xmllint); --png renders them
# (pngcheck); a bad CSV is one line naming FILE:LINE and exit 2.
PREFIX=cli_chart.
. tests/lib_cli.sh

expect help 0 "$S" chart --help
expect no_csv 2 "$S" chart
expect missing_csv 2 "$S" chart "$T/nothing.csv"
expect bad_option 2 "$S" chart --bogus x.csv
printf 'a,b,c\n1,2,3\n' >"$T/notsweep.csv"
expect not_a_sweep_csv 2 "$S" chart "$T/notsweep.csv" -o "$T/x"
grep -q "notsweep.csv:1: " "$T/err" && ok not_a_sweep_csv_names_line || fail not_a_sweep_csv_names_line "$(cat "$T/err")"

# Two schedules (clocks per pixel vary: all three charts), two settings of
# terms, cut into shards and merged.
ARGS="interp3 --widths 10:12 --schedule paper,pipe --param terms=2,3 -n 16"
"$S" sweep $ARGS -o "$T/whole" >/dev/null 2>&1
check sweep_runs [ -s "$T/whole/sweep.csv" -a -s "$T/whole/cycles_vs_error.svg" ]
"$S" sweep $ARGS --shard 1/2 -o "$T/sh" >/dev/null 2>&1
"$S" sweep $ARGS --shard 2/2 -o "$T/sh" >/dev/null 2>&1
"$S" merge "$T/sh/sweep-2-of-2.csv" "$T/sh/sweep-1-of-2.csv" -o "$T/merged.csv" >/dev/null 2>&1
expect chart_merged 0 "$S" chart "$T/merged.csv" -o "$T/fromcsv"
same=1
for c in error_vs_width area_vs_error cycles_vs_error; do
    cmp -s "$T/whole/$c.svg" "$T/fromcsv/$c.svg" || { same=0; fail "merged_same_bytes_$c" "differs from the sweep's"; }
done
[ $same -eq 1 ] && ok merged_same_bytes

# A bad row: one line naming the file and line.
head -3 "$T/merged.csv" >"$T/cut.csv"
echo "7,12,x" >>"$T/cut.csv"
expect short_row 2 "$S" chart "$T/cut.csv" -o "$T/y"
grep -q "cut.csv:4: " "$T/err" && ok short_row_names_line || fail short_row_names_line "$(cat "$T/err")"

# Default folder: the CSV's.
cp "$T/whole/sweep.csv" "$T/copy.csv"
expect default_folder 0 "$S" chart "$T/copy.csv"
cmp -s "$T/whole/area_vs_error.svg" "$T/area_vs_error.svg" && ok default_folder_same_bytes || fail default_folder_same_bytes

if command -v xmllint >/dev/null 2>&1; then
    xmllint --noout "$T"/fromcsv/*.svg 2>"$T/xl" && ok charts_xmllint || fail charts_xmllint "$(head -c 300 "$T/xl")"
else
    echo "skip ${PREFIX}charts_xmllint: xmllint not installed (Debian: libxml2-utils)"
fi
if command -v rsvg-convert >/dev/null 2>&1; then
    expect png 0 "$S" chart "$T/merged.csv" -o "$T/png" --png
    if command -v pngcheck >/dev/null 2>&1; then
        # a PNG for every chart drawn (an SVG each)
        nsvg=$(ls "$T"/png/*.svg | wc -l)
        pngcheck -q "$T"/png/*.png >/dev/null 2>&1 && [ "$(ls "$T"/png/*.png | wc -l)" -eq "$nsvg" ] \
            && [ "$nsvg" -ge 3 ] && ok png_valid || fail png_valid "$(ls "$T/png")"
    else
        echo "skip ${PREFIX}png_valid: pngcheck not installed"
    fi
else
    echo "skip ${PREFIX}png: rsvg-convert not installed (Debian: librsvg2-bin)"
fi
# Without rsvg-convert on PATH, --png is refused before anything is drawn.
PATH=/nonexistent "$S" chart "$T/merged.csv" -o "$T/nopng" --png >/dev/null 2>"$T/err"
[ $? -eq 2 ] && grep -q 'rsvg-convert' "$T/err" && [ ! -e "$T/nopng" ] && ok png_without_rsvg_refused \
    || fail png_without_rsvg_refused "$(cat "$T/err")"
