// The OpenCL device the kernel tests run on, shared by all tests of one executable.
//
//   TEST_CASE("advect: matches the CPU reference") {
//     auto* cc = fw::test::device_or_skip();
//     if (!cc) return;          // no device and not under CI: the test warns and passes nothing
//     ...
//   }
//
// Under CI (the environment variable CI is set) a missing device FAILS the test instead: CI must prove
// the kernels on PoCL. FORESTWIND_DEVICE picks the device, as for the program.
#pragma once

#include "host/runtime/ComputeContext.hpp"

namespace fw::test {

host::ComputeContext* device_or_skip();

}  // namespace fw::test
