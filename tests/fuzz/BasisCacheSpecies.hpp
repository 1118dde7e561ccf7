// The one species of the basis cache fuzz target and of its seed (tests/fuzz/basis_cache_seed.cpp): a bent
// four-node stem with two modes and one wind sample, small so that its cache entry is a short seed.
#pragma once

#include <vector>

#include "trees/BasisCache.hpp"

namespace fw::fuzz {

inline trees::Skeleton cache_species_skeleton() {
  return trees::Skeleton::from_nodes(std::vector<trees::SkeletonNode>{{-1, {0.0, 0.0, 0.0}, 0.1},
                                                                      {0, {0.0, 0.0, 1.0}, 0.08},
                                                                      {1, {0.2, 0.0, 2.0}, 0.06},
                                                                      {2, {0.5, 0.1, 2.8}, 0.04}});
}

inline trees::SpeciesSettings cache_species_settings() {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 2;
  settings.wind.samples = 1;
  settings.wind.leaf_area_index = 1.0;  // foliage in the projections, as a leafy species stores them
  return settings;
}

}  // namespace fw::fuzz
