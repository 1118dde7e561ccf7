#include "host/stages/PressureSolver.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <utility>

#include "base/ExactSum.hpp"

namespace fw::host {
namespace {

// Relaxation weight of the damped Jacobi smoother: 6/7 minimises the amplification of the high-frequency
// half of the spectrum of the 7-point Laplacian.
constexpr float kJacobiWeight = 6.0f / 7.0f;

// prolong_add's slope for linear interpolation: a child sits a quarter of the coarse spacing from its
// parent's centre.
constexpr float kLinearSlope = 0.25f;

// How often CG starts again from the true residual when its recursive one met the tolerance and the true one
// did not (see solve_cg).
constexpr int kCgRestarts = 2;

// No -cl-unsafe-math-optimizations: with it the compiler reorders a cell's arithmetic differently in the
// vectorised and the scalar runs of a row, so a cell's bits depended on where the work-items' runs begin
// (the rows and the cells mapping parted in the last bits). Without it every cell computes the same bits
// under any mapping and, over MPI, in any block; it cost 0.6 ms of the 19 ms a CG solve takes on
// 128x128x64 under PoCL.
constexpr const char* kPressureBuildOptions = "";
// The work-group of red_black_sweeps: under the GPU work mapping enough items for a compute unit; under the
// CPU's rows mapping one item, as a CPU runs a group on one core whatever its size and one item spares PoCL
// the barriers (a group of 256 items took 5x as long). The mapping, not the device, decides, so that CI
// runs the GPU's group on PoCL.
constexpr std::size_t kOneGroupItemsGpu = 256;

FwLevel level_dims(const fluid::PressureLevel& L, const fluid::GridSpec& spec) {
  FwLevel d{};
  d.nx = L.nx;
  d.ny = L.ny;
  d.nz = L.nz;
  d.periodic = (spec.periodic(0) ? 1 : 0) | (spec.periodic(1) ? 2 : 0) | (spec.periodic(2) ? 4 : 0);
  return d;
}

// How many levels, from the fine one, the blocks split (extents: every level's cells along x, y, z): a level
// l is split while every cut lies on a multiple of 2^l and every block holds at least min_split_cells of its
// cells (kSplitLevelCells). The coarser levels are whole on every rank, their residual gathered once a
// V-cycle: a small level's smoothing passes would each cost an exchange, worth more than its cells' work.
int split_level_count(const fluid::Decomposition& d, const std::vector<std::array<int, 3>>& extents,
                      long long min_split_cells) {
  const int levels = int(extents.size());
  int count = 1;
  while (count < levels) {
    const int scale = 1 << count;
    const std::array<int, 3>& e = extents[std::size_t(count)];
    bool whole = true;
    for (int r = 0; r < d.ranks(); ++r) {
      const fluid::Block b = d.block(r);
      long long cells = e[2];
      for (int axis = 0; axis < 2; ++axis) {
        if (d.blocks()[axis] > 1) {
          whole = whole && b.first[axis] % scale == 0 && b.count[axis] % scale == 0;
          cells *= b.count[axis] / scale;
        } else {
          cells *= e[std::size_t(axis)];
        }
      }
      whole = whole && cells >= min_split_cells;
    }
    if (!whole) break;
    ++count;
  }
  return count;
}

bool spans_ranks(const PressureBlocks* blocks) {
  return blocks != nullptr && blocks->world != nullptr && blocks->decomposition.splits();
}

// Level l's array on a rank: its block with the halo on a split level, else the whole level.
BlockArray level_array(const std::array<int, 3>& extent, int l, const BlockShare& share, int fine_halo,
                       int split_levels) {
  if (share.splits() && l < split_levels)
    return block_array(*share.decomposition, share.rank, l, extent[2], l == 0 ? fine_halo : 1);
  BlockArray whole;
  whole.extent = extent;
  return whole;
}

}  // namespace

std::size_t PressureSolver::estimate_device_bytes(const fluid::GridSpec& spec, const BlockShare& share) {
  // As the constructor allocates: per level its mask (a byte a cell), b, phi and scratch; the gathered
  // coarse residual over ranks; CG's five fine vectors and the fine level's column sums.
  const auto bytes = [](std::size_t n) { return ComputeContext::allocation_bytes(n); };
  const std::vector<std::array<int, 3>> extents = fluid::pressure_level_extents(spec);
  const int levels = int(extents.size());
  const int split_levels =
      share.splits() ? split_level_count(*share.decomposition, extents, kSplitLevelCells) : levels;
  const int fine_halo = share.splits() ? share.decomposition->halo() : 0;
  std::size_t total = 0;
  for (int l = 0; l < levels; ++l) {
    const std::size_t cells = level_array(extents[std::size_t(l)], l, share, fine_halo, split_levels).cells();
    total += bytes(cells) + 3 * bytes(cells * sizeof(float));
  }
  if (share.splits() && split_levels < levels) {
    const std::array<int, 3>& e = extents[std::size_t(split_levels - 1)];
    total += bytes(std::size_t(e[0]) * e[1] * e[2] * sizeof(float));
  }
  const BlockArray fine = level_array(extents[0], 0, share, fine_halo, split_levels);
  total += 5 * bytes(fine.cells() * sizeof(float));
  return total + bytes(std::size_t(fine.extent[0]) * fine.extent[1] * sizeof(float));
}

PressureSolver::PressureSolver(ComputeContext& cc, const fluid::GridSpec& spec,
                               std::vector<fluid::PressureLevel> levels,
                               const fluid::PressureSettings& settings, const PressureBlocks* blocks)
    : cc_(cc), spec_(spec), settings_(settings), host_levels_(std::move(levels)) {
  if (host_levels_.empty()) throw std::invalid_argument("PressureSolver: no pressure levels");
  split_levels_ = int(host_levels_.size());
  if (spans_ranks(blocks)) {
    world_ = blocks->world;
    decomposition_ = blocks->decomposition;
    std::vector<std::array<int, 3>> extents;
    for (const fluid::PressureLevel& L : host_levels_) extents.push_back({L.nx, L.ny, L.nz});
    split_levels_ = split_level_count(decomposition_, extents, blocks->min_split_cells);
  }
  for (int l = 0; l < int(host_levels_.size()); ++l) {
    const fluid::PressureLevel& L = host_levels_[l];
    DeviceLevel d;
    d.dims = level_dims(L, spec_);
    d.own = {0, L.nx, 0, L.ny};
    std::vector<std::uint8_t> mask;
    if (split(l)) {
      const BlockArray a = level_array({L.nx, L.ny, L.nz}, l, BlockShare{&decomposition_, world_->rank()},
                                       blocks->fine_halo, split_levels_);
      d.dims.nx = a.extent[0], d.dims.ny = a.extent[1];
      d.dims.ox = a.origin[0], d.dims.oy = a.origin[1];
      // A cut axis wraps through the halo, not inside the block.
      for (int axis = 0; axis < 2; ++axis)
        if (decomposition_.blocks()[axis] > 1) d.dims.periodic &= ~(1 << axis);
      d.own = {a.halo_low[0], a.extent[0] - a.halo_high[0], a.halo_low[1], a.extent[1] - a.halo_high[1]};
      d.halo.emplace(cc_, *world_, a);
      mask = block_of(L.mask, L.nx, L.ny, a);
    }
    const std::vector<std::uint8_t>& cells_mask = split(l) ? mask : L.mask;
    d.cells = cells_mask.size();
    d.mask = cc_.upload(cells_mask);
    d.b = cc_.zero_floats(d.cells);
    d.phi = cc_.zero_floats(d.cells);
    d.scratch = cc_.buffer(d.cells * sizeof(float));
    levels_.push_back(std::move(d));
  }
  if (split_levels_ < int(host_levels_.size()) && decomposition_.splits()) {
    gathered_dims_ = level_dims(host_levels_[split_levels_ - 1], spec_);
    gathered_ = cc_.buffer(host_levels_[split_levels_ - 1].cell_count() * sizeof(float));
  }
  for (auto m : host_levels_[0].mask)
    if (m & FW_MASK_FLUID) ++fluid_cells_;
  const std::size_t n = levels_[0].cells;
  for (cl::Buffer* buf : {&r_, &z_, &d_, &q_, &scratch_}) *buf = cc_.zero_floats(n);
  columns_host_.resize(std::size_t(levels_[0].dims.nx) * levels_[0].dims.ny);  // the finest has the most
  columns_ = cc_.buffer(columns_host_.size() * sizeof(float));

  cl::Program program = cc_.build("fluid_pressure.cl", kPressureBuildOptions);
  jacobi_ = Kernel(program, "jacobi_sweep");
  red_black_ = Kernel(program, "red_black_pass");
  red_black_update_ = Kernel(program, "red_black_update");
  red_black_sweeps_ = Kernel(program, "red_black_sweeps");
  smoothing_start_ = Kernel(program, "smoothing_start");
  one_group_items_ = cc_.mapping() == WorkMapping::rows
                         ? 1
                         : std::min(kOneGroupItemsGpu, red_black_sweeps_.max_group_size(cc_));
  residual_ = Kernel(program, "residual");
  apply_ = Kernel(program, "apply_operator");
  restrict_ = Kernel(program, "restrict_residual");
  prolong_ = Kernel(program, "prolong_add");
  cg_update_ = Kernel(program, "cg_update_columns");
  cg_direction_ = Kernel(program, "cg_direction");
  dot_ = Kernel(program, "dot_product_columns");
  add_ = Kernel(program, "add_on_fluid");
  sum_ = Kernel(program, "sum_on_fluid_columns");
}

float PressureSolver::correction_scale() const {
  // The rediscretised coarse equation (coarse spacing 2h). With linear prolongation it makes stand-alone
  // V-cycles converge (2 cycles to 1e-3 on the wind tunnel); with the piecewise-constant prolongation used
  // before, only the Galerkin scale 2 did, at 5.6 cycles, and 4 diverged.
  return 4.0f;
}

float PressureSolver::prolongation_slope() const {
  // Linear interpolation for stand-alone cycles; CG's preconditioner must be symmetric, and piecewise
  // constant is the transpose of the averaging restriction (it needs as many CG iterations, 2.0, on the
  // wind tunnel).
  return settings_.solver == fluid::PressureSolverType::cg ? 0.0f : kLinearSlope;
}

// Bytes each kernel streams per cell of its level (the memory-traffic model behind traffic_bytes(): every
// array element a kernel reads or writes counted once, neighbours taken as cached, masks 1 byte, floats 4).
namespace traffic {
constexpr double kSmoothPass = 13;     // mask, b, phi read; phi written (a Jacobi sweep or a colour pass)
constexpr double kResidual = 13;       // mask, b, phi read; r written
constexpr double kRestrictFine = 4;    // the fine residual read ...
constexpr double kRestrictCoarse = 9;  // ... coarse mask read, coarse b and first pass written
constexpr double kProlongFine = 9;     // fine mask read, fine phi read and written ...
constexpr double kProlongCoarse = 5;   // ... coarse mask and phi read (the side rows cached)
constexpr double kDot = 8;             // a, b read
constexpr double kApply = 9;           // mask, d read; q written
constexpr double kCgUpdate = 24;       // d, q, x, r read; x, r written
constexpr double kCgDirection = 12;    // z, d read; d written
constexpr double kSmoothingStart = 9;  // mask, b read; the first pass written
constexpr double kSumOnFluid = 5, kAddOnFluid = 9;
}  // namespace traffic

void PressureSolver::count_traffic(int level, double bytes_per_cell) {
  traffic_bytes_ += bytes_per_cell * double(levels_[level].cells);
}

cl::NDRange PressureSolver::column_rows(int level) const {
  const FwLevel& L = levels_[level].dims;
  return cc_.rows(L.nx, L.ny, 1);
}

void PressureSolver::exchange(int l, cl::Buffer& field) {
  // The solver's stencils (the smoothers, the residual, the prolongation, A d) read one cell past the block.
  if (split(l)) levels_[l].halo->exchange(field, kStencilReach);
}

HaloTraffic PressureSolver::halo_traffic() const {
  HaloTraffic total;
  for (const DeviceLevel& level : levels_)
    if (level.halo) total += level.halo->traffic();
  return total;
}

double PressureSolver::dot(int level, cl::Buffer& a, cl::Buffer& b) {
  dot_.set_args(levels_[level].dims, a, b, columns_).enqueue(cc_, column_rows(level));
  count_traffic(level, traffic::kDot);
  return sum_columns(level);
}

double PressureSolver::sum_columns(int level) {
  const DeviceLevel& L = levels_[level];
  const std::size_t nx = std::size_t(L.dims.nx), count = nx * L.dims.ny;
  cc_.queue().enqueueReadBuffer(columns_, CL_TRUE, 0, count * sizeof(float), columns_host_.data());
  // The block's own columns only: its halo's are another rank's (and wrong here).
  base::ExactSum sum;
  for (int j = L.own[2]; j < L.own[3]; ++j)
    sum.add(
        std::span<const float>(columns_host_.data() + nx * j + L.own[0], std::size_t(L.own[1] - L.own[0])));
  return split(level) ? world_->sum(sum) : sum.value();
}

void PressureSolver::enqueue_own_rows(Kernel& kernel, int level) {
  const auto& L = levels_[level];
  const cl::NDRange all = cc_.rows(L.dims.nx, L.dims.ny, L.dims.nz);
  if (!split(level)) return kernel.enqueue(cc_, all);
  kernel.enqueue_from(cc_, cl::NDRange(0, std::size_t(L.own[2]), 0),
                      cl::NDRange(all[0], std::size_t(L.own[3] - L.own[2]), all[2]));
}

void PressureSolver::enqueue_jacobi_sweep(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& phi_out,
                                          float relaxation_weight) {
  auto& L = levels_[level];
  enqueue_own_rows(jacobi_.set_args(L.dims, L.mask, b, phi, phi_out, relaxation_weight), level);
  count_traffic(level, traffic::kSmoothPass);
}

void PressureSolver::enqueue_red_black_pass(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& phi_out,
                                            int colour) {
  auto& L = levels_[level];
  enqueue_own_rows(red_black_.set_args(L.dims, L.mask, b, phi, phi_out, colour), level);
  count_traffic(level, traffic::kSmoothPass);
}

void PressureSolver::enqueue_red_black_update(int level, cl::Buffer& b, cl::Buffer& phi, int colour) {
  auto& L = levels_[level];
  enqueue_own_rows(red_black_update_.set_args(L.dims, L.mask, b, phi, colour), level);
  count_traffic(level, traffic::kSmoothPass);
}

bool PressureSolver::updates_in_place(int level) const {
  return settings_.smoother == fluid::MultigridSmoother::red_black &&
         host_levels_[level].cell_count() > kOneGroupCells;
}

cl::Buffer& PressureSolver::first_pass_buffer(int l, cl::Buffer& phi) {
  return updates_in_place(l) ? phi : levels_[l].scratch;
}

void PressureSolver::enqueue_red_black_sweeps(int level, cl::Buffer& b, cl::Buffer& phi, int sweeps,
                                              int first_colour, int first_pass) {
  auto& L = levels_[level];
  red_black_sweeps_.set_args(L.dims, L.mask, b, phi, L.scratch, sweeps, first_colour, first_pass)
      .enqueue(cc_, cl::NDRange(one_group_items_), cl::NDRange(one_group_items_));
  count_traffic(level, (2.0 * sweeps - first_pass) * traffic::kSmoothPass);
}

float PressureSolver::start_relaxation_weight() const {
  return settings_.smoother == fluid::MultigridSmoother::jacobi ? kJacobiWeight : 1.0f;
}

int PressureSolver::start_colour() const {
  return settings_.smoother == fluid::MultigridSmoother::jacobi ? FW_SMOOTH_ALL_CELLS : 0;
}

void PressureSolver::enqueue_smoothing_start(int level, cl::Buffer& b, cl::Buffer& out) {
  auto& L = levels_[level];
  enqueue_own_rows(
      smoothing_start_.set_args(L.dims, L.mask, b, out, start_relaxation_weight(), start_colour()), level);
  count_traffic(level, traffic::kSmoothingStart);
}

void PressureSolver::enqueue_residual(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& r) {
  auto& L = levels_[level];
  enqueue_own_rows(residual_.set_args(L.dims, L.mask, b, phi, r), level);
  count_traffic(level, traffic::kResidual);
}

double PressureSolver::residual_norm2(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& r) {
  enqueue_residual(level, b, phi, r);
  return dot(level, r, r);
}

void PressureSolver::enqueue_restrict_residual(int fine_level, cl::Buffer& b, cl::Buffer& phi) {
  auto& F = levels_[fine_level];
  auto& C = levels_[fine_level + 1];
  // The residual kernel's branch-free interior run is much faster than recomputing the residual inside the
  // restriction; the scratch buffer is free at this point of the cycle.
  enqueue_residual(fine_level, b, phi, F.scratch);
  // From the last level split over ranks, the whole residual is restricted on every rank alike.
  const bool gather = split(fine_level) && !split(fine_level + 1);
  if (gather) gather_residual(fine_level);
  restrict_
      .set_args(gather ? gathered_dims_ : F.dims, C.dims, C.mask, gather ? gathered_ : F.scratch, C.b,
                level_first_pass(fine_level + 1), correction_scale(), start_relaxation_weight(),
                start_colour())
      .enqueue(cc_, cc_.rows(C.dims.nx, C.dims.ny, C.dims.nz));
  count_traffic(fine_level, traffic::kRestrictFine);
  count_traffic(fine_level + 1, traffic::kRestrictCoarse);
  exchange(fine_level + 1, level_first_pass(fine_level + 1));
}

void PressureSolver::gather_residual(int l) {
  const DeviceLevel& F = levels_[l];
  const fluid::PressureLevel& whole = host_levels_[l];
  const int scale = 1 << l;
  const auto ranks = static_cast<std::size_t>(decomposition_.ranks());  // a block each
  // Every rank's own cells at level l, in global indices: first x, first y, count x, count y.
  std::vector<std::array<int, 4>> boxes(ranks);
  std::vector<int> counts(ranks), offsets(ranks);
  int total = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    const fluid::Block b = decomposition_.block(int(r));
    boxes[r] = {b.first[0] / scale, b.first[1] / scale, b.count[0] / scale, b.count[1] / scale};
    counts[r] = boxes[r][2] * boxes[r][3] * whole.nz;
    offsets[r] = total;
    total += counts[r];
  }
  const auto& mine = boxes[std::size_t(world_->rank())];
  std::vector<float> own(static_cast<std::size_t>(counts[std::size_t(world_->rank())]));
  std::vector<float> all(static_cast<std::size_t>(total));
  const std::size_t row = std::size_t(F.dims.nx) * sizeof(float), slice = row * F.dims.ny;
  cc_.queue().enqueueReadBufferRect(
      F.scratch, CL_TRUE, {std::size_t(F.own[0]) * sizeof(float), std::size_t(F.own[2]), 0}, {0, 0, 0},
      {std::size_t(mine[2]) * sizeof(float), std::size_t(mine[3]), std::size_t(whole.nz)}, row, slice,
      std::size_t(mine[2]) * sizeof(float), std::size_t(mine[2]) * sizeof(float) * mine[3], own.data());
  MPI_Allgatherv(own.data(), counts[world_->rank()], MPI_FLOAT, all.data(), counts.data(), offsets.data(),
                 MPI_FLOAT, world_->comm());
  std::vector<float> level(whole.cell_count());
  for (std::size_t r = 0; r < ranks; ++r) {
    const auto [x0, y0, nx, ny] = boxes[r];
    const float* from = all.data() + offsets[r];
    for (int k = 0; k < whole.nz; ++k)
      for (int j = 0; j < ny; ++j, from += nx)
        std::copy_n(
            from, nx,
            level.begin() + (x0 + std::ptrdiff_t(whole.nx) * (y0 + j + std::ptrdiff_t(whole.ny) * k)));
  }
  cc_.queue().enqueueWriteBuffer(gathered_, CL_TRUE, 0, level.size() * sizeof(float), level.data());
}

void PressureSolver::enqueue_prolong_add(int fine_level, cl::Buffer& phi) {
  auto& F = levels_[fine_level];
  auto& C = levels_[fine_level + 1];
  enqueue_own_rows(prolong_.set_args(F.dims, C.dims, F.mask, C.mask, C.phi, phi, prolongation_slope()),
                   fine_level);
  count_traffic(fine_level, traffic::kProlongFine);
  count_traffic(fine_level + 1, traffic::kProlongCoarse);
  exchange(fine_level, phi);
}

void PressureSolver::vcycle(cl::Buffer& b, cl::Buffer& phi) {
  vcycle_level(0, b, phi, false);
}

void PressureSolver::vcycle_from_zero(cl::Buffer& b, cl::Buffer& phi) {
  enqueue_smoothing_start(0, b, first_pass_buffer(0, phi));
  exchange(0, first_pass_buffer(0, phi));
  vcycle_level(0, b, phi, true);
}

void PressureSolver::smooth(int l, cl::Buffer& b, cl::Buffer& phi, int sweeps, bool after_correction,
                            bool started) {
  // A started smoothing (only ever before the correction) has its pass 0 in first_pass_buffer already.
  const int first_pass = started ? 1 : 0;
  if (settings_.smoother == fluid::MultigridSmoother::jacobi) {
    // Damped Jacobi, phi -> scratch -> phi, an odd count rounded up to pairs; the same before and after the
    // correction, so the cycle is symmetric.
    auto& scratch = levels_[l].scratch;
    for (int p = first_pass; p < sweeps + sweeps % 2; ++p) {
      enqueue_jacobi_sweep(l, b, p % 2 ? scratch : phi, p % 2 ? phi : scratch, kJacobiWeight);
      exchange(l, p % 2 ? phi : scratch);
    }
    return;
  }
  // Red-black Gauss-Seidel, one colour per pass; reversing the colour order after the correction keeps the
  // cycle symmetric. Small levels take all their passes in one launch, large ones update in place.
  const int first = after_correction ? 1 : 0;
  const auto colour = [first](int pass) { return pass % 2 ? 1 - first : first; };
  if (updates_in_place(l)) {
    for (int p = first_pass; p < 2 * sweeps; ++p) {
      enqueue_red_black_update(l, b, phi, colour(p));
      exchange(l, phi);
    }
    return;
  }
  if (!split(l)) {
    enqueue_red_black_sweeps(l, b, phi, sweeps, first, first_pass);
    return;
  }
  // A small level split over ranks: red_black_sweeps' passes one launch each, with the halo exchanged
  // between them (the same values).
  auto& scratch = levels_[l].scratch;
  for (int p = first_pass; p < 2 * sweeps; ++p) {
    enqueue_red_black_pass(l, b, p % 2 ? scratch : phi, p % 2 ? phi : scratch, colour(p));
    exchange(l, p % 2 ? phi : scratch);
  }
}

void PressureSolver::vcycle_level(int l, cl::Buffer& b, cl::Buffer& phi, bool started) {
  const int last = level_count() - 1;
  if (l == last) {
    // Coarsest level: enough symmetric sweeps to carry information across it.
    const auto& L = host_levels_[l];
    const int sweeps = std::max(4, std::max({L.nx, L.ny, L.nz}));
    smooth(l, b, phi, sweeps, false, started);
    smooth(l, b, phi, sweeps, true, false);
    return;
  }
  smooth(l, b, phi, settings_.smoothing_sweeps, false, started);
  enqueue_restrict_residual(l, b, phi);
  vcycle_level(l + 1, levels_[l + 1].b, levels_[l + 1].phi, true);
  enqueue_prolong_add(l, phi);
  smooth(l, b, phi, settings_.smoothing_sweeps, true, false);
}

void PressureSolver::remove_mean(cl::Buffer& b) {
  auto& L = levels_[0];
  sum_.set_args(L.dims, L.mask, b, columns_).enqueue(cc_, column_rows(0));
  count_traffic(0, traffic::kSumOnFluid + traffic::kAddOnFluid);
  const double mean = fluid_cells_ ? sum_columns(0) / double(fluid_cells_) : 0.0;
  add_.set_args(L.dims, L.mask, static_cast<float>(-mean), b)
      .enqueue(cc_, cc_.rows(L.dims.nx, L.dims.ny, L.dims.nz));
}

PressureSolveStatus PressureSolver::solve() {
  if (!spec_.has_dirichlet_pressure()) remove_mean(levels_[0].b);
  exchange(0, levels_[0].phi);  // the warm start's halo: the last solve's, or an upload's
  const PressureSolveStatus status = solve_with(settings_.solver);
  // The solve filled one cell of the halo; the whole of it once now, for what reads further (a frame writes
  // a rank's block with its halo).
  if (split(0)) levels_[0].halo->exchange(levels_[0].phi);
  return status;
}

PressureSolveStatus PressureSolver::solve_with(fluid::PressureSolverType solver) {
  switch (solver) {
    case fluid::PressureSolverType::jacobi:
      return solve_jacobi();
    case fluid::PressureSolverType::multigrid:
      return solve_multigrid();
    case fluid::PressureSolverType::cg:
      return solve_cg();
  }
  throw std::logic_error("PressureSolver: unknown solver");
}

PressureSolveStatus PressureSolver::solve_jacobi() {
  auto& L = levels_[0];
  PressureSolveStatus st;
  st.solver = "jacobi";
  const double bnorm = std::sqrt(dot(0, L.b, L.b));
  // Ping-pong between phi and scratch; an even count of sweeps ends in phi.
  const int sweeps = settings_.jacobi_iterations + (settings_.jacobi_iterations % 2);
  for (int s = 0; s < sweeps; s += 2) {
    enqueue_jacobi_sweep(0, L.b, L.phi, scratch_, 1.0f);
    exchange(0, scratch_);
    enqueue_jacobi_sweep(0, L.b, scratch_, L.phi, 1.0f);
    exchange(0, L.phi);
  }
  st.iterations = sweeps;
  st.relative_residual = bnorm > 0 ? std::sqrt(residual_norm2(0, L.b, L.phi, r_)) / bnorm : 0.0;
  st.converged = true;
  return st;
}

PressureSolveStatus PressureSolver::solve_multigrid() {
  auto& L = levels_[0];
  PressureSolveStatus st;
  st.solver = "multigrid";
  const double bnorm = std::sqrt(dot(0, L.b, L.b));
  if (bnorm == 0.0) {
    cc_.queue().enqueueFillBuffer(L.phi, 0.0f, 0, L.cells * sizeof(float));
    st.converged = true;
    return st;
  }
  double rel = std::sqrt(residual_norm2(0, L.b, L.phi, r_)) / bnorm;
  st.initial_residual = rel;
  while (rel > settings_.tolerance && st.iterations < settings_.max_iterations) {
    vcycle(L.b, L.phi);
    ++st.iterations;
    rel = std::sqrt(residual_norm2(0, L.b, L.phi, r_)) / bnorm;  // NaN ends the loop too
  }
  st.relative_residual = rel;
  st.converged = rel <= settings_.tolerance;
  return st;
}

PressureSolveStatus PressureSolver::solve_cg() {
  auto& L = levels_[0];
  PressureSolveStatus st;
  st.solver = "cg";
  const std::size_t bytes = L.cells * sizeof(float);
  const auto range = cc_.rows(L.dims.nx, L.dims.ny, L.dims.nz);
  const auto columns = column_rows(0);  // cg_update's

  const double bnorm = std::sqrt(dot(0, L.b, L.b));
  if (bnorm == 0.0) {
    cc_.queue().enqueueFillBuffer(L.phi, 0.0f, 0, bytes);
    st.converged = true;
    return st;
  }
  double rr = residual_norm2(0, L.b, L.phi, r_);
  st.initial_residual = std::sqrt(rr) / bnorm;
  const double target = settings_.tolerance * bnorm;
  // CG stops on its recursively updated residual, which drifts from b - A phi in float: near the float floor
  // it meets the target while the true residual is still above it (1.12e-5 of ||b|| for a target of 1e-5,
  // the floor being ~8e-6, in tests/kernels/pressure_solver_test.cpp). Then it starts again from the true
  // residual, which residual_norm2 leaves in r_: one restart reaches the floor, a second is the margin.
  for (int run = 0; run <= kCgRestarts && std::sqrt(rr) > target && st.iterations < settings_.max_iterations;
       ++run) {
    vcycle_from_zero(r_, z_);
    double rho = dot(0, r_, z_);
    std::swap(z_, d_);  // d = z without a copy: the next preconditioning writes all of z
    while (st.iterations < settings_.max_iterations) {
      apply_.set_args(L.dims, L.mask, d_, q_).enqueue(cc_, range);
      count_traffic(0, traffic::kApply);
      const double dq = dot(0, d_, q_);
      if (!(dq > 0.0)) break;  // breakdown: direction has no energy left (or NaN)
      const float alpha = static_cast<float>(rho / dq);
      cg_update_.set_args(L.dims, alpha, d_, q_, L.phi, r_, columns_).enqueue(cc_, columns);
      count_traffic(0, traffic::kCgUpdate);
      const double recursive = sum_columns(0);
      ++st.iterations;
      if (std::sqrt(recursive) <= target || !std::isfinite(recursive)) break;
      vcycle_from_zero(r_, z_);
      const double rho_new = dot(0, r_, z_);
      const float beta = static_cast<float>(rho_new / rho);
      rho = rho_new;
      cg_direction_.set_args(L.dims, beta, z_, d_).enqueue(cc_, range);
      count_traffic(0, traffic::kCgDirection);
    }
    rr = residual_norm2(0, L.b, L.phi, r_);  // the true residual, reported or restarted from
  }
  st.relative_residual = std::sqrt(rr) / bnorm;
  st.converged = st.relative_residual <= settings_.tolerance;
  return st;
}

}  // namespace fw::host
