#include "host/runtime/ComputeContext.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "host/runtime/ClError.hpp"
#include "host/runtime/KernelSources.hpp"
#include "host/runtime/StderrCapture.hpp"

namespace fw::host {

namespace {

// Work-group shape of the reductions (header): 8 rows on the rows mapping (few groups, so PoCL's per-group
// cost stays small), 64 cells on the cells mapping (two warps, a common GPU reduction width). Powers of two:
// the group is summed as a tree.
constexpr int kRowsPerGroup = 8, kCellsPerGroup = 64;

std::size_t round_up(std::size_t n, std::size_t to) {
  return (n + to - 1) / to * to;
}

}  // namespace

std::optional<WorkMapping> work_mapping_from_env() {
  const char* value = std::getenv("FORESTWIND_WORK_MAPPING");
  if (!value || !*value) return std::nullopt;
  const std::string text = value;
  if (text == "rows") return WorkMapping::rows;
  if (text == "cells") return WorkMapping::cells;
  throw std::invalid_argument(
      fmt::format("FORESTWIND_WORK_MAPPING: expected rows or cells (or unset), got '{}'", text));
}

ComputeContext::ComputeContext(DeviceInfo device, bool profiling, std::optional<WorkMapping> mapping)
    : device_(std::move(device)) {
  try {
    context_ = cl::Context(device_.device);
    queue_ = cl::CommandQueue(context_, device_.device, profiling ? CL_QUEUE_PROFILING_ENABLE : 0);
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("creating a context on '{}' ({})", device_.device_name, e.what()), e.err());
  }
  if (profiling) profiler_ = std::make_unique<Profiler>();
  mapping_ = mapping ? *mapping
                     : work_mapping_from_env().value_or(is_cpu() ? WorkMapping::rows : WorkMapping::cells);
  // A whole x-row per work-item on the rows mapping (see header); rows are never longer than this.
  row_chunk_ = mapping_ == WorkMapping::rows ? (1 << 20) : 1;
}

cl::Program ComputeContext::build(const std::string& file, const std::string& extra_options) {
  return build_source(file, kernel_source(file), extra_options);
}

cl::Program ComputeContext::build_source(const std::string& name, const std::string& source,
                                         const std::string& extra_options) {
  cl::Program program(context_, source);
  const auto [group_x, group_y] = reduction_group();
  const std::string options =
      fmt::format("-cl-std=CL1.2 -DFW_ROW_CHUNK={} -DFW_CPU_LAYOUT={} -DFW_GROUP_X={} -DFW_GROUP_Y={} {}",
                  row_chunk_, mapping_ == WorkMapping::rows ? 1 : 0, group_x, group_y, extra_options);
  const auto build_log = [&] {
    try {
      return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_.device);
    } catch (const cl::Error&) {
      return std::string();
    }
  };
  // The compiler's chatter on stderr is held back and shown only with a failure (see StderrCapture).
  StderrCapture chatter;
  try {
    program.build({device_.device}, options.c_str());
  } catch (const cl::Error& e) {
    throw KernelBuildError(name, fmt::format("{} ({})\n{}{}", cl_status_name(e.err()), e.what(), build_log(),
                                             chatter.release()));
  }
  chatter.release();
  if (warnings_as_errors_) {
    const std::string log = build_log();
    if (log.find("warning") != std::string::npos)
      throw KernelBuildError(name, "a warning, and this context treats warnings as errors:\n" + log);
  }
  return program;
}

cl::Buffer ComputeContext::zero_floats(std::size_t count) {
  cl::Buffer b = buffer(count * sizeof(float));
  if (count > 0) queue_.enqueueFillBuffer(b, 0.0f, 0, count * sizeof(float));
  return b;
}

cl::NDRange ComputeContext::rows(int extent_x, int ny, int nz) const {
  const int items_x = (extent_x + row_chunk_ - 1) / row_chunk_;
  return cl::NDRange(static_cast<std::size_t>(items_x), static_cast<std::size_t>(ny),
                     static_cast<std::size_t>(nz));
}

std::array<std::size_t, 2> ComputeContext::reduction_group() const {
  return mapping_ == WorkMapping::rows ? std::array<std::size_t, 2>{1, kRowsPerGroup}
                                       : std::array<std::size_t, 2>{kCellsPerGroup, 1};
}

ReductionRange ComputeContext::reduction_rows(int extent_x, int ny, int nz) const {
  const auto [group_x, group_y] = reduction_group();
  const cl::NDRange r = this->rows(extent_x, ny, nz);
  const std::size_t gx = round_up(r[0], group_x), gy = round_up(r[1], group_y);
  return {cl::NDRange(gx, gy, r[2]), cl::NDRange(group_x, group_y, 1),
          (gx / group_x) * (gy / group_y) * r[2]};
}

std::size_t ComputeContext::flat_items(std::size_t n) const {
  // Rows mapping: a few contiguous blocks per core; cells: enough items to fill the device, each striding.
  const std::size_t items = mapping_ == WorkMapping::rows ? std::size_t(device_.compute_units) * 64
                                                          : std::size_t(device_.compute_units) * 2048;
  return std::max<std::size_t>(1, std::min(n, items));
}

cl::Buffer ComputeContext::buffer(std::size_t bytes, cl_mem_flags flags) {
  try {
    cl::Buffer buffer(context_, flags, allocation_bytes(bytes));
    allocated_bytes_ += allocation_bytes(bytes);
    return buffer;
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("allocating {} bytes on '{}'", bytes, device_.device_name), e.err());
  }
}

Kernel::Kernel(const cl::Program& program, const std::string& name) : name_(name) {
  try {
    kernel_ = cl::Kernel(program, name.c_str());
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("creating kernel {}", name), e.err());
  }
}

void Kernel::throw_arg_error(cl_uint index, int status) const {
  throw ClError(fmt::format("kernel {}: setting argument {}", name_, index), status);
}

void Kernel::enqueue(ComputeContext& cc, const cl::NDRange& global, const cl::NDRange& local) {
  try {
    if (cc.profiling()) {
      cl::Event event;
      cc.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, global, local, nullptr, &event);
      cc.profiler()->record(name_, event);
    } else {
      cc.queue().enqueueNDRangeKernel(kernel_, cl::NullRange, global, local);
    }
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("enqueue kernel {}", name_), e.err());
  }
}

std::size_t Kernel::max_group_size(const ComputeContext& cc) const {
  try {
    return kernel_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(cc.device().device);
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("kernel {}: querying its work-group size", name_), e.err());
  }
}

}  // namespace fw::host
