# The two set-up commands of the README:
#   make demo   installs the Debian packages, builds, runs the demo (scenarios/storm.yaml into out/storm) and
#               draws its last frame and its probes
#   make test   the fast tier, CI's: installs the Debian packages, checks the formatting of the tracked sources
#               (clang-format), builds (compiler warnings as errors under CI), runs every CTest test (unit,
#               kernel under both work mappings, CLI, MPI at 1, 2 and 4 ranks, the replay of every fuzz seed
#               and regression) and prints the 15 slowest; about 13 minutes from a fresh clone on 2 cores
# The long tier, each on demand (README, "Tests"):
#   make fuzz       builds the fuzz targets (tests/fuzz) with clang and runs each for FUZZ_SECONDS (FUZZ_SEED=N:
#                   repeatably, from the tracked seeds)
#   make sanitize   builds the host and kernel tests with ASan + UBSan (clang, the fuzz build) and runs them
#   make validate   builds and runs the long validations (tests/validation) that CTest runs in short form
#   make scaling    bench wind and bench coupled over 1, 2 and 4 MPI ranks
#   make fuzz-check the mutation fuzz of `forestwind check` (tests/fuzz/check_mutants.py): MUTANTS of the
#                   example scenarios, each with one number swapped for an extreme
#   make test-long  all five
BUILD_DIR ?= build
BUILD_TYPE ?= Release
# Compiler warnings as errors: on under CI (the variable CI is set), off otherwise, so that a user's newer
# compiler only warns. Changing it rebuilds everything.
WERROR ?= $(if $(CI),ON,OFF)
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: deps configure build build-cli test test-long validate scaling demo format format-check clean \
        fuzz-configure fuzz sanitize fuzz-check

deps:
	$(SUDO) bash scripts/install-deps.sh

configure:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFORESTWIND_WERROR=$(WERROR)

build: configure
	cmake --build $(BUILD_DIR)

# Only the binary, for the demo: no test is built.
build-cli: configure
	cmake --build $(BUILD_DIR) --target forestwind

# CTest runs CTEST_JOBS tests at once (one a core: much of a test is one thread, a program's compile or the
# host's work; the MPI tests and the validations take the cores they use, CMakeLists.txt). Its results go
# to $(BUILD_DIR)/ctest-junit.xml, from which the 15 slowest tests are printed, pass or fail; the fast tier
# keeps every test under a minute (docs/testing.md). CTEST_FLAGS adds options (-R ..., --repeat ...).
CTEST_JOBS ?= $(shell nproc)
CTEST_FLAGS ?=
test: deps format-check build
	@status=0; ctest --test-dir $(BUILD_DIR) --output-on-failure --output-junit ctest-junit.xml \
	  -j $(CTEST_JOBS) $(CTEST_FLAGS) || status=$$?; \
	python3 scripts/slowest-tests.py $(BUILD_DIR)/ctest-junit.xml 15; exit $$status

test-long: fuzz sanitize validate scaling fuzz-check

# Every [validation] test case at its long length (FORESTWIND_VALIDATION=full; CTest runs the same cases short):
# the periodic canopies, decaying turbulence, the tree models, and storm damage (tests/validation/Damage_test.cpp:
# Hale's relation over an hour in three stands, the edge behind a clearing, the gap; docs/damage-validation.md).
# The scanned tree needs FORESTWIND_QSM_TREE and is left out.
validate: build
	FORESTWIND_VALIDATION=full $(BUILD_DIR)/validation_tests "[validation]~[scanned]"

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

# Issue 44 (docs/fuzzing.md, "The mutation fuzz of check"): exits 1 on a mutant that check answers with exit 1,
# a signal, an exit 2 without FILE:LINE: KEY, or not within MUTANT_SECONDS of CPU time; names each.
MUTANTS ?= 3000
MUTANT_SEED ?= 44
MUTANT_SECONDS ?= 5
fuzz-check: build-cli
	python3 tests/fuzz/check_mutants.py --forestwind $(BUILD_DIR)/forestwind --count $(MUTANTS) \
	  --seed $(MUTANT_SEED) --timeout $(MUTANT_SECONDS) --keep $(BUILD_DIR)/fuzz-check scenarios/*.yaml

sanitize: fuzz-configure
	cmake --build $(FUZZ_DIR) --target $(SANITIZE_TESTS)
	set -e; for t in $(SANITIZE_TESTS); do echo "== $$t"; CI=true $(SANITIZE_ENV) $(FUZZ_DIR)/$$t; done

DEMO_OUT := out/storm

# The scaling runs (docs/parallel.md, "Benchmarks over ranks"): each rank's step and halo and the weak-scaling
# estimate, printed and kept in $(SCALING_DIR) (bench-wind-N.txt, bench-coupled-N.txt).
SCALING_DIR ?= out/scaling
SCALING_RANKS ?= 1 2 4
MPIRUN = OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe
scaling: build-cli
	mkdir -p $(SCALING_DIR)
	set -e; for n in $(SCALING_RANKS); do for what in wind coupled; do \
	  echo "== forestwind bench $$what over $$n ranks"; \
	  $(MPIRUN) -np $$n $(BUILD_DIR)/forestwind bench $$what | tee $(SCALING_DIR)/bench-$$what-$$n.txt; \
	done; done

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
