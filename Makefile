# geardyn quick start:  make demo  |  make test
# Both install the dependencies (scripts/install-deps, idempotent), configure and build.
BUILD ?= build
JOBS ?= $(shell nproc)
# WERROR=ON|OFF sets GEARDYN_WERROR; when not given the build folder keeps its setting (so
# `make demo` after `make test WERROR=ON` does not rebuild everything).
WERROR ?=
WERROR_FLAG = $(if $(WERROR),-DGEARDYN_WERROR=$(WERROR),)
CMAKE_FLAGS ?=
DEMO_MODEL ?= examples/geared_rotor_hcf/model.toml
DEMO_OUT ?= results/geared_rotor_hcf

.PHONY: all deps build demo test test-all test-slow sanitize fuzz bench format clean

all: build

deps:
	./scripts/install-deps

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(WERROR_FLAG) $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	cmake $(WERROR_FLAG) $(BUILD) >/dev/null
	cmake --build $(BUILD) -j $(JOBS)

# The program's last line is "Report: <absolute path>/report.html".
demo: build
	$(BUILD)/apps/geardyn/geardyn run $(DEMO_MODEL) -o $(DEMO_OUT)

# Default test run: unit + validation (slow tests excluded).
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE slow

test-slow: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L slow

test-all: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# AddressSanitizer + UndefinedBehaviorSanitizer build and full test run.
sanitize: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARDYN_SANITIZE=ON -DGEARDYN_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS)

FUZZ_SECONDS ?= 60
# libFuzzer (clang) on the model parser (validation, assembly) and the mesh, matrix and gear CSV
# readers, FUZZ_SECONDS each.
fuzz: deps
	for t in model nastran matrix_market gear_csv; do FUZZ_TARGET=$$t ./scripts/run-fuzz $(FUZZ_SECONDS) || exit $$?; done

bench: build
	$(BUILD)/bench/geardyn_bench --benchmark_min_time=0.2

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) build-asan build-fuzz
