# shadesim build. One library of every layer (sim/ units/ vectors/ scene/ testbench/)
# linked into bin/shadesim, each tests/test_*.c and each bench/*.c.
# `make test` runs the suite twice: plain (-O2) and under ASan+UBSan;
# `make test-clang` runs the same two flavours built by clang (build-clang*).

CC      ?= cc
CSTD    := -std=c11 -D_POSIX_C_SOURCE=200809L
WARN    := -Wall -Wextra -Wmissing-prototypes
OPT     ?= -O2
CFLAGS  ?=
ALLCFLAGS = $(CSTD) $(WARN) $(OPT) -I. $(CFLAGS)
LDLIBS  := -lm -lpthread

LAYERS  := sim units vectors scene testbench
LIBSRC  := $(filter-out testbench/main.c,$(foreach d,$(LAYERS),$(wildcard $(d)/*.c)))
HDRS    := $(foreach d,$(LAYERS),$(wildcard $(d)/*.h)) $(wildcard tests/*.h)
TESTSRC := $(wildcard tests/test_*.c)
BENCHSRC:= $(wildcard bench/*.c)

B ?= build
LIBOBJ  := $(patsubst %.c,$(B)/%.o,$(LIBSRC))
TESTBIN := $(patsubst tests/%.c,$(B)/tests/%,$(TESTSRC))
BENCHBIN:= $(patsubst bench/%.c,$(B)/bench/%,$(BENCHSRC))

.PHONY: all test bench run clean vectors docs
all: bin/shadesim

# Copy then rename: a running bin/shadesim is replaced, not overwritten.
bin/shadesim: $(B)/shadesim
	@mkdir -p bin
	cp $< $@.tmp && mv -f $@.tmp $@

$(B)/shadesim: $(B)/testbench/main.o $(B)/libshadesim.a
	$(CC) $(ALLCFLAGS) -o $@ $^ $(LDLIBS)

$(B)/libshadesim.a: $(LIBOBJ)
	@rm -f $@
	ar rcs $@ $^

# The compiler and flags a build folder was made with: a change (make test
# CC=clang after a gcc build, other CFLAGS) rebuilds it instead of linking
# the other compiler's objects.
FLAGSTAMP := $(B)/.flags
.PHONY: FORCE
$(FLAGSTAMP): FORCE
	@mkdir -p $(B)
	@echo '$(CC) $(ALLCFLAGS)' | cmp -s - $@ || echo '$(CC) $(ALLCFLAGS)' > $@

$(B)/%.o: %.c $(HDRS) Makefile $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALLCFLAGS) -c -o $@ $<

$(B)/tests/%: tests/%.c $(B)/libshadesim.a $(HDRS) $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALLCFLAGS) -o $@ $< $(B)/libshadesim.a $(LDLIBS)

$(B)/bench/%: bench/%.c $(B)/libshadesim.a $(HDRS) $(FLAGSTAMP)
	@mkdir -p $(dir $@)
	$(CC) $(ALLCFLAGS) -o $@ $< $(B)/libshadesim.a $(LDLIBS)

# Build-only target used by the test script for each flavour.
.PHONY: testbins
testbins: $(TESTBIN) $(B)/shadesim

# The suite, plain (-O2) and under ASan+UBSan, in one run so that the
# closing "N passed, N failed" line is the total. make test CC=clang builds
# with clang (its own build folders: objects of one compiler are never
# reused by the other); make test-clang does that with clang's name.
# CLANG=clang-18 picks a version.
CLANG ?= clang
ASAN_FLAGS = OPT="-O1 -g -fno-omit-frame-pointer" \
	    CFLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
TB := $(if $(filter clang%,$(notdir $(CC))),build-clang,build)

test:
	@$(MAKE) -s testbins B=$(TB) >/dev/null
	@$(MAKE) -s testbins B=$(TB)-asan $(ASAN_FLAGS) >/dev/null
	@$(MAKE) -s bin/shadesim >/dev/null
	@sh tests/run.sh $(TB) $(TB)-asan

.PHONY: test-clang
test-clang:
	@$(MAKE) -s testbins B=build-clang CC=$(CLANG) >/dev/null
	@$(MAKE) -s testbins B=build-clang-asan CC=$(CLANG) $(ASAN_FLAGS) >/dev/null
	@sh tests/run.sh build-clang build-clang-asan

bench: $(BENCHBIN) bin/shadesim
	@for b in $(BENCHBIN); do $$b || exit 1; done

# Every unit on its default vectors, then the default face scene through
# the hardware: the paper's configuration next to corrected ones (a table;
# images in out/scene-face/*/).
run: bin/shadesim
	@./bin/shadesim run all
	@echo
	@./bin/shadesim scene face --compare -j 2

# Regenerate the checked-in default vectors of every unit (tests compare
# them byte for byte with what the float reference gives).
vectors: bin/shadesim
	@for u in $$(./bin/shadesim list | sed -n 's/^\([a-z0-9_]*\) — .*/\1/p'); do \
	    ./bin/shadesim vectors $$u -o vectors/$$u.vec || exit 1; echo "vectors/$$u.vec"; done

# Regenerate docs made from the unit descriptors.
docs: bin/shadesim
	./bin/shadesim list --markdown > docs/units.md.tmp && mv docs/units.md.tmp docs/units.md

clean:
	rm -rf build build-asan build-clang build-clang-asan bin
