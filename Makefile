# pgsim — one non-recursive Makefile.
#   make          build build/pgsim (no package installs)
#   make run      install missing Debian packages, build, run the quickstart
#   make test     install missing packages, build, check include layers,
#                 run every cmocka suite
#   make check    the tests under ASan + UBSan (-fno-sanitize-recover=all)
#   make fuzz SECONDS=N  each libFuzzer harness for N s (needs clang)
#   make bench    benchmarks that print figures (never part of make test)
#   make golden   rewrite the scenario tests' golden results (review the diff)
#   make coverage gcov line/branch summary per folder, unexecuted functions
#   make mutate N=200 SEED=1   sampled mutation testing (scripts/mutate)
#   make install PREFIX=/usr/local ; make format ; make clean

PREFIX  ?= /usr/local
BUILD   ?= build
CC      ?= cc
PKGS    := glib-2.0 gio-2.0 json-glib-1.0 yaml-0.1 libpng
HAVE_MPI := $(shell pkg-config --exists ompi-c 2>/dev/null && echo 1)
ifeq ($(HAVE_MPI),1)
PKGS    += ompi-c
MPIDEF  := -DPGSIM_HAVE_MPI=1
endif
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null)
OPT     ?= -O2 -g
CFLAGS  += -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $(OPT) \
           -Wall -Wextra -MMD -MP -I. \
           $(PKG_CFLAGS) $(MPIDEF) $(EXTRA_CFLAGS)
LDLIBS  += $(PKG_LIBS) -lm $(EXTRA_LDFLAGS)

MAIN    := sim/app/cli/main.c
LIBSRC  := $(filter-out $(MAIN),$(shell find sim -name '*.c' | LC_ALL=C sort))
LIBOBJ  := $(LIBSRC:%.c=$(BUILD)/obj/%.o)
TESTSRC := $(shell find tests -name 'test_*.c' | LC_ALL=C sort)
TESTBIN := $(TESTSRC:tests/%.c=$(BUILD)/tests/%)
TESTLIB := $(shell find tests -name '*.c' ! -name 'test_*.c' \
                ! -path 'tests/fuzz/*' | LC_ALL=C sort)
TESTLOBJ := $(TESTLIB:%.c=$(BUILD)/obj/%.o)
# libFuzzer harnesses (tests/fuzz/fuzz_<name>.c).  make test runs each as
# replay_<name>, a gcc build that replays its corpus and past crashes.
FUZZERS := cfg model obj ply render trace structdb plotcsv simgrid map
FUZZBIN := $(FUZZERS:%=$(BUILD)/tests/fuzz/replay_%)
SECONDS ?= 60
SANITIZE := address,undefined,float-cast-overflow,pointer-overflow

.PHONY: all deps run test check bench install format clean golden coverage \
        mutate fuzz
all: $(BUILD)/pgsim

deps:
	@sh scripts/deps.sh

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@

# The build's version in every result (git describe at build time): the
# stamp file changes only when the version does, so provenance.o rebuilds
# then.
GIT_DESCRIBE := $(shell git describe --always --dirty 2>/dev/null || echo unknown)
VERSION_STAMP := $(BUILD)/version.stamp
$(shell mkdir -p $(BUILD); echo '$(GIT_DESCRIBE)' | cmp -s - $(VERSION_STAMP) || echo '$(GIT_DESCRIBE)' > $(VERSION_STAMP))
$(BUILD)/obj/sim/output/provenance.o: $(VERSION_STAMP)
$(BUILD)/obj/sim/output/provenance.o: CFLAGS += -DPGSIM_GIT_VERSION='"$(GIT_DESCRIBE)"'

$(BUILD)/libpgsim.a: $(LIBOBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/pgsim: $(BUILD)/obj/$(MAIN:.c=.o) $(BUILD)/libpgsim.a
	$(CC) $(CFLAGS) $^ -o $@ $(LDFLAGS) $(LDLIBS)

$(BUILD)/tests/%: $(BUILD)/obj/tests/%.o $(TESTLOBJ) $(BUILD)/libpgsim.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $^ -o $@ $(LDFLAGS) $(LDLIBS) -lcmocka

run: deps
	@$(MAKE) -s all
	./$(BUILD)/pgsim run configs/quickstart.yaml --out out/quickstart
	@echo
	@echo "Next:  $(BUILD)/pgsim help run                       # workloads and what they need"
	@echo "       $(BUILD)/pgsim run configs/quickstart.yaml --trace run.json   # open in ui.perfetto.dev"
	@echo "       $(BUILD)/pgsim reproduce kurc96               # the paper's tables against the simulator"
	@echo "       $(BUILD)/pgsim sweep configs/sweep-pixelmerge.yaml   # a sweep, with charts"

$(BUILD)/tests/fuzz/replay_%: $(BUILD)/obj/tests/fuzz/fuzz_%.o \
                             $(BUILD)/obj/tests/fuzz/replay.o $(BUILD)/libpgsim.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $^ -o $@ $(LDFLAGS) $(LDLIBS)

# The clang/libFuzzer build of a harness (make fuzz only).
$(BUILD)/fuzz/fuzz_%: $(BUILD)/obj/tests/fuzz/fuzz_%.o $(BUILD)/libpgsim.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fsanitize=fuzzer $^ -o $@ $(LDFLAGS) $(LDLIBS)

test: deps
	@$(MAKE) -s all $(TESTBIN) $(FUZZBIN)
	@sh scripts/check-layers.sh
	@sh scripts/run-tests.sh $(BUILD) $(TESTBIN) $(FUZZBIN)

check: deps
	@$(MAKE) -s BUILD=build-san OPT="-O1 -g -fno-omit-frame-pointer" \
	  EXTRA_CFLAGS="-fsanitize=$(SANITIZE) -fno-sanitize-recover=all" \
	  EXTRA_LDFLAGS="-fsanitize=$(SANITIZE)" \
	  build-san/pgsim $(TESTBIN:$(BUILD)/%=build-san/%) \
	  $(FUZZBIN:$(BUILD)/%=build-san/%)
	@G_SLICE=always-malloc PGSIM_SANITIZE=1 sh scripts/run-tests.sh build-san \
	  $(TESTBIN:$(BUILD)/%=build-san/%) $(FUZZBIN:$(BUILD)/%=build-san/%)

# libFuzzer (Debian clang): every harness for SECONDS seconds, one after
# another; new inputs go to build-fuzz/corpus/<name>, crashes to
# tests/fuzz/crashes/<name>/ (commit them: make test replays them).
fuzz:
	@sh scripts/deps.sh fuzz
	@$(MAKE) -s BUILD=build-fuzz CC=clang OPT="-O1 -g -fno-omit-frame-pointer" \
	  EXTRA_CFLAGS="-fsanitize=fuzzer-no-link,address,undefined" \
	  EXTRA_LDFLAGS="-fsanitize=address,undefined" \
	  $(FUZZERS:%=build-fuzz/fuzz/fuzz_%)
	@sh scripts/fuzz.sh build-fuzz $(SECONDS) $(FUZZERS)

# Rewrites tests/data/golden/*.json after a deliberate model change.
golden: all $(BUILD)/tests/app/run/test_scenarios
	PGSIM_UPDATE_GOLDEN=1 ./$(BUILD)/tests/app/run/test_scenarios

# Never part of make test: each takes minutes.
coverage: deps
	@$(MAKE) -s BUILD=build-cov OPT="-O0 -g" EXTRA_CFLAGS=--coverage \
	  EXTRA_LDFLAGS=--coverage build-cov/pgsim \
	  $(TESTBIN:$(BUILD)/%=build-cov/%)
	@sh scripts/coverage.sh build-cov

N    ?= 200
SEED ?= 1
mutate: deps
	@sh scripts/mutate $(N) $(SEED)

bench: deps
	@$(MAKE) -s all
	@sh scripts/bench.sh $(BUILD)

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/pgsim
	install -m 755 $(BUILD)/pgsim $(DESTDIR)$(PREFIX)/bin/pgsim
	cp -r models configs $(DESTDIR)$(PREFIX)/share/pgsim/

format:
	clang-format -i $$(find sim tests -name '*.[ch]')

clean:
	rm -rf build build-san build-cov build-fuzz

-include $(shell find $(BUILD) build-san build-fuzz -name '*.d' 2>/dev/null)
.SECONDARY:
