// A terrain height field: samples on a regular horizontal lattice, interpolated bilinearly, from a PGM image
// (read here) or from a georeferenced raster (read through GDAL by the scenario's terrain.raster,
// io/scenario/Terrain.cpp). SolidMap::add_terrain turns it into solid cells.
//
//   auto terrain = fw::fluid::Heightmap::read("hills.pgm", /*cell_size_m=*/4.0, /*max_height_m=*/20.0);
//   double z = terrain.height_at(120.0, 80.0);   // metres above the domain floor at world (x, y)
//
// Coordinates are the domain's world frame (x east, y north, metres). Heights are metres above the domain's
// floor (GridSpec::origin[2]), not absolute elevations.
//
// The PGM reader takes P2 (ASCII) or P5 (binary; 16-bit big-endian samples when maxval > 255), maxval
// 1..65535, '#' comments in the header, chosen from the content, never from the extension. A pixel v becomes
// v / maxval * max_height_m metres. Pixels are cell_size_m apart; the image's first row is the north edge,
// columns run east, and the south-west pixel's centre lies at world (0.5, 0.5) * cell_size_m, so the image
// covers [0, columns * cell_size_m] x [0, rows * cell_size_m]. (GDAL's PNM driver reads P5 only, so both
// forms stay here, one reader.)
//
// Every read error throws std::runtime_error("FILE:LINE: what was expected, got what"), or
// "FILE: binary data: ..." inside P5 pixel data.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace fw::fluid {

class Heightmap {
 public:
  /// Reads a PGM (P2/P5), see the header comment; cell_size_m > 0, max_height_m >= 0. Throws
  /// std::runtime_error naming the file and line.
  static Heightmap read(const std::string& path, double cell_size_m, double max_height_m);

  /// A height field from samples already in memory. heights_m holds columns * rows values, row-major with
  /// row 0 the SOUTH row (index = column + columns * row); sw_centre_m is the world (x, y) of sample (0, 0).
  /// Throws std::invalid_argument for a size mismatch, non-positive dimensions or cell size, or
  /// non-finite values.
  Heightmap(int columns, int rows, double cell_size_m, std::array<double, 2> sw_centre_m,
            std::vector<double> heights_m);

  /// Height in metres above the domain floor at world (x_m, y_m): bilinear between sample centres; outside
  /// the lattice of centres, the nearest edge value (clamped, no extrapolation).
  double height_at(double x_m, double y_m) const;

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  /// Distance between neighbouring samples, m.
  double cell_size() const { return cell_size_; }
  /// World (x, y) of the south-west sample's centre, m.
  const std::array<double, 2>& sw_centre() const { return sw_centre_; }
  /// Sample at (column, row), row 0 = south, m.
  double sample(int column, int row) const {
    return heights_[std::size_t(column) + std::size_t(columns_) * row];
  }
  /// Largest sample, m: the top of the terrain's bounding box.
  double max_height() const { return max_height_; }

 private:
  int columns_ = 0, rows_ = 0;
  double cell_size_ = 0.0;
  std::array<double, 2> sw_centre_{0, 0};
  std::vector<double> heights_;  // row 0 = south
  double max_height_ = 0.0;
};

}  // namespace fw::fluid
