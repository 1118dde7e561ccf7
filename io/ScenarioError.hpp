// A scenario that cannot be used, and where in its file: every problem the loader (io/Scenario.hpp,
// load_scenario) finds, and every one the checks past it find in the file's values.
//
//   throw fw::io::ScenarioError("storm.yaml", 12, "wind.speed", "a number >= 0 expected, got '-3'");
//   // what(): "storm.yaml:12: wind.speed: a number >= 0 expected, got '-3'"
#pragma once

#include <stdexcept>
#include <string>

namespace fw::io {

/// A scenario that cannot be used: what() is "FILE:LINE: KEY: what was expected[, got 'VALUE']".
class ScenarioError : public std::invalid_argument {
 public:
  /// message is the part after "KEY: ".
  ScenarioError(std::string file, int line, std::string key, const std::string& message);

  const std::string& file() const { return file_; }
  /// 1-based line of the offending node; 0 when the file could not be read at all.
  int line() const { return line_; }
  /// Dotted path such as "wind.speed" or "forest.species[0].modes.count"; "(file)" when the file could
  /// not be read, "(yaml)" for a YAML syntax error.
  const std::string& key() const { return key_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string key_;
};

}  // namespace fw::io
