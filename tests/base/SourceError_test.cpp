// base/SourceError: the FILE:LINE: KEY: message every reader of user files gives, as an input error.
#include "base/SourceError.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

TEST_CASE("SourceError: reads FILE:LINE: KEY: expected, got value, and is an input error", "[base]") {
  const fw::base::SourceError error("oak.tree", 12, "radius", "a number > 0", "'-0.1'");
  CHECK(std::string(error.what()) == "oak.tree:12: radius: a number > 0, got '-0.1'");
  CHECK(error.file() == "oak.tree");
  CHECK(error.line() == 12);
  // The command line maps std::invalid_argument to exit code 2 (bad input).
  const std::invalid_argument& input = error;
  CHECK(std::string(input.what()) == error.what());
}

TEST_CASE("SourceError: line 0 and an empty got are left out, and a whole-file error names only the file",
          "[base]") {
  CHECK(std::string(fw::base::SourceError("a.txt", 0, "id", "at least one node", "").what()) ==
        "a.txt: id: at least one node");
  const auto unreadable = fw::base::SourceError::unreadable("missing.tree", "cannot open: No such file");
  CHECK(std::string(unreadable.what()) == "missing.tree: cannot open: No such file");
  CHECK(unreadable.line() == 0);
}
