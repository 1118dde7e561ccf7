// Angles: the file gives them in degrees (yaws), every struct past the loader holds radians.
//
//   fw::io::radians(90.0);   // pi / 2
#pragma once

#include <numbers>

namespace fw::io {

/// An angle the file gives in degrees (yaws), in the radians of every struct past the loader.
constexpr double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

}  // namespace fw::io
