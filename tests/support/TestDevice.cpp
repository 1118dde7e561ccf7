#include "tests/support/TestDevice.hpp"

// Catch's event listeners (GuardBandCheck below) are declared only with this.
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "host/runtime/ClError.hpp"
#include "host/runtime/Device.hpp"

namespace fw::test {

namespace {
// The test binary's device, made on the first call of device_or_skip().
std::unique_ptr<host::ComputeContext> context;
}  // namespace

host::ComputeContext* device_or_skip() {
  static std::string failure;
  static bool tried = false;
  if (!tried) {
    tried = true;
    try {
      context = std::make_unique<host::ComputeContext>(host::select_device(host::device_filter_from_env("")),
                                                       false);
      // Every program a test builds must build without a warning (docs/design.md, "Kernels").
      context->set_warnings_as_errors(true);
      // And no kernel may write past its arrays: GuardBandCheck below reads the bands after each test case.
      context->set_guard_bands(true);
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }
  if (context) return context.get();
  if (std::getenv("CI") != nullptr) FAIL("no OpenCL device under CI: " << failure);
  WARN("no OpenCL device, kernel test not run: " << failure);
  return nullptr;
}

namespace {

// After each test case, the guard bands of every buffer it allocated on the shared device: a kernel that
// wrote past its array (an item past a range rounded up to whole work-groups, without its bounds guard)
// aborts the test binary, naming the buffers. A listener cannot fail the test case itself, and CTest runs
// each test case in a process of its own, so the abort fails exactly that test.
struct GuardBandCheck : Catch::TestEventListenerBase {
  using TestEventListenerBase::TestEventListenerBase;
  void testCaseEnded(const Catch::TestCaseStats& stats) override {
    if (!context) return;
    const std::vector<std::string> breaches = context->guard_band_breaches();
    if (breaches.empty()) return;
    std::cerr << "\n" << stats.testInfo.name << ": a kernel wrote past the end of a buffer:\n";
    for (const std::string& breach : breaches) std::cerr << "  " << breach << "\n";
    std::abort();
  }
};
CATCH_REGISTER_LISTENER(GuardBandCheck)

}  // namespace

}  // namespace fw::test
