// Holds back what this process writes to its standard error (file descriptor 2) while it lives, so that a
// library that prints to stderr on its own can be kept quiet unless its work fails.
//
//   StderrCapture capture;                 // fd 2 now goes to a temporary file
//   program.build(...);                    // PoCL prints "N warnings generated." here
//   const std::string said = capture.release();   // fd 2 restored; what was written, for an error message
//
// Why: PoCL's kernel compiler writes its diagnostics' count straight to stderr on every build, whatever the
// caller asks for, and the build log already holds the diagnostics themselves. The capture is process-wide
// (a file descriptor has no threads), so it is meant for short calls made while no other thread writes to
// stderr, such as building programs while a run is set up. If the descriptor cannot be redirected, nothing
// is captured and stderr stays as it was.
#pragma once

#include <string>

namespace fw::host {

class StderrCapture {
 public:
  StderrCapture();
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  /// Restores stderr and returns what was written to it since construction (empty after the first call).
  std::string release();

 private:
  int saved_ = -1;     // the original fd 2, dup'ed; -1 when nothing is captured
  int captured_ = -1;  // the unlinked temporary file fd 2 points to meanwhile
};

}  // namespace fw::host
