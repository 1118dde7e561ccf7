// The u and v faces that the log-law wall stress acts on, listed once for the device
// (kernels/subgrid_stress.cl wall_stress_faces and wall_stress_store). The wall cells are a thin layer (the
// ground and the tops of solids) inside a box that spans the tallest obstacle, so a list costs a step only
// the faces the stress changes.
//
//   WallFaces list = list_wall_faces(spec, fluid::wall_cells(spec, solid));
//   // list.faces[5 n]: the face's index in its component (u for n < list.u_count, else v);
//   // list.faces[5 n + 1 .. 5 n + 4]: the faces of the other horizontal component whose mean is its value
//   // at the face; list.weights[n]: the mean wall weight of the two cells sharing the face (0.5 or 1).
//
// The cells sharing a face are those of fluid::reference::wall_stress, the oracle: the cell below it along
// its own axis and the cell above, wrapped across a periodic axis and clamped into the grid elsewhere.
#pragma once

#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::host {

struct WallFaces {
  static constexpr int kIndicesPerFace = 5;  // the face, then the four faces averaged across it
  int u_count = 0;                           // entries 0 .. u_count - 1 are u faces, the rest v faces
  std::vector<std::int32_t> faces;           // kIndicesPerFace a face
  std::vector<float> weights;                // one a face, in (0, 1]
  int size() const { return static_cast<int>(weights.size()); }
};

/// Every u and v face with a non-zero weight. `walls`: one float a cell (fluid::wall_cells). Throws
/// std::invalid_argument when its size is not spec.cell_count().
WallFaces list_wall_faces(const fluid::GridSpec& spec, const std::vector<float>& walls);

}  // namespace fw::host
