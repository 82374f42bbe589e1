# worker: a batch render-farm worker around a sampler-study path tracer.
# One non-recursive Makefile. `make` builds bin/worker; `make test`, `make run`, `make asan`.
CC      ?= cc
PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build
BIN     ?= bin
OPT     ?= -O2 -g
SAN     ?=
SIMD    ?= 1
VERSION := 0.1.0

WARN    := -std=c11 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wno-unused-parameter
# snprintf into fixed buffers truncates on purpose (paths and messages are bounded). GCC's warning
# only: clang has none of that name, and its -Werror refuses an unknown -Wno- (asked once here).
WARN    += $(shell $(CC) -Werror -Wno-format-truncation -fsyntax-only -x c /dev/null 2>/dev/null && \
             echo -Wno-format-truncation)
# packet.c passes 32-byte vectors between always-inline helpers: GCC's note that their ABI
# changed in GCC 4.6 concerns calls between separately compiled files, of which there are none.
WARN    += -Wno-psabi
# No a*b+c contracted into one rounding: GCC's ISO C mode already does not; clang's default
# would, and the images (and packet.c's lanes, which repeat the scalar tests bit for bit) must not
# depend on the compiler.
WARN    += -ffp-contract=off
DEFS    := -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -DWORKER_VERSION='"$(VERSION)"'
ifeq ($(SIMD),0)
DEFS    += -DWORKER_NO_SIMD # no vector paths (common/base/simd.h): the determinism test's reference
endif
PKGS    := yaml-0.1 zlib
PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lyaml -lz)
# OpenEXR: only its C core (OpenEXRCore, openexr.h). pkg-config's OpenEXR module names the C++
# libraries too; of its --libs we keep the search paths and the core (its name carries the
# version, OpenEXRCore-3_1 on Debian 12).
EXR_CFLAGS := $(shell pkg-config --cflags OpenEXR 2>/dev/null || echo -I/usr/include/OpenEXR)
EXR_LIBS   := $(filter -L% -lOpenEXRCore%,$(shell pkg-config --libs OpenEXR 2>/dev/null))
EXR_LIBS   := $(if $(filter -lOpenEXRCore%,$(EXR_LIBS)),$(EXR_LIBS),-lOpenEXRCore-3_1)
PKG_CFLAGS += $(EXR_CFLAGS)
PKG_LIBS   += $(EXR_LIBS)
CFLAGS_ALL  = $(WARN) $(OPT) $(SAN) $(DEFS) -Icommon -Iworker $(PKG_CFLAGS) -MMD -MP $(CFLAGS)
LDLIBS_ALL  = $(SAN) $(PKG_LIBS) -lm $(LDFLAGS) $(LDLIBS)

ifeq ($(V),1)
Q :=
else
Q := @
endif

COMMON_SRC := $(wildcard common/*/*.c)
# worker/study/ is one folder deeper, a subfolder per stage (load, judge, present, run)
WORKER_SRC := $(filter-out worker/cli/main.c,$(wildcard worker/*/*.c worker/*/*/*.c))
TEST_SRC   := $(wildcard tests/test_*.c)
TOOL_SRC   := $(wildcard tools/*.c)
COMMON_OBJ := $(COMMON_SRC:%.c=$(BUILD)/%.o)
WORKER_OBJ := $(WORKER_SRC:%.c=$(BUILD)/%.o)
TEST_BIN   := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TOOL_BIN   := $(TOOL_SRC:tools/%.c=$(BUILD)/tools/%)
LIBCOMMON  := $(BUILD)/libcommon.a
LIBWORKER  := $(BUILD)/libworker.a
WORKER_BIN := $(BIN)/worker

.SECONDARY:
.PHONY: all build-parallel test stress test-big unit run install uninstall clean asan deps golden bench bench-peers lint scenes fuzz valgrind test-slurm
all: deps $(WORKER_BIN)

# Set-up: when libyaml, zlib or OpenEXR headers are missing, root on Debian installs them
# (NO_INSTALL=1 skips that); otherwise, or if that fails, one line naming the Debian packages.
# The include path is asked of pkg-config afresh: the one computed above predates the install.
HAVE_HEADERS = printf '\#include <yaml.h>\n\#include <zlib.h>\n\#include <openexr.h>\n' | \
  $(CC) $(PKG_CFLAGS) $$(pkg-config --cflags OpenEXR 2>/dev/null) -E -x c - >/dev/null 2>&1
DEB_PKGS = libyaml-dev zlib1g-dev libopenexr-dev pkg-config
deps:
	@$(HAVE_HEADERS) || { \
	  if [ -z "$(NO_INSTALL)" ] && [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "make: installing $(DEB_PKGS) (apt-get)" >&2; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEB_PKGS); } >/dev/null 2>&1; \
	  fi; \
	  $(HAVE_HEADERS) || { echo "error: libyaml, zlib or OpenEXR headers are missing: apt-get install libyaml-dev zlib1g-dev libopenexr-dev" >&2; exit 1; }; }

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS_ALL) -c $< -o $@

# The pmj02bn sampler's sequences (common/sample/pmj02_table.h), drawn by our own generator at
# build time into a generated source: the tool links the generator alone, the library then holds
# the table, so a change to pmj02.c regenerates it.
GEN_OBJ := $(BUILD)/gen/pmj02_table.o
$(BUILD)/tools/gen_pmj02: $(BUILD)/tools/gen_pmj02.o $(BUILD)/common/sample/pmj02.o
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(OPT) -o $@ $^ $(LDLIBS_ALL)
$(BUILD)/gen/pmj02_table.c: $(BUILD)/tools/gen_pmj02
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  GEN     $@")
	$(Q)$< $@
$(GEN_OBJ): $(BUILD)/gen/pmj02_table.c
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS_ALL) -c $< -o $@

$(LIBCOMMON): $(COMMON_OBJ) $(GEN_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^
$(LIBWORKER): $(WORKER_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

$(WORKER_BIN): $(BUILD)/worker/cli/main.o $(LIBWORKER) $(LIBCOMMON)
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(OPT) -o $@ $^ $(LDLIBS_ALL)

$(BUILD)/tests/%: $(BUILD)/tests/%.o $(LIBWORKER) $(LIBCOMMON)
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(OPT) -o $@ $^ $(LDLIBS_ALL)

# Scene generators (tools/*.c): C programs linked with the renderer library.
$(BUILD)/tools/%: $(BUILD)/tools/%.o $(LIBCOMMON)
	@$(if $(Q),echo "  LD      $@")
	$(Q)$(CC) $(OPT) -o $@ $^ $(LDLIBS_ALL)

# Regenerate the generated scene data (a test checks the committed files match).
scenes: $(TOOL_BIN)
	$(Q)mkdir -p scenes/textures
	$(BUILD)/tools/gen_planet scenes/textures/planet.png
	$(BUILD)/tools/gen_final scenes/final.yaml

# Re-render tests/golden/*.png on purpose: after a deliberate change to a scene or to what the
# renderer computes (not after a speed-up, which must still pass the golden check as it is).
golden: all
	$(Q)WORKER=$(abspath $(WORKER_BIN)) GOLDEN_UPDATE=1 sh tests/e2e_golden.sh

# `make run` and `make test` compile with one job per core (a plain `make` is serial), once the
# dependencies are in place.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
build-parallel:
	$(Q)$(MAKE) --no-print-directory deps
	$(Q)$(MAKE) --no-print-directory -j$(JOBS) $(BUILD_GOALS)

# Unit binaries, then the end-to-end scripts; the runner prints "N passed, N failed".
test:
	$(Q)$(MAKE) --no-print-directory build-parallel BUILD_GOALS='all $(TEST_BIN) $(TOOL_BIN)'
	$(Q)WORKER=$(abspath $(WORKER_BIN)) TEST_BIN_DIR=$(abspath $(BUILD)/tests) \
	  TOOLS_DIR=$(abspath $(BUILD)/tools) sh tests/run.sh

# The long runs of issue 21's must-shows: a kill -9 storm over 200 jobs for 5 minutes, and a
# 10240x10240 job (1.05e8 pixels) rendered in 4 parts and merged (about 2 minutes, 2 GB).
stress: all
	$(Q)WORKER=$(abspath $(WORKER_BIN)) STRESS_JOBS=200 STRESS_SECONDS=300 sh tests/e2e_queue_stress.sh
test-big: all
	$(Q)WORKER=$(abspath $(WORKER_BIN)) sh tests/long/big_merge.sh

unit: all $(TEST_BIN)
	$(Q)WORKER=$(abspath $(WORKER_BIN)) TEST_BIN_DIR=$(abspath $(BUILD)/tests) E2E=0 sh tests/run.sh

# Same suite under AddressSanitizer + UndefinedBehaviorSanitizer, in its own build tree.
asan:
	$(Q)$(MAKE) --no-print-directory test BUILD=build/asan BIN=build/asan/bin OPT='-O1 -g' \
	  SAN='-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all' ASAN_FAST=1

# The Slurm examples in ci/slurm/ through a one-node Slurm on localhost (daemons started and
# stopped by the script; needs Debian's slurm-wlm and munge).
test-slurm: all
	$(Q)WORKER=$(abspath $(WORKER_BIN)) bash ci/slurm/test-local.sh

# The headline study: a suite of four studies (jobs/studies/), one verdict over them all
# (out/compare/report.html).
run:
	$(Q)$(MAKE) --no-print-directory build-parallel BUILD_GOALS=all
	$(WORKER_BIN) jobs/compare.yaml

install: all
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 0755 $(WORKER_BIN) $(DESTDIR)$(PREFIX)/bin/worker
	install -d $(DESTDIR)$(PREFIX)/share/worker/scenes/textures
	install -m 0644 scenes/*.yaml $(DESTDIR)$(PREFIX)/share/worker/scenes/
	install -m 0644 scenes/textures/* $(DESTDIR)$(PREFIX)/share/worker/scenes/textures/
uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/worker
	rm -rf $(DESTDIR)$(PREFIX)/share/worker

# One small render (two forked children, Poisson pixel and light sets) under valgrind memcheck:
# zero errors, nothing lost.
valgrind: all
	$(Q)mkdir -p build/valgrind && printf 'scene: %s/scenes/checker.yaml\nwidth: 24\nheight: 16\nsampler: poisson\nthreshold: 8\nlight_sampler: poisson\nlight_threshold: 5\nprocesses: 2\n' \
	  "$(CURDIR)" >build/valgrind/job.yaml
	$(Q)valgrind -q --error-exitcode=3 --leak-check=full --show-leak-kinds=definite \
	  --errors-for-leak-kinds=definite --trace-children=yes --child-silent-after-fork=no \
	  $(WORKER_BIN) --quiet --out build/valgrind/out build/valgrind/job.yaml
	@echo "valgrind: 0 errors, 0 bytes definitely lost"

# Benchmarks with the release flags: a table on stdout and bench/results.json (see BENCH.md).
build/bench_bridson: bench/bench_bridson.c $(LIBCOMMON)
	$(Q)$(CC) $(CFLAGS_ALL) -o $@ $< $(LIBCOMMON) $(LDLIBS_ALL)
bench: all build/bench_bridson
	$(Q)sh bench/bench.sh

# Our renderer against Blender's Cycles at equal error on the book-3 Cornell box (installs
# Debian's blender when missing; not part of make test or CI; see BENCH.md).
bench-peers: all
	$(Q)WORKER=$(abspath $(WORKER_BIN)) sh bench/peers.sh

# Fuzzing (libFuzzer, clang): each target for SECONDS; new crashes land in tests/fuzz/regress/,
# which `make test` replays. `make fuzz SECONDS=600` is the long local run.
FUZZ_CC     ?= clang
SECONDS     ?= 30
FUZZ_TARGETS ?= job scene image summary
FUZZ_FLAGS  := -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -ffp-contract=off -Wno-psabi
FUZZ_OBJ    := $(patsubst %.c,build/fuzz/obj/%.o,$(COMMON_SRC) $(WORKER_SRC)) build/fuzz/obj/gen/pmj02_table.o
build/fuzz/obj/gen/pmj02_table.o: $(BUILD)/gen/pmj02_table.c
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) -std=c11 $(DEFS) $(PKG_CFLAGS) -Icommon -Iworker $(FUZZ_FLAGS) -c $< -o $@
# The library once, in parallel; each target links it with its own entry point.
build/fuzz/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(Q)$(FUZZ_CC) -std=c11 $(DEFS) $(PKG_CFLAGS) -Icommon -Iworker $(FUZZ_FLAGS) -c $< -o $@
build/fuzz/fuzz_%: $(FUZZ_OBJ) tests/fuzz/fuzz_targets.c tests/fuzz/fuzz_main.c tests/fuzz/fuzz_targets.h
	$(Q)$(FUZZ_CC) -std=c11 $(DEFS) $(PKG_CFLAGS) -Icommon -Iworker -Itests/fuzz $(FUZZ_FLAGS) \
	  -DFUZZ_TARGET=fuzz_$* tests/fuzz/fuzz_targets.c tests/fuzz/fuzz_main.c $(FUZZ_OBJ) -o $@ $(PKG_LIBS) -lm
fuzz: deps
	@mkdir -p build/fuzz
	$(Q)$(MAKE) --no-print-directory -j$(JOBS) $(FUZZ_TARGETS:%=build/fuzz/fuzz_%)
	$(Q)set -e; for t in $(FUZZ_TARGETS); do \
	  mkdir -p build/fuzz/corpus-$$t; \
	  echo "fuzz_$$t: $(SECONDS) s"; \
	  build/fuzz/fuzz_$$t -max_total_time=$(SECONDS) -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
	    -print_final_stats=1 -artifact_prefix=tests/fuzz/regress/$$t- \
	    build/fuzz/corpus-$$t tests/fuzz/$$t 2>build/fuzz/fuzz_$$t.log || \
	    { tail -n 40 build/fuzz/fuzz_$$t.log; exit 1; }; \
	  grep -E '^stat::number_of_executed_units|^#[0-9]+.*DONE' build/fuzz/fuzz_$$t.log | tail -n 2; \
	done

lint:
	clang-format --dry-run --Werror common/*/*.[ch] worker/*/*.[ch] worker/*/*/*.[ch] tests/*.[ch] tests/fuzz/*.[ch] tools/*.c
	cppcheck --quiet --error-exitcode=1 --enable=warning,portability --std=c11 -Icommon -Iworker common worker
	python3 tests/check_checks.py tests/*.sh ci/*/*.sh

clean:
	rm -rf build bin

-include $(COMMON_OBJ:.o=.d) $(GEN_OBJ:.o=.d) $(WORKER_OBJ:.o=.d) $(BUILD)/worker/cli/main.d $(TEST_BIN:=.d) $(TOOL_BIN:=.d)
