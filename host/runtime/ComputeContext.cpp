#include "host/runtime/ComputeContext.hpp"

#include <fmt/format.h>

#include "host/runtime/ClError.hpp"
#include "host/runtime/KernelSources.hpp"

namespace fw::host {

ComputeContext::ComputeContext(DeviceInfo device, bool profiling) : device_(std::move(device)) {
  try {
    context_ = cl::Context(device_.device);
    queue_ = cl::CommandQueue(context_, device_.device, profiling ? CL_QUEUE_PROFILING_ENABLE : 0);
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("creating a context on '{}' ({})", device_.device_name, e.what()), e.err());
  }
  if (profiling) profiler_ = std::make_unique<Profiler>();
  // A whole x-row per work-item on CPUs (see header); rows are never longer than this.
  row_chunk_ = is_cpu() ? (1 << 20) : 1;
}

cl::Program ComputeContext::build(const std::string& file, const std::string& extra_options) {
  const std::string source = kernel_source(file);
  cl::Program program(context_, source);
  const std::string options = fmt::format("-cl-std=CL1.2 -DFW_ROW_CHUNK={} -DFW_CPU_LAYOUT={} {}", row_chunk_,
                                          is_cpu() ? 1 : 0, extra_options);
  try {
    program.build({device_.device}, options.c_str());
  } catch (const cl::BuildError& e) {
    std::string log;
    for (const auto& [dev, text] : e.getBuildLog()) log += text;
    throw KernelBuildError(file, log);
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_.device);
    } catch (const cl::Error&) {
    }
    throw KernelBuildError(file, fmt::format("{} ({})\n{}", cl_status_name(e.err()), e.what(), log));
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

std::size_t ComputeContext::flat_items(std::size_t n) const {
  // CPU: a few contiguous blocks per core; GPU: enough items to fill the device, each striding.
  const std::size_t items =
      is_cpu() ? std::size_t(device_.compute_units) * 64 : std::size_t(device_.compute_units) * 2048;
  return std::max<std::size_t>(1, std::min(n, items));
}

cl::Buffer ComputeContext::buffer(std::size_t bytes, cl_mem_flags flags) {
  try {
    return cl::Buffer(context_, flags, std::max<std::size_t>(bytes, 4));
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

}  // namespace fw::host
