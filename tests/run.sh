#!/bin/sh
# Runs every test binary of each build flavour given (build dirs), plus the
# command-line tests tests/cli_*.sh against that flavour's shadesim, and
# prints the closing line "N passed, N failed[, N skipped]".
# Each test prints one line: "ok NAME", "FAIL NAME" or "skip NAME: why";
# a test program that crashes or exits non-zero without a FAIL line counts
# as one failure of its own.
cd "$(dirname "$0")/.." || exit 2
log=$(mktemp); out=$(mktemp)
trap 'rm -f "$log" "$out"' EXIT
one() {   # one NAME CMD...
    name=$1; shift
    echo "== $name"
    "$@" >"$out" 2>&1
    rc=$?
    sed 's|^|  |' "$out"
    cat "$out" >>"$log"
    if [ $rc -ne 0 ] && ! grep -q '^FAIL ' "$out"; then
        echo "FAIL $name: exit status $rc" | tee -a "$log"
    fi
}
for b in "$@"; do
    export SHADESIM="$b/shadesim" TST_BUILD="$b"
    for t in "$b"/tests/test_*; do
        [ -x "$t" ] && one "$t" "$t"
    done
    for t in tests/cli_*.sh; do
        [ -f "$t" ] && one "$t [$b]" sh "$t"
    done
done
pass=$(grep -c '^ok ' "$log")
fail=$(grep -c '^FAIL ' "$log")
skip=$(grep -c '^skip ' "$log")
if [ "$fail" -gt 0 ]; then echo "failed tests:"; grep '^FAIL ' "$log" | sed 's/^/  /'; fi
if [ "$skip" -gt 0 ]; then
    echo "$pass passed, $fail failed, $skip skipped"
else
    echo "$pass passed, $fail failed"
fi
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ]
