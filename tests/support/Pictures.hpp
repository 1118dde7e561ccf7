// PNG pictures read back through VTK's PNG reader, independent of how viz/ wrote them (cairo).
#pragma once

#include <catch2/catch.hpp>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "viz/ColourMap.hpp"

namespace fw::test {

struct Picture {
  vtkSmartPointer<vtkImageData> image;
  int width = 0, height = 0, channels = 0;
  /// Pixel (i, j) with j counted from the TOP, as viz/Canvas counts (VTK's rows start at the bottom).
  std::array<int, 3> at(int i, int j) const {
    // Not REQUIRE: the tests scan whole pictures, and a million assertions would drown the report.
    if (i < 0 || j < 0 || i >= width || j >= height)
      throw std::out_of_range("Picture: pixel " + std::to_string(i) + ", " + std::to_string(j) + " outside");
    const auto* p = static_cast<const std::uint8_t*>(image->GetScalarPointer(i, height - 1 - j, 0));
    return {p[0], p[1], p[2]};
  }
};

inline Picture read_png(const std::filesystem::path& path) {
  REQUIRE(std::filesystem::is_regular_file(path));
  vtkNew<vtkPNGReader> reader;
  REQUIRE(reader->CanReadFile(path.string().c_str()) != 0);
  reader->SetFileName(path.string().c_str());
  reader->Update();
  Picture p;
  p.image = reader->GetOutput();
  int dims[3];
  p.image->GetDimensions(dims);
  p.width = dims[0], p.height = dims[1], p.channels = p.image->GetNumberOfScalarComponents();
  REQUIRE(p.channels >= 3);
  return p;
}

/// A colour as the PNG stores it: each channel rounded to 8 bits.
inline std::array<int, 3> bytes(const viz::Rgb& c) {
  return {int(std::lround(c.r * 255)), int(std::lround(c.g * 255)), int(std::lround(c.b * 255))};
}

/// The largest channel difference of two colours, 0..255.
inline int colour_distance(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

}  // namespace fw::test
