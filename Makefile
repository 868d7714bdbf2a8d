# pm — photon-map global illumination toolset. See README.md.
include config.mk

B        ?= build
LIB_C    := $(wildcard lib/*/*.c)
LIB_CXX  := $(filter-out lib/scene/oiio.cpp,$(wildcard lib/*/*.cpp))
LIB_H    := $(wildcard lib/*/*.h)
LIB_OBJ  := $(LIB_C:%.c=$(B)/%.o) $(LIB_CXX:%.cpp=$(B)/%.o)
TOOL_SRC := $(wildcard tools/pm-*.c)
TOOLS    := $(TOOL_SRC:tools/%.c=$(B)/bin/%)
UTIL_OBJ := $(B)/tools/util.o $(B)/tools/bar.o $(B)/tools/options.o
UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNITS    := $(UNIT_SRC:tests/unit/%.c=$(B)/tests/%)

# OpenImageIO's module, loaded when an image is first read (lib/scene/oiio.h).
PLUGIN   := $(B)/lib/pm/pm-oiio.so

all: $(TOOLS) $(PLUGIN)

$(PLUGIN): lib/scene/oiio.cpp lib/scene/oiio.h lib/scene/texfilter.h config.mk
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(OIIO_CFLAGS) -fPIC -shared $< -o $@ $(LDFLAGS) $(OIIO_LIBS)

$(B)/lib/scene/oiio_load.o: CFLAGS += -DPM_BUILD_PLUGINS='"$(abspath $(B))/lib/pm"'

$(B)/lib/%.o: lib/%.c $(LIB_H) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -c $< -o $@

$(B)/lib/%.o: lib/%.cpp $(LIB_H) config.mk
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -c $< -o $@

$(B)/libpm.a: $(LIB_OBJ)
	@rm -f $@
	$(AR) rcs $@ $^

$(B)/tools/%.o: tools/%.c tools/util.h tools/bar.h tools/options.h $(LIB_H) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itools -c $< -o $@

$(B)/bin/%: $(B)/tools/%.o $(UTIL_OBJ) $(B)/libpm.a
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(B)/tests/%: tests/unit/%.c tests/check.h $(B)/libpm.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itests -c $< -o $@.o
	$(CXX) $(LDFLAGS) $@.o $(B)/libpm.a $(LDLIBS) -o $@

deps:
	@sh mk/deps.sh

# make check builds with one job a CPU (JOBS=N to choose).
JOBS ?= $(shell nproc 2>/dev/null || echo 1)
check: deps
	@$(MAKE) --no-print-directory -j$(JOBS) all-tests
	@$(MAKE) --no-print-directory -j$(JOBS) asan-tests
	@sh tests/run.sh $(B) $(B)-asan

all-tests: $(TOOLS) $(UNITS) $(PLUGIN)

demo: deps
	@$(MAKE) --no-print-directory all
	@sh examples/cornell/run.sh
	@sh examples/room/compare.sh

install: all
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin
	install -d $(DESTDIR)$(PREFIX)/lib/pm
	install -m 644 $(PLUGIN) $(DESTDIR)$(PREFIX)/lib/pm
	install -d $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 644 $(wildcard man/pm-*.1) $(DESTDIR)$(PREFIX)/share/man/man1

clean:
	rm -rf $(B)

.PHONY: all deps check all-tests demo install clean
.SECONDARY:

# Helper programs that tests use to make inputs (not tests themselves).
TESTTOOL_SRC := $(wildcard tests/tools/*.c)
TESTTOOLS    := $(TESTTOOL_SRC:tests/tools/%.c=$(B)/tests/tools/%)
all-tests: $(TESTTOOLS)
$(B)/tests/tools/%: tests/tools/%.c $(B)/libpm.a
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itests -c $< -o $@.o
	$(CXX) $(LDFLAGS) $@.o $(B)/libpm.a $(LDLIBS) -o $@

# Fuzz targets (tests/fuzz/): every target also builds as a replay program
# that runs given files once each, so make check replays the seed corpus and
# the regression inputs without clang. `make fuzz` builds them with libFuzzer.
FUZZ_SRC     := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_TARGETS := $(FUZZ_SRC:tests/fuzz/fuzz_%.c=%)
all-tests: $(FUZZ_TARGETS:%=$(B)/fuzz/replay-%)
$(B)/fuzz/%.o: tests/fuzz/%.c tests/fuzz/fuzz.h $(LIB_H) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -Itests/fuzz -c $< -o $@
$(B)/fuzz/replay-%: $(B)/fuzz/fuzz_%.o $(B)/fuzz/util.o $(B)/fuzz/replay.o $(B)/libpm.a
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

# The same tests in a second tree built with AddressSanitizer and
# UndefinedBehaviorSanitizer (compile and link, C and C++); tests/run.sh
# collects their reports through ASAN_OPTIONS/UBSAN_OPTIONS log_path.
SAN      := -fsanitize=address,undefined -fno-sanitize-recover=all
SAN_OPT  := -O1 -g -fno-omit-frame-pointer $(SAN)
asan-tests:
	@$(MAKE) --no-print-directory B=$(B)-asan OPT='$(SAN_OPT)' LDFLAGS='-fopenmp $(SAN)' all-tests

# make fuzz [FUZZ_SECONDS=60]: each target under libFuzzer (clang, ASan,
# UBSan) for FUZZ_SECONDS, from the seed corpus in tests/fuzz/corpus/TARGET
# (read only; new inputs go to $(FUZZ_B)/corpus/TARGET). Crashes are left
# as $(FUZZ_B)/crash/TARGET-*; copy them to tests/fuzz/regress/TARGET/.
FUZZ_B       ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_FLAGS   ?= -rss_limit_mb=3072 -timeout=20
fuzz:
	@sh mk/deps.sh fuzz
	@$(MAKE) --no-print-directory B=$(FUZZ_B) CC=clang CXX=clang++ \
		OPT='-O1 -g -fno-omit-frame-pointer $(SAN) -fsanitize=fuzzer-no-link' \
		LDFLAGS='-fopenmp $(SAN)' $(FUZZ_B)/libpm.a $(FUZZ_B)/lib/pm/pm-oiio.so \
		$(FUZZ_TARGETS:%=$(FUZZ_B)/fuzz/fuzz_%.o) $(FUZZ_B)/fuzz/util.o
	@set -e; for t in $(FUZZ_TARGETS); do \
		clang++ -fopenmp $(SAN) -fsanitize=fuzzer $(FUZZ_B)/fuzz/fuzz_$$t.o \
			$(FUZZ_B)/fuzz/util.o $(FUZZ_B)/libpm.a $(LDLIBS) -o $(FUZZ_B)/fuzz/fuzz-$$t; \
	done
	@mkdir -p $(FUZZ_B)/crash
	@st=0; for t in $(FUZZ_TARGETS); do \
		mkdir -p $(FUZZ_B)/corpus/$$t; \
		echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
		$(FUZZ_B)/fuzz/fuzz-$$t -max_total_time=$(FUZZ_SECONDS) $(FUZZ_FLAGS) \
			-artifact_prefix=$(FUZZ_B)/crash/$$t- -print_final_stats=1 \
			$(FUZZ_B)/corpus/$$t tests/fuzz/corpus/$$t 2>$(FUZZ_B)/fuzz-$$t.log || st=1; \
		grep -E '^stat::number_of_executed_units|^stat::new_units_added|^SUMMARY|^==.*ERROR' $(FUZZ_B)/fuzz-$$t.log; \
	done; exit $$st

# make fuzz-scenes [N=200] [FIRST=1]: N scenes of extreme values from
# tests/tools/genextreme (seeds FIRST..FIRST+N-1) through pm-shoot, pm-build
# and pm-render with every estimator, on the ASan+UBSan tree
# (tests/fuzz/scenes.sh): each must give finite images or a one-line
# refusal naming FILE:LINE. Failing scenes are left in
# $(FUZZ_B)/scenes-fail/seed-N; move them to tests/fuzz/regress/pipeline/,
# which make check replays.
N     ?= 200
FIRST ?= 1
fuzz-scenes:
	@$(MAKE) --no-print-directory asan-tests
	@sh tests/fuzz/scenes.sh $(B)-asan $(FIRST) $$(($(FIRST) + $(N) - 1)) $(FUZZ_B)/scenes-fail

# make memcheck: the end-to-end tests with every program under valgrind
# (tests/memcheck.sh); zero memory errors and zero definite leaks.
memcheck:
	@sh mk/deps.sh memcheck
	@$(MAKE) --no-print-directory all-tests
	@sh tests/memcheck.sh $(B)

.PHONY: asan-tests fuzz fuzz-scenes memcheck

# Benchmarks (bench/, BENCHMARKS.md): make bench-quick (minutes), make bench
# (the full sweep and the paper's workload). Not tests; they print numbers.
BENCH_SRC  := $(wildcard bench/*.c)
BENCH      := $(BENCH_SRC:bench/%.c=$(B)/bench/%)
BENCH_XOBJ := $(patsubst bench/%.cpp,$(B)/bench/%.o,$(wildcard bench/*.cpp))
$(B)/bench/%.o: bench/%.c bench/timing.h $(LIB_H) config.mk
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(PKG_CFLAGS) -c $< -o $@
$(B)/bench/%.o: bench/%.cpp config.mk
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -c $< -o $@
$(B)/bench/%: $(B)/bench/%.o $(BENCH_XOBJ) $(B)/libpm.a
	$(CXX) $(LDFLAGS) $(BENCH_LDFLAGS) $< $(BENCH_XOBJ) $(B)/libpm.a $(LDLIBS) -o $@
$(B)/bench/hot: BENCH_LDFLAGS = -Wl,--wrap=pm_accel_hit
bench-progs: $(TOOLS) $(BENCH) $(PLUGIN)
bench bench-quick: deps
	@sh mk/deps.sh bench
	@$(MAKE) --no-print-directory bench-progs $(if $(filter bench,$@),all-tests)
	@sh bench/run.sh $(if $(filter bench-quick,$@),quick,full) $(B)
.PHONY: bench bench-quick bench-progs

# The torture harness (tests/torture/): make torture [SCENES=200] runs
# SCENES generated scenes (seeds 1..SCENES) and the regression scenes in
# tests/torture/regress/, compensated and classical estimates against the
# path tracer, 2 at a time; writes $(TORTURE_OUT)/report.md and contact
# sheets. Settings: see tests/torture/scene.sh and report.sh.
SCENES      ?= 200
TORTURE_OUT ?= tests/torture/out
KNOWN       ?= 0
torture:
	@$(MAKE) --no-print-directory all-tests
	@KNOWN=$(KNOWN) sh tests/torture/report.sh $(SCENES) 1 $(TORTURE_OUT)
.PHONY: torture

# make check-scenes (not part of make check): pm-import on the public scenes
# of ../shared/scenes, when that directory exists, and pm's path tracer on
# each against the reference image shipped with it (tests/public/scenes.sh).
check-scenes: deps
	@$(MAKE) --no-print-directory $(TOOLS) $(B)/tests/tools/exrblocks
	@sh tests/public/scenes.sh $(B)
.PHONY: check-scenes

# make check-peers (not part of make check): scenes written by
# tests/peers/pbrt_*.sh, rendered by pbrt-v4 (PM_PBRT, default
# ../shared/peers/pbrt; skipped when absent) and by pm after pm-import, the
# images compared by their means (tests/peers/run.sh). PEERS=PATTERN runs
# the scripts whose name holds it.
check-peers: deps
	@$(MAKE) --no-print-directory $(TOOLS) $(B)/tests/tools/exrblocks $(B)/tests/tools/exrstat
	@sh tests/peers/run.sh $(B) $(PEERS)
.PHONY: check-peers

# make check-blender (as root; not part of make check): Debian's blender,
# scenes built from bpy primitives, exported by tools/pm-blender.py and
# rendered by pm (tests/blender/).
check-blender:
	@sh mk/deps.sh blender
	@$(MAKE) --no-print-directory all-tests
	@PM_SUITE=tests/blender sh tests/run.sh $(B)
.PHONY: check-blender

# make check-cluster (as root; not part of make check): the SLURM fan-out,
# examples/fanout/slurm.sh, on a throwaway one-node cluster (tests/cluster/,
# tests/cluster.sh), at most 15 minutes.
check-cluster:
	@sh mk/deps.sh cluster
	@$(MAKE) --no-print-directory all
	@PM_SUITE=tests/cluster timeout 900 sh tests/run.sh $(B)
.PHONY: check-cluster
