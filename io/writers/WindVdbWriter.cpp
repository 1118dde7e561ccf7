#include "io/writers/WindVdbWriter.hpp"

#include <fmt/format.h>

#include <utility>

#include "io/VdbWriter.hpp"
#include "io/WindFrame.hpp"

namespace fw::io {

WindVdbWriter::WindVdbWriter(std::filesystem::path directory, fluid::GridSpec spec,
                             std::vector<std::uint8_t> solid, bool vel, bool speed, bool leaves)
    : directory_(std::move(directory)),
      spec_(std::move(spec)),
      solid_(std::move(solid)),
      vel_(vel),
      speed_(speed),
      leaves_(leaves) {}

void WindVdbWriter::begin() {
  std::filesystem::create_directories(directory_ / "vdb");
}

void WindVdbWriter::write(const OutputFrame& frame) {
  const WindFrame wind = make_wind_frame(spec_, frame.velocity, {}, solid_, {}, frame.time, frame.step);
  write_wind_vdb(directory_ / fmt::format("vdb/wind.{:04d}.vdb", frame.index), wind, vel_, speed_,
                 leaves_ ? &frame.leaves : nullptr);
}

}  // namespace fw::io
