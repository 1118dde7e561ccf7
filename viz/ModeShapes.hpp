// `tree modes ... -o DIR` draws modes.png: the first vibration modes of a tree side by side, each exaggerated
// over the tree at rest, with its frequency.
//
//   fw::viz::Canvas picture = fw::viz::draw_mode_shapes(skeleton, shapes, "broadleaf.tree");
//   picture.write_png("out/modes/modes.png");
//
// Each panel looks at the tree across the mode's motion: in the x-z plane when the mode moves the nodes more
// along x than y, else in the y-z plane (a torsion mode still shows the direction its branches swing in). The
// rest shape is light grey; the mode shape is rest + s phi, coloured by |phi| on the "displacement" map, s
// chosen per mode so that its largest nodal displacement is kExaggeration of the tree's height (a mode's
// amplitude is arbitrary: M-normalised).
#pragma once

#include <string>
#include <vector>

#include "io/SkeletonVtk.hpp"
#include "trees/Skeleton.hpp"
#include "viz/Canvas.hpp"

namespace fw::viz {

/// The largest displacement of a drawn mode, as a fraction of the tree's height.
constexpr double kExaggeration = 0.15;
/// Modes drawn at most.
constexpr int kModesDrawn = 6;

/// Throws std::invalid_argument("draw_mode_shapes: ...") when there are no modes or a mode's displacement
/// does not have one row per node.
Canvas draw_mode_shapes(const trees::Skeleton& skeleton, const std::vector<io::ModeShape>& modes,
                        const std::string& title);

}  // namespace fw::viz
