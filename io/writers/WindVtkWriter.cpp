#include "io/writers/WindVtkWriter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "io/WindFrame.hpp"
#include "io/WindVtk.hpp"

namespace fw::io {

WindVtkWriter::WindVtkWriter(std::filesystem::path directory, fluid::GridSpec spec,
                             std::vector<std::uint8_t> solid, std::vector<float> canopy_density,
                             std::vector<std::string> fields, std::optional<WindPieces> pieces,
                             std::optional<SiteSettings> site)
    : directory_(std::move(directory)),
      spec_(std::move(spec)),
      solid_(std::move(solid)),
      canopy_density_(std::move(canopy_density)),
      fields_(std::move(fields)),
      pieces_(std::move(pieces)),
      site_(std::move(site)),
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

void WindVtkWriter::resume(const OutputResume& resume) {
  begin();
  if (!pieces_) collection_.continue_existing(resume.time);
}

std::string WindVtkWriter::frame_file(int index, bool pieces) {
  return fmt::format("wind/wind_{:06d}.{}", index, pieces ? "pvti" : "vti");
}

void WindVtkWriter::write(const OutputFrame& frame) {
  WindFrame wind =
      make_wind_frame(spec_, frame.velocity, frame.pressure, solid_, canopy_density_, frame.time, frame.step);
  wind.site = site_ ? &*site_ : nullptr;
  if (!pieces_) {
    const std::string file = frame_file(frame.index, false);
    write_wind_vti(directory_ / file, wind, fields_);
    collection_.add(frame.time, file);
    return;
  }
  VtkArrays arrays;
  write_wind_vti(directory_ / "wind" / piece_file("wind", frame.index, pieces_->rank, "vti"), wind, fields_,
                 &pieces_->piece, &arrays);
  if (pieces_->rank != 0) return;
  std::vector<std::pair<std::array<int, 6>, std::string>> listed;
  for (std::size_t r = 0; r < pieces_->extents.size(); ++r)
    listed.emplace_back(pieces_->extents[r], piece_file("wind", frame.index, int(r), "vti"));
  const std::array<int, 2> n = spec_.domain_cells();  // the block's grid knows the domain's
  write_pvti(directory_ / frame_file(frame.index, true), arrays, spec_.origin, spec_.h,
             {0, n[0], 0, n[1], 0, spec_.nz}, listed);
}

}  // namespace fw::io
