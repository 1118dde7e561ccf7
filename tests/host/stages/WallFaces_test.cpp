// The wall stress's face list (host/stages/WallFaces), on the host: which faces, which weights, which faces
// averaged across. The device's use of it is checked against the CPU reference in
// tests/kernels/subgrid_stress_test.cpp.
#include <catch2/catch.hpp>

#include <set>

#include "fluid/SubgridStress.hpp"
#include "host/stages/WallFaces.hpp"

using namespace fw;
using B = fluid::BoundaryType;

namespace {

fluid::GridSpec box(int nx, int ny, int nz, B x_sides) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = 1.0;
  spec.boundary = {x_sides, x_sides, B::periodic, B::periodic, B::slip, B::slip};
  return spec;
}

}  // namespace

TEST_CASE("wall faces: a flat ground lists every u and v face of the first layer with weight 1",
          "[wall_faces]") {
  const auto spec = box(4, 3, 5, B::periodic);
  const auto list = host::list_wall_faces(spec, fluid::wall_cells(spec, {}));
  // Every face of the bottom layer: (nx + 1) ny u faces and nx (ny + 1) v faces (the face arrays hold a
  // periodic seam twice, at index 0 and n).
  CHECK(list.u_count == (4 + 1) * 3);
  CHECK(list.size() == (4 + 1) * 3 + 4 * (3 + 1));
  CHECK(list.faces.size() == std::size_t(host::WallFaces::kIndicesPerFace * list.size()));
  std::set<int> u_faces;
  for (int n = 0; n < list.size(); ++n) {
    CHECK(list.weights[n] == 1.0f);
    if (n < list.u_count) u_faces.insert(list.faces[host::WallFaces::kIndicesPerFace * n]);
  }
  // u faces i = 0 .. nx of the bottom layer: index i + (nx + 1) j, all below (nx + 1) ny.
  CHECK(*u_faces.rbegin() < (4 + 1) * 3);
  CHECK(u_faces.size() == std::size_t(list.u_count));
}

TEST_CASE("wall faces: a u face beside a wall cell on a closed side gets half the weight", "[wall_faces]") {
  // Closed x sides: the boundary faces i = 0 and i = nx clamp onto the edge cells, so every u face of the
  // ground layer lists with weight 1 (both its cells are wall cells); a roof over half the domain makes the
  // faces at its edge one wall cell and one not.
  auto spec = box(4, 1, 3, B::slip);
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  solid[0 + 4 * 1 * 0] = 1;  // cell (0, 0, 0): the cell above it, (0, 0, 1), is a wall cell
  const auto walls = fluid::wall_cells(spec, solid);
  const auto list = host::list_wall_faces(spec, walls);
  // u face (1, 0, 1): between cell (0, 0, 1) (wall) and (1, 0, 1) (not): weight 0.5, and its v faces are
  // those of cells (0, 0, 1) and (1, 0, 1).
  const int face = 1 + 5 * (0 + 1 * 1);
  bool found = false;
  for (int n = 0; n < list.u_count; ++n)
    if (list.faces[host::WallFaces::kIndicesPerFace * n] == face) {
      found = true;
      CHECK(list.weights[n] == 0.5f);
      const int* across = &list.faces[host::WallFaces::kIndicesPerFace * n + 1];
      // v faces (i, j, k) index i + nx (j + (ny + 1) k): cell (0, 0, 1) has v faces j = 0 and 1.
      CHECK(across[0] == 0 + 4 * (0 + 2 * 1));
      CHECK(across[1] == 0 + 4 * (1 + 2 * 1));
      CHECK(across[2] == 1 + 4 * (0 + 2 * 1));
      CHECK(across[3] == 1 + 4 * (1 + 2 * 1));
    }
  CHECK(found);
  CHECK_THROWS_AS(host::list_wall_faces(spec, {1.0f}), std::invalid_argument);
}
