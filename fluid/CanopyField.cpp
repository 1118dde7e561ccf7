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

// The 1/2 of the drag convention F = 1/2 rho_air C_D A |u| u: k = 1/2 sum C_D A / h^3.
constexpr double kDynamicPressureFactor = 0.5;

double length(const CanopyElement& e) {
  const double dx = e.end[0] - e.start[0], dy = e.end[1] - e.start[1], dz = e.end[2] - e.start[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

CellBox CellBox::around(const GridSpec& spec, const std::array<double, 3>& low,
                        const std::array<double, 3>& high) {
  CellBox box;
  for (std::size_t a = 0; a < 3; ++a)
    if (!(low[a] <= high[a])) return box;
  const int cells[3] = {spec.nx, spec.ny, spec.nz};
  for (int a = 0; a < 3; ++a) {
    // Clamped in double first: a reach far outside the grid is no int.
    const auto cell = [&](double x) {
      return int(std::clamp(std::floor((x - spec.origin[std::size_t(a)]) / spec.h), -1.0, double(cells[a])));
    };
    const int first = std::max(0, cell(low[std::size_t(a)]) - 1);
    const int last = std::min(cells[a] - 1, cell(high[std::size_t(a)]) + 1);
    box.first[std::size_t(a)] = std::min(first, cells[a]);
    box.count[std::size_t(a)] = std::max(0, last - first + 1);
  }
  return box;
}

bool CellBox::overlaps(const CellBox& other) const {
  for (std::size_t a = 0; a < 3; ++a)
    if (first[a] >= other.first[a] + other.count[a] || other.first[a] >= first[a] + count[a]) return false;
  return true;
}

CanopyField::CanopyField(const GridSpec& spec, const CellBox& box) : spec_(validated(spec)), box_(box) {
  const int n[3] = {spec_.nx, spec_.ny, spec_.nz};
  for (int a = 0; a < 3; ++a)
    if (box.first[a] < 0 || box.count[a] < 0 || box.first[a] + box.count[a] > n[a])
      throw std::invalid_argument(
          fmt::format("CanopyField: a box of cells {}..{} along axis {}, outside the "
                      "grid's 0..{}",
                      box.first[a], box.first[a] + box.count[a] - 1, a, n[a] - 1));
  area_.assign(box_.cell_count(), 0.0);
  drag_.assign(box_.cell_count(), 0.0);
}

float CanopyField::drag_density_at(int i, int j, int k) const {
  const int cell[3] = {i, j, k};
  for (int a = 0; a < 3; ++a)
    if (cell[a] < box_.first[a] || cell[a] >= box_.first[a] + box_.count[a])
      throw std::out_of_range(fmt::format("CanopyField: cell ({}, {}, {}) outside the box", i, j, k));
  return float(drag_[box_index(i, j, k)]);
}

std::size_t CanopyField::box_index(int i, int j, int k) const {
  const int local[3] = {i - box_.first[0], j - box_.first[1], k - box_.first[2]};
  for (int a = 0; a < 3; ++a)
    if (local[a] < 0 || local[a] >= box_.count[a])
      throw std::logic_error(
          fmt::format("CanopyField: an element reaches cell ({}, {}, {}), outside the box "
                      "of cells the field stores",
                      i, j, k));
  return std::size_t(local[0]) +
         std::size_t(box_.count[0]) * (local[1] + std::size_t(box_.count[1]) * local[2]);
}

CanopyTreeReport CanopyField::add_elements(std::span<const CanopyElement> elements) {
  if (elements.empty()) throw std::invalid_argument("CanopyField: a tree needs at least one element");
  for (std::size_t m = 0; m < elements.size(); ++m) {
    const auto& e = elements[m];
    bool finite = std::isfinite(e.frontal_area_per_metre) && std::isfinite(e.drag_area_per_metre);
    for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(e.start[a]) && std::isfinite(e.end[a]);
    if (!finite || e.frontal_area_per_metre < 0.0 || e.drag_area_per_metre < 0.0)
      throw std::invalid_argument(
          fmt::format("CanopyField: element {} needs finite positions and finite areas per metre >= 0", m));
  }

  CanopyTreeReport report;
  double inside = 0.0;
  for (const auto& e : elements) {
    const double L = length(e);
    report.frontal_area += L * e.frontal_area_per_metre;
    report.drag_area += L * e.drag_area_per_metre;
    const Split split = rasterise(e);
    inside += split.frontal_inside;
    report.dropped_area += split.frontal_outside;
    report.dropped_drag_area += split.drag_outside;
  }
  report.outside = !(inside > 0.0);
  total_area_ += report.frontal_area;
  dropped_area_ += report.dropped_area;
  ++trees_;
  if (report.outside) ++trees_outside_;
  return report;
}

CanopyField::Split CanopyField::rasterise(const CanopyElement& e) {
  const double L = length(e);
  Split split;
  if (!(L > 0.0)) return split;
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
  for (std::size_t s = 0; s + 1 < cuts.size(); ++s) {
    const double t0 = cuts[s], t1 = cuts[s + 1];
    if (!(t1 > t0)) continue;
    const double piece = L * (t1 - t0);  // m; the areas per metre are constant along the element
    const double tm = 0.5 * (t0 + t1);   // the piece lies in one cell: the one holding its midpoint
    int cell[3];
    bool in_domain = true;
    for (int a = 0; a < 3; ++a) {
      const double x = std::floor(p0[a] + tm * d[a]);
      in_domain = in_domain && x >= 0.0 && x < n[a];
      cell[a] = in_domain ? int(x) : 0;
    }
    if (!in_domain) {
      split.frontal_outside += piece * e.frontal_area_per_metre;
      split.drag_outside += piece * e.drag_area_per_metre;
      continue;
    }
    const std::size_t id = box_index(cell[0], cell[1], cell[2]);
    area_[id] += piece * e.frontal_area_per_metre * inv_h3;
    drag_[id] += kDynamicPressureFactor * piece * e.drag_area_per_metre * inv_h3;
    split.frontal_inside += piece * e.frontal_area_per_metre;
  }
  return split;
}

double CanopyField::frontal_area_in_domain() const {
  double sum = 0.0;
  for (double a : area_) sum += a;
  return sum * spec_.h * spec_.h * spec_.h;
}

double CanopyField::drag_in_domain() const {
  double sum = 0.0;
  for (double k : drag_) sum += k;
  return sum * spec_.h * spec_.h * spec_.h;
}

CanopyColumns CanopyField::columns_in(const std::array<double, 2>& min,
                                      const std::array<double, 2>& max) const {
  CanopyColumns out;
  double sum = 0.0;  // of a over the cells, 1/m
  const auto centre_inside = [&](int index, int axis) {
    const double centre = spec_.origin[std::size_t(axis)] + (index + 0.5) * spec_.h;
    return centre >= min[std::size_t(axis)] && centre <= max[std::size_t(axis)];
  };
  // The grid's columns in the rectangle; the area only the box's cells can hold, summed in the grid's order.
  int along[2] = {0, 0};
  for (int axis = 0; axis < 2; ++axis)
    for (int index = 0; index < (axis == 0 ? spec_.nx : spec_.ny); ++index)
      along[axis] += centre_inside(index, axis);
  out.columns = along[0] * along[1];
  for (int j = box_.first[1]; j < box_.first[1] + box_.count[1]; ++j) {
    if (!centre_inside(j, 1)) continue;
    for (int i = box_.first[0]; i < box_.first[0] + box_.count[0]; ++i) {
      if (!centre_inside(i, 0)) continue;
      for (int k = box_.first[2]; k < box_.first[2] + box_.count[2]; ++k) sum += area_[box_index(i, j, k)];
    }
  }
  out.ground_area = out.columns * spec_.h * spec_.h;
  out.frontal_area = sum * spec_.h * spec_.h * spec_.h;
  return out;
}

std::size_t CanopyField::occupied_cells() const {
  return std::size_t(std::count_if(area_.begin(), area_.end(), [](double a) { return float(a) > 0.0f; }));
}

std::vector<float> CanopyField::to_float(const std::vector<double>& v) const {
  if (box_.cell_count() == spec_.cell_count()) return std::vector<float>(v.begin(), v.end());
  std::vector<float> out(spec_.cell_count(), 0.0f);
  for (int k = 0; k < box_.count[2]; ++k)
    for (int j = 0; j < box_.count[1]; ++j)
      for (int i = 0; i < box_.count[0]; ++i) {
        const std::size_t cell =
            std::size_t(box_.first[0] + i) +
            std::size_t(spec_.nx) *
                (std::size_t(box_.first[1] + j) + std::size_t(spec_.ny) * std::size_t(box_.first[2] + k));
        out[cell] =
            float(v[std::size_t(i) + std::size_t(box_.count[0]) * (j + std::size_t(box_.count[1]) * k)]);
      }
  return out;
}

}  // namespace fw::fluid
