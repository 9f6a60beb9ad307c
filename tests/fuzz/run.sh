#!/bin/sh
# tests/fuzz/run.sh - `make fuzz`: build the libFuzzer targets with clang
# (-fsanitize=fuzzer,address) into build-fuzz/ and run each a fixed number
# of inputs (FUZZ_RUNS, default 5000) from its seed corpus under
# tests/fuzz/corpus/. New inputs libFuzzer finds go to a scratch folder,
# never into the tree. Skips (exit 0, a "skip" line) when clang or its
# libFuzzer runtime is missing. Not part of `make test`.
#   FUZZ_RUNS=-1 sh tests/fuzz/run.sh vec    # one target until stopped
B=${B:-build-fuzz}
RUNS=${FUZZ_RUNS:-5000}
CLANG=${CLANG:-clang}
TARGETS=${*:-vec fmt scene obj}
MAKE=${MAKE:-make}

if ! command -v "$CLANG" >/dev/null 2>&1; then echo "skip fuzz: clang not installed"; exit 0; fi
probe=$(mktemp -d /tmp/shadesim_fuzzprobe.XXXXXX) || exit 2
printf 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n);\nint LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }\n' >"$probe/p.c"
if ! "$CLANG" -fsanitize=fuzzer,address "$probe/p.c" -o "$probe/p" >/dev/null 2>&1; then
    rm -rf "$probe"; echo "skip fuzz: $CLANG has no libFuzzer (-fsanitize=fuzzer)"; exit 0
fi
rm -rf "$probe"

# The library, instrumented for coverage and ASan (not linked with the
# fuzzer's main: the targets bring that).
FLAGS="-g -fsanitize=fuzzer-no-link,address -fno-omit-frame-pointer"
$MAKE -s B="$B" CC="$CLANG" OPT=-O1 CFLAGS="$FLAGS" "$B/libshadesim.a" || exit 2
mkdir -p "$B/fuzz"
rc=0
for t in $TARGETS; do
    src=tests/fuzz/fuzz_$t.c
    [ -f "$src" ] || { echo "fuzz: no target '$t' (vec fmt scene obj)" >&2; exit 2; }
    "$CLANG" -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wmissing-prototypes -I. -O1 -g \
        -fsanitize=fuzzer,address -o "$B/fuzz/fuzz_$t" "$src" "$B/libshadesim.a" -lm -lpthread || exit 2
    scratch=$(mktemp -d /tmp/shadesim_fuzz_$t.XXXXXX) || exit 2
    if "$B/fuzz/fuzz_$t" -runs="$RUNS" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
           -artifact_prefix="$B/fuzz/crash-$t-" "$scratch" "tests/fuzz/corpus/$t" >"$B/fuzz/$t.log" 2>&1; then
        echo "ok fuzz_$t: $(tail -1 "$B/fuzz/$t.log")"
    else
        echo "FAIL fuzz_$t: see $B/fuzz/$t.log (the input: $B/fuzz/crash-$t-*)"
        rc=1
    fi
    rm -rf "$scratch"
done
exit $rc
