// The canopy drag of the trees still standing (docs/damage.md, "What follows a failure"): the plan's drag
// density over the whole grid, with the cells the fallen trees reached recomputed from the standing trees
// alone, so that the stand opens where trees fall and the wind finds the gap at once.
//
//   fw::host::StandingCanopy canopy(spec, forest, plan.coupling.drag_density);
//   if (canopy.fell({12, 40}))                          // ids into `forest` (Forest::id)
//     wind.set_canopy(canopy.drag_density(), law);     // the whole grid, as the plan gave it
//
// Each recomputed cell is the sum over the standing trees that reach it, in instance order, in double, as
// the plan's own field: the field is a function of which trees stand, whatever the order they fell in, so a
// resumed run that removes every fallen tree at once gets the same bits as the run that removed them one
// step at a time, and every rank the same as one process.
#pragma once

#include <vector>

#include "fluid/CanopyField.hpp"
#include "fluid/GridSpec.hpp"
#include "trees/CanopyDrag.hpp"
#include "trees/Forest.hpp"

namespace fw::host {

class StandingCanopy {
 public:
  /// forest: the whole forest (every rank's), which must outlive this; drag_density: the plan's field of
  /// it, k per cell of the whole grid (1/m; CouplingSettings::drag_density).
  StandingCanopy(const fluid::GridSpec& spec, const trees::Forest& forest, std::vector<float> drag_density);

  /// Removes the trees `fallen` (instance indices of the whole forest; those already removed are
  /// skipped) and recomputes the cells they reached. Returns whether any cell changed.
  bool fell(const std::vector<int>& fallen);
  const std::vector<float>& drag_density() const { return drag_density_; }
  bool standing(int instance) const { return !fallen_.at(std::size_t(instance)); }

 private:
  fluid::GridSpec spec_;
  const trees::Forest& forest_;
  std::vector<float> drag_density_;
  std::vector<bool> fallen_;
  std::vector<fluid::CellBox> boxes_;  // the cells each tree's drag reaches (trees::instance_cells)
  // Each species' elements once; a neighbour's are theirs moved into place, with no crown hull of its own.
  trees::ForestCanopy canopy_;
};

}  // namespace fw::host
