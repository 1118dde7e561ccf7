#include "fluid/SubgridTke.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fluid/ReferenceStages.hpp"
#include "fluid/SubgridStress.hpp"

namespace fw::fluid {

double tke_mixing_length(double h, bool on_wall) {
  return on_wall ? std::min(h, kTkeWallLengthFactor * wall_centre_height(h)) : h;
}

double tke_dissipation_coefficient(double l, double h) {
  return kTkeDissipationBase + kTkeDissipationSlope * l / h;
}

TkeCoefficients tke_coefficients(double h) {
  if (!std::isfinite(h) || !(h > 0.0))
    throw std::invalid_argument(fmt::format("tke_coefficients: needs a cell size > 0, got {} m", h));
  TkeCoefficients c;
  for (int wall = 0; wall < 2; ++wall) {
    const double l = tke_mixing_length(h, wall == 1);
    c.viscosity_length[wall] = kTkeViscosityConstant * l;
    c.dissipation_rate[wall] = tke_dissipation_coefficient(l, h) / l;
  }
  return c;
}

FwTke tke_device_parameters(double h) {
  const TkeCoefficients c = tke_coefficients(h);
  FwTke t{};
  for (int wall = 0; wall < 2; ++wall) {
    t.viscosity_length[wall] = float(c.viscosity_length[wall]);
    t.dissipation_rate[wall] = float(c.dissipation_rate[wall]);
  }
  t.canopy_sink = float(kCanopySinkFactor);
  t.wake_fraction = float(kWakeProductionFraction);
  t.floor = float(kTkeFloor);
  t.inflow = float(kTkeInflow);
  return t;
}

double tke_shear_equilibrium(double l, double h, double strain_squared) {
  return kTkeViscosityConstant / tke_dissipation_coefficient(l, h) * l * l * strain_squared;
}

double tke_canopy_equilibrium(double l, double h, double drag_density, double speed) {
  const double ku = drag_density * std::abs(speed);
  if (!(ku > 0.0) || kWakeProductionFraction == 0.0) return 0.0;
  // In x = sqrt(e): f(x) = b x^3 + s kU x^2 - f_w kU U^2, increasing and convex for x > 0, and positive at
  // the root without dissipation, x = U sqrt(f_w / s). Newton from there falls monotonically onto the root.
  const double b = tke_dissipation_coefficient(l, h) / l, s = kCanopySinkFactor * ku;
  const double w = kWakeProductionFraction * ku * speed * speed;
  double x = std::abs(speed) * std::sqrt(kWakeProductionFraction / kCanopySinkFactor);
  for (int n = 0; n < 100; ++n) {
    const double f = (b * x + s) * x * x - w, slope = (3.0 * b * x + 2.0 * s) * x;
    const double next = x - f / slope;
    if (!(next < x)) break;  // converged to rounding
    x = next;
  }
  return x * x;
}

double tke_decay(double e0, double l, double h, double t) {
  const double denominator = 1.0 + tke_dissipation_coefficient(l, h) * std::sqrt(e0) * t / (2.0 * l);
  return e0 / (denominator * denominator);
}

namespace reference {
namespace {

int cells_along(const GridSpec& spec, int a) {
  return a == 0 ? spec.nx : (a == 1 ? spec.ny : spec.nz);
}

std::size_t cell_at(const GridSpec& spec, const int idx[3]) {
  return std::size_t(idx[0]) + std::size_t(spec.nx) * (std::size_t(idx[1]) + std::size_t(spec.ny) * idx[2]);
}

void check_cells(const GridSpec& spec, std::size_t size, const char* who, const char* what) {
  if (size != spec.cell_count())
    throw std::invalid_argument(
        fmt::format("{}: {} has {} values, the grid {} cells", who, what, size, spec.cell_count()));
}

void check_solid(const GridSpec& spec, const std::vector<std::uint8_t>& solid, const char* who) {
  if (!solid.empty()) check_cells(spec, solid.size(), who, "the solid map");
}

bool is_solid(const std::vector<std::uint8_t>& solid, std::size_t id) {
  return !solid.empty() && solid[id] != 0;
}

// Calls visit(idx, id) for each cell of the grid that is not solid, in index order.
template <typename Visit>
void for_each_air_cell(const GridSpec& spec, const std::vector<std::uint8_t>& solid, Visit visit) {
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const int idx[3] = {i, j, k};
        const std::size_t id = cell_at(spec, idx);
        if (!is_solid(solid, id)) visit(idx, id);
      }
}

// The cell-centred resolved velocity of cell idx: the mean of its two faces per component, m/s.
std::array<double, 3> centre_velocity(const GridSpec& spec, const MacVelocity& vel, const int idx[3]) {
  std::array<double, 3> u{};
  for (int c = 0; c < 3; ++c) {
    int hi[3] = {idx[0], idx[1], idx[2]};
    hi[c] += 1;
    u[c] = 0.5 * (double(vel.component(c)[face_index(spec, c, idx[0], idx[1], idx[2])]) +
                  vel.component(c)[face_index(spec, c, hi[0], hi[1], hi[2])]);
  }
  return u;
}

// Where a neighbour index x along axis a lands: inside (x wrapped on a periodic axis), across an inflow
// face, or across a closed one (a wall or outflow: zero gradient).
enum class Across { inside, inflow, closed };
Across resolve_axis(const GridSpec& spec, int a, int& x) {
  const int n = cells_along(spec, a);
  if (x >= 0 && x < n) return Across::inside;
  if (spec.periodic(a)) {
    x = ((x % n) + n) % n;
    return Across::inside;
  }
  return spec.boundary[2 * a + (x < 0 ? 0 : 1)] == BoundaryType::inflow ? Across::inflow : Across::closed;
}

}  // namespace

std::vector<float> tke_equilibrium(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                   const MacVelocity& vel) {
  check_solid(spec, solid, "tke_equilibrium");
  const std::vector<float> walls = wall_cells(spec, solid);
  std::vector<float> e(spec.cell_count(), 0.0f);
  for_each_air_cell(spec, solid, [&](const int idx[3], std::size_t id) {
    const double l = tke_mixing_length(spec.h, walls[id] != 0.0f);
    e[id] = float(std::max(
        kTkeFloor, tke_shear_equilibrium(l, spec.h, strain_rate_squared(spec, vel, idx[0], idx[1], idx[2]))));
  });
  return e;
}

std::vector<float> tke_viscosity(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                 const std::vector<float>& energy, double cap) {
  check_solid(spec, solid, "tke_viscosity");
  check_cells(spec, energy.size(), "tke_viscosity", "the subgrid energy");
  const std::vector<float> walls = wall_cells(spec, solid);
  std::vector<float> nu(spec.cell_count(), 0.0f);
  for (std::size_t id = 0; id < nu.size(); ++id) {
    if (is_solid(solid, id)) continue;
    const double c_m_l = kTkeViscosityConstant * tke_mixing_length(spec.h, walls[id] != 0.0f);
    nu[id] = float(std::min(c_m_l * std::sqrt(double(energy[id])), cap));
  }
  return nu;
}

std::vector<float> tke_advect(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                              const MacVelocity& vel, const std::vector<float>& energy, double dt) {
  check_solid(spec, solid, "tke_advect");
  check_cells(spec, energy.size(), "tke_advect", "the subgrid energy");
  std::vector<float> out(spec.cell_count(), 0.0f);
  for_each_air_cell(spec, solid, [&](const int idx[3], std::size_t id) {
    const double own = energy[id];
    const auto u = centre_velocity(spec, vel, idx);
    int base[3];
    double t[3];
    for (int a = 0; a < 3; ++a) {
      const double s = idx[a] - dt * u[a] / spec.h;  // the departure point, in cell-centre units
      base[a] = int(std::floor(s));
      t[a] = s - base[a];
    }
    // One corner: the ghost rules of fluid/SubgridTke.hpp, step 2.
    auto corner = [&](int di, int dj, int dk) {
      int at[3] = {base[0] + di, base[1] + dj, base[2] + dk};
      bool inflow = false;
      for (int a = 0; a < 3; ++a) {
        const Across across = resolve_axis(spec, a, at[a]);
        inflow = inflow || across == Across::inflow;
        if (across == Across::closed) at[a] = std::clamp(at[a], 0, cells_along(spec, a) - 1);
      }
      if (inflow) return kTkeInflow;
      const std::size_t c = cell_at(spec, at);
      return is_solid(solid, c) ? own : double(energy[c]);
    };
    double value = 0.0;
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di)
          value += (di ? t[0] : 1.0 - t[0]) * (dj ? t[1] : 1.0 - t[1]) * (dk ? t[2] : 1.0 - t[2]) *
                   corner(di, dj, dk);
    out[id] = float(value);
  });
  return out;
}

std::vector<float> tke_update(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                              const MacVelocity& vel, const std::vector<float>& nu_t,
                              const std::vector<float>& drag_density, const std::vector<float>& advected,
                              double dt, double cap) {
  check_solid(spec, solid, "tke_update");
  check_cells(spec, nu_t.size(), "tke_update", "the eddy viscosity");
  check_cells(spec, advected.size(), "tke_update", "the advected subgrid energy");
  if (!drag_density.empty()) check_cells(spec, drag_density.size(), "tke_update", "the drag density");
  const std::vector<float> walls = wall_cells(spec, solid);
  const TkeCoefficients tc = tke_coefficients(spec.h);
  std::vector<float> out(spec.cell_count(), 0.0f);
  for_each_air_cell(spec, solid, [&](const int idx[3], std::size_t id) {
    const double e = advected[id], nu = nu_t[id];
    double flux = 0.0;  // sum of K_f (e_nb - e), m^4/s^3
    for (int a = 0; a < 3; ++a)
      for (int side = -1; side <= 1; side += 2) {
        int nb[3] = {idx[0], idx[1], idx[2]};
        nb[a] += side;
        const Across across = resolve_axis(spec, a, nb[a]);
        if (across == Across::inflow) flux += std::min(2.0 * nu, cap) * (kTkeInflow - e);
        if (across != Across::inside) continue;
        const std::size_t n = cell_at(spec, nb);
        if (is_solid(solid, n)) continue;
        flux += std::min(nu + double(nu_t[n]), cap) * (double(advected[n]) - e);
      }
    const auto u = centre_velocity(spec, vel, idx);
    const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double drag = drag_density.empty() ? 0.0 : double(drag_density[id]);
    const double production = nu * strain_rate_squared(spec, vel, idx[0], idx[1], idx[2]) +
                              kWakeProductionFraction * drag * speed * speed * speed;
    const double sink_rate =
        tc.dissipation_rate[walls[id] != 0.0f] * std::sqrt(e) + kCanopySinkFactor * drag * speed;
    const double next = (e + dt * (flux / (spec.h * spec.h) + production)) / (1.0 + dt * sink_rate);
    out[id] = float(std::max(kTkeFloor, next));
  });
  return out;
}

std::vector<float> tke_step(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                            const MacVelocity& vel, const std::vector<float>& drag_density,
                            const std::vector<float>& energy, double dt, std::vector<float>* nu_t) {
  const double cap = eddy_viscosity_cap(spec.h, dt);
  const std::vector<float> nu = tke_viscosity(spec, solid, energy, cap);
  const std::vector<float> advected = tke_advect(spec, solid, vel, energy, dt);
  if (nu_t) *nu_t = nu;
  return tke_update(spec, solid, vel, nu, drag_density, advected, dt, cap);
}

}  // namespace reference
}  // namespace fw::fluid
