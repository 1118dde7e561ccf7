// wind.pvd + wind/wind_NNNNNN.vti: the wind grid's cell arrays of every frame, for ParaView (io/WindVtk.hpp
// has the layout).
//
//   fw::io::WindVtkWriter wind("out/storm", spec, solid, canopy_density, {"velocity", "speed", "solid"});
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "io/PvdCollection.hpp"
#include "io/WindVtk.hpp"
#include "io/settings/SiteSettings.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

/// A run over MPI ranks: this rank's piece of every frame (its own cells of the frames it gets, which hold
/// its block with the halo), and every rank's piece extent, from which rank 0 writes each frame's .pvti.
struct WindPieces {
  int rank = 0;
  WindPiece piece;
  std::vector<std::array<int, 6>> extents;  ///< per rank: its piece's point extent in the domain
};

class WindVtkWriter : public FrameWriter {
 public:
  /// solid: 1 byte a cell (empty = none); canopy_density: a per cell, 1/m (empty = none); fields: names from
  /// wind_field_names() (an unknown one throws std::invalid_argument at the first frame).
  /// Over ranks (pieces given): spec, solid and canopy_density are this rank's block with the halo; it
  /// writes wind/wind_NNNNNN_RRRR.vti, rank 0 also wind/wind_NNNNNN.pvti, and the run adds the frame to
  /// wind.pvd once every rank has written it. site: the run's, into every frame (io/SiteVtk.hpp).
  WindVtkWriter(std::filesystem::path directory, fluid::GridSpec spec, std::vector<std::uint8_t> solid,
                std::vector<float> canopy_density, std::vector<std::string> fields,
                std::optional<WindPieces> pieces = std::nullopt,
                std::optional<SiteSettings> site = std::nullopt);
  /// The file wind.pvd lists for frame `index`: its .vti, or over ranks its .pvti.
  static std::string frame_file(int index, bool pieces);

  std::string name() const override { return "wind VTK"; }
  FrameNeeds needs() const override;
  void begin() override;
  /// In one process the .pvd keeps its frames up to the checkpoint (over ranks the run lists them).
  void resume(const OutputResume& resume) override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  fluid::GridSpec spec_;
  std::vector<std::uint8_t> solid_;
  std::vector<float> canopy_density_;
  std::vector<std::string> fields_;
  std::optional<WindPieces> pieces_;
  std::optional<SiteSettings> site_;  // written into every frame's field data
  PvdCollection collection_;
};

}  // namespace fw::io
