// The scenario loader's errors (io::ScenarioError "FILE:LINE: KEY: ..."), checked once for every test of it.
//
//   fw::test::expect_scenario_error(dir, "no_speed", text, 4, "wind.speed", "a number");
#pragma once

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <string>

#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

namespace fw::test {

/// Loads `text` as NAME.yaml in dir and checks the ScenarioError: file, line, key, the "FILE:LINE: KEY: "
/// prefix of what() and a fragment of the rest.
inline void expect_scenario_error(const TempDir& dir, const std::string& name, const std::string& text,
                                  int line, const std::string& key, const std::string& fragment) {
  INFO("case " << name << ":\n" << text);
  const std::string path = dir.write(name + ".yaml", text);
  try {
    io::load_scenario(path);
    FAIL("load_scenario accepted the file");
  } catch (const io::ScenarioError& error) {
    const std::string what = error.what();
    INFO("what(): " << what);
    CHECK(error.file() == path);
    CHECK(error.line() == line);
    CHECK(error.key() == key);
    CHECK_THAT(what, Catch::Matchers::StartsWith(fmt::format("{}:{}: {}: ", path, line, key)));
    CHECK_THAT(what, Catch::Matchers::Contains(fragment));
  }
}

}  // namespace fw::test
