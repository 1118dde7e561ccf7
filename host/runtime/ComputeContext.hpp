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
// Work-groups. Every launch has an explicit work-group, chosen once per kernel and device
// (work_group_shape): 32 rows or items on the rows mapping, where an item already holds a whole row or block,
// and kCellsGroupItems items on the cells mapping, x a multiple of the kernel's preferred multiple (a warp).
// Kernel::enqueue rounds the range up to whole groups, and every kernel leaves the items past its array idle
// (FW_ROWS_GUARD in kernels/common.cl). So a kernel compiles once per program build whatever the grid or the
// rank's block: PoCL specialises a kernel for each work-group size it is launched with, and left to choose
// (a null local range) it picked a divisor of each global range, a compile for every grid.
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

/// What a work-item of a grid sweep holds along x (the stage says, when it makes the Kernel): a run of
/// row_chunk() values (a whole row under the rows mapping, one cell under the cells mapping), or FW_LANES
/// consecutive values of a row in vector arithmetic (the lane kernels: advection, kernels/lanes.cl).
enum class RowItems { runs, lanes };

/// Items of a work-group under the rows mapping: 32 rows of a sweep (or 32 lane items of a row, or 32 items
/// of a flat range), each already a whole row's or block's work. A group runs on one core, so fewer, larger
/// groups cost PoCL less per launch: 32 rows ran the pressure solver's small levels 20% faster than 8
/// (docs/performance.md, 2026-12-06). A lane kernel's group runs along the row, so that the lanes of one row
/// stay on one core: across groups of rows, two cores wrote neighbouring lanes of a row into the same cache
/// lines, and the upwind stages took 50% longer.
inline constexpr std::size_t kRowsGroupItems = 32;

/// Items of a work-group under the cells mapping: two warps of 32 or one wavefront of 64 and more, enough
/// for a GPU to hide memory latency, small enough for every kernel's register budget. A power of two, as
/// work_group_shape's halving needs.
inline constexpr std::size_t kCellsGroupItems = 128;

/// The work-group of a launch over `dims` (1 to 3) dimensions under `mapping`, for a kernel whose items hold
/// `items` (3 dimensions only) and whose device prefers groups in multiples of `preferred_multiple` items
/// and runs at most `max_items` a group (CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE,
/// CL_KERNEL_WORK_GROUP_SIZE):
/// - rows, a sweep of runs: kRowsGroupItems rows (1, 32, 1); of lanes: kRowsGroupItems along the row (32, 1,
///   1); a flat or two-dimensional range: (32) or (32, 1);
/// - cells, one dimension: kCellsGroupItems;
/// - cells, two or three: x the preferred multiple (at most kCellsGroupItems; 1 if it is not a power of two),
///   y the rest of kCellsGroupItems, z 1;
/// halved (y first) until it fits max_items. Every size is a power of two, so a smaller group of a kernel
/// divides a larger one (flat_items' ranges are whole groups of any kernel).
cl::NDRange work_group_shape(WorkMapping mapping, cl_uint dims, std::size_t preferred_multiple,
                             std::size_t max_items, RowItems items = RowItems::runs);

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
  /// The most groups reduction_rows() gives for these extents under any mapping and row chunk (a chunk of
  /// one cell under the rows mapping's groups): a partials buffer of this size fits every device, so that
  /// its bytes are known before a device is.
  static std::size_t reduction_groups_bound(int extent_x, int ny, int nz);

  /// Number of work-items a flat (1D) kernel over n values uses (a whole number of flat_group()s; the items
  /// past n, or past what each needs, stay idle: FW_FLAT_FOR).
  std::size_t flat_items(std::size_t n) const;
  /// The largest work-group a flat kernel gets (work_group_shape's one-dimensional group).
  std::size_t flat_group() const;

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

  /// Guard bands, for tests: while on, every buffer() gets kGuardBandBytes of a known pattern past the bytes
  /// asked for (allocated_bytes() does not count them), so that a kernel writing past its array, as an item
  /// past its range would without its bounds guard, is caught. guard_band_breaches() reads every band since
  /// the last call, names the buffers whose band changed (their size and the order they were allocated in)
  /// and forgets them all (tests/support/TestDevice.cpp checks after each test case).
  void set_guard_bands(bool on) { guard_bands_ = on; }
  std::vector<std::string> guard_band_breaches();
  static constexpr std::size_t kGuardBandBytes = 256;

 private:
  DeviceInfo device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::unique_ptr<Profiler> profiler_;
  WorkMapping mapping_;
  int row_chunk_;
  std::size_t allocated_bytes_ = 0;
  bool warnings_as_errors_ = false;
  struct GuardedBuffer {
    cl::Buffer buffer;
    std::size_t bytes = 0;    // the array's (allocation_bytes); the band follows them
    std::size_t ordinal = 0;  // the how-manieth buffer since the bands went on
  };
  bool guard_bands_ = false;
  std::vector<GuardedBuffer> guarded_;
  std::size_t guarded_count_ = 0;
};

/// A kernel that knows its name, so failures say which one.
class Kernel {
 public:
  Kernel() = default;
  /// `items`: what an item of a grid sweep holds along x (RowItems), for its work-group.
  Kernel(const cl::Program& program, const std::string& name, RowItems items = RowItems::runs);

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

  /// Launches the kernel over `items`, rounded up to whole work-groups of its group_shape(); the kernel
  /// leaves the items past `items` idle.
  void enqueue(ComputeContext& cc, const cl::NDRange& items);
  /// The same over `items` starting at item `first` (OpenCL's global offset: get_global_id counts from it),
  /// so that a kernel skips the rows before it.
  void enqueue_from(ComputeContext& cc, const cl::NDRange& first, const cl::NDRange& items);
  /// Launches it with the work-group `local` (a reduction's, a one-group kernel's); `global` must be a whole
  /// number of them.
  void enqueue(ComputeContext& cc, const cl::NDRange& global, const cl::NDRange& local,
               const cl::NDRange& first = cl::NullRange);

  /// This kernel's work-group for a range of `dims` dimensions on cc's device: work_group_shape of its items,
  /// its preferred multiple and its largest group, queried on the first call and kept.
  cl::NDRange group_shape(const ComputeContext& cc, cl_uint dims);

  /// The largest work-group this kernel can run with on cc's device (CL_KERNEL_WORK_GROUP_SIZE).
  std::size_t max_group_size(const ComputeContext& cc) const;

 private:
  [[noreturn]] void throw_arg_error(cl_uint index, int status) const;
  cl::Kernel kernel_;
  std::string name_;
  RowItems items_ = RowItems::runs;
  std::array<cl::NDRange, 3> group_shapes_{};  // per dimension count; NullRange (0 dimensions) until chosen
};

}  // namespace fw::host
