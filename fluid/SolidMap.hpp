// Which cells of the wind grid are solid: one byte per cell (1 = solid, 0 = fluid), voxelised from boxes,
// cylinders, spheres and heightmap terrain.
//
//   fw::fluid::SolidMap solids(spec);                                   // all fluid
//   solids.add(fw::fluid::SolidBox{"barn", {300, 100, 6}, {30, 15, 12}, 15.0 * std::numbers::pi / 180});
//   solids.add(fw::fluid::SolidCylinder{"silo", {340, 60, 0}, 4.0, 20.0});
//   solids.add_terrain(fw::fluid::Heightmap::read("hills.pgm", 4.0, 20.0));
//   upload(solids.cells());                                             // x-fastest, like GridSpec
//
// A cell is solid when its CENTRE lies inside a shape; shapes only ever add solid cells. Faces whose
// coordinate is the shape's minimum count as inside and faces at its maximum (box faces on the local +x, +y,
// +z sides, the cylinder's top, the terrain surface) as outside, so a shape whose faces lie on cell
// boundaries marks exactly volume / h^3 cells, and shapes that touch do not overlap. A centre exactly on a
// curved surface (cylinder side, sphere) counts as inside. Only the cells of a shape's bounding box are
// visited.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/Heightmap.hpp"

namespace fw::fluid {

/// A box, possibly turned about the vertical axis through its centre.
struct SolidBox {
  std::string name;                // for error messages
  std::array<double, 3> center{};  // world position of the box's centre, m
  std::array<double, 3> size{};    // full edge lengths along the box's own x, y, z axes, m (> 0)
  double yaw_rad = 0.0;            // rotation about +z, counter-clockwise seen from above
};

/// A vertical cylinder standing on its base.
struct SolidCylinder {
  std::string name;              // for error messages
  std::array<double, 3> base{};  // world position of the centre of the bottom disc, m
  double radius = 0.0;           // m (> 0)
  double height = 0.0;           // extent upwards from the base, m (> 0)
};

/// A sphere.
struct SolidSphere {
  std::string name;                // for error messages
  std::array<double, 3> center{};  // world position, m
  double radius = 0.0;             // m (> 0)
};

class SolidMap {
 public:
  /// All cells fluid. Validates the spec (std::invalid_argument from GridSpec::validate).
  explicit SolidMap(const GridSpec& spec);

  /// Each add marks the cells whose centres lie inside the shape and returns how many were fluid before
  /// (cells already solid are not counted again). Throws std::invalid_argument("SolidMap: ...") naming the
  /// shape and field for non-finite values or a non-positive size, radius or height.
  std::size_t add(const SolidBox& box);
  std::size_t add(const SolidCylinder& cylinder);
  std::size_t add(const SolidSphere& sphere);
  /// Marks every cell whose centre is below the terrain: z < spec.origin[2] + terrain.height_at(x, y), the
  /// heightmap's (x, y) being world coordinates. Terrain heights are measured from the domain floor.
  std::size_t add_terrain(const Heightmap& terrain);

  const GridSpec& spec() const { return spec_; }
  /// One byte per cell, x-fastest: index = i + nx * (j + ny * k); 1 = solid, 0 = fluid.
  const std::vector<std::uint8_t>& cells() const { return cells_; }
  /// Throws std::out_of_range outside the grid.
  bool solid(int i, int j, int k) const;
  std::size_t solid_count() const { return solid_count_; }

 private:
  GridSpec spec_;
  std::vector<std::uint8_t> cells_;
  std::size_t solid_count_ = 0;
};

}  // namespace fw::fluid
