#include "viz/ViewScriptWriter.hpp"

#include <stdexcept>
#include <system_error>
#include <utility>

#include "base/AtomicFile.hpp"

namespace fw::viz {

ViewScriptWriter::ViewScriptWriter(std::filesystem::path directory, ViewScriptSettings settings)
    : directory_(std::move(directory)), path_(directory_ / "view.py"), script_(view_script(settings)) {}

void ViewScriptWriter::begin() {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  // A folder that cannot be made is reported by the write below, with the path and the reason.
  base::write_text_atomically("ViewScriptWriter", path_, script_);
}

}  // namespace fw::viz
