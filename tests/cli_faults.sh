#!/bin/sh
# cli_faults.sh - the cell tests caught planting faults: each patch in
# tests/faults/ (its first line says what it breaks) is applied to a copy
# of the sources, the copy is built, and test_cells and test_elem run
# there. test_cells must fail on every fault (test_elem may too); the copy
# without a fault must pass both, so a failure is the fault's.
#
# The faults are the kinds a fast path gets wrong while every unit's
# outputs still look plausible: an off-by-one in the vector multiplier,
# a wrong select range, a rounding mode swapped in one engine, an
# interval rounded inward. Each patch touches one .c file, so the copy
# (taking the plain build's objects with it) recompiles that file and
# relinks: about a minute of CPU in all. In tests/long.list (make
# test-long); `make faults` runs it alone.
. tests/lib_cli.sh
PREFIX=cli_faults.
b=${TST_BUILD:-build}
case $b in
*-asan|*-portable) echo "skip cli_faults: the plain build plants them"; exit 0 ;;
esac
if ! command -v patch >/dev/null 2>&1; then echo "skip cli_faults: patch not installed"; exit 0; fi

src=$T/src
mkdir "$src" || exit 1
# the sources as they are now, committed or not; the build's objects
# keep their times, so that make compiles again only what a patch touches
tar --exclude=./.git --exclude=./out --exclude='./build*' --exclude=./bin -cf - . | tar -xf - -C "$src" || exit 1
if [ -d "$b" ]; then cp -a "$b" "$src/build" || exit 1; fi

# Build the copy and run both tests: the names of those that fail, one
# a line, in $T/failed; "build" when the copy does not build.
run_cells() {
    : >"$T/failed"
    if ! (cd "$src" && make -s -j2 B=build build/tests/test_cells build/tests/test_elem) >"$T/make.log" 2>&1; then
        echo build >"$T/failed"
        return
    fi
    for t in test_cells test_elem; do
        (cd "$src" && "build/tests/$t") >"$T/$t.out" 2>&1 || echo "$t" >>"$T/failed"
    done
}

# Where the CPU has AVX2 (the batch's vector loops need BMI2 with it),
# test_cells runs the AVX2 loops; elsewhere the vector fault cannot run.
has_avx2() { grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw bmi2 /proc/cpuinfo 2>/dev/null; }

run_cells
if [ -s "$T/failed" ]; then
    fail control "the copy without a fault fails: $(tr '\n' ' ' <"$T/failed")$(grep -h '^FAIL' "$T"/test_*.out 2>/dev/null | head -3)"
    exit 0
fi
ok control

for p in tests/faults/*.patch; do
    name=$(basename "$p" .patch)
    what=$(head -1 "$p" | sed 's/^# *//')
    if [ "$name" = vec_mul_off_by_one ] && ! has_avx2; then
        echo "skip ${PREFIX}$name: no AVX2 on this CPU"
        continue
    fi
    if ! patch -s -p1 -d "$src" <"$p" >"$T/patch.log" 2>&1; then
        fail "$name" "the patch no longer applies: $(head -3 "$T/patch.log" | tr '\n' ' ')"
        continue
    fi
    run_cells
    if grep -qx test_cells "$T/failed"; then
        ok "$name"
        echo "  fault: $what"
        echo "  failed: $(tr '\n' ' ' <"$T/failed")"
        for t in $(cat "$T/failed"); do
            grep -h '^FAIL\|^  ' "$T/$t.out" | grep -v '^  [0-9]* input combinations' | head -2 | cut -c1-230 | sed "s/^/  $t: /"
        done
    elif grep -qx build "$T/failed"; then
        fail "$name" "the copy with the fault does not build: $(tail -3 "$T/make.log" | tr '\n' ' ')"
    else
        fail "$name" "test_cells passes with the fault in ($what)"
    fi
    patch -s -R -p1 -d "$src" <"$p" >/dev/null 2>&1 || { fail "$name" "cannot take the patch out"; exit 0; }
done
