// VTK XML PolyData (.vtp) writer for the leaves of one output frame (docs/leaves.md), for ParaView.
//
//   fw::io::LeafFrame leaves = ...;                        // OutputFrame::leaves
//   fw::io::write_leaves_vtp("out/leaves/leaves_000025.vtp", /*time=*/12.5, leaves);
//
// ParaView: open leaves.pvd (see PvdCollection.hpp), Apply; colour by "state" or "tree_id". To draw every
// leaf as a square blade of its real size facing its normal: Filters > Glyph with
//   Glyph Type: Box, X Length 0.02, Y Length 1, Z Length 1 (a thin plate across the glyph's x axis), or
//     2D Glyph Square (Filled) with Glyph Transform > Rotate 0 90 0 (the square turned into the y-z plane),
//   Orientation Array: normal, Scale Array: size, Scale Factor: 1, Glyph Mode: All Points.
// The Glyph filter turns a glyph's x axis onto the orientation vector, so the blade's plane must be the
// glyph's y-z plane; a square left in its default x-y plane would be drawn edge-on. Both glyphs are 1 wide,
// so scale factor 1 with the scale array "size" (the blade side) gives each blade its real side.
//
// Layout: a single vtkPolyData, one point per written leaf in LeafFrame order. Points (float32, m, world
// frame) are the blade centres. Cells: one vertex per point (point k is vertex k), so that ParaView renders
// the points and filters that need cells work. Point arrays:
//   normal   float32 x 3, the blade's unit normal   [the active normals]
//   state    uint8, trees::LeafState: 0 attached, 1 flying, 2 landed (3 exited, not written by a run)
//   tree_id  int32, instance index of the tree the leaf grew on
//   size     float32, m, the blade side l = sqrt(area)
// Field data: "TimeValue" (float64, 1 tuple, s), as the trees' files.
// Files are binary (appended raw data, LZ4, 64-bit headers; io/VtkXml) and written through AtomicFile.
#pragma once

#include <filesystem>

#include "io/ParallelVtk.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

/// Checks that every array of `leaves` has one entry per position, that positions, normals and sizes are
/// finite and states are trees::LeafState values. Throws std::invalid_argument("FUNCTION: leaves: ...")
/// naming the array (and the leaf). Shared by the leaves' writers (this file, io/VdbWriter).
void validate_leaf_frame(const char* function, const LeafFrame& leaves);

/// Writes `leaves` at `time` (s) as described above. An empty LeafFrame gives a valid file without points.
/// Throws std::invalid_argument("write_leaves_vtp: leaves: ...") as validate_leaf_frame, and
/// std::runtime_error naming the path when the folder does not exist or the file cannot be written (no
/// partial file or temporary is left behind).
void write_leaves_vtp(const std::filesystem::path& path, double time, const LeafFrame& leaves);

/// The arrays every leaves file has, for the .pvtp that lists a frame's pieces over ranks.
VtkArrays leaves_vtp_arrays();

}  // namespace fw::io
