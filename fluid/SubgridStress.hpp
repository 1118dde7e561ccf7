// The subgrid and wall stresses of the wind grid (docs/design.md, "Numerics: Wind grid: Turbulence"): a
// Smagorinsky eddy viscosity for the stress of the eddies smaller than a cell, and a log-law rough-wall
// stress on the first fluid cell above the ground and above solid cells. The constants and the rules both the
// CPU reference (fluid/ReferenceStages: eddy_viscosity, diffuse_eddy, wall_stress) and the device
// (kernels/subgrid_stress.cl, host/stages/WindGrid stages "subgrid" and "wall") use.
//
//   double cap = fw::fluid::eddy_viscosity_cap(spec.h, dt);              // m^2/s
//   double cw = fw::fluid::wall_drag_coefficient(spec.h, 0.1);           // z0 = 0.1 m
//   std::vector<float> walls = fw::fluid::wall_cells(spec, solid);       // 1 on the wall cells
//
// Smagorinsky (stage "subgrid", WindSettings::smagorinsky_constant C_s):
//   nu_t = min((C_s h)^2 |S|, nu_max)  (m^2/s, one value a cell, 0 in solid cells),
//   |S| = sqrt(2 S_ij S_ij),  S_ij = (d_j u_i + d_i u_j) / 2  (1/s),
// with d_j u_i central differences of the cell-centred velocities over 2h, one-sided over h at a domain edge
// and wrapping across periodic axes (through the ghosts). Then every face of component c takes one explicit
// step of the diffusion in flux form,
//   q += dt / h^2 * sum over its six neighbours of nu_edge (q_nb - q),  nu_edge = (nu_face + nu_face_nb) / 2,
// nu_face the mean of the two cells sharing a face, the neighbours through the ghost rules of
// fluid::reference::fetch (the constant-viscosity stage's). That is div(nu_t grad u), the diagonal part of
// the stress divergence div(2 nu_t S) = div(nu_t grad u) + div(nu_t (grad u)^T); the dropped transpose part
// is (grad u)^T . grad nu_t (as div u = 0): zero in a horizontally uniform boundary layer (w = 0), small
// where nu_t varies slowly, and of the order of C_s's own uncertainty (a factor of two) elsewhere.
// The flux form matters: every pair of faces exchanges the same flux, so the stage conserves momentum
// exactly. The non-conservative nu_t laplacian(u) does not: in a column it adds
// sum_k (nu_k - nu_k+1)(u_k+1 - u_k) > 0 wherever nu_t falls with height, which in a column driven by a
// body force over a rough wall made the wall carry 1.69 times the force in steady state (the first cell
// 30% too fast), whatever C_s. The step is a convex combination of each face and its six neighbours (while
// nu dt / h^2 <= 1/6): it can never create a new extremum, whatever nu_t does.
//
// Stability. The explicit step is that convex combination while nu dt / h^2 <= 1/6 (3D). With
// nu_t dt / h^2 = C_s^2 |S| dt, and |S| about dU / h for a velocity jump dU across a cell, this is
// C_s^2 dU dt / h <= C_s^2 * 2 CFL (dU <= 2 max|u|): 0.08 for C_s = 0.2 at CFL 1, so the bound is far off in
// ordinary runs. Nothing bounds |S| in general, though (a gust front or a fresh solid can make it large), so
// nu_t is clamped at nu_max = kEddyDiffusionLimit h^2 / dt, and the step can never blow up; the clamp costs
// no reduction and no read-back.
//
// Wall stress (stage "wall", WindSettings::wall_roughness_length z0): the first fluid cell above a wall feels
// the log law's stress tau / rho = u_*^2 with u_* = kappa |U_1| / ln(z_1 / z0), z_1 = h / 2 its centre's
// height above the wall. Spread over the cell's height h that is a drag on its horizontal faces
//   du/dt = -C_w |U_1| u / h,   C_w = (kappa / ln(z_1 / z0))^2,
// applied implicitly, u <- u / (1 + dt C_w |U_1| / h) with |U_1| from the old velocity, like the canopy
// drag: it never reverses or amplifies the flow at any dt. The air loses rho C_w |U_1^n| U_1^(n+1) h^2 per
// wall cell and step, i.e. rho u_*^2 times the cell's floor area, the stress taken implicitly. u and v get
// it, w does not. With the wall model on, the ground should be a slip boundary: the stress replaces the
// no-slip condition, which a no-slip ghost would impose a second time, and wrongly at metre-sized cells,
// through the advection and diffusion stencils (the scenario's `ground: rough` means slip + this stress).
// Over solid cells (terrain, roofs) the zero velocity of the solid faces plays that no-slip ghost; the eddy
// diffusion therefore treats the face below a wall cell as slip (diffuse_eddy's wall_slip). Advection still
// interpolates towards the solid's zero faces; that remains (voxel terrain is only first-order anyway).
#pragma once

#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::fluid {

/// The von Karman constant of the log law u(z) = u_* / kappa ln(z / z0). Measured values scatter between
/// about 0.38 and 0.42; 0.41 is the usual choice of boundary-layer meteorology and wind engineering, so a
/// roughness length taken from their tables means what it says here.
inline constexpr double kVonKarman = 0.41;

/// Largest nu dt / h^2 the explicit eddy diffusion may reach: 0.9 of the 3D stability bound 1/6, the same
/// margin as the constant-viscosity stage's sub-steps, so that rounding never tips a face over the bound.
inline constexpr double kEddyDiffusionLimit = 0.15;

/// nu_max = kEddyDiffusionLimit h^2 / dt, m^2/s: the clamp on the eddy viscosity for a step of dt.
/// Throws std::invalid_argument unless h and dt are finite and > 0.
double eddy_viscosity_cap(double h, double dt);

/// z_1 = h / 2, m: the height of the first fluid cell's centre above a wall, where the log law is evaluated.
/// A roughness length must lie below it (wall_drag_coefficient, and the scenario's roughness keys).
constexpr double wall_centre_height(double h) {
  return 0.5 * h;
}

/// C_w = (kappa / ln(z_1 / z0))^2 with z_1 = wall_centre_height(h), dimensionless. Throws
/// std::invalid_argument unless 0 < z0 < z_1 (the log law needs the first cell's centre above the roughness
/// length).
double wall_drag_coefficient(double h, double roughness_length);

/// True when the log-law stress applies on the domain's ground: a slip or no-slip wall (not inflow,
/// outflow or periodic).
bool ground_is_wall(const GridSpec& spec);

/// One float a cell (x fastest): 1 on the wall cells, the fluid cells with a solid cell right below or,
/// when ground_is_wall, on the ground (k = 0); 0 elsewhere. `solid`: one byte a cell, non-zero = solid,
/// or empty for none. Throws std::invalid_argument for a solid map of the wrong size.
std::vector<float> wall_cells(const GridSpec& spec, const std::vector<std::uint8_t>& solid);

}  // namespace fw::fluid
