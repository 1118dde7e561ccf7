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

// Work-group shape of the reductions (header): 8 rows on the rows mapping (a partial for every 8 rows), 64
// cells on the cells mapping (two warps, a common GPU reduction width). Powers of two: the group is summed
// as a tree.
constexpr std::size_t kReductionRows = 8, kReductionCells = 64;

std::size_t round_up(std::size_t n, std::size_t to) {
  return (n + to - 1) / to * to;
}

// The guard bands' byte: neither 0 nor a float a kernel is likely to write there by chance.
constexpr cl_uchar kGuardBandPattern = 0xA5;

bool is_power_of_two(std::size_t n) {
  return n > 0 && (n & (n - 1)) == 0;
}

}  // namespace

cl::NDRange work_group_shape(WorkMapping mapping, cl_uint dims, std::size_t preferred_multiple,
                             std::size_t max_items, RowItems items) {
  if (dims < 1 || dims > 3) throw std::invalid_argument(fmt::format("work_group_shape: {} dimensions", dims));
  std::array<std::size_t, 3> shape{1, 1, 1};
  if (mapping == WorkMapping::rows) {
    shape[dims == 3 && items == RowItems::runs ? 1 : 0] = kRowsGroupItems;
  } else if (dims == 1) {
    shape[0] = kCellsGroupItems;
  } else {
    shape[0] = is_power_of_two(preferred_multiple) ? std::min(preferred_multiple, kCellsGroupItems) : 1;
    shape[1] = kCellsGroupItems / shape[0];
  }
  // A kernel of many registers may run smaller groups: halve y, then x (powers of two stay powers of two).
  while (shape[0] * shape[1] > std::max<std::size_t>(max_items, 1)) (shape[1] > 1 ? shape[1] : shape[0]) /= 2;
  if (dims == 1) return cl::NDRange(shape[0]);
  if (dims == 2) return cl::NDRange(shape[0], shape[1]);
  return cl::NDRange(shape[0], shape[1], shape[2]);
}

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
  return mapping_ == WorkMapping::rows ? std::array<std::size_t, 2>{1, kReductionRows}
                                       : std::array<std::size_t, 2>{kReductionCells, 1};
}

ReductionRange ComputeContext::reduction_rows(int extent_x, int ny, int nz) const {
  const auto [group_x, group_y] = reduction_group();
  const cl::NDRange r = this->rows(extent_x, ny, nz);
  const std::size_t gx = round_up(r[0], group_x), gy = round_up(r[1], group_y);
  return {cl::NDRange(gx, gy, r[2]), cl::NDRange(group_x, group_y, 1),
          (gx / group_x) * (gy / group_y) * r[2]};
}

std::size_t ComputeContext::reduction_groups_bound(int extent_x, int ny, int nz) {
  const std::size_t rows_groups =
      std::size_t(extent_x) * round_up(std::size_t(ny), kReductionRows) / kReductionRows * std::size_t(nz);
  const std::size_t cells_groups =
      round_up(std::size_t(extent_x), kReductionCells) / kReductionCells * std::size_t(ny) * std::size_t(nz);
  return std::max(rows_groups, cells_groups);
}

std::size_t ComputeContext::flat_items(std::size_t n) const {
  // Rows mapping: a few contiguous blocks per core; cells: enough items to fill the device, each striding.
  const std::size_t items = mapping_ == WorkMapping::rows ? std::size_t(device_.compute_units) * 64
                                                          : std::size_t(device_.compute_units) * 2048;
  return round_up(std::max<std::size_t>(1, std::min(n, items)), flat_group());
}

std::size_t ComputeContext::flat_group() const {
  // Any kernel's one-dimensional group divides this one (work_group_shape: powers of two, only halved).
  return work_group_shape(mapping_, 1, 1, kCellsGroupItems)[0];
}

cl::Buffer ComputeContext::buffer(std::size_t bytes, cl_mem_flags flags) {
  try {
    allocated_bytes_ += allocation_bytes(bytes);
    if (!guard_bands_) return cl::Buffer(context_, flags, allocation_bytes(bytes));
    // The band follows the array in one allocation, and the caller gets the array alone as a sub-buffer, so
    // that its size (CL_MEM_SIZE, which saved states read) is the one asked for.
    const std::size_t array_bytes = allocation_bytes(bytes);
    cl::Buffer whole(context_, flags, array_bytes + kGuardBandBytes);
    queue_.enqueueFillBuffer(whole, kGuardBandPattern, array_bytes, kGuardBandBytes);
    guarded_.push_back({whole, array_bytes, ++guarded_count_});
    const cl_buffer_region array{0, array_bytes};
    return whole.createSubBuffer(0, CL_BUFFER_CREATE_TYPE_REGION, &array);
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("allocating {} bytes on '{}'", bytes, device_.device_name), e.err());
  }
}

std::vector<std::string> ComputeContext::guard_band_breaches() {
  std::vector<std::string> breaches;
  std::vector<cl_uchar> band(kGuardBandBytes);
  for (const GuardedBuffer& g : guarded_) {
    try {
      queue_.enqueueReadBuffer(g.buffer, CL_TRUE, g.bytes, band.size(), band.data());
    } catch (const cl::Error& e) {
      throw ClError(fmt::format("reading the guard band of buffer {}", g.ordinal), e.err());
    }
    const auto written =
        std::find_if(band.begin(), band.end(), [](cl_uchar b) { return b != kGuardBandPattern; });
    if (written != band.end())
      breaches.push_back(fmt::format("buffer {} of {} bytes: written at byte {} past its end", g.ordinal,
                                     g.bytes, written - band.begin()));
  }
  guarded_.clear();
  return breaches;
}

Kernel::Kernel(const cl::Program& program, const std::string& name, RowItems items)
    : name_(name), items_(items) {
  try {
    kernel_ = cl::Kernel(program, name.c_str());
  } catch (const cl::Error& e) {
    throw ClError(fmt::format("creating kernel {}", name), e.err());
  }
}

void Kernel::throw_arg_error(cl_uint index, int status) const {
  throw ClError(fmt::format("kernel {}: setting argument {}", name_, index), status);
}

cl::NDRange Kernel::group_shape(const ComputeContext& cc, cl_uint dims) {
  if (dims < 1 || dims > 3)
    throw std::invalid_argument(fmt::format("kernel {}: a range of {} dimensions", name_, dims));
  cl::NDRange& shape = group_shapes_[dims - 1];
  if (shape.dimensions() == 0) {
    std::size_t multiple = 1;
    try {
      multiple = kernel_.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(cc.device().device);
    } catch (const cl::Error& e) {
      throw ClError(fmt::format("kernel {}: querying its preferred work-group multiple", name_), e.err());
    }
    shape = work_group_shape(cc.mapping(), dims, multiple, max_group_size(cc), items_);
  }
  return shape;
}

void Kernel::enqueue(ComputeContext& cc, const cl::NDRange& items) {
  enqueue_from(cc, cl::NullRange, items);
}

void Kernel::enqueue_from(ComputeContext& cc, const cl::NDRange& first, const cl::NDRange& items) {
  const cl::NDRange local = group_shape(cc, items.dimensions());
  std::array<std::size_t, 3> global{};
  for (cl_uint a = 0; a < items.dimensions(); ++a) global[a] = round_up(items[a], local[a]);
  if (items.dimensions() == 1) return enqueue(cc, cl::NDRange(global[0]), local, first);
  if (items.dimensions() == 2) return enqueue(cc, cl::NDRange(global[0], global[1]), local, first);
  enqueue(cc, cl::NDRange(global[0], global[1], global[2]), local, first);
}

void Kernel::enqueue(ComputeContext& cc, const cl::NDRange& global, const cl::NDRange& local,
                     const cl::NDRange& first) {
  try {
    if (cc.profiling()) {
      cl::Event event;
      cc.queue().enqueueNDRangeKernel(kernel_, first, global, local, nullptr, &event);
      cc.profiler()->record(name_, event);
    } else {
      cc.queue().enqueueNDRangeKernel(kernel_, first, global, local);
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
