// The one place that includes the Khronos C++ bindings, so every file agrees on the target version.
// Debian's opencl.hpp does not compile with target 300 and minimum 120, so both are pinned to 1.2.
#pragma once

#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>
