// Plain C++ reference of every wind-grid stage: the oracle the OpenCL kernels are tested against.
//
// Written for clarity, not speed: loops over (k, j, i), arithmetic in double, storage in float like the
// device. Each function is one stage of kernels/fluid_*.cl; see those files for the same numerics.
//
//   using namespace fw::fluid;
//   MacVelocity vel(spec);                                          // u, v, w on faces, m/s
//   auto out = reference::advect_semi_lagrangian(spec, env, vel, vel, dt);
//   auto b = reference::divergence_rhs(spec, levels[0], vel);     // -h * (net outflow), m^2/s
//
// Conventions shared with the kernels:
//   * Positions are in cell units: world = origin + h * X. Face u(i,j,k) sits at X = (i, j+1/2, k+1/2).
//   * The pressure unknown is phi = p dt / rho (m^2/s); the projection subtracts grad(phi) from the faces,
//     and phi solves  A phi = b  with A from fluid/PressureLevels.hpp and b = -h^2 div u = -h * net flux.
#pragma once

#include <cstdint>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/InflowState.hpp"
#include "fluid/MacVelocity.hpp"
#include "fluid/PressureLevels.hpp"
#include "fluid/UpwindStencil.hpp"
#include "kernels/shared_types.h"

namespace fw::fluid {

namespace reference {

/// Extent of component c's array along axis a (n_a, plus one along its own axis).
int extent(const GridSpec& spec, int component, int axis);
std::size_t face_index(const GridSpec& spec, int component, int i, int j, int k);

/// Value of component c at integer face index (i,j,k), which may lie outside the array: periodic axes
/// wrap, inflow faces give the ambient profile, no-slip walls mirror tangential components with a sign
/// flip (zero at the wall), other walls and outflow repeat the edge value.
double fetch(const GridSpec& spec, const InflowState& inflow, const std::vector<float>& q, int c, int i,
             int j, int k);

/// Trilinear interpolation of component c at position X (cell units).
double sample(const GridSpec& spec, const InflowState& inflow, const std::vector<float>& q, int c, double X,
              double Y, double Z);

/// Back-traced position of face (i,j,k) of component c through `vel` over `dt` (negative dt traces forward),
/// explicit midpoint (RK2).
void backtrace(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel, int c, int i, int j,
               int k, double dt, double& X, double& Y, double& Z);

/// q advected through vel by semi-Lagrangian RK2 with trilinear interpolation.
MacVelocity advect_semi_lagrangian(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel,
                                   const MacVelocity& q, double dt);

/// Clamped MacCormack: forward SL step, backward SL step, half the round-trip error added back, and the
/// result replaced by the forward value where it leaves the range of the 8 values it was interpolated from.
MacVelocity advect_maccormack(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel,
                              const MacVelocity& q, double dt);

/// One Runge-Kutta stage of flux-form upwind advection (fluid/UpwindStencil.hpp): every face of base +
/// coef_dt R(stage), R = -(sum over the axes of upper minus lower flux U q) / h, the fluxes' values through
/// fetch()'s ghost rules and their orders from `orders`.
MacVelocity upwind_stage(const GridSpec& spec, const InflowState& inflow, const UpwindOrders& orders,
                         const MacVelocity& stage, const MacVelocity& base, double coef_dt);

/// Wicker & Skamarock's three-stage Runge-Kutta of upwind_stage over dt: u1 = u + dt/3 R(u), u2 = u + dt/2
/// R(u1), u + dt R(u2), the first two stages' prescribed faces imposed (enforce_boundaries); no projection.
MacVelocity advect_upwind5(const GridSpec& spec, const PressureLevel& fine, const InflowState& inflow,
                           const UpwindOrders& orders, const MacVelocity& vel, double dt);

/// vel += dt * g on every face (m/s^2).
void add_body_force(MacVelocity& vel, const std::array<double, 3>& g, double dt);

/// vel += dt * (gust acceleration at t + dt/2) for every gust (see FwGust).
void add_gusts(const GridSpec& spec, MacVelocity& vel, const std::vector<FwGust>& gusts, double t, double dt);

/// Cell-centred vorticity (1/s): 4 floats a cell (wx, wy, wz, |w|), central differences of cell-centred
/// velocities with edge cells clamped.
std::vector<float> vorticity(const GridSpec& spec, const MacVelocity& vel);

/// Vorticity confinement f = epsilon h (N x w), N = grad|w| / |grad|w||, added as dt * f averaged to faces.
void add_vorticity_confinement(const GridSpec& spec, MacVelocity& vel, double epsilon, double dt);

/// Implicit canopy drag F = -k f(|u|) |u| u (f: the drag law's factor, fluid/DragLaw.hpp): every face becomes
/// q / (1 + dt k_face f(|u|_face) |u|_face). k (1/m, one float a
/// cell) is averaged from the two cells beside the face (the inner one at the domain's edge); |u|_face uses
/// the face's own component and the other two averaged from the four faces of those two cells, all from
/// the old velocity.
MacVelocity canopy_drag(const GridSpec& spec, const MacVelocity& vel, const std::vector<float>& drag_density,
                        double dt, const DragLaw& law = {});

/// One explicit step of q += dt * nu * laplacian(q), with the ghost rules of fetch().
MacVelocity diffuse(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel, double nu,
                    double dt);

/// 2 S_ij S_ij of cell (i,j,k), 1/s^2: S_ij = (d_j u_i + d_i u_j) / 2 from central differences of the
/// cell-centred velocities over 2h (one-sided over h at a non-periodic edge, wrapping across a periodic
/// axis); the squared strain rate |S|^2 both subgrid models read (fluid/SubgridStress.hpp,
/// fluid/SubgridTke.hpp).
double strain_rate_squared(const GridSpec& spec, const MacVelocity& vel, int i, int j, int k);

/// Smagorinsky eddy viscosity (fluid/SubgridStress.hpp), m^2/s, one float a cell (x fastest):
/// min((C_s h)^2 |S|, cap) with |S| = sqrt(2 S_ij S_ij) from central differences of the cell-centred
/// velocities (one-sided at a non-periodic edge, wrapping across a periodic axis); 0 in solid cells.
/// `solid`: one byte a cell, non-zero = solid, or empty. Throws std::invalid_argument for a wrong size.
std::vector<float> eddy_viscosity(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                  const MacVelocity& vel, double smagorinsky_constant, double cap);

/// One explicit step of the eddy diffusion in flux form, q += dt div(nu grad q) (fluid/SubgridStress.hpp):
/// q += dt / h^2 * sum over the six neighbours of (nu_face + nu_face_nb) / 2 * (q_nb - q), nu_face the mean
/// of `nu_t` (one float a cell, m^2/s) over the two cells sharing a face (wrapped across a periodic axis,
/// clamped into the grid elsewhere, also for a neighbour outside the array), the neighbours through
/// fetch()'s ghost rules. With wall_slip, a u or v face whose neighbour below touches a solid cell exchanges
/// nothing with it (the wall stress replaces that flux). Throws std::invalid_argument for wrong sizes.
MacVelocity diffuse_eddy(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                         const InflowState& inflow, const MacVelocity& vel, const std::vector<float>& nu_t,
                         double dt, bool wall_slip);

/// Implicit log-law wall stress (fluid/SubgridStress.hpp): u and v faces become
/// q / (1 + dt C_w weight |U| / h), weight the mean of fluid::wall_cells over the two cells sharing the face
/// (cells found as in diffuse_eddy), |U| the horizontal speed with the other horizontal component averaged
/// from the four faces of those two cells, all from the old velocity; w is copied. drag_coefficient: C_w.
MacVelocity wall_stress(const GridSpec& spec, const std::vector<std::uint8_t>& solid, const MacVelocity& vel,
                        double drag_coefficient, double dt);

/// Imposes prescribed face velocities: inflow faces get the profile, walls and faces touching a solid get 0,
/// periodic faces copy the low face to the high one. Faces open to the pressure solve are left alone.
void enforce_boundaries(const GridSpec& spec, const PressureLevel& fine, const InflowState& inflow,
                        MacVelocity& vel);

/// b = -h * (net outflow of each fluid cell) = -h^2 div u, m^2/s; 0 in solid cells.
std::vector<float> divergence_rhs(const GridSpec& spec, const PressureLevel& fine, const MacVelocity& vel);

/// Max over fluid cells of |div u|, 1/s.
double max_divergence(const GridSpec& spec, const PressureLevel& fine, const MacVelocity& vel);

/// (A phi) on a pressure level. Levels share the domain's boundary types (periodicity) with `spec`.
std::vector<float> apply_operator(const GridSpec& spec, const PressureLevel& level,
                                  const std::vector<float>& phi);

/// b - A phi.
std::vector<float> residual(const GridSpec& spec, const PressureLevel& level, const std::vector<float>& b,
                            const std::vector<float>& phi);

/// One weighted Jacobi sweep: phi <- (1 - w) phi + w (b + sum phi_nb) / diag, w = relaxation_weight.
std::vector<float> jacobi_sweep(const GridSpec& spec, const PressureLevel& level, const std::vector<float>& b,
                                const std::vector<float>& phi, double relaxation_weight);

/// Gauss-Seidel on the cells of one colour ((i+j+k) % 2 == colour), in place.
void red_black_sweep(const GridSpec& spec, const PressureLevel& level, const std::vector<float>& b,
                     std::vector<float>& phi, int colour);

/// Coarse right-hand side: scale * mean of the fine residual over the coarse cell's children. scale = 4
/// matches the rediscretised coarse equation (H^2 = 4 h^2), scale = 2 the Galerkin operator P^T A P of
/// piecewise-constant prolongation (the solver uses 4).
std::vector<float> restrict_residual(const GridSpec& spec, const PressureLevel& fine,
                                     const PressureLevel& coarse, const std::vector<float>& b,
                                     const std::vector<float>& phi, double scale);

/// phi_fine += the interpolated e_coarse on every fluid child: e_P + slope * sum over the axes of
/// (e_N - e_P), with P the parent and N its neighbour on the child's side along the axis. slope = 1/4 is
/// linear interpolation (the child sits a quarter of the coarse spacing from P's centre towards N), 0
/// piecewise constant. Across an open face N wraps on a periodic axis and is 0 beyond an outflow face (the
/// operator's ghost); across a closed face N = P (zero gradient). A lone child of an odd fine extent takes
/// the lower side.
void prolong_add(const GridSpec& spec, const PressureLevel& fine, const PressureLevel& coarse,
                 const std::vector<float>& e_coarse, double slope, std::vector<float>& phi_fine);

/// Subtracts grad(phi) from every face that is open in the pressure mask.
void subtract_gradient(const GridSpec& spec, const PressureLevel& fine, const std::vector<float>& phi,
                       MacVelocity& vel);

/// Solves A phi = b by conjugate gradients in double precision to relative residual `tolerance`.
/// For a singular A (no outflow face) the mean of b over fluid cells is removed first.
/// Returns the iterations used.
int solve_pressure_cg(const GridSpec& spec, const PressureLevel& fine, const std::vector<float>& b,
                      std::vector<float>& phi, double tolerance, int max_iterations);

}  // namespace reference
}  // namespace fw::fluid
