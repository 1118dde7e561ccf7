#include "fluid/CanopyField.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::fluid {
namespace {

GridSpec validated(const GridSpec& spec) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("CanopyField: {}", e.what()));
  }
  return spec;
}

void check_coefficient(const char* name, double value) {
  if (!std::isfinite(value) || value < 0.0)
    throw std::invalid_argument(fmt::format("CanopyField: {} must be finite and >= 0, got {}", name, value));
}

double length(const CanopyElement& e) {
  const double dx = e.end[0] - e.start[0], dy = e.end[1] - e.start[1], dz = e.end[2] - e.start[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// Area of the convex hull of points in the plane (Andrew's monotone chain, then the shoelace formula).
double hull_area(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return 0.0;
  auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& a,
                  const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * std::abs(twice);
}

}  // namespace

CanopyField::CanopyField(const GridSpec& spec)
    : spec_(validated(spec)), area_(spec_.cell_count(), 0.0), drag_(spec_.cell_count(), 0.0) {}

CanopyTreeReport CanopyField::add_elements(std::span<const CanopyElement> elements,
                                           double branch_drag_coefficient, double leaf_area_index,
                                           double leaf_drag_coefficient) {
  check_coefficient("branch drag coefficient", branch_drag_coefficient);
  check_coefficient("leaf area index", leaf_area_index);
  check_coefficient("leaf drag coefficient", leaf_drag_coefficient);
  if (elements.empty()) throw std::invalid_argument("CanopyField: a tree needs at least one element");
  for (std::size_t m = 0; m < elements.size(); ++m) {
    const auto& e = elements[m];
    bool finite = std::isfinite(e.start_radius) && std::isfinite(e.end_radius);
    for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(e.start[a]) && std::isfinite(e.end[a]);
    if (!finite || e.start_radius < 0.0 || e.end_radius < 0.0)
      throw std::invalid_argument(
          fmt::format("CanopyField: element {} needs finite positions and radii >= 0", m));
  }

  CanopyTreeReport report;
  double inside = 0.0;
  // Woody area: the diameter runs linearly from 2 r0 to 2 r1 along the element.
  for (const auto& e : elements) {
    report.woody_area += length(e) * (e.start_radius + e.end_radius);
    const auto [in, out] = rasterise(e, 2.0 * e.start_radius, 2.0 * e.end_radius, branch_drag_coefficient);
    inside += in;
    report.dropped_area += out;
  }

  // Leaves: LAI x horizontal crown hull, spread uniformly per metre of leaf-bearing element.
  std::vector<std::array<double, 2>> crown;
  double leaf_length = 0.0;
  for (const auto& e : elements)
    if (e.leaf_bearing) {
      crown.push_back({e.start[0], e.start[1]});
      crown.push_back({e.end[0], e.end[1]});
      leaf_length += length(e);
    }
  report.crown_projected_area = hull_area(std::move(crown));
  if (leaf_area_index > 0.0 && report.crown_projected_area > 0.0 && leaf_length > 0.0) {
    report.leaf_area = leaf_area_index * report.crown_projected_area;
    const double per_metre = report.leaf_area / leaf_length;
    for (const auto& e : elements)
      if (e.leaf_bearing) {
        const auto [in, out] = rasterise(e, per_metre, per_metre, leaf_drag_coefficient);
        inside += in;
        report.dropped_area += out;
      }
  }
  report.outside = !(inside > 0.0);
  total_area_ += report.woody_area + report.leaf_area;
  dropped_area_ += report.dropped_area;
  ++trees_;
  if (report.outside) ++trees_outside_;
  return report;
}

std::pair<double, double> CanopyField::rasterise(const CanopyElement& e, double a0, double a1, double cd) {
  const double L = length(e);
  if (!(L > 0.0)) return {0.0, 0.0};
  // Cell coordinates: X = (world - origin) / h; cell (i, j, k) spans [i, i+1) x [j, j+1) x [k, k+1).
  std::array<double, 3> p0, d;
  for (int a = 0; a < 3; ++a) {
    p0[a] = (e.start[a] - spec_.origin[a]) / spec_.h;
    d[a] = (e.end[a] - e.start[a]) / spec_.h;
  }
  // Parameters t in (0, 1) where the segment crosses a cell boundary plane.
  std::vector<double> cuts{0.0, 1.0};
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) continue;
    const double lo = std::min(p0[a], p0[a] + d[a]), hi = std::max(p0[a], p0[a] + d[a]);
    for (double m = std::floor(lo) + 1.0; m < hi; m += 1.0) {
      const double t = (m - p0[a]) / d[a];
      if (t > 0.0 && t < 1.0) cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  const int n[3] = {spec_.nx, spec_.ny, spec_.nz};
  const double inv_h3 = 1.0 / (spec_.h * spec_.h * spec_.h);
  double inside = 0.0, outside = 0.0;
  for (std::size_t s = 0; s + 1 < cuts.size(); ++s) {
    const double t0 = cuts[s], t1 = cuts[s + 1];
    if (!(t1 > t0)) continue;
    // Exact for a linear taper: piece length times the mean of the per-length area at its ends.
    const double piece = L * (t1 - t0) * (a0 + 0.5 * (a1 - a0) * (t0 + t1));
    const double tm = 0.5 * (t0 + t1);  // the piece lies in one cell: the one holding its midpoint
    int cell[3];
    bool in_domain = true;
    for (int a = 0; a < 3; ++a) {
      const double x = std::floor(p0[a] + tm * d[a]);
      in_domain = in_domain && x >= 0.0 && x < n[a];
      cell[a] = in_domain ? int(x) : 0;
    }
    if (!in_domain) {
      outside += piece;
      continue;
    }
    const std::size_t id = std::size_t(cell[0]) + std::size_t(n[0]) * (cell[1] + std::size_t(n[1]) * cell[2]);
    area_[id] += piece * inv_h3;
    drag_[id] += cd * piece * inv_h3;
    inside += piece;
  }
  return {inside, outside};
}

double CanopyField::frontal_area_in_domain() const {
  double sum = 0.0;
  for (double a : area_) sum += a;
  return sum * spec_.h * spec_.h * spec_.h;
}

std::vector<float> CanopyField::to_float(const std::vector<double>& v) {
  return std::vector<float>(v.begin(), v.end());
}

}  // namespace fw::fluid
