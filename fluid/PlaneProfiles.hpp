// The wind's statistics against height, as LES users read them (PALM's and MicroHH's profiles): at every
// height, averages over the horizontal plane's fluid cells of the cell-centred wind and its moments. This is
// the definition and the CPU reference that the device's accumulation and the stats.nc output follow
// (docs/statistics.md).
//
//   fw::fluid::PlaneProfiles p = fw::fluid::plane_profiles(spec, velocity, solid, {&nu_t, &e, &drag});
//   double uw_at_canopy_top = p.at(fw::fluid::Profile::u_w, k_top);      // m^2/s^2
//
// Every quantity lives at the cell centres of height k (z = origin_z + (k + 1/2) h); a face velocity is the
// mean of a cell's two faces. With N_k the plane's fluid cells and <.> their mean:
//   area   = N_k / (nx ny)                        u, v, w = <u>, <v>, <w>
//   u_2    = <(u - <u>)^2>   (v_2, w_2 alike)     u_3, w_3 = <(u - <u>)^3>, <(w - <w>)^3>
//   u_w    = <(u - <u>)(w - <w>)>  (v_w alike)    u_diff = <-2 nu_t S_xz>,  v_diff = <-2 nu_t S_yz>
//   u_flux = u_w + u_diff  (v_flux alike)         tke = (u_2 + v_2 + w_2) / 2,  sgs_tke = <e>,  lad = <a>
// with S_xz = (du/dz + dw/dx) / 2 from central differences of the cell-centred velocity over 2h, one-sided
// over h at a non-periodic edge and wrapped across a periodic one (the subgrid models' own rule,
// kernels/strain_rate.cl), nu_t the subgrid model's eddy viscosity, e its subgrid energy and a the canopy's
// drag density. Moments are central about the plane's own mean at that moment (its resolved turbulence). A
// height with no fluid cell has area 0 and every other value 0.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"

namespace fw::fluid {

/// The profiles, in the order stats.nc lists them.
enum class Profile {
  area,
  u,
  v,
  w,
  u_2,
  v_2,
  w_2,
  u_3,
  w_3,
  u_w,
  v_w,
  u_diff,
  v_diff,
  u_flux,
  v_flux,
  tke,
  sgs_tke,
  lad,
  count
};
inline constexpr int kProfileCount = static_cast<int>(Profile::count);

/// A profile's name in stats.nc (MicroHH's), its units (UDUNITS), its long name, and its CF standard name
/// where the CF table has one ("" where not).
struct ProfileVariable {
  const char* name;
  const char* units;
  const char* long_name;
  const char* standard_name;
};
/// Every profile's, in Profile's order.
const std::array<ProfileVariable, kProfileCount>& profile_variables();

/// What the subgrid model and the canopy add, one float a cell each (x fastest), or null: no eddy viscosity
/// (u_diff, v_diff 0), no subgrid energy (sgs_tke 0), no canopy (lad 0).
struct PlaneFields {
  const std::vector<float>* eddy_viscosity = nullptr;  // m^2/s
  const std::vector<float>* subgrid_energy = nullptr;  // m^2/s^2
  const std::vector<float>* drag_density = nullptr;    // 1/m
};

/// Every profile at every height: values[p][k].
struct PlaneProfiles {
  int nz = 0;
  std::array<std::vector<double>, kProfileCount> values;
  double at(Profile p, int k) const { return values[std::size_t(p)][std::size_t(k)]; }
};

/// The profiles of `vel` on `spec` (solid: one byte a cell, non-zero solid, or empty for none), by the
/// definitions above. Throws std::invalid_argument when an array's size is not the grid's.
PlaneProfiles plane_profiles(const GridSpec& spec, const MacVelocity& vel,
                             const std::vector<std::uint8_t>& solid, const PlaneFields& fields = {});

}  // namespace fw::fluid
