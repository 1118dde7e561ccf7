# The two set-up commands of the README:
#   make demo   installs the Debian packages, builds, runs the demo (scenarios/storm.yaml into out/storm) and
#               draws its last frame and its probes
#   make test   installs the Debian packages, checks the formatting of the tracked sources (clang-format),
#               builds (compiler warnings as errors under CI), runs every test through CTest, and then
#               every fuzz target for 10 s (repeatably: seed 1, from the tracked seeds)
#   make validate   builds and runs the long validations (tests/validation) that CI runs in short form
#   make fuzz       builds the fuzz targets (tests/fuzz) with clang and runs each for FUZZ_SECONDS (FUZZ_SEED=N:
#                   repeatably, from the tracked seeds)
#   make sanitize   builds the host tests with ASan + UBSan (clang, the fuzz build) and runs them
BUILD_DIR ?= build
BUILD_TYPE ?= Release
# Compiler warnings as errors: on under CI (the variable CI is set), off otherwise, so that a user's newer
# compiler only warns. Changing it rebuilds everything.
WERROR ?= $(if $(CI),ON,OFF)
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: deps configure build build-cli test validate demo format format-check clean fuzz-configure fuzz sanitize

deps:
	$(SUDO) bash scripts/install-deps.sh

configure:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFORESTWIND_WERROR=$(WERROR)

build: configure
	cmake --build $(BUILD_DIR)

# Only the binary, for the demo: no test is built.
build-cli: configure
	cmake --build $(BUILD_DIR) --target forestwind

# Then every fuzz target briefly (TEST_FUZZ_SECONDS each): a reader change that crashes near the seeds stops CI.
# The run is repeatable (seed TEST_FUZZ_SEED, from the tracked seeds only): what it finds, `make fuzz
# FUZZ_SEED=1` finds too, and it is not red at random (docs/fuzzing.md).
TEST_FUZZ_SECONDS ?= 10
TEST_FUZZ_SEED ?= 1
test: deps format-check build
	ctest --test-dir $(BUILD_DIR) --output-on-failure
	$(MAKE) fuzz FUZZ_SECONDS=$(TEST_FUZZ_SECONDS) FUZZ_SEED=$(TEST_FUZZ_SEED)

validate: build
	FORESTWIND_VALIDATION=full $(BUILD_DIR)/validation_tests "[validation]"

# --- fuzzing and sanitizers (docs/fuzzing.md): one clang build with ASan + UBSan + fuzzer coverage -----
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
# Empty: each run draws new mutations and grows the working corpus in $(FUZZ_DIR)/fuzz/corpus. A number: a
# repeatable run from the tracked seeds (tests/fuzz/run.sh).
FUZZ_SEED ?=
# The host tests, and the kernel tests, whose PoCL runs under ASan too (docs/fuzzing.md).
SANITIZE_TESTS ?= base_tests fluid_tests trees_tests host_tests io_tests viz_tests kernel_tests
# Leaks are reported (LeakSanitizer) except the third-party ones tests/fuzz/lsan.supp lists.
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp \
               UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# -O1 and line tables: what the sanitizers' reports need, built much faster than -O3 with full debug info.
fuzz-configure:
	cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DFORESTWIND_FUZZ=ON \
	  -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -gline-tables-only" -DFORESTWIND_WERROR=$(WERROR)

# Exits non-zero when a target finds a crash, a hang or a huge allocation; names the artifacts' folder.
fuzz: fuzz-configure
	cmake --build $(FUZZ_DIR) --target fuzz
	FUZZ_SEED=$(FUZZ_SEED) bash tests/fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS)

sanitize: fuzz-configure
	cmake --build $(FUZZ_DIR) --target $(SANITIZE_TESTS)
	set -e; for t in $(SANITIZE_TESTS); do echo "== $$t"; CI=true $(SANITIZE_ENV) $(FUZZ_DIR)/$$t; done

DEMO_OUT := out/storm

demo: deps build-cli
	$(BUILD_DIR)/forestwind run scenarios/storm.yaml
	$(BUILD_DIR)/forestwind render $(DEMO_OUT) -o $(DEMO_OUT)/storm.png
	$(BUILD_DIR)/forestwind plot $(DEMO_OUT) --spectrum -o $(DEMO_OUT)/probes.png
	@echo "picture: $(DEMO_OUT)/storm.png   probes: $(DEMO_OUT)/probes.png   ParaView: paraview --script=$(DEMO_OUT)/view.py"

SOURCES = $$(git ls-files '*.cpp' '*.hpp' '*.h' '*.cl')

format:
	clang-format -i $(SOURCES)

# Fails, naming the file and line, when a tracked source differs from what clang-format would write.
format-check:
	clang-format --dry-run --Werror $(SOURCES)

clean:
	rm -rf $(BUILD_DIR)
