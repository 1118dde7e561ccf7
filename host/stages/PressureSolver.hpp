// Pressure projection on the device: solves A phi = b on the MAC grid's cells.
//
//   PressureSolver solver(cc, spec, fluid::build_pressure_levels(spec, solid), settings.pressure);
//   // ... fill solver.rhs() (e.g. FluidStages::enqueue_divergence_rhs) ...
//   PressureSolveStatus st = solver.solve();       // warm-starts from the last solution
//   // st.iterations, st.relative_residual = ||b - A phi|| / ||b||, recomputed at the end
//
// Solvers (fluid::PressureSolverType):
//   jacobi     fixed iteration count (the seed's method, kept as a baseline);
//   multigrid  geometric multigrid V-cycles until the relative residual is below the tolerance;
//   cg         conjugate gradients preconditioned by one V-cycle, same stopping rule (the default); when its
//              recursively updated residual meets the tolerance and the true one does not (they part near the
//              float floor), it restarts from the true residual, at most twice.
// The V-cycle smooths with damped Jacobi or red-black Gauss-Seidel (both symmetric, so it is a valid CG
// preconditioner), restricts the residual by averaging, and prolongs linearly (stand-alone cycles) or
// piecewise-constant (in CG, where the cycle must be symmetric). Where a level
// starts from a zero guess (every coarse level, and level 0 in CG's preconditioner) the smoother's first
// pass needs no neighbours and is written directly: by the restriction on coarse levels, by
// smoothing_start on level 0. Red-black passes update phi in place on large levels (updates_in_place);
// small levels take all their passes in one launch, out of place through the level's scratch. When no face is
// an outflow the operator is singular, and the mean of b over fluid cells is removed before solving.
//
// Over MPI ranks (PressureBlocks, docs/parallel.md) each rank holds its block of the fine level, with the
// velocity's halo, and of the coarse levels whose cells the blocks still split whole (the decomposition's
// alignment), each with a one-cell halo. The kernels update every cell of a block, halo included; the halo's
// own values are wrong and are replaced by an exchange after each pass, so a block's own cells get exactly
// the values of one process. Below those levels each rank gathers the whole residual and solves the coarse
// levels as one process would, the same on every rank. Sums add the blocks' own columns exactly over all
// ranks. So the solve gives the bits of one process on any number of ranks.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/PressureLevels.hpp"
#include "fluid/WindSettings.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/HaloExchange.hpp"

namespace fw::host {

/// The fewest cells of a level a block holds for the level to stay split over ranks, by default
/// (PressureBlocks::min_split_cells). A smoothing pass over fewer takes less time than the exchange after it
/// (about 15 us through PoCL on a CPU: a device finish, two rectangle copies, a wait). On bench wind
/// 128x128x64 over 2 ranks it cut the exchanges a step from 144 to 62 and the halo time from 2.2 to 1.3 ms
/// (docs/parallel.md, "The split's speed").
inline constexpr long long kSplitLevelCells = 4096;

/// A solve over ranks: this rank's place in the decomposition and the fine level's halo (the velocity's).
struct PressureBlocks {
  const Communicator* world = nullptr;
  fluid::Decomposition decomposition;
  int fine_halo = 1;  // cells
  /// A coarse level stays split while every block holds this many of its cells; the coarser ones are whole
  /// on every rank. 0: every level the cuts divide (the tests' way to split small levels).
  long long min_split_cells = kSplitLevelCells;
};

struct PressureSolveStatus {
  std::string solver;              // "jacobi", "multigrid" or "cg"
  int iterations = 0;              // Jacobi sweeps, V-cycles or CG iterations
  double initial_residual = 0.0;   // ||b - A phi0|| / ||b|| with the warm start phi0
  double relative_residual = 0.0;  // ||b - A phi|| / ||b||, recomputed from phi after the solve
  bool converged = false;          // relative_residual <= tolerance (always true for jacobi)
};

class PressureSolver {
 public:
  /// `levels`: the whole grid's hierarchy. blocks: null for one process; else this rank solves its block
  /// (rhs(), solution() and mask() are then its block with the halo: block_array(decomposition, rank, 0,
  /// nz, fine_halo)).
  PressureSolver(ComputeContext& cc, const fluid::GridSpec& spec, std::vector<fluid::PressureLevel> levels,
                 const fluid::PressureSettings& settings, const PressureBlocks* blocks = nullptr);

  /// Device bytes a solver of `spec` allocates, over `blocks` or in one process: exactly, before allocating
  /// (the hierarchy's shape depends on the grid alone, fluid::pressure_level_extents).
  /// `share`: the rank's block of a decomposition whose halo is the fine level's (PressureBlocks::fine_halo).
  static std::size_t estimate_device_bytes(const fluid::GridSpec& spec, const BlockShare& share = {});

  PressureSolveStatus solve();

  cl::Buffer& rhs() { return levels_[0].b; }         // b, level 0, m^2/s
  cl::Buffer& solution() { return levels_[0].phi; }  // phi = p dt / rho, m^2/s
  cl::Buffer& mask() { return levels_[0].mask; }
  const fluid::PressureSettings& settings() const { return settings_; }
  /// Device memory traffic of every kernel this solver has enqueued so far, bytes: each kernel's arrays per
  /// cell of its level, counted once (the model in PressureSolver.cpp), for the benchmark's bandwidth.
  double traffic_bytes() const { return traffic_bytes_; }
  /// What this solver's halo exchanges have sent over ranks, and their time (zero in one process).
  HaloTraffic halo_traffic() const;
  void set_settings(const fluid::PressureSettings& s) { settings_ = s; }
  int level_count() const { return static_cast<int>(levels_.size()); }
  const fluid::PressureLevel& level(int l) const { return host_levels_[l]; }

  // One stage each, exposed for the kernel tests. `level` indexes the hierarchy (0 = fine grid).
  void enqueue_jacobi_sweep(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& phi_out,
                            float relaxation_weight);
  /// One colour of red-black Gauss-Seidel, out of place: phi_out = phi with the colour's cells updated.
  void enqueue_red_black_pass(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& phi_out, int colour);
  /// One colour of red-black Gauss-Seidel in place: the values of enqueue_red_black_pass, fewer bytes moved.
  /// Relies on every neighbour of a cell having the other colour, which the hierarchy guarantees (periodic
  /// extents stay even or 1, see fluid/PressureLevels.hpp).
  void enqueue_red_black_update(int level, cl::Buffer& b, cl::Buffer& phi, int colour);
  /// Whether smooth() updates this level in place: the red-black smoother on a level of more than
  /// kOneGroupCells cells (smaller ones take enqueue_red_black_sweeps, out of place).
  bool updates_in_place(int level) const;
  /// `sweeps` red-black sweeps (colour first_colour, then the other) in one launch by one work-group: the
  /// same values as 2 * sweeps enqueue_red_black_pass (phi -> scratch -> phi); smooth() uses it on levels of
  /// at most kOneGroupCells cells. first_pass = 1 skips the first pass, whose result is already in the
  /// level's scratch (enqueue_smoothing_start, enqueue_restrict_residual).
  void enqueue_red_black_sweeps(int level, cl::Buffer& b, cl::Buffer& phi, int sweeps, int first_colour,
                                int first_pass = 0);
  /// out = the smoother's first pass of A phi = b from phi = 0 (a red-black pass of colour 0, or a damped
  /// Jacobi sweep), without the fill of phi and without reading neighbours.
  void enqueue_smoothing_start(int level, cl::Buffer& b, cl::Buffer& out);
  /// Under PoCL a launch costs about 0.1 ms, more than one core takes for a colour pass over this many cells
  /// (16,384 cells, one more level, came out slower on one core than in parallel).
  static constexpr std::size_t kOneGroupCells = 4096;
  /// r = b - A phi on `level`.
  void enqueue_residual(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& r);
  /// r = b - A phi and returns ||r||^2 (blocks).
  double residual_norm2(int level, cl::Buffer& b, cl::Buffer& phi, cl::Buffer& r);
  /// sum of a b over `level` (blocks): column sums on the device, added exactly on the host (base/ExactSum),
  /// so that the bits do not depend on the work mapping.
  double dot(int level, cl::Buffer& a, cl::Buffer& b);
  /// Coarse rhs = correction_scale() * mean of the children's residual, and the coarse level's first
  /// smoothing pass from a zero guess in level_first_pass(fine_level + 1).
  void enqueue_restrict_residual(int fine_level, cl::Buffer& b, cl::Buffer& phi);
  float correction_scale() const;
  /// phi += the coarse correction of level fine_level + 1, interpolated with prolongation_slope().
  void enqueue_prolong_add(int fine_level, cl::Buffer& phi);
  /// prolong_add's slope: 1/4 (linear interpolation) for stand-alone V-cycles, 0 (piecewise constant) for
  /// CG's preconditioner, which must stay symmetric.
  float prolongation_slope() const;
  /// One V-cycle on level 0 for A phi = b, starting from phi's content.
  void vcycle(cl::Buffer& b, cl::Buffer& phi);
  /// phi = one V-cycle on level 0 for A phi = b from phi = 0 (CG's preconditioner); phi is only written.
  void vcycle_from_zero(cl::Buffer& b, cl::Buffer& phi);
  cl::Buffer& level_rhs(int level) { return levels_[level].b; }
  cl::Buffer& level_solution(int level) { return levels_[level].phi; }
  /// Where a smoothing started from a zero guess finds its first pass: the level's solution when it
  /// updates in place, else its scratch.
  cl::Buffer& level_first_pass(int level) { return first_pass_buffer(level, levels_[level].phi); }

 private:
  struct DeviceLevel {
    FwLevel dims{};  // the block with its halo on a rank's level, else the whole level
    cl::Buffer mask, b, phi, scratch;
    std::size_t cells = 0;
    std::optional<HaloExchange> halo;    // on a rank's level over several ranks
    std::array<int, 4> own{0, 0, 0, 0};  // the block's own cells: x from, x to, y from, y to
  };

  /// Fills the halo of `field` on level l (nothing on a whole level or in one process).
  void exchange(int l, cl::Buffer& field);
  /// How far past a cell the solver's stencils read: the halo its exchanges fill during a solve.
  static constexpr int kStencilReach = 1;
  PressureSolveStatus solve_with(fluid::PressureSolverType solver);
  /// Launches `kernel` over level l's own rows when the level is split (what an exchange, a dot over the own
  /// columns or a restriction then reads: the halo rows are the neighbours' to fill), else over every row.
  void enqueue_own_rows(Kernel& kernel, int level);
  /// The levels held as blocks over ranks (the rest are whole on every rank); all of them in one process.
  bool split(int l) const { return l < split_levels_ && decomposition_.splits(); }
  /// Level fine_level's residual (in its scratch) gathered from every rank's block into gathered_, whole.
  void gather_residual(int fine_level);

  /// started: the first smoothing pass from phi = 0 is already in first_pass_buffer(l, phi).
  void vcycle_level(int l, cl::Buffer& b, cl::Buffer& phi, bool started);
  void smooth(int l, cl::Buffer& b, cl::Buffer& phi, int sweeps, bool after_correction, bool started);
  /// The smoother's first pass as the start kernels take it: its relaxation weight (kJacobiWeight, or 1 for
  /// a red-black colour) and its colour (or FW_SMOOTH_ALL_CELLS).
  float start_relaxation_weight() const;
  int start_colour() const;
  /// phi where level l updates in place, else the level's scratch.
  cl::Buffer& first_pass_buffer(int l, cl::Buffer& phi);
  /// The exact sum of the column sums a *_columns kernel left for `level` (blocks).
  double sum_columns(int level);
  void count_traffic(int level, double bytes_per_cell);
  /// The range of the *_columns kernels on `level`: rows over x and y, each item taking every k.
  cl::NDRange column_rows(int level) const;
  void remove_mean(cl::Buffer& b);
  PressureSolveStatus solve_jacobi();
  PressureSolveStatus solve_multigrid();
  PressureSolveStatus solve_cg();

  ComputeContext& cc_;
  const Communicator* world_ = &Communicator::alone();
  fluid::Decomposition decomposition_;
  int split_levels_ = 0;  // levels 0 .. split_levels_ - 1 are blocks (all levels in one process)
  cl::Buffer gathered_;   // the whole residual of level split_levels_ - 1, over several ranks
  FwLevel gathered_dims_{};
  fluid::GridSpec spec_;
  fluid::PressureSettings settings_;
  std::vector<fluid::PressureLevel> host_levels_;
  std::vector<DeviceLevel> levels_;
  cl::Buffer r_, z_, d_, q_, scratch_, columns_;  // columns_: one float per x-y column of level 0
  std::vector<float> columns_host_;
  std::size_t one_group_items_ = 1;  // red_black_sweeps' work-group
  double traffic_bytes_ = 0.0;
  std::size_t fluid_cells_ = 0;
  Kernel jacobi_, red_black_, red_black_update_, red_black_sweeps_, smoothing_start_, residual_, apply_,
      restrict_, prolong_, cg_update_, cg_direction_, dot_, add_, sum_;
};

}  // namespace fw::host
