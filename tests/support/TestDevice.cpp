#include "tests/support/TestDevice.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <memory>
#include <string>

#include "host/runtime/ClError.hpp"
#include "host/runtime/Device.hpp"

namespace fw::test {

host::ComputeContext* device_or_skip() {
  static std::unique_ptr<host::ComputeContext> context;
  static std::string failure;
  static bool tried = false;
  if (!tried) {
    tried = true;
    try {
      context = std::make_unique<host::ComputeContext>(host::select_device(host::device_filter_from_env("")),
                                                       false);
      // Every program a test builds must build without a warning (docs/design.md, "Kernels").
      context->set_warnings_as_errors(true);
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  if (context) return context.get();
  if (std::getenv("CI") != nullptr) FAIL("no OpenCL device under CI: " << failure);
  WARN("no OpenCL device, kernel test not run: " << failure);
  return nullptr;
}

}  // namespace fw::test
