// vdb/wind.NNNN.vdb: the wind grid of every frame as OpenVDB grids, for Houdini and Blender (io/VdbWriter.hpp
// has the layout), and with leaves on the frame's leaves as the points grid "leaves". Over MPI ranks only
// rank 0 has one, and it writes the frame's gathered velocity and leaves (OutputFrame::gathered).
//
//   fw::io::WindVdbWriter vdb("out/storm", spec, solid, /*vel=*/true, /*speed=*/true, /*leaves=*/true);
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "io/settings/SiteSettings.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class WindVdbWriter : public FrameWriter {
 public:
  /// solid: 1 byte a cell (empty = none); solid cells are inactive voxels. leaves: write each frame's
  /// leaves (OutputFrame::leaves) as the points grid "leaves", also when a frame has none.
  WindVdbWriter(std::filesystem::path directory, fluid::GridSpec spec, std::vector<std::uint8_t> solid,
                bool vel, bool speed, bool leaves = false, std::optional<SiteSettings> site = std::nullopt);

  std::string name() const override { return "VDB"; }
  FrameNeeds needs() const override { return {.velocity = true, .leaves = leaves_}; }
  void begin() override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  fluid::GridSpec spec_;
  std::vector<std::uint8_t> solid_;
  bool vel_ = true, speed_ = true, leaves_ = false;
  std::optional<SiteSettings> site_;  // into every file's metadata
};

}  // namespace fw::io
