// terrain: the heightmap under the wind grid.
#include "io/scenario/Terrain.hpp"

#include <fmt/format.h>

#include <exception>
#include <fstream>
#include <utility>
#include <vector>

#include "io/schema/TerrainKeys.hpp"

namespace fw::io::reader {

TerrainSettings read_terrain(const Loader& loader, const Field& field, const DomainSettings& domain) {
  const Section<schema::kTerrainKeys, "terrain"> map(loader, field);
  TerrainSettings terrain;
  const Field heightmap = map.require<"heightmap">();
  terrain.heightmap = loader.readable_file(heightmap);
  // The format comes from the content (fluid/Heightmap.hpp); cell size and height scale matter for PGM only.
  char magic[2] = {0, 0};
  std::ifstream(terrain.heightmap, std::ios::binary).read(magic, 2);
  const bool pgm = magic[0] == 'P' && (magic[1] == '2' || magic[1] == '5');
  const auto cell_size = map.get<"cell_size">();
  const auto max_height = map.get<"max_height">();
  if (cell_size) terrain.cell_size = loader.number(*cell_size);
  if (max_height) terrain.max_height = loader.number(*max_height);
  const std::string reason = "needed for a PGM heightmap";
  if (pgm && !cell_size) map.require<"cell_size">(reason);
  if (pgm && !max_height) map.require<"max_height">(reason);
  try {
    terrain.map = fluid::Heightmap::read(terrain.heightmap.string(), pgm ? terrain.cell_size : 1.0,
                                         pgm ? terrain.max_height : 0.0);
  } catch (const std::exception& error) {
    loader.expected(heightmap, fmt::format("a PGM or ESRI ASCII grid ({})", error.what()));
  }
  if (pgm) {
    // An image has no georeference: its south-west corner goes to the domain's, wherever the origin is.
    const fluid::Heightmap& image = *terrain.map;
    std::vector<double> heights;
    heights.reserve(std::size_t(image.columns()) * std::size_t(image.rows()));
    for (int row = 0; row < image.rows(); ++row)
      for (int column = 0; column < image.columns(); ++column) heights.push_back(image.sample(column, row));
    const double half = 0.5 * image.cell_size();
    terrain.map = fluid::Heightmap(image.columns(), image.rows(), image.cell_size(),
                                   {domain.origin[0] + half, domain.origin[1] + half}, std::move(heights));
  }
  return terrain;
}

}  // namespace fw::io::reader
