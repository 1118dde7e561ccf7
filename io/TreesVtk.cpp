#include "io/TreesVtk.hpp"

#include "io/SiteVtk.hpp"

#include "io/VtkXml.hpp"

#include <fmt/format.h>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace fw::io {
namespace {

void check_tree(std::size_t index, const TreesFrame::Tree& tree) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(
        fmt::format("write_trees_vtp: tree {} (id {}): {}", index, tree.tree_id, what));
  };
  const std::size_t n = std::size_t(tree.rest.rows());
  if (tree.radius.size() != n)
    fail(fmt::format("radius: expected {} values (one per node), got {}", n, tree.radius.size()));
  if (tree.parent.size() != n)
    fail(fmt::format("parent: expected {} values (one per node), got {}", n, tree.parent.size()));
  if (tree.displacement.size() != 0 && std::size_t(tree.displacement.rows()) != n) {
    fail(fmt::format("displacement: expected {} rows (one per node) or none, got {}", n,
                     tree.displacement.rows()));
  }
  if (!tree.rest.allFinite()) fail("rest: a position is not finite");
  if (!tree.displacement.allFinite()) fail("displacement: a value is not finite");
  for (std::size_t i = 0; i < n; ++i) {
    const int p = tree.parent[i];
    if (p < -1 || p >= int(n) || p == int(i)) {
      fail(fmt::format("parent of node {}: expected -1 or another node index below {}, got {}", i, n, p));
    }
  }
}

}  // namespace

struct TreesVtp::Layout {
  std::vector<float> rest;  // 3 per point, m, world frame
  vtkNew<vtkPolyData> data;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> displacement;
  vtkNew<vtkDoubleArray> time;
  // With damage: the points' utilisation and their tree's state, and each tree's first point and size.
  vtkNew<vtkFloatArray> utilisation;
  vtkNew<vtkIntArray> state;
  std::vector<vtkIdType> tree_first, tree_points;
};

TreesVtp::TreesVtp(const std::vector<TreesFrame::Tree>& trees, bool damage, const TreesFieldData& field_data)
    : layout_(std::make_unique<Layout>()) {
  vtkIdType point_count = 0, line_count = 0;
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const TreesFrame::Tree& tree = trees[t];
    check_tree(t, tree);
    point_count += tree.rest.rows();
    for (int p : tree.parent) line_count += p >= 0 ? 1 : 0;
  }

  // Float32 throughout: a forest frame holds millions of points, positions within a few km keep 0.1 mm, and
  // the files are half the size of float64 ones.
  Layout& l = *layout_;
  l.points->SetDataTypeToFloat();
  l.points->SetNumberOfPoints(point_count);
  l.displacement->SetName("displacement");
  l.displacement->SetNumberOfComponents(3);
  l.displacement->SetNumberOfTuples(point_count);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(point_count);
  vtkNew<vtkIntArray> tree_id;
  tree_id->SetName("tree_id");
  tree_id->SetNumberOfTuples(point_count);
  vtkNew<vtkIntArray> species;
  species->SetName("species");
  species->SetNumberOfTuples(point_count);
  vtkNew<vtkIntArray> node_id;
  node_id->SetName("node_id");
  node_id->SetNumberOfTuples(point_count);
  vtkNew<vtkCellArray> lines;
  lines->Use32BitStorage();  // point ids fit 32 bits up to 2^31 points; halves the connectivity
  lines->AllocateExact(line_count, 2 * line_count);

  l.rest.reserve(3 * std::size_t(point_count));
  vtkIdType first = 0;  // index of the current tree's node 0 among all points
  for (const TreesFrame::Tree& tree : trees) {
    l.tree_first.push_back(first);
    l.tree_points.push_back(tree.rest.rows());
    for (Eigen::Index i = 0; i < tree.rest.rows(); ++i) {
      const vtkIdType point = first + i;
      for (int c = 0; c < 3; ++c) l.rest.push_back(float(tree.rest(i, c)));
      radius->SetValue(point, float(tree.radius[std::size_t(i)]));
      tree_id->SetValue(point, tree.tree_id);
      species->SetValue(point, tree.species);
      node_id->SetValue(point, int(i));
      const int parent = tree.parent[std::size_t(i)];
      if (parent >= 0) lines->InsertNextCell({first + parent, point});
    }
    first += tree.rest.rows();
  }

  l.data->SetPoints(l.points);
  l.data->SetLines(lines);
  l.data->GetPointData()->AddArray(radius);
  l.data->GetPointData()->AddArray(l.displacement);
  l.data->GetPointData()->SetActiveVectors("displacement");
  l.data->GetPointData()->AddArray(tree_id);
  l.data->GetPointData()->AddArray(species);
  l.data->GetPointData()->AddArray(node_id);
  if (damage) {
    l.utilisation->SetName("utilisation");
    l.utilisation->SetNumberOfTuples(point_count);
    l.state->SetName("state");
    l.state->SetNumberOfTuples(point_count);
    l.data->GetPointData()->AddArray(l.utilisation);
    l.data->GetPointData()->AddArray(l.state);
  }
  l.time->SetName("TimeValue");
  l.time->SetNumberOfTuples(1);
  l.data->GetFieldData()->AddArray(l.time);
  if (field_data.site) add_site_field_data(*l.data->GetFieldData(), *field_data.site);
  if (!field_data.inventory_ids.empty()) {
    vtkNew<vtkStringArray> ids;
    ids->SetName("inventory_id");
    ids->SetNumberOfValues(vtkIdType(field_data.inventory_ids.size()));
    for (std::size_t t = 0; t < field_data.inventory_ids.size(); ++t)
      ids->SetValue(vtkIdType(t), field_data.inventory_ids[t]);
    l.data->GetFieldData()->AddArray(ids);
  }
}

TreesVtp::~TreesVtp() = default;

VtkArrays TreesVtp::arrays() const {
  return describe_arrays(layout_->data);
}

std::size_t TreesVtp::point_count() const {
  return layout_->rest.size() / 3;
}

void TreesVtp::write(const std::filesystem::path& path, double time, std::span<const float> displacement) {
  write(path, time, displacement, {}, {});
}

void TreesVtp::write(const std::filesystem::path& path, double time, std::span<const float> displacement,
                     std::span<const float> utilisation, std::span<const std::int32_t> state) {
  Layout& l = *layout_;
  if (l.utilisation->GetNumberOfTuples() > 0) {
    if ((!utilisation.empty() && utilisation.size() != point_count()) ||
        (!state.empty() && state.size() != l.tree_first.size()))
      throw std::invalid_argument(fmt::format(
          "write_trees_vtp: damage: expected {} utilisations (one per point) and {} states (one per tree) or "
          "none, got {} and {}",
          point_count(), l.tree_first.size(), utilisation.size(), state.size()));
    for (std::size_t v = 0; v < point_count(); ++v)
      l.utilisation->SetValue(vtkIdType(v), utilisation.empty() ? 0.0f : utilisation[v]);
    for (std::size_t t = 0; t < l.tree_first.size(); ++t)
      for (vtkIdType i = 0; i < l.tree_points[t]; ++i)
        l.state->SetValue(l.tree_first[t] + i, state.empty() ? 0 : state[t]);
  }
  const std::size_t n = point_count();
  if (!displacement.empty() && displacement.size() != 3 * n) {
    throw std::invalid_argument(
        fmt::format("write_trees_vtp: displacement: expected {} values (3 per point) or none, got {}", 3 * n,
                    displacement.size()));
  }
  float* points = static_cast<vtkFloatArray*>(l.points->GetData())->GetPointer(0);
  float* moved = l.displacement->GetPointer(0);
  for (std::size_t v = 0; v < 3 * n; ++v) {
    const float d = displacement.empty() ? 0.0f : displacement[v];
    if (!std::isfinite(d))
      throw std::invalid_argument(
          fmt::format("write_trees_vtp: displacement of point {} is not finite", v / 3));
    moved[v] = d;
    points[v] = l.rest[v] + d;
  }
  l.time->SetValue(0, time);
  // A written array keeps its range in its information, and the next write prints it (an empty information
  // element) or, for a changed value, the stale range: every array starts each write afresh, so that a
  // frame's file does not depend on the frames written before it (a resumed run writes the same bytes).
  l.points->Modified();
  vtkPointData* point_data = l.data->GetPointData();
  for (int a = 0; a < point_data->GetNumberOfArrays(); ++a) point_data->GetArray(a)->Modified();
  l.time->Modified();

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(l.data);
  write_vtk_xml("write_trees_vtp", path, writer);
}

void write_trees_vtp(const std::filesystem::path& path, const TreesFrame& frame) {
  TreesVtp forest(frame.trees);
  std::vector<float> displacement;
  bool moved = false;
  for (const TreesFrame::Tree& tree : frame.trees) moved = moved || tree.displacement.size() != 0;
  if (moved) {
    displacement.reserve(3 * forest.point_count());
    for (const TreesFrame::Tree& tree : frame.trees) {
      for (Eigen::Index i = 0; i < tree.rest.rows(); ++i) {
        for (int c = 0; c < 3; ++c)
          displacement.push_back(tree.displacement.size() != 0 ? float(tree.displacement(i, c)) : 0.0f);
      }
    }
  }
  forest.write(path, frame.time, displacement);
}

}  // namespace fw::io
