// host/app/StandingCanopy: the canopy drag after trees fall is the field of the standing trees alone, bit for
// bit, whatever the order they fell in.
#include "host/app/StandingCanopy.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "fluid/CanopyField.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "trees/CanopyDrag.hpp"

using namespace fw;

namespace {

fluid::GridSpec canopy_grid() {
  fluid::GridSpec spec;
  spec.nx = 40;
  spec.ny = 30;
  spec.nz = 12;
  spec.h = 1.0;
  return spec;
}

// 30 overlapping crowns of two species, 4 m apart.
trees::Forest crowded_forest() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 1, 5, 4, 2, 3.0),
                                              test::small_species("conifer", 7.0, 2, 4, 4, 2, 3.0)};
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 30; ++k)
    trees.push_back({k % 2, {6.0 + 4.0 * (k % 6), 5.0 + 4.0 * (k / 6), 0.0}, 0.7 * k, 0.9 + 0.01 * k});
  return trees::Forest(std::move(species), std::move(trees));
}

// The field of the trees not in `fallen`, rasterised from scratch as the plan does.
std::vector<float> standing_field(const fluid::GridSpec& spec, const trees::Forest& forest,
                                  const std::vector<int>& fallen) {
  fluid::CanopyField field(spec);
  for (int k = 0; k < forest.instance_count(); ++k)
    if (std::find(fallen.begin(), fallen.end(), k) == fallen.end()) trees::ForestCanopy(forest).add(field, k);
  return field.drag_density();
}

}  // namespace

TEST_CASE("StandingCanopy: the field after trees fall is the standing trees' own, in any order of falling",
          "[trees]") {
  const fluid::GridSpec spec = canopy_grid();
  const trees::Forest forest = crowded_forest();
  const std::vector<float> whole = standing_field(spec, forest, {});
  const std::vector<int> fallen = {3, 14, 15, 27, 8};

  host::StandingCanopy one_by_one(spec, forest, whole);
  for (const int k : fallen) CHECK(one_by_one.fell({k}));
  host::StandingCanopy at_once(spec, forest, whole);
  std::vector<int> shuffled = fallen;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
  CHECK(at_once.fell(shuffled));
  CHECK_FALSE(at_once.fell({14}));  // already down: nothing changes

  const std::vector<float> expected = standing_field(spec, forest, fallen);
  CHECK(one_by_one.drag_density() == expected);  // bit for bit
  CHECK(at_once.drag_density() == expected);
  CHECK_FALSE(one_by_one.standing(27));
  CHECK(one_by_one.standing(26));
  // The stand did open: less drag over the grid.
  double before = 0.0, after = 0.0;
  for (std::size_t c = 0; c < whole.size(); ++c) before += whole[c], after += expected[c];
  CHECK(after < before);
}
