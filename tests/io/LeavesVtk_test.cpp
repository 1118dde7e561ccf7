// The leaves' .vtp (io/LeavesVtk) read back with VTK, and the leaves.pvd series of LeavesVtkWriter.
#include "io/LeavesVtk.hpp"

#include "io/writers/LeavesVtkWriter.hpp"
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

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;
using fw::io::LeafFrame;

namespace {

using fw::test::file_text;
using fw::test::has_temporary;
using fw::test::pvd_datasets;
using fw::test::read_vtp;

// Four leaves of two trees in every state a run writes (and one exited, which the format accepts), with
// values that need all of a float's bits.
LeafFrame four_leaves() {
  LeafFrame leaves;
  leaves.position = {{10.125f, 20.0f, 5.5f},
                     {11.0f / 3.0f, -2.718281828f, 7.25f},
                     {0.1f, 0.2f, 0.0f},
                     {1234.5678f, 987.65432f, 31.0f}};
  const float r = 1.0f / std::sqrt(3.0f);
  leaves.normal = {{0.0f, 0.0f, 1.0f}, {r, r, r}, {0.6f, 0.0f, 0.8f}, {-1.0f, 0.0f, 0.0f}};
  leaves.state = {0, 1, 2, 3};
  leaves.tree_id = {7, 7, 12, 2147483647};
  leaves.side = {0.07f, 0.0316227766f, 0.05f, 0.1f};
  leaves.counts = {.shed = 3, .flying = 1, .landed = 1, .exited = 1, .attached = 5};
  return leaves;
}

// The (timestep, file) attributes of every <DataSet> of a .pvd, in file order.
std::vector<std::pair<double, std::string>> pvd_entries(const fs::path& path) {
  const std::string text = file_text(path);
  REQUIRE(text.find("<VTKFile type=\"Collection\"") != std::string::npos);
  return pvd_datasets(text);
}

}  // namespace

TEST_CASE("leaves vtk: points, one vertex each, and every point array read back with its type", "[output]") {
  fw::test::TempDir dir("fw_out");
  const LeafFrame leaves = four_leaves();
  const fs::path path = fs::path(dir.path()) / "leaves_000004.vtp";
  fw::io::write_leaves_vtp(path, 2.75, leaves);
  CHECK_FALSE(has_temporary(dir.path()));

  const auto data = read_vtp(path);
  REQUIRE(data->GetNumberOfPoints() == 4);
  CHECK(data->GetPoints()->GetDataType() == VTK_FLOAT);
  vtkPointData* pd = data->GetPointData();
  vtkDataArray* normal = pd->GetArray("normal");
  vtkDataArray* state = pd->GetArray("state");
  vtkDataArray* tree_id = pd->GetArray("tree_id");
  vtkDataArray* size = pd->GetArray("size");
  REQUIRE(normal != nullptr);
  REQUIRE(state != nullptr);
  REQUIRE(tree_id != nullptr);
  REQUIRE(size != nullptr);
  CHECK(pd->GetNumberOfArrays() == 4);
  CHECK(normal->GetDataType() == VTK_FLOAT);
  CHECK(normal->GetNumberOfComponents() == 3);
  CHECK(state->GetDataType() == VTK_UNSIGNED_CHAR);
  CHECK(state->GetNumberOfComponents() == 1);
  CHECK(tree_id->GetDataType() == VTK_INT);
  CHECK(size->GetDataType() == VTK_FLOAT);
  CHECK(size->GetNumberOfComponents() == 1);
  REQUIRE(pd->GetNormals() != nullptr);
  CHECK(std::string(pd->GetNormals()->GetName()) == "normal");

  for (vtkIdType k = 0; k < 4; ++k) {
    INFO("leaf " << k);
    const std::size_t i = std::size_t(k);
    double p[3];
    data->GetPoint(k, p);
    for (int c = 0; c < 3; ++c) {
      // Exact: float32 in, float32 stored, read back as double.
      CHECK(p[c] == double(leaves.position[i][std::size_t(c)]));
      CHECK(normal->GetComponent(k, c) == double(leaves.normal[i][std::size_t(c)]));
    }
    CHECK(state->GetTuple1(k) == double(leaves.state[i]));
    CHECK(tree_id->GetTuple1(k) == double(leaves.tree_id[i]));
    CHECK(size->GetTuple1(k) == double(leaves.side[i]));
  }

  // One vertex cell per point, vertex k holding point k, and no other cells.
  REQUIRE(data->GetNumberOfVerts() == 4);
  CHECK(data->GetNumberOfLines() == 0);
  CHECK(data->GetNumberOfPolys() == 0);
  CHECK(data->GetNumberOfCells() == 4);
  vtkNew<vtkIdList> ids;
  for (vtkIdType k = 0; k < 4; ++k) {
    data->GetVerts()->GetCellAtId(k, ids);
    REQUIRE(ids->GetNumberOfIds() == 1);
    CHECK(ids->GetId(0) == k);
  }

  vtkDataArray* time = data->GetFieldData()->GetArray("TimeValue");
  REQUIRE(time != nullptr);
  CHECK(time->GetDataType() == VTK_DOUBLE);
  CHECK(time->GetTuple1(0) == 2.75);
}

TEST_CASE("leaves vtk: an empty leaf frame gives a valid file without points", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "leaves.vtp";
  LeafFrame empty;
  empty.counts.attached = 100;  // counts alone write nothing
  fw::io::write_leaves_vtp(path, 1.5, empty);
  const auto data = read_vtp(path);
  CHECK(data->GetNumberOfPoints() == 0);
  CHECK(data->GetNumberOfVerts() == 0);
  REQUIRE(data->GetFieldData()->GetArray("TimeValue") != nullptr);
  CHECK(data->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == 1.5);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("leaves vtk: inconsistent leaves throw invalid_argument, a missing folder runtime_error",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "leaves.vtp";
  LeafFrame leaves = four_leaves();
  leaves.side.pop_back();
  CHECK_THROWS_MATCHES(
      fw::io::write_leaves_vtp(path, 0.0, leaves), std::invalid_argument,
      Catch::Matchers::Message("write_leaves_vtp: leaves: size: expected 4 values (one per leaf), got 3"));
  leaves = four_leaves();
  leaves.tree_id.push_back(1);
  CHECK_THROWS_AS(fw::io::write_leaves_vtp(path, 0.0, leaves), std::invalid_argument);
  leaves = four_leaves();
  leaves.normal[2][1] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_MATCHES(fw::io::write_leaves_vtp(path, 0.0, leaves), std::invalid_argument,
                       Catch::Matchers::Message("write_leaves_vtp: leaves: normal of leaf 2 is not finite"));
  leaves = four_leaves();
  leaves.position[0][2] = std::numeric_limits<float>::infinity();
  CHECK_THROWS_AS(fw::io::write_leaves_vtp(path, 0.0, leaves), std::invalid_argument);
  leaves = four_leaves();
  leaves.state[1] = 4;
  CHECK_THROWS_MATCHES(
      fw::io::write_leaves_vtp(path, 0.0, leaves), std::invalid_argument,
      Catch::Matchers::Message("write_leaves_vtp: leaves: state of leaf 1: expected 0 to 3, got 4"));
  CHECK_FALSE(fs::exists(path));

  const fs::path missing = fs::path(dir.path()) / "leaves" / "leaves_000000.vtp";
  CHECK_THROWS_MATCHES(
      fw::io::write_leaves_vtp(missing, 0.0, four_leaves()), std::runtime_error,
      Catch::Matchers::Message("write_leaves_vtp: cannot write " + missing.string() + ": the folder " +
                               missing.parent_path().string() + " does not exist"));
  CHECK(fs::is_empty(dir.path()));
}

TEST_CASE("leaves vtk writer: leaves.pvd lists every frame's file in the leaves folder at its time",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path out = fs::path(dir.path()) / "run";
  fw::io::LeavesVtkWriter writer(out);
  CHECK(writer.needs().leaves);
  CHECK_FALSE(writer.needs().velocity);
  CHECK_FALSE(writer.needs().displacement);
  writer.begin();
  CHECK(fs::is_directory(out / "leaves"));

  fw::io::OutputFrame frame;
  frame.index = 0;
  frame.time = 0.5;
  frame.leaves = four_leaves();
  writer.write(frame);
  frame.index = 1;
  frame.time = 1.25;
  frame.leaves.position.resize(2);  // two leaves fewer: the written set changes between frames
  frame.leaves.normal.resize(2);
  frame.leaves.state.resize(2);
  frame.leaves.tree_id.resize(2);
  frame.leaves.side.resize(2);
  writer.write(frame);
  writer.finish(fw::io::RunOutcome{});

  const std::vector<std::pair<double, std::string>> expected = {{0.5, "leaves/leaves_000000.vtp"},
                                                                {1.25, "leaves/leaves_000001.vtp"}};
  CHECK(pvd_entries(out / "leaves.pvd") == expected);
  CHECK(read_vtp(out / "leaves/leaves_000000.vtp")->GetNumberOfPoints() == 4);
  const auto second = read_vtp(out / "leaves/leaves_000001.vtp");
  CHECK(second->GetNumberOfPoints() == 2);
  CHECK(second->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == 1.25);
  CHECK_FALSE(has_temporary(out / "leaves"));
  CHECK_FALSE(has_temporary(out));
}
