// Deardorff's 1.5-order subgrid closure with the canopy's terms (WindSettings::subgrid = tke; issue 26): each
// cell carries the kinetic energy e of the eddies smaller than a cell (m^2/s^2), and the eddy viscosity of
// the subgrid stage comes from it instead of from the strain alone (Smagorinsky, fluid/SubgridStress.hpp).
// The constants and rules both the CPU reference (fluid::reference::tke_*, below) and the device
// (kernels/subgrid_tke.cl, host/stages/WindGrid stage "subgrid") use.
//
//   const fw::fluid::TkeCoefficients tc = fw::fluid::tke_coefficients(spec.h);
//   double e = fw::fluid::tke_shear_equilibrium(spec.h, spec.h, 0.25);   // m^2/s^2 for |S|^2 = 0.25 1/s^2
//
// The model (Deardorff 1980; Moeng 1984; PALM's 1.5-order closure, Maronga et al. 2015):
//   de/dt + U . grad e = div(2 nu_t grad e) + nu_t |S|^2 - C_eps e^(3/2) / l
//                        - kCanopySinkFactor k |U| e + kWakeProductionFraction k |U|^3,
//   nu_t = C_m l sqrt(e),  C_m = 0.1,  C_eps = 0.19 + 0.74 l / h,
// with |S|^2 = 2 S_ij S_ij the resolved strain (fluid::reference::strain_rate_squared;
// kernels/strain_rate.cl) and k = sum C_d a the canopy's drag density (1/m, the one
// host::WindGrid::set_canopy uploads: the momentum loses k |u| u). U is the resolved velocity at the cell
// centre (the mean of the cell's two faces per component).
//   * Mixing length: l = h in neutral flow (no buoyancy here), and l = min(h, 1.8 z) near a wall as in PALM
//     (l <= 1.8 z, z the distance to the wall): only the cells whose cell below is solid, or which sit on a
//     wall ground (fluid::wall_cells), are close enough to feel it, z = h / 2 and l = 0.9 h. Walls beside a
//     cell do not shorten l (PALM's newer wall distance does; the wall stress here acts on floors too).
//   * Shear production P = nu_t |S|^2 is what the eddy diffusion of the velocity takes from the resolved flow
//     (with the same nu_t). Balanced by the dissipation alone (homogeneous shear),
//       C_m l sqrt(e) |S|^2 = C_eps e^(3/2) / l   =>   e = (C_m / C_eps) l^2 |S|^2,
//     and then nu_t = sqrt(C_m^3 / C_eps) l^2 |S|: Smagorinsky's form with C_s = (C_m^3 / C_eps)^(1/4) = 0.18
//     at l = h (Lilly's 0.17 in the same range).
//   * The canopy (Shaw & Schumann 1992; PALM's plant canopy model). Drag on the subgrid eddies drains them:
//     linearising the drag -k |u| u about the resolved U for isotropic fluctuations takes
//     k |U| (<u'_i u'_i> + <u'_U^2>) = k |U| (2e + 2e/3) = 8/3 k |U| e from e; PALM keeps the first part,
//     -2 c_d LAD |U| e ("a similar sink term", doc/tec/canopy), and so do we (kCanopySinkFactor). The
//     resolved flow loses k |U|^3 per unit mass to the drag; Shaw & Schumann return that work to the subgrid
//     energy as wake production, PALM leaves it out. We return it whole (kWakeProductionFraction = 1): the
//     energy stays accounted for, and the sink above carries it on to dissipation fast, as the wakes' small
//     eddies do. In a steady uniform wind inside a canopy (no strain) e then settles where
//       kWakeProductionFraction k |U|^3 = kCanopySinkFactor k |U| e + C_eps e^(3/2) / l
//     (tke_canopy_equilibrium), below |U|^2 / 2, the balance without the dissipation.
//
// Discretisation, per step of dt, after the forces and the canopy drag and before the eddy diffusion of the
// velocity (which reuses diffuse_eddy with this nu_t):
//   1. nu_t = min(C_m l sqrt(e^n), nu_max) per cell, 0 in solids; nu_max = fluid::eddy_viscosity_cap(h, dt).
//   2. Advection, semi-Lagrangian: e* = e^n at the cell centre traced back over dt along the cell-centred
//      velocity (one Euler step), interpolated trilinearly between cell centres. The result is a convex
//      combination of old values, so it is monotone (no new extremum, e* >= 0) and stable at any Courant
//      number, which an explicit upwind scheme is not: dt may reach h / |u| per component (semi-Lagrangian
//      momentum, a fixed dt), a summed Courant number past 1. Not conservative, as the momentum's default.
//      Ghosts: periodic axes wrap, an inflow side gives kTkeInflow, other sides (walls, outflow) repeat the
//      edge cell (zero gradient); a solid cell among the eight reads as the departing cell's own e^n.
//   3. Diffusion of e* in flux form, q += dt / h^2 sum over the six faces of K_f (e_nb - e), with
//      K_f = min(nu_t + nu_t,nb, nu_max) (2 nu_t, the mean of the two cells') capped like the momentum's, so
//      the step stays a convex combination (K dt / h^2 <= 0.15 < 1/6). Faces to walls, outflow and solid
//      cells pass nothing (zero gradient); an inflow face exchanges with kTkeInflow at K = min(2 nu_t,
//      nu_max); periodic ones wrap.
//   4. Sources explicit, sinks implicit (linearised, Patankar's way), floor last:
//        e^(n+1) = max(kTkeFloor, (e* + dt D + dt (P + W)) / (1 + dt (C_eps sqrt(e*) / l + s k |U|))),
//      W = kWakeProductionFraction k |U|^3, s = kCanopySinkFactor. Explicit sinks would need
//      dt (C_eps sqrt(e) / l + 2 k |U|) < 1 to keep e >= 0, and the canopy term alone is 2 k h CFL: 0.8 for
//      k = 0.2 1/m, h = 2 m at CFL 1, past 1 in denser stands. The implicit form keeps e >= 0 at any dt and
//      has the same steady states as the equations above (the equilibria are exact in the scheme).
//   Solid cells hold 0. Stability as a whole: steps 2 and 3 are convex combinations, production grows
//   sqrt(e) at most linearly in time, and step 4's denominator is >= 1.
// Initial e: in equilibrium with the strain (tke_shear_equilibrium per cell, at least kTkeFloor) of the
// velocity the first subgrid stage sees, unless set (host::WindGrid::upload_subgrid_energy). Starting at 0
// would never start at all: P = nu_t |S|^2 vanishes with e.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"
#include "kernels/shared_types.h"

namespace fw::fluid {

/// C_m of nu_t = C_m l sqrt(e) (Deardorff 1980; Moeng 1984; PALM).
inline constexpr double kTkeViscosityConstant = 0.1;
/// C_eps = kTkeDissipationBase + kTkeDissipationSlope l / h (Deardorff 1980; Moeng 1984): 0.93 at l = h.
inline constexpr double kTkeDissipationBase = 0.19;
inline constexpr double kTkeDissipationSlope = 0.74;
/// l <= kTkeWallLengthFactor z near a wall, z the distance to it (PALM).
inline constexpr double kTkeWallLengthFactor = 1.8;
/// s of the canopy's sink -s k |U| e: PALM's 2, the fluctuations' own drag k |U| u'_i u'_i. The full
/// linearisation adds the drag's change with the speed, 2/3 more (8/3); the drag coefficient itself is
/// uncertain by more than that.
inline constexpr double kCanopySinkFactor = 2.0;
/// The share of the resolved flow's work against the drag, k |U|^3, that enters e as wake production:
/// Shaw & Schumann's whole (PALM: none).
inline constexpr double kWakeProductionFraction = 1.0;
/// The smallest e a fluid cell holds, m^2/s^2: sigma = sqrt(2e/3) = 0.8 mm/s, still air to any
/// anemometer, with nu_t = C_m h sqrt(e) = 2e-4 m^2/s at h = 2 m, against typical 0.1. Above 0 so that a
/// flow that starts without strain (a uniform wind meeting an obstacle) can still produce e:
/// d sqrt(e) / dt = C_m l |S|^2 / 2 does not depend on where it starts.
inline constexpr double kTkeFloor = 1e-6;
/// e of the air entering through inflow faces, m^2/s^2: a laminar inflow carries none; inflow turbulence
/// is resolved and makes its subgrid energy through the strain inside.
inline constexpr double kTkeInflow = 0.0;

/// l, m: h, or kTkeWallLengthFactor h / 2 (0.9 h) for a cell on a wall (fluid::wall_cells).
double tke_mixing_length(double h, bool on_wall);
/// C_eps = kTkeDissipationBase + kTkeDissipationSlope l / h, dimensionless.
double tke_dissipation_coefficient(double l, double h);

/// The per-cell factors of the model at cell size h, [0] for an open cell, [1] for a cell on a wall:
/// nu_t = viscosity_length sqrt(e) (C_m l, m) and dissipation = dissipation_rate e^(3/2) (C_eps / l, 1/m).
struct TkeCoefficients {
  std::array<double, 2> viscosity_length{};
  std::array<double, 2> dissipation_rate{};
};
TkeCoefficients tke_coefficients(double h);
/// The kernels' FwTke at cell size h: tke_coefficients and the constants above, in float.
FwTke tke_device_parameters(double h);

/// e = (C_m / C_eps) l^2 |S|^2, m^2/s^2: shear production balancing dissipation. strain_squared: |S|^2.
double tke_shear_equilibrium(double l, double h, double strain_squared);
/// The e > 0 at which kWakeProductionFraction k U^3 = kCanopySinkFactor k U e + C_eps e^(3/2) / l, m^2/s^2
/// (0 when k U = 0): the canopy's balance in a steady wind of speed U (m/s) through drag density k (1/m).
double tke_canopy_equilibrium(double l, double h, double drag_density, double speed);
/// e(t) of de/dt = -C_eps e^(3/2) / l from e0 (no flow gradients, no canopy):
/// e0 / (1 + C_eps sqrt(e0) t / (2 l))^2, m^2/s^2.
double tke_decay(double e0, double l, double h, double t);

namespace reference {

/// The CPU reference of the four device stages (kernels/subgrid_tke.cl), in double, stored in float; one
/// float a cell (x fastest) for every field. `solid`: one byte a cell, non-zero = solid, or empty.
/// `drag_density`: k per cell (1/m), or empty for no canopy. Throw std::invalid_argument for wrong sizes.

/// The initial e: max(kTkeFloor, tke_shear_equilibrium(l, h, |S|^2)) in fluid cells, 0 in solids.
std::vector<float> tke_equilibrium(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                   const MacVelocity& vel);
/// Step 1: nu_t = min(C_m l sqrt(e), cap), m^2/s, 0 in solids.
std::vector<float> tke_viscosity(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                 const std::vector<float>& energy, double cap);
/// Step 2: e* = e traced back over dt from each cell centre, trilinear, with the ghosts of the header; 0 in
/// solids.
std::vector<float> tke_advect(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                              const MacVelocity& vel, const std::vector<float>& energy, double dt);
/// Steps 3 and 4 on the advected e*: diffusion by K_f = min(nu_f + nu_nb, cap), production nu_t |S|^2 from
/// vel, the dissipation and the canopy's terms; the new e, 0 in solids.
std::vector<float> tke_update(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                              const MacVelocity& vel, const std::vector<float>& nu_t,
                              const std::vector<float>& drag_density, const std::vector<float>& advected,
                              double dt, double cap);

/// One whole step of the model: tke_viscosity (into nu_t, when not null), tke_advect, tke_update.
std::vector<float> tke_step(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                            const MacVelocity& vel, const std::vector<float>& drag_density,
                            const std::vector<float>& energy, double dt, std::vector<float>* nu_t = nullptr);

}  // namespace reference
}  // namespace fw::fluid
