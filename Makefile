# The two set-up commands of the README:
#   make demo   installs the Debian packages, builds, runs the demo (scenarios/storm.yaml into out/storm) and
#               draws its last frame and its probes
#   make test   installs the Debian packages, checks the formatting of the tracked sources (clang-format),
#               builds (compiler warnings as errors under CI), and runs every test through CTest
#   make validate   builds and runs the long validations (tests/validation) that CI runs in short form
BUILD_DIR ?= build
BUILD_TYPE ?= Release
# Compiler warnings as errors: on under CI (the variable CI is set), off otherwise, so that a user's newer
# compiler only warns. Changing it rebuilds everything.
WERROR ?= $(if $(CI),ON,OFF)
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: deps configure build build-cli test validate demo format format-check clean

deps:
	$(SUDO) bash scripts/install-deps.sh

configure:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DFORESTWIND_WERROR=$(WERROR)

build: configure
	cmake --build $(BUILD_DIR)

# Only the binary, for the demo: no test is built.
build-cli: configure
	cmake --build $(BUILD_DIR) --target forestwind

test: deps format-check build
	ctest --test-dir $(BUILD_DIR) --output-on-failure

validate: build
	FORESTWIND_VALIDATION=full $(BUILD_DIR)/validation_tests "[validation]"

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
