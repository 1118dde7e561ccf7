// The pressure kernels against the CPU reference, and the solvers' convergence on the device.
#include <catch2/catch.hpp>

#include <cmath>

#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "host/stages/PressureSolver.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;

namespace {

// Float kernels against the double reference: a few ulps of the magnitude.
constexpr double kKernelTolerance = 1e-5;

struct SolverFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec;
  std::vector<std::uint8_t> solid = test::box_solid(spec);
  std::vector<fluid::PressureLevel> levels = fluid::build_pressure_levels(spec, solid, 64);
  host::PressureSolver solver;
  explicit SolverFixture(host::ComputeContext& c, fluid::PressureSettings settings = {},
                         const fluid::GridSpec& grid = test::mixed_boundary_spec())
      : cc(c), spec(grid), solver(c, spec, levels, settings) {}
  std::size_t n(int l) const { return levels[l].cell_count(); }
};

// Norm of b - A phi in double, computed here from scratch (independent of both the kernels and the
// reference's float residual).
double residual_norm(const fluid::GridSpec& spec, const fluid::PressureLevel& L, const std::vector<float>& b,
                     const std::vector<float>& phi) {
  const auto Aphi = ref::apply_operator(spec, L, phi);
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!(L.mask[i] & FW_MASK_FLUID)) continue;
    const double r = double(b[i]) - double(Aphi[i]);
    sum += r * r;
  }
  return std::sqrt(sum);
}

}  // namespace

TEST_CASE("pressure kernels: Jacobi, red-black, residual, restriction and prolongation match the reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // The ragged grid's levels (37 x 23 x 11, 19 x 12 x 6) end in part-filled work-groups (test::ragged_spec).
  SolverFixture f(*cc, {}, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  REQUIRE(f.levels.size() >= 2);
  const auto b = test::random_cells(f.n(0), 1.0, 5);
  const auto phi = test::random_cells(f.n(0), 1.0, 6);
  cl::Buffer db = cc->buffer(f.n(0) * 4), dphi = cc->buffer(f.n(0) * 4), dout = cc->buffer(f.n(0) * 4);
  auto reset = [&] { test::upload(*cc, b, db), test::upload(*cc, phi, dphi); };

  reset();
  f.solver.enqueue_jacobi_sweep(0, db, dphi, dout, 0.8f);
  CHECK(test::relative_error(test::download(*cc, dout, f.n(0)),
                             ref::jacobi_sweep(f.spec, f.levels[0], b, phi, 0.8)) < kKernelTolerance);

  reset();
  f.solver.enqueue_red_black_pass(0, db, dphi, dout, 0);
  f.solver.enqueue_red_black_pass(0, db, dout, dphi, 1);
  auto expected = phi;
  ref::red_black_sweep(f.spec, f.levels[0], b, expected, 0);
  ref::red_black_sweep(f.spec, f.levels[0], b, expected, 1);
  CHECK(test::relative_error(test::download(*cc, dphi, f.n(0)), expected) < kKernelTolerance);

  reset();
  const double rr = f.solver.residual_norm2(0, db, dphi, dout);
  const auto expected_r = ref::residual(f.spec, f.levels[0], b, phi);
  CHECK(test::relative_error(test::download(*cc, dout, f.n(0)), expected_r) < kKernelTolerance);
  CHECK(std::sqrt(rr) == Approx(residual_norm(f.spec, f.levels[0], b, phi)).epsilon(1e-5));

  reset();
  f.solver.enqueue_restrict_residual(0, db, dphi);
  const auto expected_bc =
      ref::restrict_residual(f.spec, f.levels[0], f.levels[1], b, phi, f.solver.correction_scale());
  CHECK(test::relative_error(test::download(*cc, f.solver.level_rhs(1), f.n(1)), expected_bc) <
        kKernelTolerance);
  // The restriction also writes the coarse level's first smoothing pass from a zero guess.
  std::vector<float> expected_start(f.n(1), 0.0f);
  ref::red_black_sweep(f.spec, f.levels[1], expected_bc, expected_start, 0);
  CHECK(test::relative_error(test::download(*cc, f.solver.level_first_pass(1), f.n(1)), expected_start) <
        kKernelTolerance);

  reset();
  f.solver.enqueue_smoothing_start(0, db, dout);
  std::vector<float> expected_fine_start(f.n(0), 0.0f);
  ref::red_black_sweep(f.spec, f.levels[0], b, expected_fine_start, 0);
  CHECK(test::relative_error(test::download(*cc, dout, f.n(0)), expected_fine_start) < kKernelTolerance);

  const auto e = test::random_cells(f.n(1), 1.0, 7);
  test::upload(*cc, e, f.solver.level_solution(1));
  reset();
  f.solver.enqueue_prolong_add(0, dphi);
  auto expected_phi = phi;
  ref::prolong_add(f.spec, f.levels[0], f.levels[1], e, f.solver.prolongation_slope(), expected_phi);
  CHECK(test::relative_error(test::download(*cc, dphi, f.n(0)), expected_phi) < kKernelTolerance);
}

TEST_CASE("pressure kernels: linear and piecewise-constant prolongation match the reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Odd fine extents (lone children), periodic y, the outflow face (ghost 0) and the box's closed faces.
  auto spec = test::mixed_boundary_spec();
  spec.nx = 25;
  spec.nz = 11;
  const auto levels = fluid::build_pressure_levels(spec, test::box_solid(spec), 64);
  REQUIRE(levels.size() >= 2);
  const auto phi = test::random_cells(levels[0].cell_count(), 1.0, 8);
  const auto e = test::random_cells(levels[1].cell_count(), 1.0, 9);
  for (const auto solver_type : {fluid::PressureSolverType::multigrid, fluid::PressureSolverType::cg}) {
    fluid::PressureSettings settings;
    settings.solver = solver_type;
    host::PressureSolver solver(*cc, spec, levels, settings);
    INFO("slope " << solver.prolongation_slope());
    cl::Buffer dphi = cc->buffer(levels[0].cell_count() * 4);
    test::upload(*cc, phi, dphi);
    test::upload(*cc, e, solver.level_solution(1));
    solver.enqueue_prolong_add(0, dphi);
    auto expected = phi;
    ref::prolong_add(spec, levels[0], levels[1], e, solver.prolongation_slope(), expected);
    CHECK(test::relative_error(test::download(*cc, dphi, levels[0].cell_count()), expected) <
          kKernelTolerance);
  }
}

TEST_CASE("pressure kernels: in-place red-black passes match the reference's passes") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Rows of 70 cells: four vector chunks and a scalar tail in each interior run, wrap-around in x and y,
  // the box's masked rows, and the walls' planes.
  auto spec = test::mixed_boundary_spec();
  spec.nx = 70;
  spec.ny = 12;
  spec.nz = 10;
  spec.boundary[0] = spec.boundary[1] = fluid::BoundaryType::periodic;
  const auto levels = fluid::build_pressure_levels(spec, test::box_solid(spec), 64);
  host::PressureSolver solver(*cc, spec, levels, {});
  REQUIRE(solver.updates_in_place(0));
  const std::size_t n = levels[0].cell_count();
  const auto b = test::random_cells(n, 1.0, 31);
  auto expected = test::random_cells(n, 1.0, 32);
  cl::Buffer db = cc->buffer(n * 4), dphi = cc->buffer(n * 4);
  test::upload(*cc, b, db);
  test::upload(*cc, expected, dphi);
  constexpr int kSweeps = 2;
  for (int s = 0; s < kSweeps; ++s) {
    for (const int colour : {0, 1}) {
      solver.enqueue_red_black_update(0, db, dphi, colour);
      ref::red_black_sweep(spec, levels[0], b, expected, colour);
    }
  }
  CHECK(test::relative_error(test::download(*cc, dphi, n), expected) < kKernelTolerance);
}

TEST_CASE("pressure kernels: red-black sweeps in one work-group match the reference's sweeps") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  SolverFixture f(*cc);
  // The finest level (24 x 16 x 12: edges, periodic y, the solid box) and the coarsest, in both colour orders
  // (before and after the coarse correction).
  for (const int l : {0, int(f.levels.size()) - 1}) {
    for (const int first : {0, 1}) {
      INFO("level " << l << ", first colour " << first);
      const auto b = test::random_cells(f.n(l), 1.0, 15 + l);
      const auto phi = test::random_cells(f.n(l), 1.0, 16 + l);
      cl::Buffer db = cc->buffer(f.n(l) * 4), dphi = cc->buffer(f.n(l) * 4);
      test::upload(*cc, b, db);
      test::upload(*cc, phi, dphi);
      constexpr int kSweeps = 3;
      f.solver.enqueue_red_black_sweeps(l, db, dphi, kSweeps, first);
      auto expected = phi;
      for (int s = 0; s < kSweeps; ++s) {
        ref::red_black_sweep(f.spec, f.levels[l], b, expected, first);
        ref::red_black_sweep(f.spec, f.levels[l], b, expected, 1 - first);
      }
      CHECK(test::relative_error(test::download(*cc, dphi, f.n(l)), expected) < kKernelTolerance);
    }
  }
}

TEST_CASE("PressureSolver: a V-cycle from a zero guess equals a V-cycle started from a zero-filled phi") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Both smoothers: the shortcut replaces the fill and the first pass (red-black colour 0, or a damped
  // Jacobi sweep) by the start kernel; every later pass is the same.
  for (const auto smoother : {fluid::MultigridSmoother::red_black, fluid::MultigridSmoother::jacobi}) {
    INFO("smoother " << int(smoother));
    fluid::PressureSettings settings;
    settings.smoother = smoother;
    SolverFixture f(*cc, settings);
    const auto b = test::random_cells(f.n(0), 1.0, 21);
    cl::Buffer db = cc->buffer(f.n(0) * 4), from_zero = cc->buffer(f.n(0) * 4),
               from_fill = cc->buffer(f.n(0) * 4);
    test::upload(*cc, b, db);
    test::upload(*cc, test::random_cells(f.n(0), 1.0, 22), from_zero);  // only written, never read
    test::upload(*cc, std::vector<float>(f.n(0), 0.0f), from_fill);
    f.solver.vcycle_from_zero(db, from_zero);
    f.solver.vcycle(db, from_fill);
    CHECK(test::relative_error(test::download(*cc, from_zero, f.n(0)),
                               test::download(*cc, from_fill, f.n(0))) < kKernelTolerance);
  }
}

namespace {

// Projects a random velocity field with `solver` on the device and checks divergence and residual.
void check_projection(fluid::PressureSolverType type, const fluid::GridSpec& spec,
                      std::vector<std::uint8_t> solid, std::uint32_t seed) {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  fluid::PressureSettings settings;
  settings.solver = type;
  // 1e-5: just above the float32 floor of ||b - A phi|| / ||b|| on these random fields, where the true
  // residual stops falling (7.4e-6 for V-cycles, 8e-6 for CG, measured over three seeds) and CG's recursively
  // updated residual parts from it (it falls below 1e-5 while the true one is 1.12e-5: solve_cg restarts).
  settings.tolerance = 1e-5;
  settings.max_iterations = 200;
  const auto fine = fluid::build_fine_pressure_level(spec, solid);
  host::PressureSolver solver(*cc, spec, fluid::build_pressure_levels(spec, solid), settings);
  host::FluidStages stages(*cc, spec);
  const auto inflow = test::test_inflow(spec);
  stages.set_profile(test::upload_profile(*cc, inflow, spec));
  FwStep step{};
  for (int a = 0; a < 3; ++a) step.ambient[a] = inflow.ambient[a];
  stages.set_step(step);

  auto vel = test::random_velocity(spec, 3.0, seed);
  ref::enforce_boundaries(spec, fine, inflow, vel);
  auto dvel = stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  stages.enqueue_divergence_rhs(solver.mask(), dvel, solver.rhs());
  const auto b = test::download(*cc, solver.rhs(), spec.cell_count());
  const host::PressureSolveStatus status = solver.solve();
  INFO("solver " << status.solver << ": " << status.iterations << " iterations, relative residual "
                 << status.relative_residual);
  WARN(status.solver << ": " << status.iterations << " iterations to " << status.relative_residual);
  CHECK(status.iterations < settings.max_iterations);
  // Converged within the tolerance asked for, by the solver's own measure: the true residual ||b - A phi|| /
  // ||b||, recomputed from phi after the solve (not CG's recursively updated one).
  REQUIRE(status.converged);
  CHECK(status.relative_residual <= settings.tolerance);
  for (int c = 0; c < 3; ++c)
    stages.enqueue_subtract_gradient(c, solver.mask(), solver.solution(), dvel.component(c));

  // Divergence after projection, relative to the flow: max|div u| h / max|u| < 1e-4.
  const auto projected = test::download(*cc, dvel, spec);
  double umax = 0.0;
  for (int c = 0; c < 3; ++c)
    for (float x : projected.component(c)) umax = std::max(umax, std::abs(double(x)));
  const double div = ref::max_divergence(spec, fine, projected);
  INFO("max|div u| = " << div << " 1/s, max|u| = " << umax << " m/s");
  CHECK(div * spec.h / umax < 1e-4);

  // The reported residual matches one recomputed here in double from phi and b.
  auto bb = b;
  if (!spec.has_dirichlet_pressure()) {  // the solver removed the mean of b first
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < bb.size(); ++i)
      if (fine.mask[i] & FW_MASK_FLUID) sum += bb[i], ++count;
    for (std::size_t i = 0; i < bb.size(); ++i)
      if (fine.mask[i] & FW_MASK_FLUID) bb[i] = float(bb[i] - sum / count);
  }
  double bnorm = 0.0;
  for (float x : bb) bnorm += double(x) * x;
  bnorm = std::sqrt(bnorm);
  const auto phi = test::download(*cc, solver.solution(), spec.cell_count());
  const double recomputed = residual_norm(spec, fine, bb, phi) / bnorm;
  // The kernel's float residual and this double one differ by the float rounding of A phi, ~1e-6 of ||b||.
  CHECK(status.relative_residual == Approx(recomputed).epsilon(0.05).margin(2e-6));
}

}  // namespace

TEST_CASE("PressureSolver: multigrid-preconditioned CG projects to max|div u| h / max|u| < 1e-4") {
  check_projection(fluid::PressureSolverType::cg, test::mixed_boundary_spec(),
                   test::box_solid(test::mixed_boundary_spec()), 101);
}

TEST_CASE("PressureSolver: multigrid V-cycles project to max|div u| h / max|u| < 1e-4") {
  check_projection(fluid::PressureSolverType::multigrid, test::mixed_boundary_spec(),
                   test::box_solid(test::mixed_boundary_spec()), 102);
}

TEST_CASE("PressureSolver: every stand-alone V-cycle contracts the residual, without a divergence guard") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Both smoothers, on the mixed boundaries with the box, from phi = 0 and a random b. The worst ratio of
  // successive residuals over six cycles is 0.33 (red-black) and 0.63 (damped Jacobi) with linear
  // prolongation and the rediscretised scale; piecewise-constant prolongation with the Galerkin scale, the
  // only stable pair before, gave 0.69 and 0.71, and with the rediscretised scale it diverged.
  const std::pair<fluid::MultigridSmoother, double> cases[] = {{fluid::MultigridSmoother::red_black, 0.45},
                                                               {fluid::MultigridSmoother::jacobi, 0.68}};
  for (const auto& [smoother, bound] : cases) {
    INFO("smoother " << int(smoother));
    fluid::PressureSettings settings;
    settings.solver = fluid::PressureSolverType::multigrid;
    settings.smoother = smoother;
    SolverFixture f(*cc, settings);
    const auto b = test::random_cells(f.n(0), 1.0, 51);
    test::upload(*cc, b, f.solver.rhs());
    test::upload(*cc, std::vector<float>(f.n(0), 0.0f), f.solver.solution());
    cl::Buffer r = cc->buffer(f.n(0) * 4);
    double norm = std::sqrt(f.solver.residual_norm2(0, f.solver.rhs(), f.solver.solution(), r));
    double worst = 0.0;
    constexpr int kCycles = 6;  // down to about 1e-5 of ||b||, above the float32 floor
    for (int c = 0; c < kCycles; ++c) {
      f.solver.vcycle(f.solver.rhs(), f.solver.solution());
      const double next = std::sqrt(f.solver.residual_norm2(0, f.solver.rhs(), f.solver.solution(), r));
      worst = std::max(worst, next / norm);
      norm = next;
    }
    INFO("worst residual ratio a V-cycle: " << worst);
    CHECK(worst < bound);
  }
}

TEST_CASE("PressureSolver: a closed, periodic domain (singular operator) still converges") {
  fluid::GridSpec spec;
  spec.nx = 32;
  spec.ny = 16;
  spec.nz = 8;
  spec.h = 0.5;
  using B = fluid::BoundaryType;
  spec.boundary = {B::periodic, B::periodic, B::no_slip, B::no_slip, B::periodic, B::periodic};
  check_projection(fluid::PressureSolverType::cg, spec, {}, 103);
}

TEST_CASE("PressureSolver: Jacobi runs its fixed count and reports an honest residual") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  fluid::PressureSettings settings;
  settings.solver = fluid::PressureSolverType::jacobi;
  settings.jacobi_iterations = 10;
  SolverFixture f(*cc, settings);
  const auto b = test::random_cells(f.n(0), 1.0, 9);
  test::upload(*cc, b, f.solver.rhs());
  cc->queue().enqueueFillBuffer(f.solver.solution(), 0.0f, 0, f.n(0) * 4);
  const auto status = f.solver.solve();
  CHECK(status.iterations == 10);
  const auto phi = test::download(*cc, f.solver.solution(), f.n(0));
  double bnorm = 0.0;
  for (float x : b) bnorm += double(x) * x;
  const double recomputed = residual_norm(f.spec, f.levels[0], b, phi) / std::sqrt(bnorm);
  CHECK(status.relative_residual == Approx(recomputed).epsilon(1e-3));
  CHECK(status.relative_residual > 0.05);  // ten Jacobi sweeps are far from converged
}

TEST_CASE("PressureSolver: the rows and the cells work mapping solve to the same bits") {
  // The sums are column sums added exactly (base/ExactSum), so a solve depends on the cells' values alone,
  // not on how the work-items cover the grid: the property that makes a run over MPI ranks equal a run in
  // one process (docs/parallel.md). Bitwise, on both boundary sets, with and without solids.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  struct Case {
    const char* name;
    fluid::GridSpec spec;
    bool solids;
  };
  const Case cases[] = {{"mixed boundaries with a box", test::mixed_boundary_spec(), true},
                        {"mixed boundaries", test::mixed_boundary_spec(), false}};
  for (const auto& c : cases) {
    for (const auto type : {fluid::PressureSolverType::cg, fluid::PressureSolverType::multigrid}) {
      INFO(c.name << ", solver " << int(type));
      fluid::PressureSettings settings;
      settings.solver = type;
      settings.tolerance = 1e-5;  // near the float floor: many iterations, so many sums, must agree
      const auto solid = c.solids ? test::box_solid(c.spec) : std::vector<std::uint8_t>{};
      const auto b = test::random_cells(c.spec.cell_count(), 1.0, 17);
      std::vector<std::vector<float>> phi;
      std::vector<host::PressureSolveStatus> status;
      for (const auto mapping : {host::WorkMapping::rows, host::WorkMapping::cells}) {
        host::ComputeContext mapped(cc->device(), false, mapping);
        host::PressureSolver solver(mapped, c.spec, fluid::build_pressure_levels(c.spec, solid), settings);
        test::upload(mapped, b, solver.rhs());
        status.push_back(solver.solve());
        phi.push_back(test::download(mapped, solver.solution(), c.spec.cell_count()));
      }
      CHECK(status[0].iterations == status[1].iterations);
      CHECK(status[0].relative_residual == status[1].relative_residual);
      CHECK(phi[0] == phi[1]);
    }
  }
}
