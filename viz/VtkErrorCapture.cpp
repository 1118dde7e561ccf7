#include "viz/VtkErrorCapture.hpp"

namespace fw::viz {

// An output window that keeps the first message instead of showing it.
class VtkErrorCapture::Window : public vtkOutputWindow {
 public:
  static Window* New() { return new Window; }
  void DisplayText(const char* text) override {
    if (text && errors.empty()) errors = text;
  }
  std::string errors;
};

VtkErrorCapture::VtkErrorCapture()
    : previous_(vtkOutputWindow::GetInstance()),
      verbosity_(vtkLogger::GetCurrentVerbosityCutoff()),
      captured_(vtkSmartPointer<Window>::New()) {
  vtkOutputWindow::SetInstance(captured_);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VtkErrorCapture::~VtkErrorCapture() {
  vtkLogger::SetStderrVerbosity(verbosity_);
  vtkOutputWindow::SetInstance(previous_);
}

const std::string& VtkErrorCapture::errors() const {
  return captured_->errors;
}

std::string VtkErrorCapture::first_error() const {
  std::string line = errors().substr(0, errors().find('\n'));
  return line.empty() ? "read error" : line;
}

}  // namespace fw::viz
