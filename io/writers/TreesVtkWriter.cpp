#include "io/writers/TreesVtkWriter.hpp"

#include <fmt/format.h>

#include <utility>

namespace fw::io {

std::vector<TreesFrame::Tree> forest_at_rest(const trees::Forest& forest) {
  std::vector<TreesFrame::Tree> rest;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& instance = forest.instances()[std::size_t(k)];
    const trees::Skeleton placed =
        forest.species_of(k).skeleton().transformed(forest.rotation(k), instance.position, instance.scale);
    TreesFrame::Tree tree;
    tree.tree_id = forest.id(k);
    tree.species = instance.species;
    tree.rest.resize(placed.size(), 3);
    for (int n = 0; n < placed.size(); ++n) {
      const trees::SkeletonNode& node = placed.node(n);
      tree.rest.row(n) = node.position.transpose();
      tree.radius.push_back(node.radius);
      tree.parent.push_back(node.parent);
    }
    rest.push_back(std::move(tree));
  }
  return rest;
}

TreesVtkWriter::TreesVtkWriter(std::filesystem::path directory, const trees::Forest& forest, bool damage,
                               const TreesFieldData& field_data)
    : directory_(std::move(directory)),
      damage_(damage),
      forest_(std::make_unique<TreesVtp>(forest_at_rest(forest), damage, field_data)),
      collection_(directory_ / "trees.pvd") {}

void TreesVtkWriter::begin() {
  std::filesystem::create_directories(directory_ / "trees");
}

TreesVtkWriter::TreesVtkWriter(std::filesystem::path directory, const trees::Forest& forest, bool damage,
                               int rank, int ranks, const TreesFieldData& field_data)
    : TreesVtkWriter(std::move(directory), forest, damage, field_data) {
  rank_ = rank;
  ranks_ = ranks;
}

void TreesVtkWriter::resume(const OutputResume& resume) {
  begin();
  if (ranks_ == 0) collection_.continue_existing(resume.time);
}

std::string TreesVtkWriter::frame_file(int index, bool pieces) {
  return fmt::format("trees/trees_{:06d}.{}", index, pieces ? "pvtp" : "vtp");
}

void TreesVtkWriter::write(const OutputFrame& frame) {
  if (ranks_ == 0) {
    const std::string file = frame_file(frame.index, false);
    forest_->write(directory_ / file, frame.time, frame.displacement, frame.utilisation, frame.tree_state);
    collection_.add(frame.time, file);
    return;
  }
  forest_->write(directory_ / "trees" / piece_file("trees", frame.index, rank_, "vtp"), frame.time,
                 frame.displacement, frame.utilisation, frame.tree_state);
  if (rank_ != 0) return;
  write_pvtp(directory_ / frame_file(frame.index, true), forest_->arrays(),
             piece_files("trees", frame.index, ranks_, "vtp"));
}

}  // namespace fw::io
