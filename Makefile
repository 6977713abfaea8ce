# Thin wrapper around CMake. `make demo` and `make test` work on a fresh Debian 12 machine:
# both first install whatever Debian packages are missing.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
CMAKE_FLAGS ?=
PREFIX     ?= /usr/local

.PHONY: all build deps demo test test-gpu test-asan test-fuzz fuzz fuzz-build install package clean abi-baseline

all: build

build:
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DOB_WERROR=ON $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

deps:
	@scripts/install-deps.sh

demo: deps build
	@scripts/demo.sh $(BUILD)/obscura out

# libobscura (shared), its header, CMake package and obscura.pc, the obscura CLI and the data
# directory (share/obscura) under PREFIX; DESTDIR works as usual.
install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

# Debian packages of this build (CPack): libobscura0.MINOR (the library), libobscura-dev (header,
# CMake package, obscura.pc) and obscura (the CLI, the viewer and the data directory), with their
# dependencies from dpkg-shlibdeps, into $(BUILD)/packages.
package: build
	@cd $(BUILD) && cpack -G DEB -B packages

# Every test: the GPU/CLI suite on llvmpipe (or a GPU) in the normal build, the CPU tests again
# under AddressSanitizer + UndefinedBehaviorSanitizer, and a short libFuzzer run of every parser
# (test-fuzz). The sanitizer tree is also the build without the viewer (OB_VIEWER=OFF: no GLFW, no
# Dear ImGui), so CI configures and builds that too.
test: deps build test-asan test-fuzz
	@ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-asan:
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DOB_WERROR=ON -DOB_SANITIZE=ON -DOB_GPU_TESTS=OFF -DOB_VIEWER=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS)
	@ctest --test-dir $(ASAN_BUILD) --output-on-failure -L cpu -j $(JOBS)

# libFuzzer (clang, ASan + UBSan) on every parser an input reaches: models (fuzz_model), sidecars
# (fuzz_sidecar), their camera paths (fuzz_path), --settings files (fuzz_settings) and the common
# options (fuzz_cli). `make fuzz`: FUZZ_SECONDS each, on corpora kept in build-fuzz/corpus-*;
# crashes land in build-fuzz/crash-*. `make test-fuzz` (in `make test`): each target from its
# committed seeds with a fixed seed and number of runs, at most FUZZ_SMOKE_SECONDS each (about 60 s
# in all), so that a parser that starts crashing fails the tests. tests/fuzz/run.sh says more.
FUZZ_BUILD         ?= build-fuzz
FUZZ_SECONDS       ?= 300
FUZZ_SMOKE_SECONDS ?= 30
FUZZ_TARGETS       := fuzz_model fuzz_sidecar fuzz_path fuzz_settings fuzz_cli
fuzz-build:
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug -DOB_FUZZ=ON -DOB_GPU_TESTS=OFF -DOB_VIEWER=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS)

fuzz: fuzz-build
	@tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

test-fuzz: fuzz-build
	@tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SMOKE_SECONDS) smoke

# The ABI baseline the test `abi` compares libobscura with, remade from this build: after a
# deliberate change of the public ABI, with its docs/changelog.md entry (and, for an incompatible
# change, the version raised: scripts/abi-baseline.sh refuses otherwise).
abi-baseline: build
	@scripts/abi-baseline.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
