#include "host/runtime/StderrCapture.hpp"

#include <unistd.h>
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

using fw::host::StderrCapture;

TEST_CASE("StderrCapture: holds back what C stdio and write(2) send to stderr, and restores it") {
  StderrCapture outer;
  {
    StderrCapture inner;
    std::fprintf(stderr, "through stdio\n");
    const std::string raw = "through the descriptor\n";
    CHECK(write(STDERR_FILENO, raw.data(), raw.size()) == static_cast<ssize_t>(raw.size()));
    CHECK(inner.release() == "through stdio\nthrough the descriptor\n");
    CHECK(inner.release().empty());  // released once
    std::fprintf(stderr, "after the inner one\n");
  }
  // The inner capture gave fd 2 back to the outer one, which saw only what came after.
  CHECK(outer.release() == "after the inner one\n");
}
