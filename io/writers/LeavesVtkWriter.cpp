#include "io/writers/LeavesVtkWriter.hpp"

#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "io/LeavesVtk.hpp"

namespace fw::io {

LeavesVtkWriter::LeavesVtkWriter(std::filesystem::path directory)
    : directory_(std::move(directory)), collection_(directory_ / "leaves.pvd") {}

LeavesVtkWriter::LeavesVtkWriter(std::filesystem::path directory, int rank, int ranks)
    : LeavesVtkWriter(std::move(directory)) {
  rank_ = rank;
  ranks_ = ranks;
}

std::string LeavesVtkWriter::frame_file(int index, bool pieces) {
  return fmt::format("leaves/leaves_{:06d}.{}", index, pieces ? "pvtp" : "vtp");
}

void LeavesVtkWriter::begin() {
  std::filesystem::create_directories(directory_ / "leaves");
}

void LeavesVtkWriter::write(const OutputFrame& frame) {
  if (ranks_ == 0) {
    const std::string file = frame_file(frame.index, false);
    write_leaves_vtp(directory_ / file, frame.time, frame.leaves);
    collection_.add(frame.time, file);
    return;
  }
  const auto piece_name = [&](int rank) {
    return fmt::format("leaves_{:06d}_{:04d}.vtp", frame.index, rank);
  };
  write_leaves_vtp(directory_ / "leaves" / piece_name(rank_), frame.time, frame.leaves);
  if (rank_ != 0) return;
  std::vector<std::string> sources;
  for (int r = 0; r < ranks_; ++r) sources.push_back(piece_name(r));
  write_pvtp(directory_ / frame_file(frame.index, true), leaves_vtp_arrays(), sources);
}

}  // namespace fw::io
