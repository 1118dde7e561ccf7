#include "host/app/StandingCanopy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "trees/CanopyDrag.hpp"

namespace fw::host {

StandingCanopy::StandingCanopy(const fluid::GridSpec& spec, const trees::Forest& forest,
                               std::vector<float> drag_density)
    : spec_(spec),
      forest_(forest),
      drag_density_(std::move(drag_density)),
      fallen_(std::size_t(forest.instance_count()), false),
      canopy_(forest) {
  if (drag_density_.size() != spec_.cell_count())
    throw std::invalid_argument(fmt::format("StandingCanopy: {} cells of drag for a grid of {}",
                                            drag_density_.size(), spec_.cell_count()));
  for (int k = 0; k < forest.instance_count(); ++k) boxes_.push_back(trees::instance_cells(spec_, forest, k));
}

bool StandingCanopy::fell(const std::vector<int>& fallen) {
  std::vector<fluid::CellBox> cleared;
  for (const int k : fallen) {
    if (fallen_.at(std::size_t(k))) continue;
    fallen_[std::size_t(k)] = true;
    if (boxes_[std::size_t(k)].cell_count() > 0) cleared.push_back(boxes_[std::size_t(k)]);
  }
  if (cleared.empty()) return false;
  // Every standing tree that reaches a cleared cell, whole (a tree adds nothing to cells outside its box),
  // on a field over the box that holds them all; only the cleared cells are taken from it.
  const auto reaches_cleared = [&](const fluid::CellBox& box) {
    for (const fluid::CellBox& c : cleared)
      if (box.overlaps(c)) return true;
    return false;
  };
  std::vector<int> neighbours;
  fluid::CellBox reach = cleared.front();
  const auto extend = [&reach](const fluid::CellBox& box) {
    for (std::size_t a = 0; a < 3; ++a) {
      const int last = std::max(reach.first[a] + reach.count[a], box.first[a] + box.count[a]);
      reach.first[a] = std::min(reach.first[a], box.first[a]);
      reach.count[a] = last - reach.first[a];
    }
  };
  for (const fluid::CellBox& c : cleared) extend(c);
  for (int k = 0; k < forest_.instance_count(); ++k) {
    if (fallen_[std::size_t(k)]) continue;
    const fluid::CellBox& box = boxes_[std::size_t(k)];
    if (!reaches_cleared(box)) continue;
    neighbours.push_back(k);
    extend(box);
  }
  fluid::CanopyField field(spec_, reach);
  for (const int k : neighbours) field.add_elements(canopy_.elements(k));
  for (const fluid::CellBox& c : cleared)
    for (int z = c.first[2]; z < c.first[2] + c.count[2]; ++z)
      for (int y = c.first[1]; y < c.first[1] + c.count[1]; ++y)
        for (int x = c.first[0]; x < c.first[0] + c.count[0]; ++x) {
          const std::size_t cell =
              std::size_t(x) +
              std::size_t(spec_.nx) * (std::size_t(y) + std::size_t(spec_.ny) * std::size_t(z));
          drag_density_[cell] = field.drag_density_at(x, y, z);
        }
  return true;
}

}  // namespace fw::host
