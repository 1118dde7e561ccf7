// ParaView's parallel formats (docs/parallel.md, "Output"): a frame written over MPI ranks is one piece
// per rank (.vti, .vtp) and one summary file (.pvti, .pvtp) that declares the pieces' arrays and lists them.
// The .pvd collections list the summaries, so ParaView opens a run over ranks as it opens one from one
// process.
//
//   fw::io::VtkArrays arrays = fw::io::describe_arrays(image);   // the arrays every piece has
//   fw::io::write_pvti("out/wind/wind_000003.pvti", arrays, origin, h, {0, 64, 0, 32, 0, 16},
//                      {{{0, 32, 0, 32, 0, 16}, "wind_000003_0000.vti"}, {{32, 64, 0, 32, 0, 16}, ...}});
//   fw::io::write_pvtp("out/trees/trees_000003.pvtp", arrays, {"trees_000003_0000.vtp", ...});
//
// Summaries are written through AtomicFile. A piece's Source is relative to the summary's folder. Pieces
// of image data share the points on their common faces (VTK's extents are point extents), and GhostLevel is
// 0: a piece holds only its rank's own cells.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

class vtkDataSet;

namespace fw::io {

/// A data array as a summary declares it: its name, VTK XML type ("Float32", "UInt8", "Int32", ...) and
/// number of components.
struct VtkArrayDeclaration {
  std::string name, type;
  int components = 1;
};

/// The arrays of a piece: point and cell data (and the point coordinates' type, for poly data), with the
/// active vectors' names (empty: none).
struct VtkArrays {
  std::vector<VtkArrayDeclaration> point_data, cell_data;
  std::string points_type = "Float32";
  std::string point_vectors, cell_vectors;
};

/// The arrays of `piece` (a vtkImageData or vtkPolyData about to be written). Throws std::invalid_argument
/// for an array of a type the XML format has no name for.
VtkArrays describe_arrays(vtkDataSet* piece);

/// A .pvti: image data of `whole_extent` (point indices i0 i1 j0 j1 k0 k1) at `origin` with spacing h,
/// made of `pieces` (each its point extent and its file). Throws std::runtime_error naming the path when it
/// cannot be written (no temporary is left behind).
void write_pvti(const std::filesystem::path& path, const VtkArrays& arrays,
                const std::array<double, 3>& origin, double h, const std::array<int, 6>& whole_extent,
                const std::vector<std::pair<std::array<int, 6>, std::string>>& pieces);

/// A .pvtp: poly data made of the pieces `sources`. Throws as write_pvti.
void write_pvtp(const std::filesystem::path& path, const VtkArrays& arrays,
                const std::vector<std::string>& sources);

/// The file name of rank `rank`'s piece of frame `index`: "<stem>_NNNNNN_RRRR.<extension>", beside the
/// frame's summary.
std::string piece_file(const std::string& stem, int index, int rank, const std::string& extension);
/// Every rank's piece_file of frame `index`, in rank order: a summary's sources.
std::vector<std::string> piece_files(const std::string& stem, int index, int ranks,
                                     const std::string& extension);

}  // namespace fw::io
