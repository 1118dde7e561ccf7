#include "host/runtime/ClError.hpp"

#include <fmt/format.h>

// Through our wrapper, which fixes the OpenCL target version before the first CL header.
#include "host/runtime/opencl.hpp"

#include <CL/cl_ext.h>

namespace fw::host {

std::string cl_status_name(int status) {
  switch (status) {
#define FW_CASE(code) \
  case code:          \
    return #code;
    FW_CASE(CL_SUCCESS)
    FW_CASE(CL_DEVICE_NOT_FOUND)
    FW_CASE(CL_DEVICE_NOT_AVAILABLE)
    FW_CASE(CL_COMPILER_NOT_AVAILABLE)
    FW_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    FW_CASE(CL_OUT_OF_RESOURCES)
    FW_CASE(CL_OUT_OF_HOST_MEMORY)
    FW_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
    FW_CASE(CL_BUILD_PROGRAM_FAILURE)
    FW_CASE(CL_INVALID_VALUE)
    FW_CASE(CL_INVALID_DEVICE)
    FW_CASE(CL_INVALID_CONTEXT)
    FW_CASE(CL_INVALID_COMMAND_QUEUE)
    FW_CASE(CL_INVALID_MEM_OBJECT)
    FW_CASE(CL_INVALID_BUILD_OPTIONS)
    FW_CASE(CL_INVALID_PROGRAM)
    FW_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
    FW_CASE(CL_INVALID_KERNEL_NAME)
    FW_CASE(CL_INVALID_KERNEL)
    FW_CASE(CL_INVALID_ARG_INDEX)
    FW_CASE(CL_INVALID_ARG_VALUE)
    FW_CASE(CL_INVALID_ARG_SIZE)
    FW_CASE(CL_INVALID_KERNEL_ARGS)
    FW_CASE(CL_INVALID_WORK_DIMENSION)
    FW_CASE(CL_INVALID_WORK_GROUP_SIZE)
    FW_CASE(CL_INVALID_WORK_ITEM_SIZE)
    FW_CASE(CL_INVALID_GLOBAL_OFFSET)
    FW_CASE(CL_INVALID_EVENT)
    FW_CASE(CL_INVALID_OPERATION)
    FW_CASE(CL_INVALID_BUFFER_SIZE)
    FW_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
    FW_CASE(CL_PLATFORM_NOT_FOUND_KHR)
#undef FW_CASE
    default:
      return "CL_UNKNOWN_ERROR";
  }
}

ClError::ClError(const std::string& where, int status)
    : std::runtime_error(fmt::format("{}: {} ({})", where, cl_status_name(status), status)),
      status_(status) {}

KernelBuildError::KernelBuildError(const std::string& file, const std::string& log)
    : std::runtime_error(fmt::format("OpenCL build of {} failed:\n{}", file, log)), file_(file), log_(log) {}

}  // namespace fw::host
