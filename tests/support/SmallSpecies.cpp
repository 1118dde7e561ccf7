#include "tests/support/SmallSpecies.hpp"

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

}  // namespace fw::test
