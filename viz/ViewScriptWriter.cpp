#include "viz/ViewScriptWriter.hpp"

#include <stdexcept>
#include <system_error>
#include <utility>

#include "base/AtomicFile.hpp"
#include "viz/DisplacementScale.hpp"

namespace fw::viz {

ViewScriptWriter::ViewScriptWriter(std::filesystem::path directory, ViewScriptSettings settings)
    : directory_(std::move(directory)),
      path_(directory_ / "view.py"),
      settings_(std::move(settings)),
      script_(view_script(settings_)) {}

io::FrameNeeds ViewScriptWriter::needs() const {
  io::FrameNeeds needs;
  needs.displacement = settings_.trees;
  return needs;
}

void ViewScriptWriter::begin() {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  // A folder that cannot be made is reported by the write below, with the path and the reason.
  base::write_text_atomically("ViewScriptWriter", path_, script_);
}

void ViewScriptWriter::write(const io::OutputFrame& frame) {
  if (!settings_.trees || frame.displacement.empty() || frame.probe_samples_only) return;
  settings_.displacement_top = displacement_scale(displacement_magnitudes(frame.displacement));
  script_ = view_script(settings_);
  base::write_text_atomically("ViewScriptWriter", path_, script_);
}

}  // namespace fw::viz
