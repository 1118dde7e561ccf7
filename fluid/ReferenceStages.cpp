#include "fluid/ReferenceStages.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "fluid/SubgridStress.hpp"

namespace fw::fluid::reference {
namespace {

int dims(const GridSpec& s, int a) {
  return a == 0 ? s.nx : (a == 1 ? s.ny : s.nz);
}

std::size_t cell_index(int nx, int ny, int i, int j, int k) {
  return std::size_t(i) + std::size_t(nx) * (std::size_t(j) + std::size_t(ny) * std::size_t(k));
}

// Staggering offset of component c along axis a: faces of the own axis sit on integer positions.
double offset(int c, int a) {
  return c == a ? 0.0 : 0.5;
}

// Neighbour value of phi across face f of cell (i,j,k) on a level: wraps on periodic axes, 0 outside.
double neighbour_phi(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& phi, int i,
                     int j, int k, int f) {
  int idx[3] = {i, j, k};
  const int n[3] = {L.nx, L.ny, L.nz};
  const int a = f / 2;
  idx[a] += (f % 2) ? 1 : -1;
  if (idx[a] < 0 || idx[a] >= n[a]) {
    if (!spec.periodic(a)) return 0.0;  // Dirichlet ghost (outflow)
    idx[a] = (idx[a] + n[a]) % n[a];
  }
  return phi[cell_index(L.nx, L.ny, idx[0], idx[1], idx[2])];
}

// Sum of phi over the open faces of a cell.
double open_neighbour_sum(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& phi, int i,
                          int j, int k, std::uint8_t m) {
  double sum = 0.0;
  for (int f = 0; f < 6; ++f)
    if (m & (1u << f)) sum += neighbour_phi(spec, L, phi, i, j, k, f);
  return sum;
}

int open_count(std::uint8_t m) {
  return std::popcount(static_cast<unsigned>(m & FW_MASK_OPEN_ALL));
}

template <typename F>
void for_each_face(const GridSpec& spec, int c, F&& f) {
  const int ex = extent(spec, c, 0), ey = extent(spec, c, 1), ez = extent(spec, c, 2);
  for (int k = 0; k < ez; ++k)
    for (int j = 0; j < ey; ++j)
      for (int i = 0; i < ex; ++i) f(i, j, k, face_index(spec, c, i, j, k));
}

// Is face (i,j,k) of component c open in the pressure mask (its velocity is solved for)? The cell on the
// low side owns the face through its high bit; the domain's low boundary face belongs to cell 0.
bool face_open(const GridSpec& spec, const PressureLevel& fine, int c, int i, int j, int k) {
  int idx[3] = {i, j, k};
  const int n = dims(spec, c);
  int bit = 2 * c + 1;
  if (idx[c] == 0)
    bit = 2 * c;
  else
    idx[c] = std::min(idx[c] - 1, n - 1);
  return fine.mask[cell_index(spec.nx, spec.ny, idx[0], idx[1], idx[2])] & (1u << bit);
}

}  // namespace

int extent(const GridSpec& spec, int component, int axis) {
  return dims(spec, axis) + (component == axis ? 1 : 0);
}

std::size_t face_index(const GridSpec& spec, int c, int i, int j, int k) {
  const std::size_t ex = extent(spec, c, 0), ey = extent(spec, c, 1);
  return std::size_t(i) + ex * (std::size_t(j) + ey * std::size_t(k));
}

double fetch(const GridSpec& spec, const InflowState& inflow, const std::vector<float>& q, int c, int i,
             int j, int k) {
  int idx[3] = {i, j, k};
  double sign = 1.0;
  for (int a = 0; a < 3; ++a) {
    const int ext = extent(spec, c, a);
    if (idx[a] >= 0 && idx[a] < ext) continue;
    const bool low = idx[a] < 0;
    const BoundaryType bc = spec.boundary[2 * a + (low ? 0 : 1)];
    const int n = dims(spec, a);
    if (bc == BoundaryType::periodic) {
      idx[a] = ((idx[a] % n) + n) % n;
      continue;
    }
    if (bc == BoundaryType::inflow) return inflow.value(spec, c, i, j, k, idx[2]);
    if (bc == BoundaryType::no_slip && a != c) {
      idx[a] = low ? (-1 - idx[a]) : (2 * ext - 1 - idx[a]);
      sign = -sign;
    }
    idx[a] = std::clamp(idx[a], 0, ext - 1);
  }
  return sign * double(q[face_index(spec, c, idx[0], idx[1], idx[2])]);
}

double sample(const GridSpec& spec, const InflowState& inflow, const std::vector<float>& q, int c, double X,
              double Y, double Z) {
  double P[3] = {X, Y, Z};
  int i0[3];
  double fr[3];
  for (int a = 0; a < 3; ++a) {
    const int n = dims(spec, a);
    // A periodic axis reads a position near its seam through the ghost layers, as the kernels do (face n of
    // a staggered axis from above, face 0 from below; fetch wraps the indices); one further out, wrapped.
    const double near = std::floor(P[a] - offset(c, a));
    if (spec.periodic(a) && !(near >= -FW_PAD && near + 1 < extent(spec, c, a) + FW_PAD))
      P[a] -= n * std::floor(P[a] / n);
    double g = P[a] - offset(c, a);
    if (!spec.periodic(a)) g = std::clamp(g, -1.0, double(extent(spec, c, a)));
    const double fl = std::floor(g);
    i0[a] = int(fl);
    fr[a] = g - fl;
  }
  double value = 0.0;
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        const double wgt = (di ? fr[0] : 1 - fr[0]) * (dj ? fr[1] : 1 - fr[1]) * (dk ? fr[2] : 1 - fr[2]);
        if (wgt == 0.0) continue;
        value += wgt * fetch(spec, inflow, q, c, i0[0] + di, i0[1] + dj, i0[2] + dk);
      }
  return value;
}

void backtrace(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel, int c, int i, int j,
               int k, double dt, double& X, double& Y, double& Z) {
  const double P[3] = {i + offset(c, 0), j + offset(c, 1), k + offset(c, 2)};
  const double s = dt / spec.h;  // m/s -> cells
  double V[3], M[3];
  for (int a = 0; a < 3; ++a) V[a] = sample(spec, inflow, vel.component(a), a, P[0], P[1], P[2]);
  for (int a = 0; a < 3; ++a) M[a] = P[a] - 0.5 * s * V[a];
  for (int a = 0; a < 3; ++a) V[a] = sample(spec, inflow, vel.component(a), a, M[0], M[1], M[2]);
  X = P[0] - s * V[0];
  Y = P[1] - s * V[1];
  Z = P[2] - s * V[2];
}

MacVelocity advect_semi_lagrangian(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel,
                                   const MacVelocity& q, double dt) {
  MacVelocity out(spec);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      double X, Y, Z;
      backtrace(spec, inflow, vel, c, i, j, k, dt, X, Y, Z);
      out.component(c)[id] = float(sample(spec, inflow, q.component(c), c, X, Y, Z));
    });
  return out;
}

MacVelocity advect_maccormack(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel,
                              const MacVelocity& q, double dt) {
  const MacVelocity forward = advect_semi_lagrangian(spec, inflow, vel, q, dt);
  const MacVelocity back = advect_semi_lagrangian(spec, inflow, vel, forward, -dt);
  MacVelocity out(spec);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      double P[3];
      backtrace(spec, inflow, vel, c, i, j, k, dt, P[0], P[1], P[2]);
      // Range of the values the forward step interpolated between.
      double lo = INFINITY, hi = -INFINITY;
      int i0[3];
      for (int a = 0; a < 3; ++a) {
        const int n = dims(spec, a);
        double p = P[a];
        if (spec.periodic(a)) p -= n * std::floor(p / n);
        double g = p - offset(c, a);
        if (!spec.periodic(a)) g = std::clamp(g, -1.0, double(extent(spec, c, a)));
        i0[a] = int(std::floor(g));
      }
      for (int d = 0; d < 8; ++d) {
        const double val = fetch(spec, inflow, q.component(c), c, i0[0] + (d & 1), i0[1] + ((d >> 1) & 1),
                                 i0[2] + ((d >> 2) & 1));
        lo = std::min(lo, val);
        hi = std::max(hi, val);
      }
      const double fwd = forward.component(c)[id];
      const double corrected = fwd + 0.5 * (double(q.component(c)[id]) - double(back.component(c)[id]));
      out.component(c)[id] = float((corrected < lo || corrected > hi) ? fwd : corrected);
    });
  return out;
}

MacVelocity upwind_stage(const GridSpec& spec, const InflowState& inflow, const UpwindOrders& orders,
                         const MacVelocity& stage, const MacVelocity& base, double coef_dt) {
  MacVelocity out(spec);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      const int p[3] = {i, j, k};
      // Values of component n at p shifted by d (any integer offsets), through fetch's ghost rules.
      auto value = [&](int n, const int d[3]) {
        return fetch(spec, inflow, stage.component(n), n, p[0] + d[0], p[1] + d[1], p[2] + d[2]);
      };
      double net = 0.0;
      for (int a = 0; a < 3; ++a) {
        // The side of the control volume at p - 1/2 e_a (side 0) and p + 1/2 e_a (side 1).
        for (int side = 0; side < 2; ++side) {
          std::array<double, 6> q{};
          for (int n = 0; n < 6; ++n) {
            int d[3] = {0, 0, 0};
            d[a] = side - 3 + n;  // q_m-2 .. q_m+3, m = p - 1 + side
            q[std::size_t(n)] = value(c, d);
          }
          double U;
          if (a == c) {
            U = 0.5 * (q[2] + q[3]);
          } else {  // component a on the two faces meeting at the side, at p and one back along c
            int here[3] = {0, 0, 0}, back[3] = {0, 0, 0};
            here[a] = back[a] = side;
            back[c] = -1;
            U = 0.5 * (value(a, back) + value(a, here));
          }
          const int order = flux_order(orders[std::size_t(c)][id], a, FluxSide(side));
          const double flux = U * upwind_interpolation(order, U, q);
          net += side == 1 ? flux : -flux;
        }
      }
      out.component(c)[id] = float(double(base.component(c)[id]) - coef_dt / spec.h * net);
    });
  return out;
}

MacVelocity advect_upwind5(const GridSpec& spec, const PressureLevel& fine, const InflowState& inflow,
                           const UpwindOrders& orders, const MacVelocity& vel, double dt) {
  MacVelocity first = upwind_stage(spec, inflow, orders, vel, vel, dt / 3.0);
  enforce_boundaries(spec, fine, inflow, first);
  MacVelocity second = upwind_stage(spec, inflow, orders, first, vel, dt / 2.0);
  enforce_boundaries(spec, fine, inflow, second);
  return upwind_stage(spec, inflow, orders, second, vel, dt);
}

void add_body_force(MacVelocity& vel, const std::array<double, 3>& g, double dt) {
  for (int c = 0; c < 3; ++c)
    for (auto& x : vel.component(c)) x = float(double(x) + dt * g[c]);
}

void add_gusts(const GridSpec& spec, MacVelocity& vel, const std::vector<FwGust>& gusts, double t,
               double dt) {
  const double tm = t + 0.5 * dt;
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      const double x[3] = {spec.origin[0] + spec.h * (i + offset(c, 0)),
                           spec.origin[1] + spec.h * (j + offset(c, 1)),
                           spec.origin[2] + spec.h * (k + offset(c, 2))};
      double add = 0.0;
      for (const FwGust& g : gusts) {
        const double tau = tm - g.start;
        if (!(tau > 0.0 && tau < g.duration)) continue;
        double r2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double d = x[a] - (g.center[a] + g.travel[a] * tau);
          r2 += d * d;
        }
        const double rate = g.peak_speed * (std::numbers::pi / g.duration) *
                            std::sin(2.0 * std::numbers::pi * tau / g.duration) *
                            std::exp(-r2 / (double(g.radius) * g.radius));
        add += dt * rate * g.direction[c];
      }
      vel.component(c)[id] = float(double(vel.component(c)[id]) + add);
    });
}

std::vector<float> vorticity(const GridSpec& spec, const MacVelocity& vel) {
  const int nx = spec.nx, ny = spec.ny, nz = spec.nz;
  auto centre = [&](int c, int i, int j, int k) {
    int hi[3] = {i, j, k};
    hi[c] += 1;
    return 0.5 * (double(vel.component(c)[face_index(spec, c, i, j, k)]) +
                  double(vel.component(c)[face_index(spec, c, hi[0], hi[1], hi[2])]));
  };
  // d(component c)/d(axis a) at cell (i,j,k), central where possible.
  auto deriv = [&](int c, int a, int i, int j, int k) {
    int p[3] = {i, j, k}, m[3] = {i, j, k};
    const int n = dims(spec, a);
    p[a] = std::min(p[a] + 1, n - 1);
    m[a] = std::max(m[a] - 1, 0);
    const int span = p[a] - m[a];
    if (span == 0) return 0.0;
    return (centre(c, p[0], p[1], p[2]) - centre(c, m[0], m[1], m[2])) / (span * spec.h);
  };
  std::vector<float> out(spec.cell_count() * 4);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double wx = deriv(2, 1, i, j, k) - deriv(1, 2, i, j, k);
        const double wy = deriv(0, 2, i, j, k) - deriv(2, 0, i, j, k);
        const double wz = deriv(1, 0, i, j, k) - deriv(0, 1, i, j, k);
        const std::size_t id = cell_index(nx, ny, i, j, k) * 4;
        out[id] = float(wx);
        out[id + 1] = float(wy);
        out[id + 2] = float(wz);
        out[id + 3] = float(std::sqrt(wx * wx + wy * wy + wz * wz));
      }
  return out;
}

void add_vorticity_confinement(const GridSpec& spec, MacVelocity& vel, double epsilon, double dt) {
  const int nx = spec.nx, ny = spec.ny, nz = spec.nz;
  const std::vector<float> w = vorticity(spec, vel);
  auto mag = [&](int i, int j, int k) { return double(w[cell_index(nx, ny, i, j, k) * 4 + 3]); };
  std::vector<double> force(spec.cell_count() * 3);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double eta[3];
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          int p[3] = {i, j, k}, m[3] = {i, j, k};
          p[a] = std::min(c[a] + 1, dims(spec, a) - 1);
          m[a] = std::max(c[a] - 1, 0);
          const int span = p[a] - m[a];
          eta[a] = span ? (mag(p[0], p[1], p[2]) - mag(m[0], m[1], m[2])) / (span * spec.h) : 0.0;
        }
        const double len = std::sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]) + 1e-20;
        const double N[3] = {eta[0] / len, eta[1] / len, eta[2] / len};
        const std::size_t id = cell_index(nx, ny, i, j, k);
        const double W[3] = {w[id * 4], w[id * 4 + 1], w[id * 4 + 2]};
        const double s = epsilon * spec.h;
        force[id * 3 + 0] = s * (N[1] * W[2] - N[2] * W[1]);
        force[id * 3 + 1] = s * (N[2] * W[0] - N[0] * W[2]);
        force[id * 3 + 2] = s * (N[0] * W[1] - N[1] * W[0]);
      }
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      int lo[3] = {i, j, k}, hi[3] = {i, j, k};
      lo[c] = std::max(lo[c] - 1, 0);
      hi[c] = std::min(hi[c], dims(spec, c) - 1);
      const double f = 0.5 * (force[cell_index(nx, ny, lo[0], lo[1], lo[2]) * 3 + c] +
                              force[cell_index(nx, ny, hi[0], hi[1], hi[2]) * 3 + c]);
      vel.component(c)[id] = float(double(vel.component(c)[id]) + dt * f);
    });
}

namespace {

// The sum of component d's four faces around a face of another component whose two cells are lo and hi:
// the faces below and above each cell along d (four times d's value at the face).
double other_faces_sum(const GridSpec& spec, const MacVelocity& vel, int d, const int lo[3],
                       const int hi[3]) {
  double m = 0.0;
  for (const int* cell : {lo, hi})
    for (int side = 0; side < 2; ++side) {
      int f[3] = {cell[0], cell[1], cell[2]};
      f[d] += side;
      m += vel.component(d)[face_index(spec, d, f[0], f[1], f[2])];
    }
  return m;
}

}  // namespace

MacVelocity canopy_drag(const GridSpec& spec, const MacVelocity& vel, const std::vector<float>& drag_density,
                        double dt, const DragLaw& law) {
  if (drag_density.size() != spec.cell_count())
    throw std::invalid_argument("canopy_drag: the drag density needs one value a cell");
  MacVelocity out(spec);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      int lo[3] = {i, j, k}, hi[3] = {i, j, k};
      // Across a periodic seam the cell on the other side, as the kernel does (fluid_forces.cl).
      const int n = dims(spec, c);
      const bool wrap = spec.periodic(c);
      lo[c] = lo[c] > 0 ? lo[c] - 1 : (wrap ? n - 1 : 0);
      hi[c] = hi[c] < n ? hi[c] : (wrap ? 0 : n - 1);
      const double kf = 0.5 * (double(drag_density[cell_index(spec.nx, spec.ny, lo[0], lo[1], lo[2])]) +
                               drag_density[cell_index(spec.nx, spec.ny, hi[0], hi[1], hi[2])]);
      const double q = vel.component(c)[id];
      double speed2 = q * q;
      for (int d = 0; d < 3; ++d) {
        if (d == c) continue;
        // Component d at the face: the mean of the d-faces below and above both neighbouring cells.
        const double m = other_faces_sum(spec, vel, d, lo, hi);
        speed2 += 0.0625 * m * m;
      }
      const double speed = std::sqrt(speed2);
      out.component(c)[id] = float(q / (1.0 + dt * kf * law.factor(speed) * speed));
    });
  return out;
}

MacVelocity diffuse(const GridSpec& spec, const InflowState& inflow, const MacVelocity& vel, double nu,
                    double dt) {
  MacVelocity out(spec);
  const double s = nu * dt / (spec.h * spec.h);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      const auto& q = vel.component(c);
      const double centre = q[id];
      const double lap = fetch(spec, inflow, q, c, i - 1, j, k) + fetch(spec, inflow, q, c, i + 1, j, k) +
                         fetch(spec, inflow, q, c, i, j - 1, k) + fetch(spec, inflow, q, c, i, j + 1, k) +
                         fetch(spec, inflow, q, c, i, j, k - 1) + fetch(spec, inflow, q, c, i, j, k + 1) -
                         6.0 * centre;
      out.component(c)[id] = float(centre + s * lap);
    });
  return out;
}

void enforce_boundaries(const GridSpec& spec, const PressureLevel& fine, const InflowState& inflow,
                        MacVelocity& vel) {
  for (int c = 0; c < 3; ++c) {
    const int n = dims(spec, c);
    auto& q = vel.component(c);
    // Loops run k, j, i ascending, so a periodic high face is visited after its low twin.
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      int idx[3] = {i, j, k};
      const bool boundary = idx[c] == 0 || idx[c] == n;
      if (boundary && spec.periodic(c) && idx[c] == n) {
        idx[c] = 0;
        q[id] = q[face_index(spec, c, idx[0], idx[1], idx[2])];
        return;
      }
      if (face_open(spec, fine, c, i, j, k)) return;
      double value = 0.0;
      if (boundary && !spec.periodic(c)) {
        const int face = 2 * c + (idx[c] == 0 ? 0 : 1);
        int cell[3] = {i, j, k};
        cell[c] = idx[c] == 0 ? 0 : n - 1;
        const bool fluid_cell =
            fine.mask[cell_index(spec.nx, spec.ny, cell[0], cell[1], cell[2])] & FW_MASK_FLUID;
        if (spec.boundary[face] == BoundaryType::inflow && fluid_cell)
          value = inflow.value(spec, c, i, j, k, k);
      }
      q[id] = float(value);
    });
  }
}

std::vector<float> divergence_rhs(const GridSpec& spec, const PressureLevel& fine, const MacVelocity& vel) {
  std::vector<float> b(spec.cell_count(), 0.f);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::size_t id = cell_index(spec.nx, spec.ny, i, j, k);
        if (!(fine.mask[id] & FW_MASK_FLUID)) continue;
        const double flux =
            double(vel.u[face_index(spec, 0, i + 1, j, k)]) - vel.u[face_index(spec, 0, i, j, k)] +
            double(vel.v[face_index(spec, 1, i, j + 1, k)]) - vel.v[face_index(spec, 1, i, j, k)] +
            double(vel.w[face_index(spec, 2, i, j, k + 1)]) - vel.w[face_index(spec, 2, i, j, k)];
        b[id] = float(-spec.h * flux);
      }
  return b;
}

double max_divergence(const GridSpec& spec, const PressureLevel& fine, const MacVelocity& vel) {
  const auto b = divergence_rhs(spec, fine, vel);
  double m = 0.0;
  for (float x : b) m = std::max(m, std::abs(double(x)));
  return m / (spec.h * spec.h);
}

namespace {

// Calls visit(i, j, k, id, mask) for each fluid cell of level L, in index order.
template <typename Visit>
void for_each_fluid_cell(const PressureLevel& L, Visit visit) {
  for (int k = 0; k < L.nz; ++k)
    for (int j = 0; j < L.ny; ++j)
      for (int i = 0; i < L.nx; ++i) {
        const std::size_t id = cell_index(L.nx, L.ny, i, j, k);
        const std::uint8_t m = L.mask[id];
        if (m & FW_MASK_FLUID) visit(i, j, k, id, m);
      }
}

// (A phi) at a fluid cell: its open faces' count times phi, less its open neighbours' phi.
double operator_at(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& phi, int i, int j,
                   int k, std::size_t id, std::uint8_t m) {
  return open_count(m) * double(phi[id]) - open_neighbour_sum(spec, L, phi, i, j, k, m);
}

}  // namespace

std::vector<float> apply_operator(const GridSpec& spec, const PressureLevel& L,
                                  const std::vector<float>& phi) {
  std::vector<float> out(L.cell_count(), 0.f);
  for_each_fluid_cell(L, [&](int i, int j, int k, std::size_t id, std::uint8_t m) {
    out[id] = float(operator_at(spec, L, phi, i, j, k, id, m));
  });
  return out;
}

std::vector<float> residual(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& b,
                            const std::vector<float>& phi) {
  std::vector<float> r(L.cell_count(), 0.f);
  for_each_fluid_cell(L, [&](int i, int j, int k, std::size_t id, std::uint8_t m) {
    r[id] = float(double(b[id]) - operator_at(spec, L, phi, i, j, k, id, m));
  });
  return r;
}

std::vector<float> jacobi_sweep(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& b,
                                const std::vector<float>& phi, double relaxation_weight) {
  std::vector<float> out(L.cell_count(), 0.f);
  for_each_fluid_cell(L, [&](int i, int j, int k, std::size_t id, std::uint8_t m) {
    const int diag = open_count(m);
    if (diag == 0) return;
    const double target = (double(b[id]) + open_neighbour_sum(spec, L, phi, i, j, k, m)) / diag;
    out[id] = float((1.0 - relaxation_weight) * phi[id] + relaxation_weight * target);
  });
  return out;
}

void red_black_sweep(const GridSpec& spec, const PressureLevel& L, const std::vector<float>& b,
                     std::vector<float>& phi, int colour) {
  for_each_fluid_cell(L, [&](int i, int j, int k, std::size_t id, std::uint8_t m) {
    const int diag = open_count(m);
    if (((i + j + k) & 1) != colour || diag == 0) return;
    phi[id] = float((double(b[id]) + open_neighbour_sum(spec, L, phi, i, j, k, m)) / diag);
  });
}

std::vector<float> restrict_residual(const GridSpec& spec, const PressureLevel& fine,
                                     const PressureLevel& coarse, const std::vector<float>& b,
                                     const std::vector<float>& phi, double scale) {
  const std::vector<float> r = residual(spec, fine, b, phi);
  std::vector<float> bc(coarse.cell_count(), 0.f);
  for (int K = 0; K < coarse.nz; ++K)
    for (int J = 0; J < coarse.ny; ++J)
      for (int I = 0; I < coarse.nx; ++I) {
        double sum = 0.0;
        int children = 0;
        for (int dk = 0; dk < 2; ++dk)
          for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) {
              const int i = 2 * I + di, j = 2 * J + dj, k = 2 * K + dk;
              if (i >= fine.nx || j >= fine.ny || k >= fine.nz) continue;
              ++children;
              sum += r[cell_index(fine.nx, fine.ny, i, j, k)];
            }
        const std::size_t id = cell_index(coarse.nx, coarse.ny, I, J, K);
        if (coarse.mask[id] & FW_MASK_FLUID) bc[id] = float(scale * sum / children);
      }
  return bc;
}

void prolong_add(const GridSpec& spec, const PressureLevel& fine, const PressureLevel& coarse,
                 const std::vector<float>& e, double slope, std::vector<float>& phi) {
  for (int k = 0; k < fine.nz; ++k)
    for (int j = 0; j < fine.ny; ++j)
      for (int i = 0; i < fine.nx; ++i) {
        const std::size_t id = cell_index(fine.nx, fine.ny, i, j, k);
        if (!(fine.mask[id] & FW_MASK_FLUID)) continue;
        const int I = i / 2, J = j / 2, K = k / 2, child[3] = {i, j, k};
        const std::size_t parent = cell_index(coarse.nx, coarse.ny, I, J, K);
        const std::uint8_t m = coarse.mask[parent];
        const double ep = e[parent];
        double correction = ep;
        for (int a = 0; a < 3; ++a) {
          const int face = 2 * a + (child[a] % 2);  // the face on the child's side
          if (m & (1u << face)) correction += slope * (neighbour_phi(spec, coarse, e, I, J, K, face) - ep);
        }
        phi[id] = float(double(phi[id]) + correction);
      }
}

void subtract_gradient(const GridSpec& spec, const PressureLevel& fine, const std::vector<float>& phi,
                       MacVelocity& vel) {
  for (int c = 0; c < 3; ++c) {
    const int n = dims(spec, c);
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      if (!face_open(spec, fine, c, i, j, k)) return;
      int lo[3] = {i, j, k}, hi[3] = {i, j, k};
      lo[c] -= 1;
      double phi_lo = 0.0, phi_hi = 0.0;
      if (lo[c] >= 0) {
        phi_lo = phi[cell_index(spec.nx, spec.ny, lo[0], lo[1], lo[2])];
      } else if (spec.periodic(c)) {
        lo[c] = n - 1;
        phi_lo = phi[cell_index(spec.nx, spec.ny, lo[0], lo[1], lo[2])];
      }
      if (hi[c] < n) {
        phi_hi = phi[cell_index(spec.nx, spec.ny, hi[0], hi[1], hi[2])];
      } else if (spec.periodic(c)) {
        hi[c] = 0;
        phi_hi = phi[cell_index(spec.nx, spec.ny, hi[0], hi[1], hi[2])];
      }
      vel.component(c)[id] = float(double(vel.component(c)[id]) - (phi_hi - phi_lo) / spec.h);
    });
  }
}

int solve_pressure_cg(const GridSpec& spec, const PressureLevel& fine, const std::vector<float>& b_in,
                      std::vector<float>& phi_out, double tolerance, int max_iterations) {
  const std::size_t n = fine.cell_count();
  std::vector<double> b(b_in.begin(), b_in.end());
  if (!spec.has_dirichlet_pressure()) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t c = 0; c < n; ++c)
      if (fine.mask[c] & FW_MASK_FLUID) sum += b[c], ++count;
    for (std::size_t c = 0; c < n; ++c)
      if (fine.mask[c] & FW_MASK_FLUID) b[c] -= sum / double(count);
  }
  // A in double, through the float operator on a scaled copy would lose digits: apply it directly.
  auto apply = [&](const std::vector<double>& x, std::vector<double>& y) {
    for (int k = 0; k < fine.nz; ++k)
      for (int j = 0; j < fine.ny; ++j)
        for (int i = 0; i < fine.nx; ++i) {
          const std::size_t id = cell_index(fine.nx, fine.ny, i, j, k);
          const std::uint8_t m = fine.mask[id];
          y[id] = 0.0;
          if (!(m & FW_MASK_FLUID)) continue;
          double sum = 0.0;
          for (int f = 0; f < 6; ++f) {
            if (!(m & (1u << f))) continue;
            int idx[3] = {i, j, k};
            const int nn[3] = {fine.nx, fine.ny, fine.nz};
            const int a = f / 2;
            idx[a] += (f % 2) ? 1 : -1;
            if (idx[a] < 0 || idx[a] >= nn[a]) {
              if (!spec.periodic(a)) continue;
              idx[a] = (idx[a] + nn[a]) % nn[a];
            }
            sum += x[cell_index(fine.nx, fine.ny, idx[0], idx[1], idx[2])];
          }
          y[id] = open_count(m) * x[id] - sum;
        }
  };
  auto dot = [&](const std::vector<double>& a, const std::vector<double>& c) {
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i) s += a[i] * c[i];
    return s;
  };
  std::vector<double> x(n, 0.0), r = b, d = b, q(n);
  const double bnorm = std::sqrt(dot(b, b));
  double rr = dot(r, r);
  int it = 0;
  if (bnorm > 0.0) {
    for (; it < max_iterations && std::sqrt(rr) > tolerance * bnorm; ++it) {
      apply(d, q);
      const double alpha = rr / dot(d, q);
      for (std::size_t i = 0; i < n; ++i) x[i] += alpha * d[i], r[i] -= alpha * q[i];
      const double rr_new = dot(r, r);
      const double beta = rr_new / rr;
      rr = rr_new;
      for (std::size_t i = 0; i < n; ++i) d[i] = r[i] + beta * d[i];
    }
  }
  phi_out.assign(n, 0.f);
  for (std::size_t i = 0; i < n; ++i) phi_out[i] = float(x[i]);
  return it;
}

// --- Subgrid and wall stresses (fluid/SubgridStress.hpp; kernels/subgrid_stress.cl) ---------------------

namespace {

void check_solid_size(const GridSpec& spec, const std::vector<std::uint8_t>& solid, const char* who) {
  if (!solid.empty() && solid.size() != spec.cell_count())
    throw std::invalid_argument(std::string(who) + ": the solid map needs one byte a cell");
}

// A cell index up to two steps outside an axis of n cells: wrapped on a periodic axis, else the edge cell.
int wrap_or_clamp(int x, int n, bool periodic) {
  if (periodic) return ((x % n) + n) % n;
  return std::clamp(x, 0, n - 1);
}

// The two cells sharing face (i,j,k) of component c, below (lo) and above (hi) it along c. The face may lie
// one face outside the array: its cells are then wrapped or clamped like the cells beside a boundary face.
void face_cells(const GridSpec& spec, int c, int i, int j, int k, int lo[3], int hi[3]) {
  lo[0] = hi[0] = i;
  lo[1] = hi[1] = j;
  lo[2] = hi[2] = k;
  lo[c] -= 1;
  for (int a = 0; a < 3; ++a) {
    lo[a] = wrap_or_clamp(lo[a], dims(spec, a), spec.periodic(a));
    hi[a] = wrap_or_clamp(hi[a], dims(spec, a), spec.periodic(a));
  }
}

}  // namespace

double strain_rate_squared(const GridSpec& spec, const MacVelocity& vel, int i, int j, int k) {
  // A face of component c, its index wrapped where it lies outside a periodic axis (the ghost's rule).
  auto face = [&](int c, int fi, int fj, int fk) {
    int idx[3] = {fi, fj, fk};
    for (int a = 0; a < 3; ++a) {
      if (idx[a] >= 0 && idx[a] < extent(spec, c, a)) continue;
      const int n = dims(spec, a);
      idx[a] = ((idx[a] % n) + n) % n;
    }
    return double(vel.component(c)[face_index(spec, c, idx[0], idx[1], idx[2])]);
  };
  auto centre = [&](int c, int ci, int cj, int ck) {
    int hi[3] = {ci, cj, ck};
    hi[c] += 1;
    return 0.5 * (face(c, ci, cj, ck) + face(c, hi[0], hi[1], hi[2]));
  };
  auto deriv = [&](int c, int a) {
    int p[3] = {i, j, k}, m[3] = {i, j, k};
    p[a] += 1;
    m[a] -= 1;
    if (!spec.periodic(a)) {
      p[a] = std::min(p[a], dims(spec, a) - 1);
      m[a] = std::max(m[a], 0);
    }
    const int span = p[a] - m[a];
    if (span == 0) return 0.0;
    return (centre(c, p[0], p[1], p[2]) - centre(c, m[0], m[1], m[2])) / (span * spec.h);
  };
  double g[3][3];  // g[c][a] = d u_c / d x_a
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) g[c][a] = deriv(c, a);
  double s2 = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < 3; ++a) {
      const double s = 0.5 * (g[c][a] + g[a][c]);
      s2 += 2.0 * s * s;
    }
  return s2;
}

std::vector<float> eddy_viscosity(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                  const MacVelocity& vel, double smagorinsky_constant, double cap) {
  check_solid_size(spec, solid, "eddy_viscosity");
  const double cs_h = smagorinsky_constant * spec.h;
  std::vector<float> nu(spec.cell_count(), 0.0f);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::size_t id = cell_index(spec.nx, spec.ny, i, j, k);
        if (!solid.empty() && solid[id]) continue;
        nu[id] = float(std::fmin(cs_h * cs_h * std::sqrt(strain_rate_squared(spec, vel, i, j, k)), cap));
      }
  return nu;
}

MacVelocity diffuse_eddy(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                         const InflowState& inflow, const MacVelocity& vel, const std::vector<float>& nu_t,
                         double dt, bool wall_slip) {
  check_solid_size(spec, solid, "diffuse_eddy");
  if (nu_t.size() != spec.cell_count())
    throw std::invalid_argument("diffuse_eddy: the eddy viscosity needs one value a cell");
  auto is_solid = [&](const int cell[3]) {
    return !solid.empty() && solid[cell_index(spec.nx, spec.ny, cell[0], cell[1], cell[2])] != 0;
  };
  auto face_nu = [&](int c, int i, int j, int k) {
    int lo[3], hi[3];
    face_cells(spec, c, i, j, k, lo, hi);
    return 0.5 * (double(nu_t[cell_index(spec.nx, spec.ny, lo[0], lo[1], lo[2])]) +
                  nu_t[cell_index(spec.nx, spec.ny, hi[0], hi[1], hi[2])]);
  };
  MacVelocity out(spec);
  const double dt_over_h2 = dt / (spec.h * spec.h);
  for (int c = 0; c < 3; ++c)
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      const auto& q = vel.component(c);
      const double centre = q[id], nu_centre = face_nu(c, i, j, k);
      double flux = 0.0;
      for (int a = 0; a < 3; ++a)
        for (int side = -1; side <= 1; side += 2) {
          int nb[3] = {i, j, k};
          nb[a] += side;
          double value = fetch(spec, inflow, q, c, nb[0], nb[1], nb[2]);
          if (wall_slip && c < 2 && a == 2 && side < 0 && k > 0) {
            int lo[3], hi[3];
            face_cells(spec, c, i, j, k - 1, lo, hi);
            if (is_solid(lo) || is_solid(hi)) value = centre;  // the wall stress carries this flux
          }
          flux += 0.5 * (nu_centre + face_nu(c, nb[0], nb[1], nb[2])) * (value - centre);
        }
      out.component(c)[id] = float(centre + dt_over_h2 * flux);
    });
  return out;
}

MacVelocity wall_stress(const GridSpec& spec, const std::vector<std::uint8_t>& solid, const MacVelocity& vel,
                        double drag_coefficient, double dt) {
  const std::vector<float> walls = wall_cells(spec, solid);
  auto wall = [&](const int cell[3]) {
    return double(walls[cell_index(spec.nx, spec.ny, cell[0], cell[1], cell[2])]);
  };
  MacVelocity out = vel;
  for (int c = 0; c < 2; ++c) {
    const int d = 1 - c;  // the other horizontal component
    for_each_face(spec, c, [&](int i, int j, int k, std::size_t id) {
      int lo[3], hi[3];
      face_cells(spec, c, i, j, k, lo, hi);
      const double weight = 0.5 * (wall(lo) + wall(hi));
      if (weight == 0.0) return;
      // Component d at the face: the mean of the d-faces below and above both cells along d.
      const double m = 0.25 * other_faces_sum(spec, vel, d, lo, hi);
      const double q = vel.component(c)[id];
      const double speed = std::sqrt(q * q + m * m);
      out.component(c)[id] = float(q / (1.0 + dt * drag_coefficient * weight * speed / spec.h));
    });
  }
  return out;
}

}  // namespace fw::fluid::reference
