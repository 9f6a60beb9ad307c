# lib_map.sh - what scripts/add_area.sh, mul_area.sh, cmul_area.sh and
# rom_area.sh share; sourced, not run. The caller sets me (its name for
# messages) and lib (the Liberty file, gzipped or not). Checks yosys and
# the file, unpacks it into a scratch folder $d (removed on exit), sets
# nand to the file's NAND2_X1 area (1 GE), and offers map_area: the mapped area of $d/m.v's
# module m through `synth; abc -liberty L; opt_clean; stat -liberty L`
# (with abc_script set, `abc -liberty L -script $abc_script`).
command -v yosys >/dev/null 2>&1 || { echo "$me: yosys not found (install the Debian package yosys)" >&2; exit 2; }
[ -r "$lib" ] || { echo "$me: $lib: cannot read" >&2; exit 2; }
d=$(mktemp -d) || exit 2
trap 'rm -rf "$d"' EXIT
trap 'exit 130' INT TERM HUP
case $lib in
*.gz) gzip -dc "$lib" >"$d/l.lib" || { echo "$me: cannot unpack $lib" >&2; exit 2; } ;;
*) cp "$lib" "$d/l.lib" || exit 2 ;;
esac
nand=$(awk '/cell *\( *"?NAND2_X1"? *\)/ { c = 1 } c && /area/ { gsub(/[^0-9.]/, "", $3); print $3; exit }' "$d/l.lib")
[ -n "$nand" ] || { echo "$me: $lib has no NAND2_X1" >&2; exit 2; }

# map_area KIND N: prints the mapped area (Liberty units) of $d/m.v, or
# exits 2 naming KIND and N when Yosys fails.
map_area() {
    area=$(cd "$d" && yosys -q -p "read_verilog m.v; synth -top m; abc -liberty l.lib${abc_script:+ -script $abc_script}; opt_clean; tee -q -o s.txt stat -liberty l.lib" >/dev/null 2>&1 &&
        sed -n 's/.*Chip area for module.*: *\([0-9.]*\).*/\1/p' "$d/s.txt")
    [ -n "$area" ] || { echo "$me: yosys failed on $1 $2" >&2; exit 2; }
    echo "$area"
}
