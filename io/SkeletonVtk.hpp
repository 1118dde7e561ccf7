// VTK XML PolyData (.vtp) writers for a tree skeleton and its vibration modes, for viewing in ParaView.
//
//   auto skeleton = fw::trees::Skeleton::from_nodes(std::move(nodes));
//   fw::io::write_skeleton_vtp("out/skeleton.vtp", skeleton);
//   std::vector<fw::io::ModeShape> modes = ...;   // one per mode: frequency, damping, n x 3 nodal
//   translations fw::io::write_modes_vtp("out/modes.vtp", skeleton, modes);   // mode arrays scaled to 10% of
//   the height
//
// Viewing a mode in ParaView:
//   1. Open modes.vtp, Apply. Filters > Warp By Vector; Vectors: mode_03; Scale Factor 1 shows the mode with
//   its
//      largest nodal displacement equal to the display amplitude. Tubes (radius array "radius") look nicer.
//   2. To animate, vary the Warp By Vector Scale Factor between -1 and 1: in the Animation View add a track
//   for
//      WarpByVector1 > ScaleFactor with a Sinusoid keyframe, or from the Python shell:
//        w = FindSource('WarpByVector1')
//        for k in range(48): w.ScaleFactor = math.sin(2 * math.pi * k / 48); Render()
//   The mode's frequency and damping ratio are entry NN-1 of the field arrays frequencies_hz and
//   damping_ratios (Information panel, or Spreadsheet view > Field Data).
//
// Files are binary (appended raw data, LZ4, 64-bit headers; io/VtkXml) and written through AtomicFile: a
// temporary name in the same folder, renamed into place once complete, so no partial file is ever visible.
#pragma once

#include "trees/Skeleton.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace fw::io {

/// Writes the skeleton as VTK XML PolyData: one point per node (positions in m, float64), one 2-point line
/// cell per element (parent, child) in Skeleton::elements() order.
/// Point arrays: "radius" (m, float64), "node_id" (int32), "parent" (int32, -1 for the root).
/// Cell array: "element" (int32, the element index k of Skeleton::elements()).
/// Throws std::invalid_argument("write_skeleton_vtp: ...") for an empty (default-constructed) skeleton, and
/// std::runtime_error naming the path if the folder does not exist or the file cannot be written; in every
/// failure no file (neither the target nor a temporary) is left behind.
void write_skeleton_vtp(const std::filesystem::path& path, const trees::Skeleton& skeleton);

struct ModeShape {
  double frequency_hz = 0.0;   ///< natural frequency
  double damping_ratio = 0.0;  ///< zeta, dimensionless
  Eigen::MatrixX3d
      displacement;  ///< #nodes by 3, m: nodal translations of the M-normalised mode (root row 0)
};

/// Name of the point array of mode `index` (0-based) among `count` modes: "mode_01", "mode_02", ... with
/// two digits, or as many digits as `count` has when that is more (three digits from 100 modes on).
std::string mode_array_name(int index, int count);

/// The same geometry and arrays as write_skeleton_vtp plus one 3-component float64 point array per mode,
/// named by mode_array_name ("mode_01", ...). Each is the M-normalised shape times modal_scale, where
/// modal_scale = display_amplitude / (largest nodal |u| of the shape), so that its largest nodal displacement
/// magnitude is display_amplitude metres and Warp By Vector with scale factor 1 shows a visible deformation.
/// A zero mode (all displacements zero) gets modal_scale 0 and an all-zero array (no division by zero).
/// The first mode is also the active vectors array, so Warp By Vector picks it by default.
/// display_amplitude: metres; 0 selects 10% of skeleton.height(), or of the bounding box diagonal when the
/// height is 0 (a flat skeleton).
/// Field data (one value per mode, in mode order): "frequencies_hz", "damping_ratios", "modal_scale" (the
/// factor applied to each M-normalised shape, so the physical shape is mode_NN / modal_scale).
/// Throws std::invalid_argument("write_modes_vtp: ...") if a displacement does not have skeleton.size() rows,
/// holds a non-finite value, display_amplitude is negative or non-finite, or the skeleton is empty; and
/// std::runtime_error naming the path on write failures, as write_skeleton_vtp.
void write_modes_vtp(const std::filesystem::path& path, const trees::Skeleton& skeleton,
                     const std::vector<ModeShape>& modes, double display_amplitude = 0.0);

}  // namespace fw::io
