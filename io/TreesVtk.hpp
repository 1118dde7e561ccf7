// VTK XML PolyData (.vtp) writer for the whole forest at one output time, at the deformed positions.
//
//   fw::io::TreesFrame frame;
//   frame.time = 12.5;
//   frame.trees.push_back({/*tree_id=*/0, /*species=*/0, rest, radius, parent, displacement});
//   fw::io::write_trees_vtp("out/trees/trees_000025.vtp", frame);
//
// A run writes the same forest every frame: TreesVtp builds the parts that never change (cells, radius,
// ids) once, and each write() fills only the points and the displacement.
//   fw::io::TreesVtp forest(frame.trees);                   // rest geometry; displacements ignored
//   forest.write("out/trees/trees_000026.vtp", 13.0, u);    // u: 3 floats per point, m
//
// ParaView: open trees.pvd (see PvdCollection.hpp), Apply; Filters > Tube (Vary Radius: By Absolute Scalar,
// scalars "radius", factor 1) draws the branches at their real thickness; colour by "tree_id" or
// "displacement". Warp By Vector on "displacement" with scale factor -1 shows the rest shape, with e.g. 10 an
// exaggerated sway.
//
// Layout: a single vtkPolyData holding all trees. Points (float32, m, world frame) are the DEFORMED node
// positions, rest + displacement, tree after tree in frame order (tree t's nodes follow those of trees
// 0..t-1, in that tree's node order). Cells: one 2-point line per element (parent node, child node), per tree
// in node order of the child. Lines rather than one polyline per branch chain keep the file a direct image of
// the elements; Tube then draws one segment per element, the segments meeting at the shared points.
// Point arrays:
//   radius        float32, m
//   displacement  float32 x 3, m (deformed minus rest)   [the active vectors]
//   tree_id       int32, the tree's id (TreesFrame::Tree::tree_id)
//   species       int32, the species index
//   node_id       int32, the node's index within its tree
// Field data: "TimeValue" (float64, 1 tuple, s); with a site, site_origin, site_epsg and site_crs
// (io/SiteVtk.hpp); with a forest inventory, "inventory_id" (String, one per tree of the whole forest, in
// tree_id order: tree t's id in the inventory, "" for a tree not from it).
// Files are binary (appended raw data, LZ4, 64-bit headers; io/VtkXml) and written through AtomicFile.
#pragma once

#include <memory>
#include <span>

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>

#include <optional>
#include <string>
#include <vector>
#include "io/ParallelVtk.hpp"
#include "io/settings/SiteSettings.hpp"

namespace fw::io {

struct TreesFrame {
  struct Tree {
    int tree_id = 0;                ///< id shown in the files (e.g. the instance index of the forest)
    int species = 0;                ///< species index
    Eigen::MatrixX3d rest;          ///< #nodes x 3, m: node positions at rest, world frame
    std::vector<double> radius;     ///< #nodes, m
    std::vector<int> parent;        ///< #nodes, parent node index within the tree, -1 for the root
    Eigen::MatrixX3d displacement;  ///< #nodes x 3, m: current translation of each node (empty = at rest)
  };
  double time = 0.0;  ///< s
  std::vector<Tree> trees;
};

/// Writes `frame` as described above. An empty forest gives a valid file without points.
/// Throws std::invalid_argument("write_trees_vtp: tree K (id I): ...") when radius, parent or displacement do
/// not have one entry (row) per rest node, a parent index lies outside -1..n-1 or is the node itself, or a
/// position or displacement is not finite; std::runtime_error naming the path when the folder does not exist
/// or the file cannot be written (no partial file or temporary is left behind).
void write_trees_vtp(const std::filesystem::path& path, const TreesFrame& frame);

/// The field data a trees frame carries besides its time (the header's list).
struct TreesFieldData {
  std::optional<SiteSettings> site;
  std::vector<std::string> inventory_ids;  ///< by tree_id; empty: none written
};

class TreesVtp {
 public:
  /// The static part of the layout from the trees' rest, radius and parent (their displacement is ignored).
  /// damage: the frames also carry each point's stress `utilisation` and its tree's `state` (0 standing, 1
  /// broken, 2 overturned: trees::TreeState; docs/damage.md). Throws std::invalid_argument
  /// ("write_trees_vtp: tree K (id I): ...") as write_trees_vtp does.
  explicit TreesVtp(const std::vector<TreesFrame::Tree>& trees, bool damage = false,
                    const TreesFieldData& field_data = {});
  ~TreesVtp();
  TreesVtp(const TreesVtp&) = delete;
  TreesVtp& operator=(const TreesVtp&) = delete;

  /// Number of points: every node of every tree.
  std::size_t point_count() const;
  /// The arrays every write() writes, as a .pvtp declares them (io/ParallelVtk.hpp).
  VtkArrays arrays() const;

  /// Writes one frame at `time` (s). displacement: 3 floats per point in point order (m), or empty for the
  /// rest shape. Throws std::invalid_argument("write_trees_vtp: ...") for another size or a non-finite
  /// value, std::runtime_error as write_trees_vtp.
  void write(const std::filesystem::path& path, double time, std::span<const float> displacement);
  /// The same with the damage arrays (a layout made with damage): utilisation one float per point, state
  /// one int per tree, each empty for zeros. Throws std::invalid_argument for other sizes.
  void write(const std::filesystem::path& path, double time, std::span<const float> displacement,
             std::span<const float> utilisation, std::span<const std::int32_t> state);

 private:
  struct Layout;
  std::unique_ptr<Layout> layout_;
};

}  // namespace fw::io
