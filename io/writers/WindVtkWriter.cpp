#include "io/writers/WindVtkWriter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "io/WindFrame.hpp"
#include "io/WindVtk.hpp"

namespace fw::io {

WindVtkWriter::WindVtkWriter(std::filesystem::path directory, fluid::GridSpec spec,
                             std::vector<std::uint8_t> solid, std::vector<float> canopy_density,
                             std::vector<std::string> fields)
    : directory_(std::move(directory)),
      spec_(std::move(spec)),
      solid_(std::move(solid)),
      canopy_density_(std::move(canopy_density)),
      fields_(std::move(fields)),
      collection_(directory_ / "wind.pvd") {}

FrameNeeds WindVtkWriter::needs() const {
  FrameNeeds needs;
  needs.velocity = true;
  needs.pressure = std::find(fields_.begin(), fields_.end(), "pressure") != fields_.end();
  return needs;
}

void WindVtkWriter::begin() {
  std::filesystem::create_directories(directory_ / "wind");
}

void WindVtkWriter::write(const OutputFrame& frame) {
  const WindFrame wind =
      make_wind_frame(spec_, frame.velocity, frame.pressure, solid_, canopy_density_, frame.time, frame.step);
  const std::string file = fmt::format("wind/wind_{:06d}.vti", frame.index);
  write_wind_vti(directory_ / file, wind, fields_);
  collection_.add(frame.time, file);
}

}  // namespace fw::io
