# shadesim build. One library of every layer linked into bin/shadesim, each
# tests/test_*.c and each bench/*.c. The layers, bottom up (an arrow only
# points down; tests/cli_layers.sh checks the #include lines):
#   sim/ (kernel, fixed point, primitives) and beside it base/ (output
#   files, JSON numbers, parallel-for, name lists) at the bottom;
#   chart/ (SVG charts) and vectors/ (float reference) on base/;
#   units/ on sim/ and vectors/; scene/ on vectors/ (and sim/'s rounding
#   names); testbench/ (the testbench engine: run, stream, batch, PPA,
#   Verilog) on top of them all, testbench/study/ (sweeps, scenes through
#   the hardware, stability, the papers' claims) on the engine, and
#   testbench/cli/ (main.c and one file per verb) on top.
# `make test` runs the suite twice: plain (-O2) and under ASan+UBSan;
# `make test-clang` runs the same two flavours built by clang (build-clang*).

CC      ?= cc
CSTD    := -std=c11 -D_POSIX_C_SOURCE=200809L
WARN    := -Wall -Wextra -Wmissing-prototypes
OPT     ?= -O2
CFLAGS  ?=
LDFLAGS ?=
# COPTS: flags for compiling only (a link of objects alone would call them
# unused: clang warns)
LINKCFLAGS = $(CSTD) $(WARN) $(OPT) -I. $(CFLAGS)
ALLCFLAGS = $(LINKCFLAGS) $(COPTS)
LDLIBS  := -lm -lpthread

LAYERS  := base sim chart units vectors scene testbench testbench/study testbench/cli
LIBSRC  := $(filter-out testbench/cli/main.c,$(foreach d,$(LAYERS),$(wildcard $(d)/*.c)))
HDRS    := $(foreach d,$(LAYERS),$(wildcard $(d)/*.h)) $(wildcard tests/*.h) $(wildcard bench/*.h)
TESTSRC := $(wildcard tests/test_*.c)
BENCHSRC:= $(wildcard bench/*.c)

B ?= build
LIBOBJ  := $(patsubst %.c,$(B)/%.o,$(LIBSRC))
TESTBIN := $(patsubst tests/%.c,$(B)/tests/%,$(TESTSRC))
BENCHBIN:= $(patsubst bench/%.c,$(B)/bench/%,$(BENCHSRC))

.PHONY: all test bench run clean vectors docs install uninstall fuzz gold
all: bin/shadesim

# Quiet builds: one short line per step; V=1 shows the full commands.
ifeq ($(V),1)
Q :=
say = @true
else ifeq ($(BRIEF),1)
Q := @
say = @true
else
Q := @
say = @printf '  %-5s %s\n'
endif

# Copy then rename: a running bin/shadesim is replaced, not overwritten.
bin/shadesim: $(B)/shadesim
	@mkdir -p bin
	$(Q)cp $< $@.tmp && mv -f $@.tmp $@

$(B)/shadesim: $(B)/testbench/cli/main.o $(B)/libshadesim.a
	$(say) LD $@
	$(Q)$(CC) $(LINKCFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(B)/libshadesim.a: $(LIBOBJ)
	@rm -f $@
	$(Q)ar rcs $@ $^

# The version --version prints: VERSION, and where git is there the commit
# (git describe); the same tree gives the same string, and without git
# just VERSION. Rewritten only when it changes, so nothing rebuilds for it.
VERSION_STR = $(shell v=$$(cat VERSION 2>/dev/null || echo unknown); \
	g=$$(git describe --always --dirty 2>/dev/null); \
	if [ -n "$$g" ]; then echo "$$v (git $$g)"; else echo "$$v"; fi)
$(B)/version.h: FORCE
	@mkdir -p $(B)
	@echo '#define SHADESIM_VERSION "$(VERSION_STR)"' | cmp -s - $@ \
	    || echo '#define SHADESIM_VERSION "$(VERSION_STR)"' > $@

$(B)/testbench/cli/main.o: testbench/cli/main.c $(B)/version.h $(HDRS) Makefile $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(say) CC $<
	$(Q)$(CC) $(ALLCFLAGS) -I$(B) -c -o $@ $<

# The compiler and flags a build folder was made with: a change (make test
# CC=clang after a gcc build, other CFLAGS) rebuilds it instead of linking
# the other compiler's objects.
FLAGSTAMP := $(B)/.flags
.PHONY: FORCE
$(FLAGSTAMP): FORCE
	@mkdir -p $(B)
	@echo '$(CC) $(ALLCFLAGS)$(if $(LDFLAGS), $(LDFLAGS))' | cmp -s - $@ || echo '$(CC) $(ALLCFLAGS)$(if $(LDFLAGS), $(LDFLAGS))' > $@

$(B)/%.o: %.c $(HDRS) Makefile $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(say) CC $<
	$(Q)$(CC) $(ALLCFLAGS) -c -o $@ $<

$(B)/tests/%: tests/%.c $(B)/libshadesim.a $(HDRS) $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(say) CC $<
	$(Q)$(CC) $(ALLCFLAGS) $(LDFLAGS) -o $@ $< $(B)/libshadesim.a $(LDLIBS)

$(B)/bench/%: bench/%.c $(B)/libshadesim.a $(HDRS) $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(say) CC $<
	$(Q)$(CC) $(ALLCFLAGS) $(LDFLAGS) -o $@ $< $(B)/libshadesim.a $(LDLIBS)

# Build-only target used by the test script for each flavour.
.PHONY: testbins
testbins: $(TESTBIN) $(B)/shadesim

# The suite, plain (-O2) and under ASan+UBSan, in one run so that the
# closing "N passed, N failed" line is the total. The sanitizer build runs
# every C test and every script; a script leaves to the plain build what
# the sanitizers add nothing to there (tool runs over bytes no build
# changes, a verb repeated over every unit where one run or a C test in
# process covers its code) and says so in a skip line (tests/lib_cli.sh's
# ASAN): a sanitized process costs 30 ms of CPU to start, a plain one 6. make test CC=clang builds
# with clang (its own build folders: objects of one compiler are never
# reused by the other); make test-clang does that with clang's name.
# CLANG=clang-18 picks a version.
CLANG ?= clang
# (-g1: line tables, enough for the sanitizers' reports, a seventh less
# compile time than -g; -no-pie: the sanitized binary's 160 000 load-time
# relocations of a position-independent executable are gone, a third less
# CPU at each of the suite's thousand-odd process starts; the sanitizer
# runtimes linked in, as clang does by default, not loaded as gcc's shared
# libasan (a compiler whose --version names clang links them so already):
# their dynamic symbol binding at each start is gone, another 30 ms of the
# 90 ms a sanitized shadesim --help takes; no redzones around globals
# (--param asan-globals=0): each string literal padded with its redzone made
# 4.7 MB of .data that every process registered at start and the leak check
# scanned at exit, a quarter of cli_conform's CPU; an index past a global
# array is still caught by UBSan's bounds check, a pointer walked past one
# by neither, which README says)
ASAN_FLAGS = $(call asan_flags,$(CC))
asan_flags = OPT="-O1 -g1 -fno-omit-frame-pointer" \
	    LDFLAGS="-no-pie$(if $(call is_clang,$(1)),, -static-libasan -static-libubsan)" \
	    CFLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -DSIM_DEBUG" \
	    COPTS="$(if $(call is_clang,$(1)),-mllvm -asan-globals=0,--param asan-globals=0)"
is_clang = $(findstring clang,$(shell $(1) --version 2>/dev/null))
TB := $(if $(filter clang%,$(notdir $(CC))),build-clang,build)
# The portable flavour (as on a CPU other than x86-64, and a compiler without
# computed goto): the batch without its vector loops and the kernel's delta
# loop compiled as a switch; the batch's and the kernel's tests (test_batch,
# test_toggle, test_kernel, test_elem and test_cells: every element kind), plain, and
# tests/cli_engine.sh and tests/cli_gold.sh on its shadesim.
PORTABLE_CFLAGS = -DSIM_BATCH_X86=0 -DSIM_KERNEL_SWITCH=1
PORTABLE_BINS = $(TB)-portable/tests/test_batch $(TB)-portable/tests/test_toggle \
	$(TB)-portable/tests/test_kernel $(TB)-portable/tests/test_elem $(TB)-portable/tests/test_cells \
	$(TB)-portable/shadesim

# The portable flags reach sim/'s files alone (no header outside sim/
# reads them), so the other layers' objects are the plain build's: copied
# (cp -u, after the folder's flag stamp is written, so that make takes the
# copies as up to date) instead of compiled a third time.
PORTABLE_SHARE = cd $(TB) && find . -name '*.o' ! -path './sim/*' ! -path './tests/*' | \
	while read -r o; do mkdir -p "../$(TB)-portable/$${o%/*}" && cp -u "$$o" "../$(TB)-portable/$$o" || exit 1; done

# Sub-makes build quietly (BRIEF=1: no per-file lines) under one line per
# step; V=1 shows every command.
SUBMAKE = $(MAKE) --no-print-directory $(if $(filter 1,$(V)),,-s BRIEF=1)
# The test builds use both cores (-j2) unless make was given its own -j.
TESTJ = $(if $(filter -j%,$(MAKEFLAGS)),,-j2)

test:
	@echo "building $(TB)/ ($(CC) $(OPT))..."
	@$(SUBMAKE) $(TESTJ) testbins B=$(TB)
	@echo "building $(TB)-asan/ ($(CC) ASan+UBSan)..."
	@$(SUBMAKE) $(TESTJ) testbins B=$(TB)-asan $(ASAN_FLAGS)
	@echo "building $(TB)-portable/ ($(CC), $(PORTABLE_CFLAGS): no vector loops, switch dispatch)..."
	@$(SUBMAKE) $(TB)-portable/.flags B=$(TB)-portable CFLAGS="$(PORTABLE_CFLAGS)"
	@$(PORTABLE_SHARE)
	@$(SUBMAKE) $(TESTJ) $(PORTABLE_BINS) B=$(TB)-portable CFLAGS="$(PORTABLE_CFLAGS)"
	@$(SUBMAKE) bin/shadesim
	@echo "testing..."
	@sh tests/run.sh $(TB) $(TB)-asan $(TB)-portable

# The edit loop's suite: the plain build only, without the slow tests
# tests/slow.list names (tool-driven, scene renders, every doc command);
# under a minute on 2 cores. make test runs everything, both flavours.
.PHONY: test-quick
test-quick:
	@echo "building $(TB)/ ($(CC) $(OPT))..."
	@$(SUBMAKE) $(TESTJ) testbins B=$(TB)
	@$(SUBMAKE) bin/shadesim
	@echo "testing (quick: $(TB)/ only, tests/slow.list left out)..."
	@TST_QUICK=1 sh tests/run.sh $(TB)

# The delay and area models against Yosys and OpenSTA on every unit at
# widths 8, 16 and 24 (tests/cli_sta.sh with STA_DESIGNS=all; make test
# runs it on five designs). Needs yosys, sta (opensta) and the NanGate45
# Liberty in shared/liberty/ beside the checkout, or STA_LIBERTY=FILE; STA_TABLE=FILE also
# writes the table docs/timing.md shows. About 3 min of CPU, two at a time.
# The long tool-driven tests (tests/long.list): OpenSTA on every unit at
# widths 8, 16 and 24, nextpnr-ice40, the exhaustive cell table; the plain
# build, its own "N passed, N failed" line. .ci/run runs it before make test.
.PHONY: test-long
test-long:
	@echo "building $(TB)/ ($(CC) $(OPT))..."
	@$(SUBMAKE) $(TESTJ) testbins B=$(TB)
	@$(SUBMAKE) bin/shadesim
	@echo "testing (long: $(TB)/ only, tests/long.list)..."
	@STA_DESIGNS=all TST_LONG=1 sh tests/run.sh $(TB)

# The planted faults (tests/faults/*.patch: an off-by-one in the vector
# multiplier, a wrong select range, a rounding mode swapped in one engine,
# an interval rounded inward), each applied to a copy of the sources and
# shown failing test_cells (tests/cli_faults.sh; also in tests/long.list).
.PHONY: faults
faults:
	@$(SUBMAKE) $(B)/tests/test_cells $(B)/tests/test_elem
	@TST_BUILD=$(B) sh tests/cli_faults.sh

.PHONY: test-clang
test-clang:
	@echo "building build-clang/ ($(CLANG) $(OPT))..."
	@$(SUBMAKE) $(TESTJ) testbins B=build-clang CC=$(CLANG)
	@echo "building build-clang-asan/ ($(CLANG) ASan+UBSan)..."
	@$(SUBMAKE) $(TESTJ) testbins B=build-clang-asan CC=$(CLANG) $(call asan_flags,$(CLANG))
	@echo "testing..."
	@sh tests/run.sh build-clang build-clang-asan

# The datapath reader (docs/datapaths.md) on mutants of examples/*.dp
# under ASan+UBSan for DP_FUZZ_SECONDS (default 300); make test runs 400.
.PHONY: fuzz-datapath
fuzz-datapath:
	@$(SUBMAKE) $(TESTJ) $(TB)-asan/tests/test_dp_fuzz B=$(TB)-asan $(ASAN_FLAGS)
	@DP_FUZZ_SECONDS=$${DP_FUZZ_SECONDS:-300} $(TB)-asan/tests/test_dp_fuzz

# libFuzzer targets (vector, format, scene and OBJ readers) built by clang
# into build-fuzz/ and run FUZZ_RUNS inputs each; skipped without libFuzzer.
fuzz:
	@sh tests/fuzz/run.sh

# bench_batch runs again with AVX2 alone (--vector 4): the machines this
# runs on may lack AVX-512 (on one without, the two tables are the same).
bench: $(BENCHBIN) bin/shadesim
	@for b in $(BENCHBIN); do $$b || exit 1; done
	@echo "bench_batch --vector 4 (AVX2 alone):"
	@$(B)/bench/bench_batch --vector 4

# Every unit on its default vectors, then the default face scene through
# the hardware: the paper's configuration next to corrected ones (a table;
# images in out/scene-face/*/).
run:
	@echo "building bin/shadesim ($(CC) $(OPT))..."
	@$(SUBMAKE) bin/shadesim
	@./bin/shadesim run all
	@echo
	@./bin/shadesim scene face --compare -j 2

# Regenerate the checked-in default vectors of every unit (tests compare
# them byte for byte with what the float reference gives).
vectors: bin/shadesim
	@for u in $$(./bin/shadesim list | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p'); do \
	    ./bin/shadesim vectors $$u -o vectors/$$u.vec || exit 1; echo "vectors/$$u.vec"; done

# Regenerate tests/gold/counters.txt: the kernel's counters (events, delta
# cycles, process runs, clocks, overflows) for every unit and schedule,
# from its reference (--reference: no fast path); tests/cli_gold.sh holds
# the fast kernel to them.
gold: bin/shadesim
	@sh tests/gold/make_gold.sh ./bin/shadesim --reference >tests/gold/counters.txt.tmp \
	    && mv -f tests/gold/counters.txt.tmp tests/gold/counters.txt && echo tests/gold/counters.txt \
	    || { rm -f tests/gold/counters.txt.tmp; exit 1; }

# Regenerate docs made from the unit descriptors.
docs: bin/shadesim
	./bin/shadesim list --markdown > docs/units.md.tmp && mv docs/units.md.tmp docs/units.md

# Install: the binary, its data (the default vectors, which the installed
# binary finds in ../share/shadesim from its own folder), the manual page
# that shadesim --man makes from its verb table and each verb's --help, and
# the documentation. DESTDIR stages a package. INSTALL_BIN=FILE installs
# that binary instead of building bin/shadesim (tests/cli_install.sh).
PREFIX ?= /usr/local
DESTDIR ?=
DEST = $(DESTDIR)$(PREFIX)
INSTALL_BIN ?=
IBIN = $(or $(INSTALL_BIN),bin/shadesim)
install:
	@if [ -z "$(INSTALL_BIN)" ]; then echo "building bin/shadesim ($(CC) $(OPT))..."; \
	    $(SUBMAKE) bin/shadesim || exit 1; fi
	@echo "installing into $(DEST)..."
	$(Q)install -d "$(DEST)/bin" "$(DEST)/share/shadesim/vectors" "$(DEST)/share/man/man1" "$(DEST)/share/doc/shadesim"
	$(Q)install -m 755 $(IBIN) "$(DEST)/bin/shadesim.tmp" && mv -f "$(DEST)/bin/shadesim.tmp" "$(DEST)/bin/shadesim"
	$(Q)install -m 644 vectors/*.vec "$(DEST)/share/shadesim/vectors/"
	$(Q)$(IBIN) --man > "$(DEST)/share/man/man1/shadesim.1.tmp" \
	    && mv -f "$(DEST)/share/man/man1/shadesim.1.tmp" "$(DEST)/share/man/man1/shadesim.1"
	$(Q)install -m 644 README.md LICENSE docs/*.md "$(DEST)/share/doc/shadesim/"
	$(Q)install -d "$(DEST)/share/doc/shadesim/examples"
	$(Q)install -m 644 examples/*.dp "$(DEST)/share/doc/shadesim/examples/"

# Uninstall removes what install put there, then the folders install may
# have made, each only if nothing else is left in it (rmdir refuses).
uninstall:
	rm -f "$(DEST)/bin/shadesim" "$(DEST)/share/man/man1/shadesim.1"
	rm -rf "$(DEST)/share/shadesim" "$(DEST)/share/doc/shadesim"
	-@for d in "$(DEST)/bin" "$(DEST)/share/man/man1" "$(DEST)/share/man" "$(DEST)/share/doc" "$(DEST)/share" "$(DEST)"; do \
	    rmdir "$$d" 2>/dev/null || true; done

clean:
	rm -rf build build-asan build-portable build-clang build-clang-asan build-clang-portable bin
