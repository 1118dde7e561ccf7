#include "io/writers/LeavesVtkWriter.hpp"

#include <fmt/format.h>

#include <utility>

#include "io/LeavesVtk.hpp"

namespace fw::io {

LeavesVtkWriter::LeavesVtkWriter(std::filesystem::path directory)
    : directory_(std::move(directory)), collection_(directory_ / "leaves.pvd") {}

void LeavesVtkWriter::begin() {
  std::filesystem::create_directories(directory_ / "leaves");
}

void LeavesVtkWriter::write(const OutputFrame& frame) {
  const std::string file = fmt::format("leaves/leaves_{:06d}.vtp", frame.index);
  write_leaves_vtp(directory_ / file, frame.time, frame.leaves);
  collection_.add(frame.time, file);
}

}  // namespace fw::io
