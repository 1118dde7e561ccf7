// The top of the trees' displacement colour scale, one rule for `forestwind render` (viz/FrameRender) and
// view.py (viz/ViewScriptWriter writes it in), so that a picture and the ParaView view of a frame colour its
// trees alike: the 99th percentile of the frame's nodal displacements, so that a few whipping tips do not
// leave every other branch at the dark end of the map (a storm's largest displacement is ~7 m, most of the
// forest moves a fraction of that).
//
//   double top = fw::viz::displacement_scale(trees.displacement);            // |d| per node, m (RunFolder)
//   double top = fw::viz::displacement_scale(fw::viz::displacement_magnitudes(frame.displacement));
#pragma once

#include <span>
#include <vector>

namespace fw::viz {

/// The quantile of the nodes' displacements at the top of the scale.
inline constexpr double kDisplacementQuantile = 0.99;

/// The kDisplacementQuantile quantile of `magnitudes` (m), by nearest rank (the ceil(0.99 n)-th smallest);
/// 0 for none.
double displacement_scale(std::vector<double> magnitudes);

/// |d| per node, m, from 3 floats a node (x, y, z, as io::OutputFrame::displacement and the trees' .vtp
/// files hold them), in double: the numbers viz::RunFolder reads back from the files.
std::vector<double> displacement_magnitudes(std::span<const float> xyz);

}  // namespace fw::viz
