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
  arrays_ = leaves_vtp_arrays();
}

std::string LeavesVtkWriter::frame_file(int index, bool pieces) {
  return fmt::format("leaves/leaves_{:06d}.{}", index, pieces ? "pvtp" : "vtp");
}

void LeavesVtkWriter::begin() {
  std::filesystem::create_directories(directory_ / "leaves");
}

void LeavesVtkWriter::resume(const OutputResume& resume) {
  begin();
  if (ranks_ == 0) collection_.continue_existing(resume.time);
}

void LeavesVtkWriter::write(const OutputFrame& frame) {
  if (ranks_ == 0) {
    const std::string file = frame_file(frame.index, false);
    write_leaves_vtp(directory_ / file, frame.time, frame.leaves);
    collection_.add(frame.time, file);
    return;
  }
  write_leaves_vtp(directory_ / "leaves" / piece_file("leaves", frame.index, rank_, "vtp"), frame.time,
                   frame.leaves);
  if (rank_ != 0) return;
  write_pvtp(directory_ / frame_file(frame.index, true), arrays_,
             piece_files("leaves", frame.index, ranks_, "vtp"));
}

}  // namespace fw::io
