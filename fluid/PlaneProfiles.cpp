#include "fluid/PlaneProfiles.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace fw::fluid {

const std::array<ProfileVariable, kProfileCount>& profile_variables() {
  // x is east and y north (a wind from 270 degrees blows along +x), so u and v are CF's eastward and
  // northward wind. The kinematic fluxes and variances have no CF standard name (CF's momentum fluxes are in
  // Pa).
  static const std::array<ProfileVariable, kProfileCount> variables{{
      {"area", "1", "fraction of the horizontal plane that is fluid", ""},
      {"u", "m s-1", "mean x velocity", "eastward_wind"},
      {"v", "m s-1", "mean y velocity", "northward_wind"},
      {"w", "m s-1", "mean vertical velocity", "upward_air_velocity"},
      {"u_2", "m2 s-2", "resolved variance of the x velocity", ""},
      {"v_2", "m2 s-2", "resolved variance of the y velocity", ""},
      {"w_2", "m2 s-2", "resolved variance of the vertical velocity", ""},
      {"u_3", "m3 s-3", "resolved third moment of the x velocity", ""},
      {"w_3", "m3 s-3", "resolved third moment of the vertical velocity", ""},
      {"u_w", "m2 s-2", "resolved vertical flux of x momentum", ""},
      {"v_w", "m2 s-2", "resolved vertical flux of y momentum", ""},
      {"u_diff", "m2 s-2", "subgrid vertical flux of x momentum", ""},
      {"v_diff", "m2 s-2", "subgrid vertical flux of y momentum", ""},
      {"u_flux", "m2 s-2", "total vertical flux of x momentum", ""},
      {"v_flux", "m2 s-2", "total vertical flux of y momentum", ""},
      {"tke", "m2 s-2", "resolved turbulent kinetic energy", ""},
      {"sgs_tke", "m2 s-2", "subgrid turbulent kinetic energy", ""},
      {"lad", "m-1", "canopy drag density (drag coefficient times frontal area density)", ""},
  }};
  return variables;
}

namespace {

std::size_t cell(const GridSpec& s, int i, int j, int k) {
  return std::size_t(i) + std::size_t(s.nx) * (std::size_t(j) + std::size_t(s.ny) * std::size_t(k));
}

// The cell-centred velocity of every cell, component by component: the mean of the cell's two faces.
std::array<std::vector<double>, 3> centred(const GridSpec& s, const MacVelocity& vel) {
  std::array<std::vector<double>, 3> out;
  for (int c = 0; c < 3; ++c) {
    out[std::size_t(c)].resize(s.cell_count());
    const int ex = s.nx + (c == 0), ey = s.ny + (c == 1);
    const auto face = [&](int i, int j, int k) {
      return double(
          vel.component(c)[std::size_t(i) + std::size_t(ex) * (std::size_t(j) + std::size_t(ey) * k)]);
    };
    for (int k = 0; k < s.nz; ++k)
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i)
          out[std::size_t(c)][cell(s, i, j, k)] =
              0.5 * (face(i, j, k) + face(i + (c == 0), j + (c == 1), k + (c == 2)));
  }
  return out;
}

// d q / d x_a at cell (i, j, k) of a cell-centred field: central over 2h, one-sided over h at a non-periodic
// edge, wrapped across a periodic one; 0 along an axis of one cell.
double derivative(const GridSpec& s, const std::vector<double>& q, int a, int i, int j, int k) {
  const int n = s.cells_along(a);
  std::array<int, 3> at{i, j, k}, plus = at, minus = at;
  const int x = at[std::size_t(a)];
  int up = x + 1, down = x - 1;
  if (s.periodic(a)) {
    up = (up + n) % n;
    down = (down + n) % n;
  } else {
    up = std::min(up, n - 1);
    down = std::max(down, 0);
  }
  const int span = s.periodic(a) ? 2 : (up - down);
  if (n == 1 || span == 0) return 0.0;
  plus[std::size_t(a)] = up;
  minus[std::size_t(a)] = down;
  return (q[cell(s, plus[0], plus[1], plus[2])] - q[cell(s, minus[0], minus[1], minus[2])]) / (span * s.h);
}

void require_cells(const GridSpec& s, std::size_t size, const char* what) {
  if (size != s.cell_count())
    throw std::invalid_argument(std::string("plane_profiles: ") + what + " has " + std::to_string(size) +
                                " values, the grid " + std::to_string(s.cell_count()) + " cells");
}

}  // namespace

PlaneProfiles plane_profiles(const GridSpec& spec, const MacVelocity& vel,
                             const std::vector<std::uint8_t>& solid, const PlaneFields& fields) {
  if (vel.u.size() != spec.u_count() || vel.v.size() != spec.v_count() || vel.w.size() != spec.w_count())
    throw std::invalid_argument("plane_profiles: the velocity is not the grid's");
  if (!solid.empty()) require_cells(spec, solid.size(), "the solid map");
  for (const auto& [field, what] : {std::pair{fields.eddy_viscosity, "the eddy viscosity"},
                                    std::pair{fields.subgrid_energy, "the subgrid energy"},
                                    std::pair{fields.drag_density, "the drag density"}})
    if (field) require_cells(spec, field->size(), what);

  const std::array<std::vector<double>, 3> q = centred(spec, vel);
  const auto& u = q[0];
  const auto& v = q[1];
  const auto& w = q[2];
  PlaneProfiles out;
  out.nz = spec.nz;
  for (auto& values : out.values) values.assign(std::size_t(spec.nz), 0.0);
  const auto set = [&](Profile p, int k, double value) {
    out.values[std::size_t(p)][std::size_t(k)] = value;
  };
  const auto fluid = [&](std::size_t id) { return solid.empty() || solid[id] == 0; };

  for (int k = 0; k < spec.nz; ++k) {
    long cells = 0;
    double sum[3] = {0, 0, 0};
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::size_t id = cell(spec, i, j, k);
        if (!fluid(id)) continue;
        ++cells;
        for (int c = 0; c < 3; ++c) sum[c] += q[std::size_t(c)][id];
      }
    set(Profile::area, k, double(cells) / (double(spec.nx) * spec.ny));
    if (cells == 0) continue;
    const double mean[3] = {sum[0] / cells, sum[1] / cells, sum[2] / cells};
    // Central moments about the plane's means, and the subgrid terms.
    double uu = 0, vv = 0, ww = 0, uuu = 0, www = 0, uw = 0, vw = 0, udiff = 0, vdiff = 0, e = 0, lad = 0;
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::size_t id = cell(spec, i, j, k);
        if (!fluid(id)) continue;
        const double du = u[id] - mean[0], dv = v[id] - mean[1], dw = w[id] - mean[2];
        uu += du * du;
        vv += dv * dv;
        ww += dw * dw;
        uuu += du * du * du;
        www += dw * dw * dw;
        uw += du * dw;
        vw += dv * dw;
        if (fields.eddy_viscosity) {
          const double nu = (*fields.eddy_viscosity)[id];
          const double s_xz = 0.5 * (derivative(spec, u, 2, i, j, k) + derivative(spec, w, 0, i, j, k));
          const double s_yz = 0.5 * (derivative(spec, v, 2, i, j, k) + derivative(spec, w, 1, i, j, k));
          udiff += -2.0 * nu * s_xz;
          vdiff += -2.0 * nu * s_yz;
        }
        if (fields.subgrid_energy) e += (*fields.subgrid_energy)[id];
        if (fields.drag_density) lad += (*fields.drag_density)[id];
      }
    const double n = double(cells);
    set(Profile::u, k, mean[0]);
    set(Profile::v, k, mean[1]);
    set(Profile::w, k, mean[2]);
    set(Profile::u_2, k, uu / n);
    set(Profile::v_2, k, vv / n);
    set(Profile::w_2, k, ww / n);
    set(Profile::u_3, k, uuu / n);
    set(Profile::w_3, k, www / n);
    set(Profile::u_w, k, uw / n);
    set(Profile::v_w, k, vw / n);
    set(Profile::u_diff, k, udiff / n);
    set(Profile::v_diff, k, vdiff / n);
    set(Profile::u_flux, k, (uw + udiff) / n);
    set(Profile::v_flux, k, (vw + vdiff) / n);
    set(Profile::tke, k, 0.5 * (uu + vv + ww) / n);
    set(Profile::sgs_tke, k, e / n);
    set(Profile::lad, k, lad / n);
  }
  return out;
}

}  // namespace fw::fluid
