// Procedural tree skeletons from stochastic bracketed L-systems (Oliapuram & Kumar 2010, section 1.4;
// Prusinkiewicz & Lindenmayer 1990), one grammar per preset.
//
//   fw::trees::GeneratorSettings settings;
//   settings.preset = "conifer";
//   settings.height = 18.0;   // m
//   settings.seed = 3;
//   fw::trees::Skeleton pine = fw::trees::generate_tree(settings);   // pine.height() == 18 m
//
//   settings.max_element_length = 0.05;   // m: finer elements, more nodes (the same tree shape)
//
// Presets (default height, rewriting iterations):
//   broadleaf (15 m, 8)  decurrent: a bare trunk that forks into 2-4 scaffold limbs, which fork again; a
//                        spreading, rounded crown held up by a weak upward tropism.
//   conifer   (20 m, 14) excurrent: one straight vertical leader with a whorl of 4-5 near-horizontal branches
//                        per iteration; a branch grows one internode per iteration, so the lower (older)
//                        branches are longer and the crown is a cone. Side shoots, slight gravitational
//                        droop.
//   palm      (12 m, 12) one unbranched, slightly curved trunk; a crown of 16 fronds at its top that start
//                        at 25-80 degrees from the trunk axis and arch down under gravity.
//   weeping   (10 m, 7)  a short trunk that forks into 3-4 scaffold limbs arching over under a weak gravity
//                        tropism; they carry long whips under a strong one, so that the whips hang below the
//                        points they grow from.
// The iteration count changes the tree's structure (more, shorter branches, and with the pipe model a
// thicker trunk); max_element_length only subdivides the same branches, so it is the knob for a node count:
// broadleaf, seed 1, 15 m: 0.33 m -> 1,002 nodes, 0.085 m -> 3,354, 0.027 m -> 10,159, 0.009 m -> 30,110.
//
// Steps: derive the preset's word with `seed` and `iterations`; draw it with the turtle (LSystem.hpp; trunk
// along +z from the origin, nothing grows below z = 0); scale uniformly so that Skeleton::height() equals
// `height` (to rounding); split every drawn segment into ceil(length / max_element_length) equal elements
// (node 0 is the root at the origin; every node's parent has a smaller index); then set node radii:
//   pipe model (broadleaf, conifer, weeping): a tip node has radius r_tip = tip_fraction * height
//     (0.0007 H for broadleaf and weeping, 0.0005 H for conifer), and every other node has
//     r^2 = sum over its children of r_child^2, so a branch's cross-section is conserved through each fork.
//     Radii are constant between forks.
//   palm (opts out of the pipe model): trunk nodes have r = r_trunk * (1 + 0.15 (1 - s / S)), with
//     r_trunk = 0.012 H, s the arc length from the root and S the trunk length (a slightly flared base,
//     nearly constant); frond nodes taper linearly from 0.15 r_trunk at the frond base to 0.3 of that at the
//     tip.
// The FEM model gives each element the mean of its two node radii.
//
// Units: metres. Determinism: the result depends only on the settings (std::mt19937_64 bits mapped to
// [0, 1) by the L-system; no standard library distributions).
#pragma once

#include "trees/Skeleton.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fw::trees {

struct GeneratorSettings {
  std::string preset = "broadleaf";  ///< broadleaf | conifer | palm | weeping
  double height = 0.0;               ///< m, total tree height; 0 = the preset's default
  std::uint64_t seed = 1;
  double max_element_length = 0.0;  ///< m; 0 = the preset's default (height / 40)
  int iterations = 0;               ///< L-system rewriting iterations; 0 = the preset's default
};

/// Builds the skeleton described in the header comment. Throws std::invalid_argument("TreeGenerator: ...")
/// for an unknown preset (the message lists the valid names), a height or max_element_length that is
/// negative or non-finite, iterations < 0, or settings that would give more than kMaxGeneratedNodes nodes.
Skeleton generate_tree(const GeneratorSettings& settings);

/// The tree of `settings` refined to about `target_nodes` nodes: bisects max_element_length (log scale,
/// 1 mm to the height) and returns the closest node count found (within 0.5% when the preset's structure
/// allows; a tree cannot get coarser than one element per L-system segment). The chosen length is stored in
/// *element_length when given. Throws what generate_tree throws, and std::invalid_argument for target < 2.
Skeleton generate_tree_with_nodes(GeneratorSettings settings, int target_nodes,
                                  double* element_length = nullptr);

/// The valid preset names, in a fixed order.
std::vector<std::string> preset_names();

/// Largest tree generate_tree builds before it refuses (a guard against runaway settings).
inline constexpr int kMaxGeneratedNodes = 2'000'000;

}  // namespace fw::trees
