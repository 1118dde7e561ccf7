// compare_runs A B: whether two run folders hold the same frames, bit for bit, whatever files they are in (a
// run in one process writes .vti and .vtp, one over MPI ranks .pvti and .pvtp pieces; docs/parallel.md).
// Every frame of A's wind.pvd and trees.pvd against B's: the same times, every cell array of the wind equal
// value for value, and the trees' points with their radius and displacement equal as sets (pieces list the
// trees in another order), and the same for the leaves' points with their state and size. Exit 0 when equal;
// 1 with the first difference; 2 when a folder does not read.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <exception>
#include <iostream>
#include <vector>

#include "viz/RunFolder.hpp"

namespace {

using Point = std::array<double, 5>;  // x, y, z, radius, |displacement|

std::vector<Point> sorted_points(const fw::viz::TreeLines& trees) {
  std::vector<Point> points;
  for (std::size_t n = 0; n < trees.points.size(); ++n)
    points.push_back(
        {trees.points[n][0], trees.points[n][1], trees.points[n][2], trees.radius[n], trees.displacement[n]});
  std::sort(points.begin(), points.end());
  return points;
}

using LeafPoint = std::array<double, 5>;  // x, y, z, state, size

std::vector<LeafPoint> sorted_points(const fw::viz::LeafPoints& leaves) {
  std::vector<LeafPoint> points;
  for (std::size_t n = 0; n < leaves.position.size(); ++n)
    points.push_back({leaves.position[n][0], leaves.position[n][1], leaves.position[n][2],
                      double(leaves.state[n]), leaves.size[n]});
  std::sort(points.begin(), points.end());
  return points;
}

// The first difference between two point sets of `what`, or empty.
template <typename P>
std::string point_difference(const char* what, const std::vector<P>& x, const std::vector<P>& y) {
  if (x.size() != y.size()) return fmt::format("{} {} points against {}", x.size(), what, y.size());
  const auto at = std::mismatch(x.begin(), x.end(), y.begin());
  if (at.first == x.end()) return "";
  return fmt::format("{} point {} of {} (sorted): ({}) against ({})", what, at.first - x.begin(), x.size(),
                     fmt::join(*at.first, ", "), fmt::join(*at.second, ", "));
}

// The first difference between two frames, or empty.
std::string difference(const fw::viz::FrameData& a, const fw::viz::FrameData& b) {
  if (a.time != b.time) return fmt::format("times {} and {}", a.time, b.time);
  if (a.wind.has_value() != b.wind.has_value()) return "one has wind, the other not";
  if (a.wind) {
    if (a.wind->cells != b.wind->cells || a.wind->origin != b.wind->origin ||
        a.wind->cell_size != b.wind->cell_size)
      return "the wind grids differ in shape or place";
    if (a.wind->solid != b.wind->solid) return "solid differs";
    if (a.wind->arrays.size() != b.wind->arrays.size()) return "the wind has other arrays";
    for (std::size_t n = 0; n < a.wind->arrays.size(); ++n) {
      const auto& x = a.wind->arrays[n];
      const auto& y = b.wind->arrays[n];
      if (x.name != y.name) return fmt::format("wind arrays {} and {}", x.name, y.name);
      const auto at = std::mismatch(x.values.begin(), x.values.end(), y.values.begin(), y.values.end());
      if (at.first != x.values.end() || at.second != y.values.end())
        return fmt::format("wind {} differs at value {}: {} against {}", x.name, at.first - x.values.begin(),
                           at.first != x.values.end() ? *at.first : 0.0f,
                           at.second != y.values.end() ? *at.second : 0.0f);
    }
  }
  if (a.trees.has_value() != b.trees.has_value()) return "one has trees, the other not";
  if (a.trees) {
    const std::string what = point_difference("tree", sorted_points(*a.trees), sorted_points(*b.trees));
    if (!what.empty()) return what;
  }
  if (a.leaves.has_value() != b.leaves.has_value()) return "one has leaves, the other not";
  if (a.leaves) return point_difference("leaf", sorted_points(*a.leaves), sorted_points(*b.leaves));
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: compare_runs FOLDER_A FOLDER_B\n";
    return 2;
  }
  try {
    const fw::viz::RunFolder a(argv[1]), b(argv[2]);
    if (a.frames().size() != b.frames().size()) {
      std::cout << fmt::format("{} frames against {}\n", a.frames().size(), b.frames().size());
      return 1;
    }
    for (std::size_t f = 0; f < a.frames().size(); ++f) {
      const std::string what = difference(a.load(a.frames()[f]), b.load(b.frames()[f]));
      if (!what.empty()) {
        std::cout << fmt::format("frame {}: {}\n", f, what);
        return 1;
      }
    }
    std::cout << fmt::format("{} frames equal\n", a.frames().size());
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "compare_runs: " << e.what() << "\n";
    return 2;
  }
}
