# The two set-up commands of the README:
#   make demo   installs the Debian packages, builds, and runs the demo: scenarios/storm.yaml into out/storm
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

demo: deps build
	$(BUILD_DIR)/forestwind run scenarios/storm.yaml

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp' '*.h' '*.cl')

clean:
	rm -rf $(BUILD_DIR)
