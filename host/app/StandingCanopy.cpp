#include "host/app/StandingCanopy.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "fluid/CanopyField.hpp"
#include "trees/CanopyDrag.hpp"

namespace fw::host {

StandingCanopy::StandingCanopy(const fluid::GridSpec& spec, const trees::Forest& forest,
                               std::vector<float> drag_density)
    : spec_(spec),
      forest_(forest),
      drag_density_(std::move(drag_density)),
      fallen_(std::size_t(forest.instance_count()), false) {
  if (drag_density_.size() != spec_.cell_count())
    throw std::invalid_argument(fmt::format("StandingCanopy: {} cells of drag for a grid of {}",
                                            drag_density_.size(), spec_.cell_count()));
}

bool StandingCanopy::fell(const std::vector<int>& fallen) {
  std::vector<fluid::CellBox> cleared;
  for (const int k : fallen) {
    if (fallen_.at(std::size_t(k))) continue;
    fallen_[std::size_t(k)] = true;
    const fluid::CellBox box = trees::instance_cells(spec_, forest_, k);
    if (box.cell_count() > 0) cleared.push_back(box);
  }
  if (cleared.empty()) return false;
  // Every standing tree that reaches a cleared cell, whole (a tree adds nothing to cells outside its box),
  // on a field of the whole grid; only the cleared cells are taken from it.
  fluid::CanopyField field(spec_);
  const auto reaches_cleared = [&](const fluid::CellBox& box) {
    for (const fluid::CellBox& c : cleared)
      if (box.overlaps(c)) return true;
    return false;
  };
  for (int k = 0; k < forest_.instance_count(); ++k)
    if (!fallen_[std::size_t(k)] && reaches_cleared(trees::instance_cells(spec_, forest_, k)))
      trees::add_to_canopy(field, forest_, k);
  const std::vector<float> standing = field.drag_density();
  for (const fluid::CellBox& c : cleared)
    for (int z = c.first[2]; z < c.first[2] + c.count[2]; ++z)
      for (int y = c.first[1]; y < c.first[1] + c.count[1]; ++y)
        for (int x = c.first[0]; x < c.first[0] + c.count[0]; ++x) {
          const std::size_t cell =
              std::size_t(x) +
              std::size_t(spec_.nx) * (std::size_t(y) + std::size_t(spec_.ny) * std::size_t(z));
          drag_density_[cell] = standing[cell];
        }
  return true;
}

}  // namespace fw::host
