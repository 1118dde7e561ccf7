// `forestwind bench coupled`: the wind grid and a whole forest stepping together on the OpenCL device.
//
// The case: a forest of `trees` copies (random yaw, scale 0.85-1.15, on a jittered lattice over the ground)
// of one broadleaf species refined to about `nodes_per_tree` nodes (Diener's walnut has 3,437), with `modes`
// modes and `samples` wind samples each, in a 10 m/s wind from the west on a grid of 2 m cells (inflow west,
// outflow east, slip sides and top, no-slip ground), pressure by multigrid-preconditioned CG to 1e-3, with
// two-way coupling (every tree's branches and leaves, LAI 3, as a canopy drag on the grid). Per step: the
// fluid (advect, forces, canopy drag, projection) then the trees (sample the wind, modal forces, exact modal
// step). Output frames add the deformation u = Phi q of every node; it is timed separately, over
// `deform_frames` frames, and compared with the device's FMA peak measured in the same process
// (kernels/bench_fma.cl): a node of a tree with m modes costs 3 m FMAs.
//
// With `turbulence`, each grid runs again with the inflow turbulence box and Stam's forcing of every tree by
// the eddies the grid cannot resolve (host/bench/BenchTurbulence.hpp): the cost of turbulence is the
// difference. The deformation is timed with the strong-wind correction (the default) and without it. With
// `leaves_per_tree`, each grid runs once more with the forest in full leaf (docs/leaves.md), a sample of that
// many leaves simulated per tree: the leaves' stage is timed on its own.
//
// The converged case also times the sample that a run with output.statistics takes every step (the profiles
// of the whole domain, docs/statistics.md), against the step and against the STREAM triad's bandwidth.
//
// Baselines run in the same process: each grid again with Oliapuram's pressure solve (a fixed
// `baseline_jacobi_iterations` Jacobi sweeps, 4 in the paper, not converged), and the trees' step and the
// deformation by the double-precision CPU reference (trees/ForestReference, one host thread).
//
//   CoupledBenchOptions opt;                                 // 1,000 trees x ~3,437 nodes x 25 modes
//   CoupledBenchResult r = run_coupled_bench(cc, opt);       // on 128x128x32 and 256x256x16
//   print_coupled_bench_table(r, std::cout);                 // or coupled_bench_json(r)
//
// Over MPI ranks (mpirun -np N, N > 1) run_coupled_bench_ranks times the converged laminar case on each grid,
// the wind split into the blocks a run would take and each tree stepped by the rank holding its root, against
// every rank stepping the whole case alone at the same time (host/bench/RanksBench.hpp). The other cases and
// the baselines run in one process only.
//
//   RanksBenchResult r = run_coupled_bench_ranks(cc, opt, world);   // collective; r.cases filled on rank 0
#pragma once

#include <array>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "host/bench/RanksBench.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/HaloExchange.hpp"

namespace fw::bench {

struct CoupledBenchOptions {
  std::vector<std::array<int, 3>> grids{{128, 128, 32}, {256, 256, 16}};
  int trees = 1000;
  int nodes_per_tree = 3437;
  int modes = 25;
  int samples = 3;
  int steps = 20;  // timed coupled steps per grid
  // Untimed steps first: 10 s of simulated time, so that the flow through the forest has developed; in the
  // first steps from the uniform start CG needs about twice the iterations (4.3 instead of 2.0).
  int warmup_steps = 100;
  int deform_frames = 10;              // timed deformation frames
  double cell_size = 2.0;              // m
  int baseline_jacobi_iterations = 4;  // Oliapuram's fixed Jacobi sweeps; 0 skips the baseline rows
  bool turbulence = true;      // also the converged case with turbulence (host/bench/BenchTurbulence.hpp)
  int leaves_per_tree = 1000;  // also the converged case with leaves (0: not)
};

struct CoupledBenchCase {
  std::array<int, 3> grid{};
  std::string pressure;                     // "cg 1e-3" or "jacobi 4" (the baseline)
  bool turbulent = false;                   // with the inflow turbulence and Stam's unresolved forcing
  long leaves = 0;                          // simulated leaves (the case with leaves)
  double ms_per_step = 0.0;                 // fluid + trees, per step
  std::map<std::string, double> stages_ms;  // per step: the wind grid's stages, "trees" (load + modal step)
  double fluid_ms = 0.0;                    // the wind grid's share of a step
  double trees_ms = 0.0;                    // sampling + modal forces + modal step
  double damage_ms =
      0.0;  // every tree's stem loads and failure check (docs/damage.md), after the trees' step
  double pressure_iterations = 0.0;
  host::HaloTraffic halo;  // this rank's halo exchanges over the timed steps (none in one process)
  // The converged case's: one sample of stats.nc's profiles (host/stages/PlaneStatistics) of the whole
  // domain after the timed steps, as a run with output.statistics takes every step; 0 for the other cases.
  double statistics_ms = 0.0;
  double statistics_gb_s = 0.0;  // the bytes it reads at least once, per second
};

struct CoupledBenchResult {
  std::string device;
  int trees = 0;
  int nodes_per_tree = 0;
  int modes = 0;
  int samples = 0;
  double species_seconds = 0.0;       // assembly + modes + wind basis of the species, host
  double real_leaves_per_tree = 0.0;  // the foliage's leaves of one tree at scale 1
  double deform_ms = 0.0;             // one output frame's deformation of every node, strong-wind corrected
  double deform_linear_ms = 0.0;      // the same, linear (the correction off)
  double deform_frames_per_s = 0.0;
  double node_modes_per_s = 0.0;                // nodes x modes deformed per second
  double fma_peak_gfma_s = 0.0;                 // measured in the same process
  double deform_fraction_of_peak = 0.0;         // 3 FMAs a node-mode at the corrected frames' rate
  double deform_linear_fraction_of_peak = 0.0;  // 3 FMAs a node-mode at the linear frames' rate
  double deform_strong_fraction_of_peak = 0.0;  // the corrected kernel's own 6 (v and w) at its rate
  double damage_fraction_of_peak = 0.0;         // the first case's damage stage: its maps' FMAs at its rate
  double stream_gb_s = 0.0;                     // STREAM triad, same process: the statistics' bandwidth limit
  double trees_reference_ms = 0.0;   // CPU reference: sampling + modal forces + modal step, per step
  double deform_reference_ms = 0.0;  // CPU reference: one frame's deformation
  std::vector<CoupledBenchCase> cases;
};

CoupledBenchResult run_coupled_bench(host::ComputeContext& cc, const CoupledBenchOptions& options);
/// The converged laminar case on each grid over the ranks of `world` (see above). Collective.
RanksBenchResult run_coupled_bench_ranks(host::ComputeContext& cc, const CoupledBenchOptions& options,
                                         const host::Communicator& world);
void print_coupled_bench_table(const CoupledBenchResult& result, std::ostream& out);
std::string coupled_bench_json(const CoupledBenchResult& result);

}  // namespace fw::bench
