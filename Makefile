# gibake — build, test, bake, demo, bench, install (GNU make).
#
#   make                 build every tool and the runtime into build/bin
#   make test            install missing packages, build, run every test, then
#                        all of them again under the sanitizers, then the fuzzers
#   make test-repeat N=  every test N times, counting failures (flakiness)
#   make demo            install missing packages, build, bake and show the Cornell box
#   make deps            apt-get install the Debian packages that are missing
#   make bake SCENE=f    bake one scene into bake/ (pattern rules: make -j works)
#   make bench           benchmarks (bench/), figures on stdout
#   make fuzz            libFuzzer targets, FUZZ_SECONDS each, from tests/fuzz/corpus
#   make install PREFIX=/usr/local
#   make clean
#
# Programs are linked with $(CXX), since the library holds the C++ adapters.
# Sources are found by their place: formats/*.c and *.cpp, common/*.c, tools/<name>/*.c and *.cpp,
# runtime/*.c (the renderer's core) and runtime/<method>/*.c (one folder per GI
# method) go into one static library, but for the adapters (ADAPTER_SOURCES:
# shared objects, loaded on first use); tools/<name>/main.c becomes
# build/bin/<name>, runtime/main.c becomes build/bin/gbview; tests/unit/test_*.c
# become test programs; shaders, PASS.STAGE.glsl beside the C file that draws
# with them, become C string literals (below). Adding a file needs no change
# here. -Iruntime lets a method's files include the core's headers by name;
# the core names a method's header by its folder (#include "topo/topo.h").

PREFIX ?= /usr/local
BUILD ?= build
CC ?= cc
CXX ?= g++
OPT ?= -O2
SANITIZE ?=
FUZZ_SECONDS ?= 20

DEB_PACKAGES = gcc g++ make perl clang libclang-rt-14-dev zlib1g-dev \
  libopenvdb-dev libtbb-dev libembree-dev libflann-dev liblz4-dev libcgal-dev libeigen3-dev \
  libopenmesh-dev libopenimageio-dev libepoxy-dev libglfw3-dev libegl-dev libstb-dev \
  libegl-mesa0 libgl1-mesa-dri xvfb xauth xdotool openbox libopenvdb-tools openimageio-tools time strace gnuplot-nox help2man \
  munge slurm-wlm nodejs python3
# What make bench needs beside: scikit-image's skeletonize_3d, thin's peer
# in bench/thin.sh (for Debian's /usr/bin/python3); Blender's Cycles,
# lightmap's peer in bench/lightmap_peer.sh (its glTF importer needs numpy).
BENCH_DEB_PACKAGES = python3-skimage python3-openvdb blender python3-numpy

SANITIZE_FLAGS = $(if $(SANITIZE),-fsanitize=$(SANITIZE) -fno-sanitize-recover=all -fno-omit-frame-pointer)
# libFuzzer's coverage instrumentation (SANITIZE with fuzzer-no-link) only in
# the sources a fuzz target reaches: COVERAGE_IGNORE names the others, and
# says why (they made the sanitized CLI suite several times slower).
COVERAGE_IGNORE = tests/fuzz/coverage_ignore.txt
COVERAGE_FLAGS = $(if $(findstring fuzzer,$(SANITIZE)),-fsanitize-coverage-ignorelist=$(COVERAGE_IGNORE))
# clang's -MMD does not name the list: every object depends on it by hand.
COVERAGE_DEPENDS = $(if $(COVERAGE_FLAGS),$(COVERAGE_IGNORE))
CPPFLAGS += -Iformats -Icommon -Itests -Iruntime -I$(BUILD)/glsl -MMD -MP -D_GNU_SOURCE
CFLAGS += -std=c11 $(OPT) -g -Wall -Wextra -pthread $(SANITIZE_FLAGS) $(COVERAGE_FLAGS)
CXXFLAGS += -std=c++17 $(OPT) -g -Wall -Wextra -pthread $(SANITIZE_FLAGS) $(COVERAGE_FLAGS) \
  -Wno-deprecated-declarations
LDFLAGS += -pthread -Wl,--as-needed $(SANITIZE_FLAGS)
LDLIBS += -lOpenMeshCore -lembree3 -lflann -lepoxy -lglfw -lEGL -lz -lm
# The adapters to heavy libraries are shared objects loaded on first use
# (formats/adapter.h), in $(BUILD)/lib/gibake/ beside $(BIN); each has its
# rule below.
OPENVDB_ADAPTER_SOURCES := $(wildcard formats/openvdb/*.cpp)
ADAPTER_SOURCES = formats/image_openimageio.cpp $(OPENVDB_ADAPTER_SOURCES)
ADAPTERS = $(BUILD)/lib/gibake/gibake-openimageio.so $(BUILD)/lib/gibake/gibake-openvdb.so
OPENIMAGEIO_LIBS = -lOpenImageIO -lOpenImageIO_Util
OPENVDB_LIBS = -lopenvdb -ltbb

TOOLS := $(patsubst tools/%/main.c,%,$(wildcard tools/*/main.c))
PROGRAMS := $(TOOLS) $(if $(wildcard runtime/main.c),gbview)
LIBRARY_C := $(wildcard formats/*.c common/*.c) $(filter-out %/main.c,$(wildcard tools/*/*.c runtime/*.c runtime/*/*.c))
LIBRARY_CXX := $(filter-out $(ADAPTER_SOURCES),$(wildcard formats/*.cpp tools/*/*.cpp))
# tools/atlas/lscm_cgal.cpp: CGAL's LSCM solves with Eigen (header-only, as CGAL is)
CXXFLAGS += -I/usr/include/eigen3
LIBRARY_OBJECTS := $(LIBRARY_C:%.c=$(BUILD)/obj/%.o) $(LIBRARY_CXX:%.cpp=$(BUILD)/obj/%.o)
LIBRARY := $(BUILD)/libgibake.a
UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/%,$(wildcard tests/unit/test_*.c))
FUZZ_TARGETS := $(patsubst tests/fuzz/%.c,%,$(wildcard tests/fuzz/fuzz_*.c))
BIN := $(BUILD)/bin

.PHONY: all deps bench-deps test check check-optimised check-sanitized check-fuzz test-repeat \
  unit-tests demo bake bench fuzz install clean
.DELETE_ON_ERROR:
.SECONDARY:

all: $(PROGRAMS:%=$(BIN)/%) $(ADAPTERS)

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing" $$missing; \
	  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q $$missing; \
	fi

# Shaders: one file a stage, PASS.STAGE.glsl (STAGE vert, tesc, tese, geom,
# frag or comp; runtime/*, runtime/<method>/*, tests/unit/*), and snippets
# that stages #include, NAME.glsl. tools/glsl.awk makes each stage the C
# string literal $(BUILD)/glsl/PATH.inc, its snippets spliced in, which the C
# file includes (-I$(BUILD)/glsl) as the source's initialiser:
#   static const char present_shader[] =
#   #include "runtime/output_present.frag.glsl.inc"
#       ;
# Objects are made after them (order-only: a first build has no .d yet);
# then an object's .d names the .inc files it includes, and each .inc's .d
# the .glsl files it was made of, so an edit remakes exactly what uses it.
GLSL_STAGES := $(wildcard runtime/*.*.glsl runtime/*/*.*.glsl tests/unit/*.*.glsl)
GLSL_SOURCES := $(GLSL_STAGES:%=$(BUILD)/glsl/%.inc)

$(BUILD)/glsl/%.glsl.inc: %.glsl tools/glsl.awk
	@mkdir -p $(@D)
	awk -f tools/glsl.awk -v target=$@ -v depfile=$(@:.inc=.d) $< >$@

$(BUILD)/obj/%.o: %.c $(COVERAGE_DEPENDS) | $(GLSL_SOURCES)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/%.o: %.cpp $(COVERAGE_DEPENDS)
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

# Every program links the library, so building one builds the adapters; all
# and unit-tests also name them, so that a deleted one is made again.
$(LIBRARY): $(LIBRARY_OBJECTS) | $(ADAPTERS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $(LIBRARY_OBJECTS)

$(BUILD)/pic/%.o: %.cpp $(COVERAGE_DEPENDS)
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -fPIC -c $< -o $@

$(BUILD)/lib/gibake/gibake-openimageio.so: $(BUILD)/pic/formats/image_openimageio.o
	@mkdir -p $(@D)
	$(CXX) -shared $(LDFLAGS) $^ $(OPENIMAGEIO_LIBS) -o $@

$(BUILD)/lib/gibake/gibake-openvdb.so: $(OPENVDB_ADAPTER_SOURCES:%.cpp=$(BUILD)/pic/%.o)
	@mkdir -p $(@D)
	$(CXX) -shared $(LDFLAGS) $^ $(OPENVDB_LIBS) -o $@

$(BIN)/gbview: $(BUILD)/obj/runtime/main.o $(LIBRARY)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BIN)/%: $(BUILD)/obj/tools/%/main.o $(LIBRARY)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BUILD)/tests/%: $(BUILD)/obj/tests/unit/%.o $(LIBRARY)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@

unit-tests: $(UNIT_TESTS) $(ADAPTERS)

# The whole suite: the unit tests and the CLI suite (tests/cli/*.t) on the
# optimised build; then all of it again on a clang build with AddressSanitizer,
# UBSan (also float-cast-overflow and float-divide-by-zero, which GCC's
# "undefined" leaves out) and LeakSanitizer; then every fuzz target replays
# its corpus and fuzzes for FUZZ_CHECK_SECONDS (the one clang build serves
# both: the code the fuzz targets reach carries libFuzzer's coverage
# instrumentation, COVERAGE_IGNORE above). Every stage runs and reports
# even when an earlier one failed; check fails if any did.
SANITIZED_BUILD = build/asan
SANITIZED_FLAGS = address,undefined,float-cast-overflow,float-divide-by-zero,fuzzer-no-link
SANITIZED_MAKE = BUILD=$(SANITIZED_BUILD) CC=clang CXX=clang++ OPT=-O1 SANITIZE=$(SANITIZED_FLAGS)
# intercept_tls_get_addr=0: clang 14's LeakSanitizer can crash its own tracer at exit
# ("Tracer caught signal 11") while a thread's dynamic TLS is being set up, which
# the dlopen'ed adapters and their TBB threads make possible; fixed in LLVM 17
# (D147459), and the option is the upstream workaround. Leaks are still reported.
SANITIZER_ENVIRONMENT = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/leak_suppressions.txt:print_suppressions=0
FUZZ_CHECK_SECONDS ?= 10
# prove runs JOBS tests at a time, in this order: the slowest first, so that
# no long test starts last and runs alone.
SLOW_TESTS = tests/cli/hard_cases.t tests/cli/report.t tests/cli/output.t tests/cli/slurm.t \
  tests/cli/make.t
CLI_TESTS = $(SLOW_TESTS) $(filter-out $(SLOW_TESTS),$(wildcard tests/cli/*.t))
SUITE = $(CLI_TESTS) $(UNIT_TESTS)
# The sanitized stage leaves out report.t: it runs the same tools as the rest
# of the suite, on 200 CPU s of renders under ASan, and asserts only the CSV;
# and slurm.t: its jobs run bake.mk's rules, which make.t runs sanitized,
# and the rest is Slurm's scheduling.
SANITIZED_SUITE = $(filter-out tests/cli/report.t tests/cli/slurm.t,$(SUITE))

JOBS ?= $(shell nproc)
test: deps
	$(MAKE) -j$(JOBS) check

check:
	@status=0; \
	$(MAKE) check-optimised || status=1; \
	$(MAKE) check-sanitized || status=1; \
	$(MAKE) check-fuzz || status=1; \
	[ $$status = 0 ] || echo "make check: a stage failed (see above)"; \
	exit $$status

check-optimised: all unit-tests
	GB_BIN=$(abspath $(BIN)) GB_ROOT=$(CURDIR) prove -j$(JOBS) --timer --exec '' $(SUITE)

check-sanitized:
	$(MAKE) $(SANITIZED_MAKE) all unit-tests
	$(SANITIZER_ENVIRONMENT) GB_BIN=$(abspath $(SANITIZED_BUILD))/bin GB_ROOT=$(CURDIR) \
	  prove -j$(JOBS) --timer --exec '' $(SANITIZED_SUITE:$(BUILD)/%=$(SANITIZED_BUILD)/%)

check-fuzz:
	$(MAKE) fuzz FUZZ_SECONDS=$(FUZZ_CHECK_SECONDS)

# The Khronos glTF validator (npm gltf-validator), which tests/cli/lightmap.t
# runs with node on lightmap's .glb. nodejs (NodeSource's on these machines)
# brings npm: Debian's npm package would conflict with it.
GLTF_VALIDATOR = build/node/node_modules/gltf-validator/package.json
$(GLTF_VALIDATOR):
	npm install --prefix build/node --no-audit --no-fund gltf-validator@2.0.0-dev.3.10
check-optimised check-sanitized: $(GLTF_VALIDATOR)

# The unit tests N times each (N/20 for those over a second) and the CLI
# suite N/20 times, counting failures: make test-repeat N=1000 (not in CI).
N ?= 100
test-repeat: all unit-tests
	GB_BIN=$(abspath $(BIN)) GB_ROOT=$(CURDIR) sh tests/repeat.sh $(N) $(SUITE)

# The demo: summarise the Cornell box, bake it, render it headless to demo/
# with each method, and open the window when there is a display.
DEMO_METHODS ?= direct flc implicit topo octree flc-iv
demo: deps
	$(MAKE) all
	$(BIN)/scene-info scenes/cornell/cornell.scene
	$(MAKE) bake SCENE=scenes/cornell/cornell.scene VOXELIZE_FLAGS="-r 64" PHOTONS_FLAGS="-n 200000"
	@mkdir -p demo
	@for m in $(DEMO_METHODS); do \
	  $(BIN)/gbview scenes/cornell/cornell.scene --headless --method $$m --frames 8 \
	    --resolution 256x256 --bake $(BAKE) -o demo/cornell-$$m.png || exit 1; \
	  echo "demo: wrote demo/cornell-$$m.png"; \
	done
	@if [ -n "$$DISPLAY" ]; then $(BIN)/gbview scenes/cornell/cornell.scene --bake $(BAKE); fi

include bake.mk

# Reference images of SCENE, one per mode: make reference [SCENE=...] [REFERENCE_SPP=256]
#   -> bake/NAME.{direct,indirect1,indirect1-unshadowed,full}.exr (+ .png)
REFERENCE_MODES ?= direct indirect1 indirect1-unshadowed full
REFERENCE_SPP ?= 256
REFERENCE_FLAGS ?=
REFERENCE_IMAGES := $(REFERENCE_MODES:%=$(BAKE)/$(SCENE_NAME).%.exr)
.PHONY: reference
reference: $(REFERENCE_IMAGES)
$(REFERENCE_IMAGES): $(BAKE)/$(SCENE_NAME).%.exr: $(SCENE) $(BIN)/reference
	@mkdir -p $(@D)
	$(BIN)/reference --mode $* --spp $(REFERENCE_SPP) $(REFERENCE_FLAGS) --png $(SCENE) -o $@ \
	  --depfile $@.d
-include $(REFERENCE_IMAGES:%=%.d)

# Benchmarks: bench/*.c and bench/*.cpp are helper programs linked against
# the library into build/bench/; each bench/*.sh prints its table (but
# common.sh, which they source, and report_*.sh, which make report runs).
BENCH_PROGRAMS := $(patsubst bench/%.c,$(BUILD)/bench/%,$(wildcard bench/*.c)) \
  $(patsubst bench/%.cpp,$(BUILD)/bench/%,$(wildcard bench/*.cpp))
$(BUILD)/bench/%: $(BUILD)/obj/bench/%.o $(LIBRARY)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) $^ $(LDLIBS) -o $@
# the voxelize helper times OpenVDB itself, not through the adapter
$(BUILD)/bench/voxelize_bench: LDLIBS += $(OPENVDB_LIBS)

bench-deps:
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(BENCH_DEB_PACKAGES)"

bench: bench-deps all $(BENCH_PROGRAMS)
	@for b in $(filter-out bench/common.sh bench/report_%.sh,$(wildcard bench/*.sh)); do GB_BIN=$(abspath $(BIN)) sh $$b || exit 1; done

# libFuzzer: the fuzz targets are linked on the sanitized build (whose code
# carries libFuzzer's coverage instrumentation); each replays its seeds
# (tests/fuzz/corpus/T) and what earlier runs found (build/fuzz-corpus/T),
# then fuzzes for FUZZ_SECONDS. A crash, leak or timeout fails.
# With make -j, targets fuzz side by side (fuzz-run/T, one each).
.PHONY: fuzz-build $(FUZZ_TARGETS:%=fuzz-run/%)
fuzz: $(FUZZ_TARGETS:%=fuzz-run/%)
fuzz-build:
	$(MAKE) $(SANITIZED_MAKE) $(FUZZ_TARGETS:%=$(SANITIZED_BUILD)/fuzz/%)
$(FUZZ_TARGETS:%=fuzz-run/%): fuzz-run/%: fuzz-build
	@mkdir -p build/fuzz-corpus/$*
	@echo "fuzz: $* for $(FUZZ_SECONDS) s"
	@$(SANITIZER_ENVIRONMENT) $(SANITIZED_BUILD)/fuzz/$* -max_total_time=$(FUZZ_SECONDS) \
	  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=build/fuzz-corpus/$*- \
	  $$(sed -n 's/^max_len = /-max_len=/p' tests/fuzz/$*.options 2>/dev/null) \
	  build/fuzz-corpus/$* tests/fuzz/corpus/$* 2>build/fuzz-corpus/$*.log \
	  || { tail -60 build/fuzz-corpus/$*.log; exit 1; }
	@grep -E '^stat::(number_of_executed_units|new_units_added)|^#[0-9]+ +DONE' \
	  build/fuzz-corpus/$*.log | sed 's/^/$*: /'

# The fuzz targets link the adapters in (formats/image.c says why).
$(BUILD)/fuzz/%: $(BUILD)/obj/tests/fuzz/%.o $(LIBRARY) $(ADAPTER_SOURCES:%.cpp=$(BUILD)/pic/%.o)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) -fsanitize=fuzzer $^ $(LDLIBS) $(OPENIMAGEIO_LIBS) $(OPENVDB_LIBS) -o $@

# gibake-TOOL, the gibake dispatcher, the adapters, man pages (tools/install.sh).
install: all
	sh tools/install.sh $(BIN) $(DESTDIR)$(PREFIX)

clean:
	rm -rf build bake demo

include bench/report.mk

-include $(shell find $(BUILD)/obj $(BUILD)/pic $(BUILD)/glsl -name '*.d' 2>/dev/null)
