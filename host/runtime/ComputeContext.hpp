// One OpenCL device, its context and its in-order queue; builds the programs of kernels/ and launches
// kernels with errors that name the kernel.
//
//   ComputeContext cc(select_device(device_filter_from_env(cli_filter)), /*profiling=*/true);
//   cl::Program prog = cc.build("fluid_project.cl");
//   Kernel divergence(prog, "divergence_rhs");
//   divergence.set_args(grid, mask, u, v, w, b).enqueue(cc, cc.rows(nx, ny, nz));
//
// Work mapping. Kernels that sweep the grid give each work-item a run of `row_chunk()` consecutive cells
// along x: on a CPU (PoCL) the whole x-row (WorkMapping::rows), which streams memory best; on a GPU one cell
// (WorkMapping::cells), for coalescing. The device type picks the mapping; FORESTWIND_WORK_MAPPING=rows|cells
// (or the constructor) forces one, so that CI runs the GPU mapping on PoCL. The chunk and the layout reach
// the kernels as the macros FW_ROW_CHUNK and FW_CPU_LAYOUT. (Advection sets its own range, see
// host/stages/FluidStages.)
//
// Maxima leave one partial per work-group, reduced in local memory: reduction_rows() gives their range,
// padded to whole groups of FW_GROUP_X x FW_GROUP_Y items (1 x 8 rows, or 64 x 1 cells), and the number of
// partials the host then takes the maximum of. (Sums do not: they leave column sums that the host adds
// exactly, so that they do not depend on the groups; see host/stages/PressureSolver.)
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/runtime/Device.hpp"
#include "host/runtime/Profiler.hpp"
#include "host/runtime/opencl.hpp"

namespace fw::host {

enum class WorkMapping { rows, cells };

/// FORESTWIND_WORK_MAPPING: "rows", "cells", or unset/empty (none). Throws std::invalid_argument naming the
/// variable for another value.
std::optional<WorkMapping> work_mapping_from_env();

/// The range of a reduction kernel: global padded to whole work-groups, the group, and how many groups
/// (= partials) there are.
struct ReductionRange {
  cl::NDRange global, local;
  std::size_t groups = 0;
};

class ComputeContext {
 public:
  /// mapping: forced, else work_mapping_from_env(), else rows on a CPU and cells on anything else.
  ComputeContext(DeviceInfo device, bool profiling, std::optional<WorkMapping> mapping = std::nullopt);

  const DeviceInfo& device() const { return device_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  bool is_cpu() const { return device_.type == "CPU"; }
  WorkMapping mapping() const { return mapping_; }
  int row_chunk() const { return row_chunk_; }
  bool profiling() const { return profiler_ != nullptr; }
  Profiler* profiler() { return profiler_.get(); }

  /// Builds kernels/<file> (with its includes). Throws KernelBuildError with the file and the log. What the
  /// compiler prints to stderr meanwhile is shown only if the build fails.
  cl::Program build(const std::string& file, const std::string& extra_options = "");
  /// The same for source text that is not in kernels/; `name` stands for the file in errors.
  cl::Program build_source(const std::string& name, const std::string& source,
                           const std::string& extra_options = "");

  /// When on, a build whose log holds a warning throws KernelBuildError too: the tests' device runs so, so
  /// that the kernels stay free of warnings. The options, and so the compiler's cache, are unchanged (the
  /// log is checked, not -Werror passed: PoCL keeps a cached program's log, so a warm cache still fails).
  void set_warnings_as_errors(bool on) { warnings_as_errors_ = on; }

  /// Global range for a row-sweeping kernel over an array of extent_x * ny * nz values.
  cl::NDRange rows(int extent_x, int ny, int nz) const;
  /// The same sweep for a reduction kernel (see above): items past the array do no work but take part in
  /// their group's reduction.
  ReductionRange reduction_rows(int extent_x, int ny, int nz) const;

  /// Number of work-items a flat (1D) kernel over n values uses, and the values each handles.
  std::size_t flat_items(std::size_t n) const;

  /// The reductions' work-group, x by y items (FW_GROUP_X, FW_GROUP_Y in the kernels).
  std::array<std::size_t, 2> reduction_group() const;

  /// A device buffer of `bytes` (at least kMinimumBufferBytes: OpenCL has no empty buffers).
  cl::Buffer buffer(std::size_t bytes, cl_mem_flags flags = CL_MEM_READ_WRITE);
  /// What buffer(bytes) allocates on the device: the stages' memory estimates count with it.
  static std::size_t allocation_bytes(std::size_t bytes) { return std::max(bytes, kMinimumBufferBytes); }
  /// Bytes of every buffer this context has allocated so far (released ones included): a stage's estimate
  /// is checked against the difference across its constructor.
  std::size_t allocated_bytes() const { return allocated_bytes_; }
  static constexpr std::size_t kMinimumBufferBytes = 4;
  /// A buffer holding `values` (blocking write; an empty vector gives an allocated but unwritten buffer).
  template <typename T>
  cl::Buffer upload(const std::vector<T>& values, cl_mem_flags flags = CL_MEM_READ_WRITE) {
    cl::Buffer b = buffer(values.size() * sizeof(T), flags);
    if (!values.empty()) queue_.enqueueWriteBuffer(b, CL_TRUE, 0, values.size() * sizeof(T), values.data());
    return b;
  }
  /// A buffer of `count` zero floats.
  cl::Buffer zero_floats(std::size_t count);
  void finish() { queue_.finish(); }

 private:
  DeviceInfo device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::unique_ptr<Profiler> profiler_;
  WorkMapping mapping_;
  int row_chunk_;
  std::size_t allocated_bytes_ = 0;
  bool warnings_as_errors_ = false;
};

/// A kernel that knows its name, so failures say which one.
class Kernel {
 public:
  Kernel() = default;
  Kernel(const cl::Program& program, const std::string& name);

  const std::string& name() const { return name_; }

  template <typename... Args>
  Kernel& set_args(const Args&... args) {
    cl_uint index = 0;
    (set_arg(index++, args), ...);
    return *this;
  }

  template <typename T>
  void set_arg(cl_uint index, const T& value) {
    try {
      kernel_.setArg(index, value);
    } catch (const cl::Error& e) {
      throw_arg_error(index, e.err());
    }
  }

  void enqueue(ComputeContext& cc, const cl::NDRange& global, const cl::NDRange& local = cl::NullRange);

  /// The largest work-group this kernel can run with on cc's device (CL_KERNEL_WORK_GROUP_SIZE).
  std::size_t max_group_size(const ComputeContext& cc) const;

 private:
  [[noreturn]] void throw_arg_error(cl_uint index, int status) const;
  cl::Kernel kernel_;
  std::string name_;
};

}  // namespace fw::host
