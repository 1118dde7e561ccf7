# The two set-up commands of the README:
#   make demo   installs the Debian packages, builds, runs the demo (scenarios/storm.yaml into out/storm) and
#               draws its last frame and its probes
#   make test   installs the Debian packages, builds, and runs every test through CTest
#   make validate   builds and runs the long validations (tests/validation) that CI runs in short form
BUILD_DIR ?= build
BUILD_TYPE ?= Release
SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: deps build test validate demo format clean

deps:
	$(SUDO) bash scripts/install-deps.sh

build:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)
	cmake --build $(BUILD_DIR)

test: deps build
	ctest --test-dir $(BUILD_DIR) --output-on-failure

validate: build
	FORESTWIND_VALIDATION=full $(BUILD_DIR)/validation_tests "[validation]"

DEMO_OUT := out/storm

demo: deps build
	$(BUILD_DIR)/forestwind run scenarios/storm.yaml
	$(BUILD_DIR)/forestwind render $(DEMO_OUT) -o $(DEMO_OUT)/storm.png
	$(BUILD_DIR)/forestwind plot $(DEMO_OUT) --spectrum -o $(DEMO_OUT)/probes.png
	@echo "picture: $(DEMO_OUT)/storm.png   probes: $(DEMO_OUT)/probes.png   ParaView: paraview --script=$(DEMO_OUT)/view.py"

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp' '*.h' '*.cl')

clean:
	rm -rf $(BUILD_DIR)
