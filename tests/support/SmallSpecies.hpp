// A small generated species for tests: a few dozen nodes (one element per drawn segment), its modes and wind
// basis computed in milliseconds.
#pragma once

#include <cstdint>
#include <string>

#include "trees/Skeleton.hpp"
#include "trees/SpeciesBasis.hpp"

namespace fw::test {

/// preset: "broadleaf" or "conifer"; height in m; L-system iterations; modes and wind samples; LAI of the
/// foliage (0: none); modal damping ratio 0.03.
trees::SpeciesBasis small_species(const std::string& preset, double height, std::uint64_t seed,
                                  int iterations, int modes, int samples, double leaf_area_index = 0.0);

/// An asymmetric 11-node tree, 4.8 m tall: a trunk along +z and four side branches.
trees::Skeleton asymmetric_skeleton();

/// A generated broadleaf: 6 m, seed 1, 5 iterations, elements of at most 0.3 m (138 nodes).
trees::Skeleton small_broadleaf();

}  // namespace fw::test
