#include "io/writers/WindVdbWriter.hpp"

#include <fmt/format.h>

#include <utility>

#include "io/VdbWriter.hpp"
#include "io/WindFrame.hpp"

namespace fw::io {

WindVdbWriter::WindVdbWriter(std::filesystem::path directory, fluid::GridSpec spec,
                             std::vector<std::uint8_t> solid, bool vel, bool speed, bool leaves,
                             std::optional<SiteSettings> site)
    : directory_(std::move(directory)),
      spec_(std::move(spec)),
      solid_(std::move(solid)),
      vel_(vel),
      speed_(speed),
      leaves_(leaves),
      site_(std::move(site)) {}

void WindVdbWriter::begin() {
  std::filesystem::create_directories(directory_ / "vdb");
}

void WindVdbWriter::write(const OutputFrame& frame) {
  // Over ranks this is rank 0, and the frame's gathered parts are the whole domain.
  const fluid::MacVelocity& velocity = frame.gathered ? frame.gathered->velocity : frame.velocity;
  const LeafFrame& leaves = frame.gathered ? frame.gathered->leaves : frame.leaves;
  WindFrame wind = make_wind_frame(spec_, velocity, {}, solid_, {}, frame.time, frame.step);
  wind.site = site_ ? &*site_ : nullptr;
  write_wind_vdb(directory_ / fmt::format("vdb/wind.{:04d}.vdb", frame.index), wind, vel_, speed_,
                 leaves_ ? &leaves : nullptr);
}

}  // namespace fw::io
