# Thin wrapper around CMake. `make demo` and `make test` work on a fresh Debian 12 machine:
# both first install whatever Debian packages are missing.
BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
CMAKE_FLAGS ?=
PREFIX     ?= /usr/local

.PHONY: all build deps demo test test-gpu test-asan fuzz install clean

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

# Every test: the GPU/CLI suite on llvmpipe (or a GPU) in the normal build, and the CPU tests
# again under AddressSanitizer + UndefinedBehaviorSanitizer. The sanitizer tree is also the
# build without the viewer (OB_VIEWER=OFF: no GLFW, no Dear ImGui), so CI configures and builds
# that too.
test: deps build test-asan
	@ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-asan:
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DOB_WERROR=ON -DOB_SANITIZE=ON -DOB_GPU_TESTS=OFF -DOB_VIEWER=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS)
	@ctest --test-dir $(ASAN_BUILD) --output-on-failure -L cpu -j $(JOBS)

# libFuzzer on the model loader and the sidecar parser (clang, ASan + UBSan), FUZZ_SECONDS each;
# crashes land in build-fuzz/crash-*. Not part of `make test`. The model target starts from
# assimp-testmodels and the hostile corpus (tests/fuzz/seed_model_corpus.py).
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 300
fuzz:
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug -DOB_FUZZ=ON -DOB_GPU_TESTS=OFF -DOB_VIEWER=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_model fuzz_sidecar
	@mkdir -p $(FUZZ_BUILD)/corpus-model $(FUZZ_BUILD)/corpus-sidecar
	@cd $(FUZZ_BUILD) && ./fuzz_sidecar -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=2048 corpus-sidecar ../scenes
	@# -detect_leaks=0: Assimp 5.2.5 leaks on some malformed ASCII STL files (its error path, not
	@# ours), which would stop the run at the first one, and LeakSanitizer's report at exit (Assimp's
	@# objects only) would fail the rule; our C code's leaks show in make test-asan.
	@python3 tests/fuzz/seed_model_corpus.py $(FUZZ_BUILD)/seeds-model >/dev/null
	@cd $(FUZZ_BUILD) && ASAN_OPTIONS=detect_leaks=0 ./fuzz_model -max_total_time=$(FUZZ_SECONDS) -detect_leaks=0 -rss_limit_mb=2048 -max_len=65536 corpus-model seeds-model

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
