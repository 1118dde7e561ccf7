// leaves.pvd + leaves/leaves_NNNNNN.vtp: the written leaves of every frame as points with their normal,
// state, tree and size, for ParaView (io/LeavesVtk.hpp has the layout and the Glyph settings that draw the
// blades). The leaves that are written change from frame to frame (shedding, thinning), so each file is built
// anew.
//
//   fw::io::LeavesVtkWriter leaves("out/storm");
#pragma once

#include <filesystem>
#include <string>

#include "io/ParallelVtk.hpp"
#include "io/PvdCollection.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class LeavesVtkWriter : public FrameWriter {
 public:
  explicit LeavesVtkWriter(std::filesystem::path directory);
  /// Over MPI ranks: it writes this rank's leaves as leaves/leaves_NNNNNN_RRRR.vtp, rank 0 also
  /// leaves/leaves_NNNNNN.pvtp listing the `ranks` pieces, and the run adds the frame to leaves.pvd once
  /// every rank has written it.
  LeavesVtkWriter(std::filesystem::path directory, int rank, int ranks);
  /// The file leaves.pvd lists for frame `index`: its .vtp, or over ranks its .pvtp.
  static std::string frame_file(int index, bool pieces);

  std::string name() const override { return "leaves VTK"; }
  FrameNeeds needs() const override { return {.leaves = true}; }
  void begin() override;
  /// In one process the .pvd keeps its frames up to the checkpoint (over ranks the run lists them).
  void resume(const OutputResume& resume) override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  PvdCollection collection_;
  int rank_ = 0, ranks_ = 0;  // ranks_ 0: one process, no pieces
  VtkArrays arrays_;          // over ranks: what the .pvtp declares
};

}  // namespace fw::io
