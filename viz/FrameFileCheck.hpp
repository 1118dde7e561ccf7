// Checks a frame file of a run folder before VTK's XML readers see it, so that a damaged or hostile file is
// refused with its name instead of crashing `render` or making it allocate what a corrupt number claims.
//
//   fw::viz::check_frame_file("out/storm/wind/wind_000012.vti");   // throws FrameReadError naming it
//
// VTK 9.1's XML readers trust their input. They allocate what the XML's counts (points, cells, extents,
// components) and the appended blocks' headers claim, and they read a block that a header does not list
// (tests/fuzz/run_folder_fuzz; docs/fuzzing.md). So this check:
//
// - accepts only the encoding forestwind writes (io/VtkXml): format version 1.0, little-endian, UInt64 block
//   headers, every data array appended as raw bytes, compressed with LZ4 or zlib or not at all;
// - requires each array's size, tuples x components x value bytes, to follow from its piece's counts (a
//   point array has one tuple per point, a cell array one per cell, a field array the tuples it declares, a
//   cell array's connectivity as many entries as its last offset, decoded from the file) and to equal what
//   its block header expands to;
// - requires every block header to fit the bytes left in the file, and what it expands to to be within what
//   LZ4 or zlib can give from the bytes stored (256 times);
// - requires one piece a file (as forestwind writes), and an image's piece to hold its whole extent, since
//   VTK sizes its arrays by the first piece's over the whole extent;
// - checks a .pvti or .pvtp summary's pieces the same way, each against the extent the summary gives it and
//   holding every array the summary declares with its type and components (VTK allocates those over the
//   whole dataset), the pieces covering the whole extent.
//
// What VTK then reads is bounded by the file's size. Values themselves (a cell's point ids) are not checked
// here: the readers of viz/RunFolder check what they use.
#pragma once

#include <filesystem>
#include <stdexcept>

namespace fw::viz {

/// A frame file that is missing, damaged or not in forestwind's encoding: bad input, so `render` exits 2 with
/// its message, "render: FILE: what is wrong".
class FrameReadError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Throws FrameReadError "render: PATH: what is wrong" when `path` is not a VTK XML image or poly data
/// file (or a parallel summary of them) in forestwind's encoding whose sizes all agree; returns otherwise.
void check_frame_file(const std::filesystem::path& path);

}  // namespace fw::viz
