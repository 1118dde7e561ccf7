// An error in a file the user gave, found as it is read (a .tree skeleton, a TreeQSM table). what() reads
// "FILE:LINE: KEY: EXPECTED, got GOT" (line 0 is left out: "FILE: KEY: ..."), or "FILE: WHAT" for a file
// that cannot be read at all. It is a std::invalid_argument, so the command line maps it to exit code 2 (bad
// input) wherever it is thrown, and no caller needs to convert it.
//
//   throw fw::base::SourceError("oak.tree", 12, "radius", "a number > 0", "-0.1");
//   // oak.tree:12: radius: a number > 0, got -0.1
//   throw fw::base::SourceError::unreadable("oak.tree", "cannot open: No such file or directory");
//   // oak.tree: cannot open: No such file or directory
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace fw::base {

class SourceError : public std::invalid_argument {
 public:
  /// A value at a line of the file: key, what was expected, and what was there (quoted by the caller if it
  /// helps; an empty `got` leaves out ", got ...").
  SourceError(std::string_view file, int line, std::string_view key, std::string_view expected,
              std::string_view got);
  /// The file as a whole (it cannot be opened, it is empty, it ends too early).
  static SourceError unreadable(std::string_view file, std::string_view what);

  const std::string& file() const { return file_; }
  int line() const { return line_; }  ///< 1-based; 0 when the error is not at a line

 private:
  SourceError(std::string message, std::string_view file, int line);
  std::string file_;
  int line_ = 0;
};

}  // namespace fw::base
