// view.py in the output folder (viz/ViewScript): written when the run begins, so that a run that is still
// going, was interrupted or failed opens in ParaView too, and, when it shows the trees, written again after
// each frame with that frame's displacement scale (viz/DisplacementScale: the one `forestwind render` uses),
// the only frame data it reads.
//
//   fw::viz::ViewScriptSettings view;                  // what the run writes, the domain (m), the slice
//   view.wind = true; view.size = {128, 64, 32}; view.cell_size = 2.0; view.slice_height = 10.0;
//   writers.push_back(std::make_unique<fw::viz::ViewScriptWriter>("out/calm", view));
//   // begin(): out/calm/view.py, through a temporary name and a rename (base/AtomicFile)
//
// Then: paraview --script=out/calm/view.py
#pragma once

#include <filesystem>
#include <string>

#include "io/writers/FrameWriter.hpp"
#include "viz/ViewScript.hpp"

namespace fw::viz {

class ViewScriptWriter : public io::FrameWriter {
 public:
  /// Throws std::invalid_argument("view_script: ...") for settings view_script() refuses, so that a bad
  /// domain fails before the run starts, not after.
  ViewScriptWriter(std::filesystem::path directory, ViewScriptSettings settings);

  std::string name() const override { return "view.py"; }
  /// The displacement when the script shows the trees; nothing else of the frames.
  io::FrameNeeds needs() const override;
  /// Creates the folder and writes view.py. Throws std::runtime_error("ViewScriptWriter: cannot write ...").
  void begin() override;
  /// With the trees shown and the frame's displacement there: view.py again, its displacement scale this
  /// frame's. Throws as begin().
  void write(const io::OutputFrame& frame) override;

  const std::filesystem::path& path() const { return path_; }
  /// The settings of the script last written (displacement_top from the last frame).
  const ViewScriptSettings& settings() const { return settings_; }

 private:
  std::filesystem::path directory_, path_;
  ViewScriptSettings settings_;
  std::string script_;
};

}  // namespace fw::viz
