#include "tests/support/SmallSpecies.hpp"

#include <vector>

#include "trees/TreeGenerator.hpp"

namespace fw::test {

trees::SpeciesBasis small_species(const std::string& preset, double height, std::uint64_t seed,
                                  int iterations, int modes, int samples, double leaf_area_index) {
  trees::GeneratorSettings g;
  g.preset = preset;
  g.height = height;
  g.seed = seed;
  g.iterations = iterations;
  g.max_element_length = height;  // one element per drawn segment: a few dozen nodes
  trees::SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.modal.damping = trees::Damping::modal_ratio(0.03);
  settings.wind.samples = samples;
  settings.wind.leaf_area_index = leaf_area_index;
  return trees::SpeciesBasis::compute(trees::generate_tree(g), settings);
}

trees::Skeleton asymmetric_skeleton() {
  std::vector<trees::SkeletonNode> nodes = {
      {-1, {0.0, 0.0, 0.0}, 0.12}, {0, {0.0, 0.0, 1.0}, 0.10},  {1, {0.0, 0.0, 2.0}, 0.08},
      {2, {0.0, 0.0, 3.0}, 0.06},  {3, {0.0, 0.0, 4.0}, 0.04},  {2, {1.0, 0.3, 3.0}, 0.04},
      {5, {1.8, 0.5, 3.6}, 0.02},  {3, {-0.6, 0.8, 3.8}, 0.03}, {7, {-1.0, 1.4, 4.3}, 0.02},
      {4, {0.2, -0.5, 4.8}, 0.02}, {1, {0.5, -0.7, 1.6}, 0.03}};
  return trees::Skeleton::from_nodes(std::move(nodes));
}

trees::Skeleton small_broadleaf() {
  trees::GeneratorSettings g;
  g.preset = "broadleaf";
  g.height = 6.0;
  g.seed = 1;
  g.iterations = 5;
  g.max_element_length = 0.3;
  return trees::generate_tree(g);
}

}  // namespace fw::test
