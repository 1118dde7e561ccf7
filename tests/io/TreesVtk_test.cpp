#include "io/TreesVtk.hpp"

#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using fw::io::TreesFrame;

namespace {

using fw::test::has_temporary;
using fw::test::read_vtp;

// Tree A (id 7, species 0): root 0 -> 1 -> {2, 3}. Tree B (id 12, species 1): listed child first, 1 -> 0.
TreesFrame two_trees() {
  TreesFrame frame;
  frame.time = 3.5;
  TreesFrame::Tree a;
  a.tree_id = 7;
  a.species = 0;
  a.rest.resize(4, 3);
  a.rest << 10.0, 20.0, 0.0, 10.0, 20.0, 5.0, 11.0, 20.0, 7.0, 9.5, 20.5, 6.5;
  a.radius = {0.3, 0.2, 0.05, 0.04};
  a.parent = {-1, 0, 1, 1};
  a.displacement.resize(4, 3);
  a.displacement << 0.0, 0.0, 0.0, 0.01, -0.002, 0.0, 0.05, 0.01, -0.003, 0.04, 0.012, -0.001;
  TreesFrame::Tree b;
  b.tree_id = 12;
  b.species = 1;
  b.rest.resize(2, 3);
  b.rest << 30.0, 5.0, 8.0, 30.0, 5.0, 1.0;
  b.radius = {0.1, 0.25};
  b.parent = {1, -1};
  b.displacement.resize(2, 3);
  b.displacement << 0.125, 0.0, -0.0625, 0.0, 0.0, 0.0;
  frame.trees = {a, b};
  return frame;
}

}  // namespace

TEST_CASE("write_trees_vtp: deformed points, element lines and point arrays read back", "[output]") {
  fw::test::TempDir dir("fw_out");
  const TreesFrame frame = two_trees();
  const fs::path path = fs::path(dir.path()) / "trees_000007.vtp";
  fw::io::write_trees_vtp(path, frame);
  CHECK_FALSE(has_temporary(dir.path()));

  const auto data = read_vtp(path);
  REQUIRE(data->GetNumberOfPoints() == 6);
  vtkPointData* pd = data->GetPointData();
  vtkDataArray* radius = pd->GetArray("radius");
  vtkDataArray* displacement = pd->GetArray("displacement");
  vtkDataArray* tree_id = pd->GetArray("tree_id");
  vtkDataArray* species = pd->GetArray("species");
  vtkDataArray* node_id = pd->GetArray("node_id");
  REQUIRE(radius != nullptr);
  REQUIRE(displacement != nullptr);
  REQUIRE(tree_id != nullptr);
  REQUIRE(species != nullptr);
  REQUIRE(node_id != nullptr);
  CHECK(radius->GetDataType() == VTK_FLOAT);
  CHECK(displacement->GetDataType() == VTK_FLOAT);
  CHECK(displacement->GetNumberOfComponents() == 3);
  CHECK(tree_id->GetDataType() == VTK_INT);
  CHECK(species->GetDataType() == VTK_INT);
  REQUIRE(pd->GetVectors() != nullptr);
  CHECK(std::string(pd->GetVectors()->GetName()) == "displacement");

  vtkIdType point = 0;
  for (const TreesFrame::Tree& tree : frame.trees) {
    for (Eigen::Index i = 0; i < tree.rest.rows(); ++i, ++point) {
      INFO("tree " << tree.tree_id << " node " << i);
      double p[3];
      data->GetPoint(point, p);
      for (int c = 0; c < 3; ++c) {
        // Exact: float64 points hold rest + displacement as computed in double.
        // Stored as float32: exact to float rounding of the double sum.
        CHECK(p[c] == double(float(tree.rest(i, c) + tree.displacement(i, c))));
        CHECK(displacement->GetComponent(point, c) == double(float(tree.displacement(i, c))));
      }
      CHECK(radius->GetTuple1(point) == double(float(tree.radius[std::size_t(i)])));
      CHECK(tree_id->GetTuple1(point) == tree.tree_id);
      CHECK(species->GetTuple1(point) == tree.species);
      CHECK(node_id->GetTuple1(point) == double(i));
    }
  }

  // One line per element, (parent, child), in global point ids, child node order within each tree.
  REQUIRE(data->GetNumberOfLines() == 4);
  CHECK(data->GetNumberOfPolys() == 0);
  const std::vector<std::pair<vtkIdType, vtkIdType>> expected = {{0, 1}, {1, 2}, {1, 3}, {5, 4}};
  vtkNew<vtkIdList> ids;
  vtkCellArray* lines = data->GetLines();
  for (vtkIdType k = 0; k < 4; ++k) {
    lines->GetCellAtId(k, ids);
    REQUIRE(ids->GetNumberOfIds() == 2);
    CHECK(std::make_pair(ids->GetId(0), ids->GetId(1)) == expected[std::size_t(k)]);
  }

  vtkDataArray* time = data->GetFieldData()->GetArray("TimeValue");
  REQUIRE(time != nullptr);
  CHECK(time->GetTuple1(0) == 3.5);
}

TEST_CASE("write_trees_vtp: an empty forest and a tree without displacement are valid", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "trees.vtp";
  TreesFrame empty;
  empty.time = 1.0;
  fw::io::write_trees_vtp(path, empty);
  auto data = read_vtp(path);
  CHECK(data->GetNumberOfPoints() == 0);
  CHECK(data->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == 1.0);

  TreesFrame still = two_trees();
  still.trees[0].displacement.resize(0, 3);  // "at rest"
  fw::io::write_trees_vtp(path, still);
  data = read_vtp(path);
  double p[3];
  data->GetPoint(2, p);
  CHECK(p[0] == 11.0);
  CHECK(p[2] == 7.0);
  CHECK(data->GetPointData()->GetArray("displacement")->GetComponent(2, 0) == 0.0);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("write_trees_vtp: inconsistent trees throw invalid_argument, a missing folder runtime_error",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "trees.vtp";
  TreesFrame frame = two_trees();
  frame.trees[1].radius.pop_back();
  CHECK_THROWS_MATCHES(
      fw::io::write_trees_vtp(path, frame), std::invalid_argument,
      Catch::Matchers::Message(
          "write_trees_vtp: tree 1 (id 12): radius: expected 2 values (one per node), got 1"));
  frame = two_trees();
  frame.trees[0].parent[2] = 4;
  CHECK_THROWS_AS(fw::io::write_trees_vtp(path, frame), std::invalid_argument);
  frame = two_trees();
  frame.trees[0].displacement.resize(3, 3);
  CHECK_THROWS_AS(fw::io::write_trees_vtp(path, frame), std::invalid_argument);
  CHECK_FALSE(fs::exists(path));

  const fs::path missing = fs::path(dir.path()) / "trees" / "trees_000000.vtp";
  CHECK_THROWS_MATCHES(
      fw::io::write_trees_vtp(missing, two_trees()), std::runtime_error,
      Catch::Matchers::Message("write_trees_vtp: cannot write " + missing.string() + ": the folder " +
                               missing.parent_path().string() + " does not exist"));
  CHECK(fs::is_empty(dir.path()));
}
