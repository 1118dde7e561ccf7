// OpenVDB (.vdb) writer for one frame of the wind grid, for Houdini, Blender and other VFX tools.
//
//   fw::io::WindFrame frame = fw::io::make_wind_frame(spec, vel, {}, solid, {}, t, step);
//   fw::io::write_wind_vdb("out/vdb/wind.0012.vdb", frame, /*vel=*/true, /*speed=*/true);
//   fw::io::write_wind_vdb("out/vdb/wind.0012.vdb", frame, true, true, &output_frame.leaves);  // + "leaves"
//
// Houdini: File SOP on out/vdb/wind.$F4.vdb; "vel" is a vector VDB usable directly as a velocity field.
// Blender: Add > Volume > Import OpenVDB (sequence detected from the frame numbers); shade by "speed".
//
// Layout:
//   grid "vel"    Vec3SGrid, m/s, vector type VEC_CONTRAVARIANT_RELATIVE, grid class GRID_UNKNOWN
//   grid "speed"  FloatGrid, |vel| in m/s, grid class GRID_FOG_VOLUME (so viewers show it as a density
//                 right away; note the values are m/s, not confined to [0, 1])
// Both grids: background 0; one voxel per cell, voxel (i,j,k) = cell (i,j,k); ACTIVE only in non-solid cells
// (solid cells are inactive and read as the background 0). Transform: linear, voxel size h, translated so
// that voxel (i,j,k)'s centre is at world origin + h * (i+1/2, j+1/2, k+1/2) (m) - the cell's centre.
//   grid "leaves" (only when leaves are given) PointDataGrid, one point per written leaf (docs/leaves.md),
//                 attributes:
//                   P        Vec3f, the blade centre, m, world (stored as the offset within its voxel)
//                   N        Vec3f, the blade's unit normal
//                   state    int32, trees::LeafState: 0 attached, 1 flying, 2 landed
//                   tree_id  int32, instance index of the tree the leaf grew on
//                   pscale   float, m, half the blade side (Houdini's point radius: a blade spans 2 pscale)
//                 Same transform as the wind grids (voxel size h, voxels on the cells), so a leaf's voxel
//                 is the wind cell it is in; points outside the domain are kept, in voxels outside it.
//                 Houdini: the File SOP loads it as a VDB points primitive; Convert VDB Points gives
//                 ordinary points with N and pscale (Copy to Points then places a blade on each). An empty
//                 LeafFrame gives an empty grid still named "leaves", so that every frame holds the same
//                 grids.
// Metadata: file metadata "time_s" (DoubleMetadata, s) and "step" (Int64Metadata); each grid also carries
// "time_s" (DoubleMetadata), since some tools (Houdini) show only grid metadata.
// Values are stored as 32-bit floats (not half). The file is written through AtomicFile.
#pragma once

#include "io/WindFrame.hpp"
#include "io/writers/FrameWriter.hpp"

#include <filesystem>

namespace fw::io {

/// Writes the selected grids of `frame` as described above, and the grid "leaves" when `leaves` is not
/// null. Initialises OpenVDB on first use (thread-safe). Throws std::invalid_argument("write_wind_vdb: ...")
/// when no grid is selected (neither vel, speed nor leaves), the frame is inconsistent or the leaves are
/// (io/LeavesVtk.hpp, validate_leaf_frame), and std::runtime_error naming the path when the folder does not
/// exist or the file cannot be written (no partial file or temporary is left behind).
void write_wind_vdb(const std::filesystem::path& path, const WindFrame& frame, bool vel, bool speed,
                    const LeafFrame* leaves = nullptr);

}  // namespace fw::io
