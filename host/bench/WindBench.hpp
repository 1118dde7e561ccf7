// `forestwind bench wind`: the wind-tunnel case, timed on the OpenCL device.
//
// The case: cubic cells of 1 m, 10 m/s inflow on the west face, outflow on the east face, free-slip on the
// others, dt = 0.05 s, and a box obstacle over x 0.4375-0.5625 and y, z 0.375-0.625 of the domain. The
// pressure uses the converging solver (multigrid-preconditioned CG) to a relative residual of 1e-3;
// multigrid V-cycles and fixed-count Jacobi (the seed's method) run the same steps for comparison.
// Baselines measured in the same process: a STREAM triad on the device (roofline), the rates of advection's
// eight-corner loads, scattered (gathers) and windowed (a smooth flow's back-traces), the smoother's
// bandwidth on a grid too large for cache, and one step of the CPU reference (fluid/ReferenceStages). Each
// stage's throughput is reported as a fraction of the limit that binds it (host/bench/StageTraffic.hpp).
//
//   WindBenchOptions opt;                 // default grids 128x128x64, 64x64x32, 256x256x16
//   WindBenchResult r = run_wind_bench(cc, opt);
//   print_wind_bench_table(r, std::cout);
//
// Over MPI ranks (mpirun -np N, N > 1) run_wind_bench_ranks times the converging solver's case on each grid,
// split into the blocks a run would take, against every rank stepping the whole grid alone at the same time
// (host/bench/RanksBench.hpp); the comparison solvers and the baselines above run in one process only.
//
//   RanksBenchResult r = run_wind_bench_ranks(cc, opt, world);   // collective; r.cases filled on rank 0
#pragma once

#include <array>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "host/bench/GatherThroughput.hpp"
#include "host/bench/RanksBench.hpp"

#include "host/runtime/ComputeContext.hpp"
#include "host/stages/WindGrid.hpp"

namespace fw::bench {

struct WindBenchOptions {
  std::vector<std::array<int, 3>> grids{{128, 128, 64}, {64, 64, 32}, {256, 256, 16}};
  int steps = 20;         // timed steps per solver
  int warmup_steps = 10;  // untimed steps first, so the wake has formed
  int jacobi_iterations = 40;
  bool reference = true;   // time one CPU-reference step on grids up to 64^3 cells
  bool turbulence = true;  // also time cg with the inflow turbulence, and with it Smagorinsky + wall stress
  bool schemes = true;     // time each advection scheme at its own dt: auto (cg, inflow turbulence, subgrid)
  std::array<int, 3> roofline_grid{256, 256, 128};  // smoother bandwidth, too large for cache
};

struct SolverRun {
  std::string solver;  // "cg", "multigrid", "jacobi"
  double ms_per_step = 0.0;
  std::map<std::string, double> stages_ms;  // per step
  double pressure_iterations = 0.0;         // mean per step
  double relative_residual = 0.0;           // mean per step
  double max_divergence = 0.0;              // max |div u| after the last projection, 1/s
  double divergence_ratio = 0.0;            // max|div u| h / max|u|
  double cells_steps_per_s = 0.0;
  double startup_ms_per_step = 0.0;          // the first steps from the uniform start (kStartupSteps)
  double startup_pressure_iterations = 0.0;  // mean over those steps
  // What the stages reach against the limit that binds them (host/bench/StageTraffic.hpp):
  double advect_loads_per_s = 0.0;  ///< corner loads of the advection kernels (padding included in the time)
  double divergence_gb_s = 0.0, pressure_gb_s = 0.0, gradient_gb_s = 0.0;
  host::HaloTraffic halo;  ///< this rank's halo exchanges over the timed steps (none in one process)
};

/// One advection scheme on the turbulent wind tunnel (cg, inflow turbulence, Smagorinsky and wall stress) at
/// its own dt: auto: the semi-Lagrangian schemes at the scenario default CFL number 0.8, upwind5 at its
/// summed Courant limit (fluid::kUpwind5CourantLimit).
struct SchemeRun {
  fluid::AdvectionScheme scheme{};
  fluid::StageProjection projection = fluid::StageProjection::final_stage;
  double cfl = 0.0;  // the CFL number the run asked for
  double ms_per_step = 0.0;
  double dt = 0.0;                       // mean step, s
  double ms_per_simulated_second = 0.0;  // ms_per_step / dt
  double advect_ms = 0.0;                // per step
  double advect_gb_s = 0.0;              // advection's traffic (host/bench/StageTraffic.hpp) over its time
};

struct WindBenchCase {
  std::array<int, 3> grid{};
  std::vector<SolverRun> runs;         // converging solver first
  std::vector<SchemeRun> schemes;      // semi-Lagrangian first, the baseline of the schemes' ratios
  double smoother_gb_s = 0.0;          // in-place red-black Gauss-Seidel pass (the solver's) on this grid
  double reference_ms_per_step = 0.0;  // 0 when not measured
};

struct WindBenchResult {
  std::string device;
  double triad_gb_s = 0.0;
  CornerLoadRates corner_loads;         // eight-corner loads (host/bench/GatherThroughput) on roofline_grid
  double roofline_smoother_gb_s = 0.0;  // in-place red-black pass on roofline_grid
  double roofline_out_of_place_gb_s = 0.0;  // out-of-place red-black pass on roofline_grid
  double roofline_jacobi_gb_s = 0.0;        // Jacobi sweep on roofline_grid
  std::array<int, 3> roofline_grid{};
  int steps = 0;
  std::vector<WindBenchCase> cases;
};

/// The wind-tunnel case on an nx x ny x nz grid, with the given pressure solver.
host::WindGridSetup wind_tunnel_setup(int nx, int ny, int nz, fluid::PressureSolverType solver,
                                      int jacobi_iterations);

WindBenchResult run_wind_bench(host::ComputeContext& cc, const WindBenchOptions& options);
/// The converging solver's case on each grid over the ranks of `world` (see above). Collective.
RanksBenchResult run_wind_bench_ranks(host::ComputeContext& cc, const WindBenchOptions& options,
                                      const host::Communicator& world);
void print_wind_bench_table(const WindBenchResult& result, std::ostream& out);
std::string wind_bench_json(const WindBenchResult& result);

/// The smoother passes the benchmark times: a red-black colour pass in place (the solver's on large levels)
/// or out of place (through a second buffer), or one Jacobi sweep.
enum class SmootherPass { red_black_in_place, red_black_out_of_place, jacobi };

/// Bandwidth of a pressure smoother pass on a grid, GB/s: the best of `passes` timed passes, counting the
/// bytes each pass streams: mask 1 + b 4 + phi read 4 + phi write 4 per cell.
double measure_smoother_gb_s(host::ComputeContext& cc, const std::array<int, 3>& grid, SmootherPass kind,
                             int passes);

}  // namespace fw::bench
