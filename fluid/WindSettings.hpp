// How the wind grid is stepped: advection scheme, forces, pressure solver, time step.
#pragma once

#include <array>
#include <string>

namespace fw::fluid {

enum class AdvectionScheme { semi_lagrangian, maccormack, upwind5 };
/// Where upwind5's Runge-Kutta step projects: once, after its last stage (with the rest of the step), or
/// after each of its first two stages as well, so that every stage advects a divergence-free field.
enum class StageProjection { final_stage, every_stage };
enum class PressureSolverType { jacobi, multigrid, cg };
/// The subgrid stress's model: Smagorinsky's eddy viscosity from the resolved strain alone
/// (fluid/SubgridStress.hpp), or Deardorff's 1.5-order closure on a prognostic subgrid kinetic energy
/// (fluid/SubgridTke.hpp).
enum class SubgridModel { smagorinsky, tke };
enum class MultigridSmoother { jacobi, red_black };

std::string to_string(AdvectionScheme scheme);
std::string to_string(PressureSolverType solver);
std::string to_string(SubgridModel model);

/// The stability limit of upwind5 (fluid/UpwindStencil.hpp) with Wicker & Skamarock's three-stage
/// Runge-Kutta, on the sum of the Courant numbers (|u| + |v| + |w|) dt / h. Von Neumann analysis of the
/// linear scheme puts the limit of that sum at 1.435 at fifth order (Wicker & Skamarock 2002: 1.43), 1.626
/// at third and 1.256 at first, the order the scheme drops to beside walls; 1.2 stays below all three,
/// with a margin for the nonlinear flow and the split forces. The step takes the sum of the components'
/// maxima, which bounds every cell's sum.
inline constexpr double kUpwind5CourantLimit = 1.2;

/// The relative residual at which the converging solvers stop, unless told otherwise (the scenario's
/// solver.tolerance reads it too): a tenth of a per cent of the divergence left, and well above the float32
/// floor near 1e-5 that a solve cannot get below.
inline constexpr double kDefaultPressureTolerance = 1e-3;

struct PressureSettings {
  PressureSolverType solver = PressureSolverType::cg;  // cg: conjugate gradients, multigrid-preconditioned
  double tolerance = kDefaultPressureTolerance;  // relative residual ||b - A p|| / ||b|| (multigrid, cg)
  int max_iterations = 100;                      // V-cycles (multigrid) or CG iterations (cg)
  int jacobi_iterations = 40;                    // fixed count (jacobi)
  MultigridSmoother smoother = MultigridSmoother::red_black;
  int smoothing_sweeps = 2;  // sweeps before and after each coarse correction (pairs, for Jacobi)
};

struct WindSettings {
  AdvectionScheme advection = AdvectionScheme::semi_lagrangian;
  StageProjection stage_projection = StageProjection::final_stage;  // upwind5 only
  PressureSettings pressure;
  double vorticity_confinement = 0.0;         // epsilon, dimensionless (0: off)
  double viscosity = 0.0;                     // kinematic, m^2/s (0: off; air is 1.5e-5)
  std::array<double, 3> body_force{0, 0, 0};  // uniform acceleration, m/s^2
  double dt = 0.05;                           // fixed time step, s (used when cfl <= 0)
  /// > 0: dt = cfl * h / max|u| each step (max over the components), capped at max_dt and at the scheme's
  /// stability limit on the sum of the components' maxima (host AdvectionMethod::courant_limit).
  double cfl = 0.0;
  double max_dt = 1.0;  // s
  /// smagorinsky: the subgrid stage runs while smagorinsky_constant > 0. tke: it always runs, its eddy
  /// viscosity C_m l sqrt(e) from the subgrid energy e each cell carries (fluid/SubgridTke.hpp); the
  /// Smagorinsky constant must then stay 0.
  SubgridModel subgrid = SubgridModel::smagorinsky;
  /// Smagorinsky constant C_s of the subgrid eddy viscosity nu_t = (C_s h)^2 |S|, dimensionless, in
  /// [0, kSmagorinskyConstantBelow) (0: off; 0.1-0.2 typical, 0.17 from Lilly's inertial-range estimate).
  /// fluid/SubgridStress.hpp.
  double smagorinsky_constant = 0.0;
  /// C_s >= 1 would make the subgrid length C_s h larger than the cell it stands for (the scenario schema
  /// takes the limit from here).
  static constexpr double kSmagorinskyConstantBelow = 1.0;
  /// The constant a scenario with `advection: upwind5` gets when it names none (docs/numerics.md, "The
  /// Smagorinsky constant with upwind5"). The scheme's own dissipation is too weak to drain the cascade:
  /// without a subgrid model decaying turbulence piles up 27% above the -5/3 line at 6 cells; 0.16 is the
  /// smallest constant that keeps it within 3% of the line down to 6 cells.
  static constexpr double kUpwind5SmagorinskyConstant = 0.16;
  /// Roughness length z0 of the log-law wall stress on the first fluid cell above the ground and above solid
  /// cells, m (0: off; needs z0 < h/2). The ground should then be slip. fluid/SubgridStress.hpp.
  double wall_roughness_length = 0.0;

  /// Throws std::invalid_argument("WindSettings: ...") for a non-positive dt (fixed mode), a negative
  /// viscosity, tolerance or confinement, non-positive iteration counts, a Smagorinsky constant outside
  /// [0, 1), a Smagorinsky constant other than 0 with the tke model, or a negative or non-finite roughness
  /// length (its bound h/2 is checked by host::WindGrid).
  void validate() const;
};

}  // namespace fw::fluid
