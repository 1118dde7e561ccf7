#include "io/TreesVtk.hpp"

#include "io/WindVtk.hpp"

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
#include <vtkXMLPolyDataWriter.h>

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

void write_trees_vtp(const std::filesystem::path& path, const TreesFrame& frame) {
  vtkIdType point_count = 0, line_count = 0;
  for (std::size_t t = 0; t < frame.trees.size(); ++t) {
    const TreesFrame::Tree& tree = frame.trees[t];
    check_tree(t, tree);
    point_count += tree.rest.rows();
    for (int p : tree.parent) line_count += p >= 0 ? 1 : 0;
  }

  // Float32 throughout: a forest frame holds millions of points, positions within a few km keep 0.1 mm, and
  // the files are half the size of float64 ones.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(point_count);
  vtkNew<vtkFloatArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(point_count);
  vtkNew<vtkFloatArray> displacement;
  displacement->SetName("displacement");
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(point_count);
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

  vtkIdType first = 0;  // index of the current tree's node 0 among all points
  for (const TreesFrame::Tree& tree : frame.trees) {
    const bool moved = tree.displacement.size() != 0;
    for (Eigen::Index i = 0; i < tree.rest.rows(); ++i) {
      const vtkIdType point = first + i;
      double d[3] = {0.0, 0.0, 0.0};
      if (moved) {
        for (int c = 0; c < 3; ++c) d[c] = tree.displacement(i, c);
      }
      points->SetPoint(point, tree.rest(i, 0) + d[0], tree.rest(i, 1) + d[1], tree.rest(i, 2) + d[2]);
      radius->SetValue(point, float(tree.radius[std::size_t(i)]));
      const float d_float[3] = {float(d[0]), float(d[1]), float(d[2])};
      displacement->SetTypedTuple(point, d_float);
      tree_id->SetValue(point, tree.tree_id);
      species->SetValue(point, tree.species);
      node_id->SetValue(point, int(i));
      const int parent = tree.parent[std::size_t(i)];
      if (parent >= 0) lines->InsertNextCell({first + parent, point});
    }
    first += tree.rest.rows();
  }

  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  data->GetPointData()->AddArray(radius);
  data->GetPointData()->AddArray(displacement);
  data->GetPointData()->SetActiveVectors("displacement");
  data->GetPointData()->AddArray(tree_id);
  data->GetPointData()->AddArray(species);
  data->GetPointData()->AddArray(node_id);

  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->SetNumberOfTuples(1);
  time->SetValue(0, frame.time);
  data->GetFieldData()->AddArray(time);

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  detail::write_vtk_xml("write_trees_vtp", path, writer);
}

}  // namespace fw::io
