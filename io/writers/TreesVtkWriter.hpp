// trees.pvd + trees/trees_NNNNNN.vtp: the whole forest at its deformed positions every frame, for ParaView
// (io/TreesVtk.hpp has the layout). The rest geometry, cells and ids are built once from the forest.
//
//   fw::io::TreesVtkWriter trees("out/storm", forest);
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "io/PvdCollection.hpp"
#include "io/TreesVtk.hpp"
#include "io/writers/FrameWriter.hpp"
#include "trees/Forest.hpp"

namespace fw::io {

/// Every instance of the forest at rest in the world frame (x + s R p per node), tree_id = Forest::id (the
/// instance index, or over ranks the whole forest's).
std::vector<TreesFrame::Tree> forest_at_rest(const trees::Forest& forest);

class TreesVtkWriter : public FrameWriter {
 public:
  /// damage: the frames carry each node's stress utilisation and its tree's state (a run with damage).
  /// field_data: the site and the inventory's ids, into every frame (io/TreesVtk.hpp).
  TreesVtkWriter(std::filesystem::path directory, const trees::Forest& forest, bool damage = false,
                 const TreesFieldData& field_data = {});
  /// Over MPI ranks: `forest` is this rank's trees; it writes trees/trees_NNNNNN_RRRR.vtp, rank 0 also
  /// trees/trees_NNNNNN.pvtp listing the `ranks` pieces, and the run adds the frame to trees.pvd once every
  /// rank has written it.
  TreesVtkWriter(std::filesystem::path directory, const trees::Forest& forest, bool damage, int rank,
                 int ranks, const TreesFieldData& field_data = {});
  /// The file trees.pvd lists for frame `index`: its .vtp, or over ranks its .pvtp.
  static std::string frame_file(int index, bool pieces);

  std::string name() const override { return "trees VTK"; }
  FrameNeeds needs() const override { return {.displacement = true, .utilisation = damage_}; }
  void begin() override;
  /// In one process the .pvd keeps its frames up to the checkpoint (over ranks the run lists them).
  void resume(const OutputResume& resume) override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  bool damage_ = false;
  std::unique_ptr<TreesVtp> forest_;
  int rank_ = 0, ranks_ = 0;  // ranks_ 0: one process, no pieces
  PvdCollection collection_;
};

}  // namespace fw::io
