# Two entry points for a new user (see README.md):
#   make demo   installs dependencies, builds, renders/analyses the default scene into out/
#   make test   installs dependencies, builds and runs every test
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# Unity builds (CMake's CMAKE_UNITY_BUILD: each target's sources compiled a few at a time as one
# file) take about half the compile time on 2 cores. UNITY=OFF builds file by file, quicker to
# rebuild after editing one file.
UNITY ?= ON

.PHONY: setup build demo test sanitize fuzz tsan format-check clean

setup:
	@./scripts/setup.sh

build: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=$(UNITY) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@./scripts/demo.sh $(BUILD)/src/cli/quadtri out

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# One clang build serves both: every layer with ASan, UBSan and libFuzzer's coverage
# (-DQUADTRI_FUZZ=ON), the unit tests linked without libFuzzer, the fuzz_NAME harnesses with it.
# -O1 and line tables only: about half the build time of -O2 -g, the same reports.
# SANITIZE_EXCLUDE: a ctest -E pattern of tests the sanitizer run leaves to `make test`: the
# convergence studies (ObservedOrders: five models converted and measured on four refinement
# levels of two shapes, the code of other tests at larger sizes, 70 s each under ASan) and the
# 1-against-2-thread bitwise comparison (ParallelConversion: every model twice on large meshes,
# 110 s; make tsan is the check for threads). Together a third of the sanitizer tests' time.
# LinePlot.MarkersAreDrawnInTheSeriesColourAtTheirPoints and
# Heatmaps.NormalMapColoursEachFaceByItsNormalRange pass, then LeakSanitizer's tracer crashes
# reading the main thread's TLS at exit ("Tracer caught signal 11"), every time, on this
# machine's kernel (6.18, 2026-12-07; the second since a later run that day; both load the
# image module; use_tls=0 avoids it but reports thread-local caches as leaks): left to
# `make test`, where they run and pass.
SANITIZE_EXCLUDE ?= ^(ObservedOrders|ParallelConversion)\.|^LinePlot\.MarkersAreDrawnInTheSeriesColourAtTheirPoints$$|^Heatmaps\.NormalMapColoursEachFaceByItsNormalRange$$
SANITIZE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DQUADTRI_FUZZ=ON -DQUADTRI_BENCH=OFF -DCMAKE_UNITY_BUILD=$(UNITY)
# A test that fails runs once more (--repeat until-pass:2): LeakSanitizer's leak check at exit
# stops the process's threads from a tracer thread, and that tracer has crashed ("Tracer caught
# signal 11", "LeakSanitizer has encountered a fatal error") after a test had passed, once in
# 573 on 2026-12-07. A real failure fails both runs.
sanitize: setup
	@CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja $(SANITIZE_FLAGS) >/dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ctest --output-on-failure -j $(JOBS) --repeat until-pass:2 -E '$(SANITIZE_EXCLUDE)'

# libFuzzer harnesses (README "Reliability"), each run for FUZZ_SECONDS, JOBS at a time, in the
# sanitizer build (built by `make sanitize` or here).
# FUZZ_SEED=N makes the run reproducible (a fixed seed and input count per harness): CI's.
FUZZ_SECONDS ?= 60
FUZZ_SEED ?=
fuzz: setup
	@CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja $(SANITIZE_FLAGS) >/dev/null
	@FUZZ_BUILD=build-asan JOBS=$(JOBS) FUZZ_SEED=$(FUZZ_SEED) ./scripts/fuzz.sh $(FUZZ_SECONDS)

# ThreadSanitizer (clang): every test of the unit-test binary, the CLI's and the soak's, with
# the parallel loops on std::threads it can see (math/parallel.h). TSAN_TESTS is a ctest -R
# pattern, TSAN_EXCLUDE a -E one (the layering probes build projects; the fuzz replays run one
# thread and are not built here).
TSAN_TESTS ?= .
TSAN_EXCLUDE ?= ^(layers|fuzz)\.
tsan: setup
	@CC=clang CXX=clang++ cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DQUADTRI_TSAN=ON -DQUADTRI_BENCH=OFF -DQUADTRI_PYTHON=OFF -DCMAKE_UNITY_BUILD=$(UNITY) >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target quadtri_tests quadtri quadtri_soak
	@cd build-tsan && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$(CURDIR)/scripts/tsan.supp" ctest --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)' -E '$(TSAN_EXCLUDE)'

format-check:
	@clang-format --dry-run --Werror $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) build-asan build-tsan out
