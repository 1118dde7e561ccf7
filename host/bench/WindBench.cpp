#include "host/bench/WindBench.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "base/WallClock.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/SolidMap.hpp"
#include "host/bench/BenchTurbulence.hpp"
#include "host/bench/GatherThroughput.hpp"
#include "host/bench/StageTraffic.hpp"
#include "host/bench/StreamTriad.hpp"
#include "io/JsonWriter.hpp"

namespace fw::bench {
namespace {

// Steps timed from the uniform start (the issue: at most 1.5x a developed step).
constexpr int kStartupSteps = 5;
// The CFL number of dt: auto that scenarios default to (io: time.cfl), for the semi-Lagrangian schemes.
constexpr double kDefaultCfl = 0.8;

using Clock = base::WallClock;
using base::ms_since;

// What a timed run adds to the laminar wind tunnel: the cost of turbulence is the difference.
enum class Turbulence {
  none,
  inflow,          // the synthetic inflow box swept through the inflow face
  inflow_subgrid,  // and a Smagorinsky eddy viscosity and the rough-wall stress
};

host::WindGridSetup bench_setup(const std::array<int, 3>& grid, fluid::PressureSolverType solver,
                                const WindBenchOptions& opt, Turbulence turbulence) {
  host::WindGridSetup setup = wind_tunnel_setup(grid[0], grid[1], grid[2], solver, opt.jacobi_iterations);
  if (turbulence == Turbulence::none) return setup;
  add_bench_turbulence(setup, grid);
  if (turbulence == Turbulence::inflow_subgrid) add_bench_subgrid_stress(setup);
  return setup;
}

// How a timed run shares the machine with other ranks (the default: one process). Every rank of `world`
// starts its clock at the same moment; over `blocks` each steps its block of the grid, without them each
// steps the whole grid on its own (the one-rank baseline of the run over ranks).
struct RanksRun {
  const host::Communicator* world = &host::Communicator::alone();
  const host::WindBlocks* blocks = nullptr;
};

SolverRun time_solver(host::ComputeContext& cc, const std::array<int, 3>& grid,
                      fluid::PressureSolverType solver, const WindBenchOptions& opt,
                      Turbulence turbulence = Turbulence::none, const RanksRun& ranks = {}) {
  host::WindGrid wind(cc, bench_setup(grid, solver, opt, turbulence), ranks.blocks);
  if (turbulence != Turbulence::none) wind.set_turbulence_sigma(kBenchTurbulenceSigma);
  wind.initialise_ambient();
  cc.finish();
  // The start-up: the first steps from the uniform start, while the wake forms (timed, not in the means).
  SolverRun run;
  const int startup = std::min(kStartupSteps, opt.warmup_steps);
  const auto startup_begin = Clock::now();
  for (int s = 0; s < startup; ++s) run.startup_pressure_iterations += wind.step().pressure.iterations;
  cc.finish();
  if (startup > 0) {
    run.startup_ms_per_step = ms_since(startup_begin) / startup;
    run.startup_pressure_iterations /= startup;
  }
  for (int s = startup; s < opt.warmup_steps; ++s) wind.step();
  cc.finish();
  wind.set_stage_timing(true);
  run.solver = fluid::to_string(solver) + (turbulence == Turbulence::inflow           ? "+turb"
                                           : turbulence == Turbulence::inflow_subgrid ? "+turb+sgs"
                                                                                      : "");
  const double traffic_before = wind.pressure().traffic_bytes();
  const host::HaloTraffic halo_before = wind.halo_traffic();
  ranks.world->barrier();
  const auto start = Clock::now();
  for (int s = 0; s < opt.steps; ++s) {
    const auto report = wind.step();
    run.pressure_iterations += report.pressure.iterations;
    run.relative_residual += report.pressure.relative_residual;
  }
  cc.finish();
  const double total_ms = ms_since(start);
  run.ms_per_step = total_ms / opt.steps;
  run.halo = wind.halo_traffic() - halo_before;
  run.pressure_iterations /= opt.steps;
  run.relative_residual /= opt.steps;
  for (const auto& [stage, ms] : wind.stage_ms()) run.stages_ms[stage] = ms / opt.steps;
  run.max_divergence = wind.max_divergence();
  const double vmax = wind.max_speed_component();
  run.divergence_ratio = vmax > 0 ? run.max_divergence * wind.spec().h / vmax : 0.0;
  run.cells_steps_per_s = double(wind.spec().cell_count()) * opt.steps / (total_ms * 1e-3);
  // Throughput of the stages against their limits: per-step traffic over per-step time.
  const auto& spec = wind.spec();
  const double cells = double(spec.cell_count());
  const double faces = double(spec.u_count() + spec.v_count() + spec.w_count());
  auto per_second = [&](double amount, const char* stage) {
    const auto it = run.stages_ms.find(stage);
    return it == run.stages_ms.end() || it->second <= 0.0 ? 0.0 : amount / (it->second * 1e-3);
  };
  run.advect_loads_per_s = per_second(faces * wind.advection_method().gathered_loads_per_face, "advect");
  run.divergence_gb_s = per_second(cells * kDivergenceBytesPerCell, "divergence") * 1e-9;
  run.gradient_gb_s = per_second(cells * kGradientBytesPerCell, "gradient") * 1e-9;
  run.pressure_gb_s =
      per_second((wind.pressure().traffic_bytes() - traffic_before) / opt.steps, "pressure") * 1e-9;
  return run;
}

// The turbulent wind tunnel with `scheme` at its own dt: auto (SchemeRun).
SchemeRun time_scheme(host::ComputeContext& cc, const std::array<int, 3>& grid, fluid::AdvectionScheme scheme,
                      fluid::StageProjection projection, const WindBenchOptions& opt) {
  host::WindGridSetup setup =
      bench_setup(grid, fluid::PressureSolverType::cg, opt, Turbulence::inflow_subgrid);
  setup.settings.advection = scheme;
  setup.settings.stage_projection = projection;
  const double limit = host::advection_method(scheme).courant_limit;
  setup.settings.cfl = std::isfinite(limit) ? limit : kDefaultCfl;
  host::WindGrid wind(cc, setup);
  wind.set_turbulence_sigma(kBenchTurbulenceSigma);
  wind.initialise_ambient();
  for (int s = 0; s < opt.warmup_steps; ++s) wind.step();
  cc.finish();
  wind.set_stage_timing(true);
  SchemeRun run;
  run.scheme = scheme;
  run.projection = projection;
  run.cfl = setup.settings.cfl;
  const double t0 = wind.time();
  const auto start = Clock::now();
  for (int s = 0; s < opt.steps; ++s) wind.step();
  cc.finish();
  run.ms_per_step = ms_since(start) / opt.steps;
  run.dt = (wind.time() - t0) / opt.steps;
  run.ms_per_simulated_second = run.ms_per_step / run.dt;
  run.advect_ms = wind.stage_ms().at("advect") / opt.steps;
  const auto& spec = wind.spec();
  const double faces = double(spec.u_count() + spec.v_count() + spec.w_count());
  run.advect_gb_s = faces * host::advection_method(scheme).bytes_per_face / (run.advect_ms * 1e-3) * 1e-9;
  return run;
}

// The scheme, and "+stages" where upwind5 projects every stage.
std::string scheme_label(const SchemeRun& run) {
  return fluid::to_string(run.scheme) +
         (run.projection == fluid::StageProjection::every_stage ? "+stages" : "");
}

// One step of the CPU reference with the same stages: advect, boundaries, divergence, CG to 1e-3, gradient.
double time_reference_step(const std::array<int, 3>& grid) {
  const auto setup = wind_tunnel_setup(grid[0], grid[1], grid[2], fluid::PressureSolverType::cg, 0);
  const auto& spec = setup.spec;
  const auto level = fluid::build_fine_pressure_level(spec, setup.solid);
  fluid::InflowState inflow;
  for (int a = 0; a < 3; ++a) inflow.ambient[a] = float(setup.ambient[a]);
  inflow.profile = setup.profile.sample_cell_centres(spec.nz, spec.h);
  fluid::MacVelocity vel(spec);
  for (auto& x : vel.u) x = inflow.ambient[0];
  fluid::reference::enforce_boundaries(spec, level, inflow, vel);
  std::vector<float> phi;
  const auto start = Clock::now();
  vel = fluid::reference::advect_semi_lagrangian(spec, inflow, vel, vel, setup.settings.dt);
  fluid::reference::enforce_boundaries(spec, level, inflow, vel);
  const auto b = fluid::reference::divergence_rhs(spec, level, vel);
  fluid::reference::solve_pressure_cg(spec, level, b, phi, 1e-3, 10000);
  fluid::reference::subtract_gradient(spec, level, phi, vel);
  return ms_since(start);
}

// The ranks' blocks of the wind tunnel, made as the planner makes a run's (host/app/plan/WindPlan.cpp): the
// split that exchanges the fewest halo cells, and the halo a back-trace needs at the ambient wind's Courant
// number.
host::WindBlocks bench_blocks(const host::WindGridSetup& setup, const host::Communicator& world) {
  const double speed = std::hypot(setup.ambient[0], setup.ambient[1], setup.ambient[2]);
  const double courant = speed * setup.settings.dt / setup.spec.h;
  return {&world,
          fluid::Decomposition::make(setup.spec, world.size(), std::nullopt,
                                     host::advection_method(setup.settings.advection).halo_cells(courant))};
}

}  // namespace

host::WindGridSetup wind_tunnel_setup(int nx, int ny, int nz, fluid::PressureSolverType solver,
                                      int jacobi_iterations) {
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = 1.0;
  spec.boundary = {fluid::BoundaryType::inflow, fluid::BoundaryType::outflow, fluid::BoundaryType::slip,
                   fluid::BoundaryType::slip,   fluid::BoundaryType::slip,    fluid::BoundaryType::slip};
  setup.settings.dt = 0.05;
  setup.settings.pressure.solver = solver;
  setup.settings.pressure.tolerance = 1e-3;
  setup.settings.pressure.max_iterations = 200;
  if (jacobi_iterations > 0) setup.settings.pressure.jacobi_iterations = jacobi_iterations;
  setup.ambient = {10.0, 0.0, 0.0};
  fluid::SolidMap solids(spec);
  const double L[3] = {nx * spec.h, ny * spec.h, nz * spec.h};
  solids.add(fluid::SolidBox{
      "obstacle", {0.5 * L[0], 0.5 * L[1], 0.5 * L[2]}, {0.125 * L[0], 0.25 * L[1], 0.25 * L[2]}, 0.0});
  setup.solid = solids.cells();
  return setup;
}

double measure_smoother_gb_s(host::ComputeContext& cc, const std::array<int, 3>& grid, SmootherPass kind,
                             int passes) {
  fluid::GridSpec spec;
  spec.nx = grid[0];
  spec.ny = grid[1];
  spec.nz = grid[2];
  spec.h = 1.0;
  spec.boundary[FW_FACE_EAST] = fluid::BoundaryType::outflow;
  std::vector<fluid::PressureLevel> fine{fluid::build_fine_pressure_level(spec, {})};
  host::PressureSolver solver(cc, spec, std::move(fine), fluid::PressureSettings{});
  cl::Buffer other = cc.buffer(spec.cell_count() * sizeof(float));
  auto pass = [&](int n) {
    cl::Buffer& from = (n & 1) ? other : solver.solution();
    cl::Buffer& to = (n & 1) ? solver.solution() : other;
    switch (kind) {
      case SmootherPass::red_black_in_place:
        return solver.enqueue_red_black_update(0, solver.rhs(), solver.solution(), n & 1);
      case SmootherPass::red_black_out_of_place:
        return solver.enqueue_red_black_pass(0, solver.rhs(), from, to, n & 1);
      case SmootherPass::jacobi:
        return solver.enqueue_jacobi_sweep(0, solver.rhs(), from, to, 1.0f);
    }
  };
  pass(0), pass(1);
  cc.finish();
  // Best single pass, as STREAM reports its best run: the machine's other load only ever slows a pass down.
  double seconds = 1e30;
  for (int n = 0; n < passes; ++n) {
    const auto start = Clock::now();
    pass(n);
    cc.finish();
    seconds = std::min(seconds, ms_since(start) * 1e-3);
  }
  const double bytes = double(spec.cell_count()) * (1 + 4 + 4 + 4);
  return bytes / seconds * 1e-9;
}

WindBenchResult run_wind_bench(host::ComputeContext& cc, const WindBenchOptions& opt) {
  WindBenchResult result;
  result.device = cc.device().device_name;
  result.steps = opt.steps;
  result.triad_gb_s = measure_stream_triad(cc, kRooflineElements, kRooflineRepetitions);
  result.corner_loads = measure_corner_load_rates(cc, opt.roofline_grid, 10);
  result.roofline_grid = opt.roofline_grid;
  result.roofline_smoother_gb_s =
      measure_smoother_gb_s(cc, opt.roofline_grid, SmootherPass::red_black_in_place, 20);
  result.roofline_out_of_place_gb_s =
      measure_smoother_gb_s(cc, opt.roofline_grid, SmootherPass::red_black_out_of_place, 20);
  result.roofline_jacobi_gb_s = measure_smoother_gb_s(cc, opt.roofline_grid, SmootherPass::jacobi, 20);
  for (const auto& grid : opt.grids) {
    WindBenchCase c;
    c.grid = grid;
    for (auto solver : {fluid::PressureSolverType::cg, fluid::PressureSolverType::multigrid,
                        fluid::PressureSolverType::jacobi})
      c.runs.push_back(time_solver(cc, grid, solver, opt));
    if (opt.turbulence) {
      c.runs.push_back(time_solver(cc, grid, fluid::PressureSolverType::cg, opt, Turbulence::inflow));
      c.runs.push_back(time_solver(cc, grid, fluid::PressureSolverType::cg, opt, Turbulence::inflow_subgrid));
    }
    if (opt.schemes)
      for (auto scheme : {fluid::AdvectionScheme::semi_lagrangian, fluid::AdvectionScheme::maccormack,
                          fluid::AdvectionScheme::upwind5})
        c.schemes.push_back(time_scheme(cc, grid, scheme, fluid::StageProjection::final_stage, opt));
    if (opt.schemes)  // and upwind5 projecting every Runge-Kutta stage
      c.schemes.push_back(
          time_scheme(cc, grid, fluid::AdvectionScheme::upwind5, fluid::StageProjection::every_stage, opt));
    c.smoother_gb_s = measure_smoother_gb_s(cc, grid, SmootherPass::red_black_in_place, 20);
    if (opt.reference && std::size_t(grid[0]) * grid[1] * grid[2] <= (std::size_t(1) << 18))
      c.reference_ms_per_step = time_reference_step(grid);
    result.cases.push_back(std::move(c));
  }
  return result;
}

RanksBenchResult run_wind_bench_ranks(host::ComputeContext& cc, const WindBenchOptions& opt,
                                      const host::Communicator& world) {
  constexpr auto cg = fluid::PressureSolverType::cg;
  RanksBenchResult result;
  result.bench = "wind";
  result.device = cc.device().device_name;
  result.workload = "the wind tunnel, cg to 1e-3";
  result.skipped =
      "the multigrid and Jacobi solvers, turbulence, the advection schemes, the smoother, the CPU reference "
      "and the roofline (STREAM triad, corner loads)";
  result.ranks = world.size();
  result.steps = opt.steps;
  for (const auto& grid : opt.grids) {
    const host::WindGridSetup setup = bench_setup(grid, cg, opt, Turbulence::none);
    const host::WindBlocks blocks = bench_blocks(setup, world);
    // The one-rank baseline: every rank steps the whole grid at once, each on its own device, so that each
    // has the share of the machine it has in the run over ranks.
    double alone_ms = 0.0;
    if (alone_run_fits(world, cc.device(), host::WindGrid::estimate_device_bytes(setup)))
      alone_ms = time_solver(cc, grid, cg, opt, Turbulence::none, {&world, nullptr}).ms_per_step;
    const SolverRun split = time_solver(cc, grid, cg, opt, Turbulence::none, {&world, &blocks});
    result.cases.push_back(
        gather_case(world, grid, blocks.decomposition,
                    {split.ms_per_step, alone_ms, split.halo, opt.steps, split.pressure_iterations}));
  }
  return result;
}

void print_wind_bench_table(const WindBenchResult& r, std::ostream& out) {
  out << fmt::format("forestwind bench wind on {}: {} timed steps per solver\n", r.device, r.steps);
  out << fmt::format("STREAM triad (device, same process): {:.1f} GB/s\n", r.triad_gb_s);
  auto of_triad = [&](double gb_s) {
    return fmt::format("{:.1f} GB/s ({:.0f}% of triad)", gb_s, 100.0 * gb_s / r.triad_gb_s);
  };
  out << fmt::format("smoother on {}x{}x{}: red-black pass in place {}, out of place {}, Jacobi sweep {}\n\n",
                     r.roofline_grid[0], r.roofline_grid[1], r.roofline_grid[2],
                     of_triad(r.roofline_smoother_gb_s), of_triad(r.roofline_out_of_place_gb_s),
                     of_triad(r.roofline_jacobi_gb_s));
  out << fmt::format("{:<12} {:<11} {:>9} {:>8} {:>8} {:>8} {:>9} {:>9} {:>8} {:>9} {:>10} {:>10} {:>12}\n",
                     "grid", "solver", "ms/step", "advect", "bound.", "sgs+wall", "diverg.", "pressure",
                     "gradient", "p-iters", "rel.res.", "max|div|", "Mcell*st/s");
  for (const auto& c : r.cases) {
    const std::string grid = fmt::format("{}x{}x{}", c.grid[0], c.grid[1], c.grid[2]);
    const double base = c.runs.front().ms_per_step;
    for (const auto& run : c.runs) {
      auto stage = [&](const char* name) {
        auto it = run.stages_ms.find(name);
        return it == run.stages_ms.end() ? 0.0 : it->second;
      };
      out << fmt::format(
          "{:<12} {:<11} {:>9.2f} {:>8.2f} {:>8.2f} {:>8.2f} {:>9.2f} {:>9.2f} {:>8.2f} {:>9.1f} {:>10.2e} "
          "{:>10.2e} {:>12.1f}   x{:.2f}\n",
          grid, run.solver, run.ms_per_step, stage("advect"), stage("boundaries"),
          stage("subgrid") + stage("wall"), stage("divergence"), stage("pressure"), stage("gradient"),
          run.pressure_iterations, run.relative_residual, run.max_divergence, run.cells_steps_per_s * 1e-6,
          run.ms_per_step / base);
    }
    out << fmt::format("{:<12} smoother (in place) {}", grid, of_triad(c.smoother_gb_s));
    if (c.reference_ms_per_step > 0)
      out << fmt::format("; CPU reference step {:.0f} ms = x{:.1f} the device's cg step",
                         c.reference_ms_per_step, c.reference_ms_per_step / base);
    out << "\n";
    const SolverRun& head = c.runs.front();
    if (head.startup_ms_per_step > 0)
      out << fmt::format(
          "{:<12} start-up: the first {} {} steps from the uniform start {:.2f} ms/step ({:.1f} "
          "pressure iterations) = x{:.2f} a developed step\n",
          grid, kStartupSteps, head.solver, head.startup_ms_per_step, head.startup_pressure_iterations,
          head.startup_ms_per_step / base);
  }
  out << "ratios (x) are to the converging solver (cg) on the same grid; +turb: with the inflow turbulence "
         "box (15%, L_u 16 cells), +sgs: and Smagorinsky (C_s 0.16) and the rough-wall stress\n";
  out << fmt::format(
      "\nagainst the limit that binds each stage: eight-corner loads on {}x{}x{} {:.2f} Gload/s windowed, "
      "{:.2f} Gload/s scattered (gathers); STREAM triad {:.1f} GB/s\n",
      r.roofline_grid[0], r.roofline_grid[1], r.roofline_grid[2], r.corner_loads.windowed * 1e-9,
      r.corner_loads.scattered * 1e-9, r.triad_gb_s);
  out << fmt::format("{:<12} {:<11} {:>29} {:>22} {:>22} {:>22}\n", "grid", "solver",
                     "advect Gload/s (wind./gath.)", "divergence GB/s", "pressure GB/s", "gradient GB/s");
  for (const auto& c : r.cases) {
    const std::string grid = fmt::format("{}x{}x{}", c.grid[0], c.grid[1], c.grid[2]);
    auto share = [](double value, double limit) { return limit > 0.0 ? 100.0 * value / limit : 0.0; };
    for (const auto& run : c.runs)
      out << fmt::format(
          "{:<12} {:<11} {:>13.2f} ({:>3.0f}% / {:>3.0f}%) {:>14.1f} ({:>3.0f}%) {:>14.1f} ({:>3.0f}%) "
          "{:>14.1f} ({:>3.0f}%)\n",
          grid, run.solver, run.advect_loads_per_s * 1e-9,
          share(run.advect_loads_per_s, r.corner_loads.windowed),
          share(run.advect_loads_per_s, r.corner_loads.scattered), run.divergence_gb_s,
          share(run.divergence_gb_s, r.triad_gb_s), run.pressure_gb_s, share(run.pressure_gb_s, r.triad_gb_s),
          run.gradient_gb_s, share(run.gradient_gb_s, r.triad_gb_s));
  }
  out << "(%: of the windowed and the scattered corner-load rates for advection, of the triad for the rest; "
         "traffic per host/bench/StageTraffic.hpp)\n";
  bool any_schemes = false;
  for (const auto& c : r.cases) any_schemes = any_schemes || !c.schemes.empty();
  if (!any_schemes) return;
  out << "\nadvection schemes at their own dt: auto (cg, inflow turbulence, Smagorinsky and wall stress)\n";
  out << fmt::format("{:<12} {:<16} {:>5} {:>9} {:>8} {:>11} {:>8} {:>18} {:>9}\n", "grid", "scheme", "CFL",
                     "ms/step", "dt ms", "ms/sim. s", "advect", "advect GB/s", "x SL/s");
  for (const auto& c : r.cases) {
    const std::string grid = fmt::format("{}x{}x{}", c.grid[0], c.grid[1], c.grid[2]);
    for (const auto& run : c.schemes)
      out << fmt::format(
          "{:<12} {:<16} {:>5.2f} {:>9.2f} {:>8.2f} {:>11.1f} {:>8.2f} {:>9.1f} ({:>3.0f}%) {:>9.2f}\n", grid,
          scheme_label(run), run.cfl, run.ms_per_step, run.dt * 1e3, run.ms_per_simulated_second,
          run.advect_ms, run.advect_gb_s, r.triad_gb_s > 0 ? 100.0 * run.advect_gb_s / r.triad_gb_s : 0.0,
          run.ms_per_simulated_second / c.schemes.front().ms_per_simulated_second);
  }
  out << "(CFL: the largest component's for the semi-Lagrangian schemes, the summed Courant number for "
         "upwind5; "
         "x SL/s: cost per simulated second over semi_lagrangian's; %: of the triad)\n";
}

namespace {
void write_case(io::JsonWriter& json, const WindBenchCase& c, const WindBenchResult& r) {
  const SolverRun& head = c.runs.front();
  json.key("grid").values(c.grid);
  json.key("solver").value(head.solver);
  json.key("ms_per_step").value(head.ms_per_step);
  json.key("stages_ms").object(head.stages_ms);
  json.key("pressure_iterations").value(head.pressure_iterations);
  json.key("relative_residual").value(head.relative_residual);
  json.key("max_divergence").value(head.max_divergence);
  json.key("divergence_ratio").value(head.divergence_ratio);
  json.key("cells_steps_per_s").value(head.cells_steps_per_s);
  json.key("startup_ms_per_step").value(head.startup_ms_per_step);
  json.key("startup_pressure_iterations").value(head.startup_pressure_iterations);
  json.key("triad_gb_s").value(r.triad_gb_s);
  json.key("gather_loads_per_s").value(r.corner_loads.scattered);
  json.key("windowed_loads_per_s").value(r.corner_loads.windowed);
  json.key("smoother_gb_s").value(c.smoother_gb_s);
  json.key("limits").begin_object();
  json.key("advect_loads_per_s").value(head.advect_loads_per_s);
  json.key("advect_gather_fraction")
      .value(r.corner_loads.scattered > 0 ? head.advect_loads_per_s / r.corner_loads.scattered : 0.0);
  json.key("advect_window_fraction")
      .value(r.corner_loads.windowed > 0 ? head.advect_loads_per_s / r.corner_loads.windowed : 0.0);
  json.key("divergence_gb_s").value(head.divergence_gb_s);
  json.key("pressure_gb_s").value(head.pressure_gb_s);
  json.key("gradient_gb_s").value(head.gradient_gb_s);
  json.key("pressure_triad_fraction").value(r.triad_gb_s > 0 ? head.pressure_gb_s / r.triad_gb_s : 0.0);
  json.end_object();
  if (c.reference_ms_per_step > 0) json.key("reference_ms_per_step").value(c.reference_ms_per_step);
  json.key("solvers").begin_array();
  for (const auto& run : c.runs) {
    json.begin_object();
    json.key("solver").value(run.solver);
    json.key("ms_per_step").value(run.ms_per_step);
    json.key("pressure_iterations").value(run.pressure_iterations);
    json.key("relative_residual").value(run.relative_residual);
    json.key("max_divergence").value(run.max_divergence);
    json.key("stages_ms").object(run.stages_ms);
    json.end_object();
  }
  json.end_array();
  json.key("schemes").begin_array();
  for (const auto& run : c.schemes) {
    json.begin_object();
    json.key("scheme").value(fluid::to_string(run.scheme));
    json.key("stage_projection")
        .value(run.projection == fluid::StageProjection::every_stage ? "every_stage" : "final_stage");
    json.key("cfl").value(run.cfl);
    json.key("ms_per_step").value(run.ms_per_step);
    json.key("dt").value(run.dt);
    json.key("ms_per_simulated_second").value(run.ms_per_simulated_second);
    json.key("advect_ms").value(run.advect_ms);
    json.key("advect_gb_s").value(run.advect_gb_s);
    json.key("advect_triad_fraction").value(r.triad_gb_s > 0 ? run.advect_gb_s / r.triad_gb_s : 0.0);
    json.end_object();
  }
  json.end_array();
}
}  // namespace

std::string wind_bench_json(const WindBenchResult& r) {
  io::JsonWriter json;
  json.begin_object();
  json.key("device").value(r.device);
  json.key("steps").value(r.steps);
  // The first case's keys at the top level, so a single --grid gives the flat object docs/design.md lists.
  if (!r.cases.empty()) write_case(json, r.cases.front(), r);
  json.key("roofline").begin_object();
  json.key("grid")
      .begin_array()
      .value(r.roofline_grid[0])
      .value(r.roofline_grid[1])
      .value(r.roofline_grid[2])
      .end_array();
  json.key("red_black_gb_s").value(r.roofline_smoother_gb_s);
  json.key("red_black_out_of_place_gb_s").value(r.roofline_out_of_place_gb_s);
  json.key("jacobi_gb_s").value(r.roofline_jacobi_gb_s);
  json.end_object();
  json.key("cases").begin_array();
  for (const auto& c : r.cases) {
    json.begin_object();
    write_case(json, c, r);
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace fw::bench
