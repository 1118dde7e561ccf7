// wind.pvd + wind/wind_NNNNNN.vti: the wind grid's cell arrays of every frame, for ParaView (io/WindVtk.hpp
// has the layout).
//
//   fw::io::WindVtkWriter wind("out/storm", spec, solid, canopy_density, {"velocity", "speed", "solid"});
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "io/PvdCollection.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class WindVtkWriter : public FrameWriter {
 public:
  /// solid: 1 byte a cell (empty = none); canopy_density: a per cell, 1/m (empty = none); fields: names from
  /// wind_field_names() (an unknown one throws std::invalid_argument at the first frame).
  WindVtkWriter(std::filesystem::path directory, fluid::GridSpec spec, std::vector<std::uint8_t> solid,
                std::vector<float> canopy_density, std::vector<std::string> fields);

  std::string name() const override { return "wind VTK"; }
  FrameNeeds needs() const override;
  void begin() override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  fluid::GridSpec spec_;
  std::vector<std::uint8_t> solid_;
  std::vector<float> canopy_density_;
  std::vector<std::string> fields_;
  PvdCollection collection_;
};

}  // namespace fw::io
