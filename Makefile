# Two entry points for a new user (see README.md):
#   make demo   installs dependencies, builds, renders/analyses the default scene into out/
#   make test   installs dependencies, builds and runs every test
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: setup build demo test sanitize fuzz tsan format-check clean

setup:
	@./scripts/setup.sh

build: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@./scripts/demo.sh $(BUILD)/src/cli/quadtri out

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

sanitize: setup
	@cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQUADTRI_SANITIZE=ON -DQUADTRI_BENCH=OFF >/dev/null
	@cmake --build build-asan -j $(JOBS)
	@cd build-asan && ctest --output-on-failure -j $(JOBS)

# libFuzzer harnesses (README "Reliability"), each run for FUZZ_SECONDS.
FUZZ_SECONDS ?= 60
fuzz: setup
	@JOBS=$(JOBS) ./scripts/fuzz.sh $(FUZZ_SECONDS)

# ThreadSanitizer (clang): the tests that run threads (tile scheduler, progress bar, adaptive
# sampler, parallel conversion, studies). TSAN_TESTS is a ctest -R pattern.
TSAN_TESTS ?= ^(Renderer|SceneRenderTest|RenderScene|Study|ConvertOutput|StopSignals|AtomicFile|CrackRate|Metrics|Convergence|RenderCheckpoint|RenderSignals)\.
tsan: setup
	@CC=clang CXX=clang++ cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQUADTRI_TSAN=ON -DQUADTRI_BENCH=OFF -DQUADTRI_PYTHON=OFF >/dev/null
	@cmake --build build-tsan -j $(JOBS) --target quadtri_tests quadtri
	@cd build-tsan && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$(CURDIR)/scripts/tsan.supp" ctest --output-on-failure -j $(JOBS) -R '$(TSAN_TESTS)'

format-check:
	@clang-format --dry-run --Werror $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) build-asan build-fuzz build-tsan out
