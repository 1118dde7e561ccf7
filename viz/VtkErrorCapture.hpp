// Collects what VTK reports while a file is read, instead of printing it, so that the caller can name the
// file that failed and say why, once.
//
//   fw::viz::VtkErrorCapture capture;       // from here until it goes out of scope
//   reader->Update();
//   if (!capture.errors().empty()) throw std::runtime_error(path + ": " + capture.first_error());
//
// VTK's XML readers and their XML parser report a damaged file through error messages (to the output window
// and, through vtkLogger, to stderr), not through their return values. While a capture lives, both are
// silenced and the first message is kept.
#pragma once

#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <string>

namespace fw::viz {

class VtkErrorCapture {
 public:
  VtkErrorCapture();
  ~VtkErrorCapture();
  VtkErrorCapture(const VtkErrorCapture&) = delete;
  VtkErrorCapture& operator=(const VtkErrorCapture&) = delete;

  /// Everything of the first message VTK reported since the capture began; empty when none.
  const std::string& errors() const;
  /// The first line of that message, or "read error" when there was none.
  std::string first_error() const;

 private:
  class Window;
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkSmartPointer<Window> captured_;
};

}  // namespace fw::viz
