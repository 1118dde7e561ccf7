#include "trees/ForestLayout.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "trees/LSystem.hpp"

namespace fw::trees {

namespace {

class UniformSource {
 public:
  explicit UniformSource(std::uint64_t seed) : engine_(seed) {}
  double next() { return unit_interval(engine_()); }
  double between(double lo, double hi) { return lo + (hi - lo) * next(); }

 private:
  std::mt19937_64 engine_;
};

std::vector<Eigen::Vector2d> grid_positions(const StandSpec& stand) {
  const Eigen::Vector2d extent = stand.max - stand.min;
  const int columns = int(std::floor(extent.x() / stand.spacing + 1e-9)) + 1;
  const int rows = int(std::floor(extent.y() / stand.spacing + 1e-9)) + 1;
  // Centre the lattice: the leftover width is shared equally by both sides.
  const Eigen::Vector2d first =
      stand.min + 0.5 * (extent - stand.spacing * Eigen::Vector2d(columns - 1, rows - 1));
  std::vector<Eigen::Vector2d> points;
  points.reserve(std::size_t(columns) * std::size_t(rows));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) points.push_back(first + stand.spacing * Eigen::Vector2d(c, r));
  }
  return points;
}

// Bridson's algorithm: a background grid of cells of size spacing / sqrt(2) holds at most one sample each, so
// a candidate only needs checking against the 5x5 cells around it.
std::vector<Eigen::Vector2d> poisson_positions(const StandSpec& stand, UniformSource& random) {
  constexpr int kTries = 30;
  const double r = stand.spacing;
  const double cell = r / std::numbers::sqrt2;
  const Eigen::Vector2d extent = stand.max - stand.min;
  const int nx = std::max(1, int(std::ceil(extent.x() / cell)));
  const int ny = std::max(1, int(std::ceil(extent.y() / cell)));
  std::vector<int> occupant(std::size_t(nx) * std::size_t(ny), -1);
  std::vector<Eigen::Vector2d> points;
  std::vector<int> active;

  auto cell_of = [&](const Eigen::Vector2d& p) {
    const int i = std::min(nx - 1, int((p.x() - stand.min.x()) / cell));
    const int j = std::min(ny - 1, int((p.y() - stand.min.y()) / cell));
    return std::pair{i, j};
  };
  auto fits = [&](const Eigen::Vector2d& p) {
    if ((p.array() < stand.min.array()).any() || (p.array() > stand.max.array()).any()) return false;
    const auto [i, j] = cell_of(p);
    for (int b = std::max(0, j - 2); b <= std::min(ny - 1, j + 2); ++b) {
      for (int a = std::max(0, i - 2); a <= std::min(nx - 1, i + 2); ++a) {
        const int other = occupant[std::size_t(a) + std::size_t(nx) * std::size_t(b)];
        if (other >= 0 && (points[std::size_t(other)] - p).squaredNorm() < r * r) return false;
      }
    }
    return true;
  };
  auto add = [&](const Eigen::Vector2d& p) {
    const auto [i, j] = cell_of(p);
    occupant[std::size_t(i) + std::size_t(nx) * std::size_t(j)] = int(points.size());
    active.push_back(int(points.size()));
    points.push_back(p);
  };

  add(stand.min + Eigen::Vector2d(random.next() * extent.x(), random.next() * extent.y()));
  while (!active.empty()) {
    const std::size_t pick = std::min(active.size() - 1, std::size_t(random.next() * double(active.size())));
    const Eigen::Vector2d centre = points[std::size_t(active[pick])];
    bool placed = false;
    for (int t = 0; t < kTries && !placed; ++t) {
      // Uniform in the annulus r..2r around the centre.
      const double radius = r * std::sqrt(1.0 + 3.0 * random.next());
      const double angle = 2.0 * std::numbers::pi * random.next();
      const Eigen::Vector2d candidate = centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      if (fits(candidate)) {
        add(candidate);
        placed = true;
      }
    }
    if (!placed) {
      active[pick] = active.back();
      active.pop_back();
    }
  }
  return points;
}

}  // namespace

void StandSpec::validate() const {
  if (!min.allFinite() || !max.allFinite() || !(max.x() > min.x()) || !(max.y() > min.y())) {
    throw std::invalid_argument(
        fmt::format("StandSpec: the region needs min < max on both axes, got min ({}, {}) "
                    "max ({}, {})",
                    min.x(), min.y(), max.x(), max.y()));
  }
  if (!std::isfinite(spacing) || !(spacing > 0.0)) {
    throw std::invalid_argument(
        fmt::format("StandSpec: spacing must be finite and positive, got {}", spacing));
  }
  if (!std::isfinite(scale_min) || !std::isfinite(scale_max) || !(scale_min > 0.0) || scale_min > scale_max) {
    throw std::invalid_argument(
        fmt::format("StandSpec: scales need 0 < min <= max, got min {} max {}", scale_min, scale_max));
  }
  if (species < 0) throw std::invalid_argument(fmt::format("StandSpec: species index {} < 0", species));
  const Eigen::Vector2d extent = max - min;
  const double most = (extent.x() / spacing + 1.0) * (extent.y() / spacing + 1.0) * 2.0;
  if (most > double(kMaxTreesPerStand)) {
    throw std::invalid_argument(
        fmt::format("StandSpec: a {:.0f} x {:.0f} m region at spacing {} m would hold up to {:.0f} trees, "
                    "more than {}; is "
                    "the spacing in metres?",
                    extent.x(), extent.y(), spacing, most, kMaxTreesPerStand));
  }
}

std::vector<PlacedTree> place_stand(const StandSpec& stand) {
  stand.validate();
  UniformSource random(stand.seed);
  const std::vector<Eigen::Vector2d> points =
      stand.layout == StandLayout::grid ? grid_positions(stand) : poisson_positions(stand, random);
  std::vector<PlacedTree> trees;
  trees.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    PlacedTree tree;
    tree.species = stand.species;
    tree.position = p;
    tree.yaw_rad = 2.0 * std::numbers::pi * random.next();
    tree.scale = random.between(stand.scale_min, stand.scale_max);
    trees.push_back(tree);
  }
  return trees;
}

}  // namespace fw::trees
