// The readers of user files (.tree, TreeQSM, ...) throw base::SourceError "FILE:LINE: KEY: ..."; these check
// what a reader says about a file, once for all of them.
//
//   CHECK(source_error(read_tree_file, "missing.tree").find("cannot open") != std::string::npos);
//   check_source_error(read_tree_file, "bad.tree", "0 -1 0 0 0 -1\n", 1, "radius", "> 0");
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "base/SourceError.hpp"
#include "tests/support/TempDir.hpp"

namespace fw::test {

/// The message of the base::SourceError that read(path) throws, or "" when it reads fine.
template <typename Read>
std::string source_error(Read read, const std::string& path) {
  try {
    read(path);
  } catch (const base::SourceError& e) {
    return e.what();
  }
  return "";
}

/// Checks that reading `content`, written to a scratch file `name`, fails with a message that starts with
/// "FILE:LINE: KEY: " and holds `detail`.
template <typename Read>
void check_source_error(Read read, const std::string& name, const std::string& content, int line,
                        const std::string& key, const std::string& detail) {
  TempDir dir("fw_source_error");
  const auto path = dir.write(name, content);
  const auto message = source_error(read, path);
  INFO("file:\n" << content << "message: " << message);
  CHECK(message.rfind(path + ":" + std::to_string(line) + ": " + key + ": ", 0) == 0);
  CHECK(message.find(detail) != std::string::npos);
}

}  // namespace fw::test
