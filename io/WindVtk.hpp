// VTK XML ImageData (.vti) writer for one frame of the wind grid, for viewing in ParaView.
//
//   fw::io::WindFrame frame = fw::io::make_wind_frame(spec, vel, pressure, solid, canopy, t, step);
//   fw::io::write_wind_vti("out/wind/wind_000012.vti", frame, {"velocity", "speed", "solid"});
//
// ParaView: open wind.pvd (see PvdCollection.hpp) or a single .vti, Apply; colour by a cell array, or
// Filters > Cell Data to Point Data then Stream Tracer / Glyph on "velocity" for streamlines and arrows.
//
// Layout: one vtkImageData whose CELLS are the grid's cells: origin = the domain's minimum corner (m),
// spacing h (m) on all axes, point extent 0..nx x 0..ny x 0..nz. Cell arrays (x-fastest, VTK's own order):
//   velocity        float32 x 3, m/s (cell-centred: mean of the two faces)       [the active vectors]
//   pressure        float32, kinematic pressure p/rho, m^2/s^2
//   speed           float32, |velocity|, m/s
//   vorticity       float32 x 3, 1/s (see wind_vorticity)
//   solid           uint8, 1 in solid cells, 0 in fluid
//   canopy_density  float32, frontal area density a, 1/m
// Field data: "TimeValue" (float64, 1 tuple, s), which ParaView uses as the dataset's time; with a site,
// site_origin, site_epsg and site_crs (io/SiteVtk.hpp).
// Files are written by io/VtkXml (binary appended data, LZ4, 64-bit headers, through AtomicFile).
#pragma once

#include "io/ParallelVtk.hpp"
#include "io/WindFrame.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace fw::io {

/// The field names write_wind_vti understands, in the order arrays are written.
const std::vector<std::string>& wind_field_names();

/// Over MPI ranks, the cells of a frame that one rank writes: `count` cells along x and y from `first`
/// (indices into the frame's cells), which are the domain's cells from `domain_first` on. The derived arrays
/// (speed, vorticity) are computed over the whole frame before the piece is cut, so that a piece's cells at
/// its border see the frame's cells beyond it (the rank's halo) as one process's cells see their
/// neighbours. Its extent is then the domain's, at the domain's origin (the frame's).
struct WindPiece {
  std::array<int, 2> first{0, 0}, count{0, 0}, domain_first{0, 0};
};

/// Writes the requested cell arrays of `frame` (by name, see above; duplicates are ignored, and pressure,
/// solid or canopy_density are skipped when the frame holds none). An empty `fields` writes the geometry
/// and TimeValue only. Throws std::invalid_argument("write_wind_vti: ...") for an unknown field name (listing
/// the choices) or an inconsistent frame, and std::runtime_error naming the path if the folder does not exist
/// or the file cannot be written; no partial file or temporary is left behind.
/// With a piece, only its cells (a .pvti then lists the pieces, io/ParallelVtk.hpp); `declared`, when
/// given, receives the arrays written.
void write_wind_vti(const std::filesystem::path& path, const WindFrame& frame,
                    const std::vector<std::string>& fields, const WindPiece* piece = nullptr,
                    VtkArrays* declared = nullptr);

}  // namespace fw::io
