#include "io/SkeletonVtk.hpp"

#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

using fw::io::ModeShape;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
namespace fs = std::filesystem;

namespace {

using fw::test::file_text;
using fw::test::has_temporary;
using fw::test::read_vtp;

// A Y-shaped tree listed with children before parents, so that elements() order differs from node order.
// Height 4 m (root at z = 0, highest tip at z = 4).
Skeleton y_tree() {
  return Skeleton::from_nodes({
      {3, {1.0, 0.0, 4.0}, 0.05},           // 0: left tip
      {-1, {0.0, 0.0, 0.0}, 0.30},          // 1: root
      {1, {0.0, 0.0, 2.0}, 0.20},           // 2: trunk
      {2, {0.125, -0.25, 3.0}, 0.1234567},  // 3: fork
      {3, {-1.0, 0.5, 3.5}, 0.05},          // 4: right tip
  });
}

// A synthetic "mode": a smooth, node-dependent shape with the root row zero, scaled by `size`.
Eigen::MatrixX3d synthetic_shape(const Skeleton& skeleton, int mode, double size) {
  Eigen::MatrixX3d u(skeleton.size(), 3);
  for (int i = 0; i < skeleton.size(); ++i) {
    const Eigen::Vector3d p = skeleton.node(i).position;
    u.row(i) << std::sin(0.7 * (mode + 1) * p.z()) + 0.1 * i, std::cos(0.3 * mode * p.z()) * p.x() - 0.2,
        0.05 * (mode + 1) * p.z() * p.y();
  }
  u.row(skeleton.root()).setZero();
  return size * u;
}

// Names of everything in `folder` (the test's own folder, so nothing else lives there).
std::vector<std::string> entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  return names;
}

// Checks the geometry, topology and node/element arrays of `data` against the skeleton.
void check_skeleton(vtkPolyData* data, const Skeleton& skeleton) {
  const int n = skeleton.size();
  REQUIRE(data->GetNumberOfPoints() == n);
  REQUIRE(data->GetNumberOfLines() == vtkIdType(skeleton.elements().size()));
  REQUIRE(data->GetNumberOfCells() == vtkIdType(skeleton.elements().size()));  // lines only
  CHECK(data->GetPoints()->GetDataType() == VTK_DOUBLE);

  vtkDataArray* radius = data->GetPointData()->GetArray("radius");
  vtkDataArray* node_id = data->GetPointData()->GetArray("node_id");
  vtkDataArray* parent = data->GetPointData()->GetArray("parent");
  REQUIRE(radius != nullptr);
  REQUIRE(node_id != nullptr);
  REQUIRE(parent != nullptr);
  CHECK(radius->GetDataType() == VTK_DOUBLE);
  CHECK(node_id->GetDataType() == VTK_INT);
  CHECK(parent->GetDataType() == VTK_INT);
  for (int i = 0; i < n; ++i) {
    const SkeletonNode& node = skeleton.node(i);
    double p[3];
    data->GetPoint(i, p);
    for (int c = 0; c < 3; ++c) CHECK(p[c] == Approx(node.position[c]).margin(1e-12));
    CHECK(radius->GetTuple1(i) == Approx(node.radius).margin(1e-12));
    CHECK(node_id->GetTuple1(i) == i);
    CHECK(parent->GetTuple1(i) == node.parent);
  }

  vtkDataArray* element = data->GetCellData()->GetArray("element");
  REQUIRE(element != nullptr);
  CHECK(element->GetDataType() == VTK_INT);
  vtkNew<vtkIdList> ids;
  for (std::size_t k = 0; k < skeleton.elements().size(); ++k) {
    data->GetCellPoints(vtkIdType(k), ids);
    REQUIRE(ids->GetNumberOfIds() == 2);
    CHECK(ids->GetId(0) == skeleton.elements()[k].first);
    CHECK(ids->GetId(1) == skeleton.elements()[k].second);
    CHECK(element->GetTuple1(vtkIdType(k)) == double(k));
  }
}

// The what() of the std::runtime_error that `write` throws; fails the test when it throws nothing or another
// type.
template <class Write>
std::string runtime_error_of(Write write) {
  try {
    write();
  } catch (const std::runtime_error& error) {
    return error.what();
  } catch (...) {
    FAIL("threw something other than std::runtime_error");
  }
  FAIL("did not throw");
  return {};
}

}  // namespace

TEST_CASE("write_skeleton_vtp: points, lines and arrays read back equal to the skeleton", "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "skeleton.vtp";
  fw::io::write_skeleton_vtp(path, skeleton);

  auto data = read_vtp(path);
  check_skeleton(data, skeleton);
  // The root's parent is -1 and the elements run parent -> child (node 1 is the root here).
  CHECK(data->GetPointData()->GetArray("parent")->GetTuple1(1) == -1);

  // Binary appended, raw and LZ4-compressed (io/VtkXml): what ParaView reads fastest.
  const std::string text = file_text(path);
  CHECK(text.find("format=\"appended\"") != std::string::npos);
  CHECK(text.find("encoding=\"raw\"") != std::string::npos);
  CHECK(text.find("compressor=\"vtkLZ4DataCompressor\"") != std::string::npos);
  CHECK(text.find("format=\"ascii\"") == std::string::npos);
}

TEST_CASE("write_modes_vtp: each mode peaks at the display amplitude along the input directions", "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const int n = skeleton.size();
  std::vector<ModeShape> modes;
  for (int j = 0; j < 4; ++j) {
    // M-normalised shapes have wildly different sizes; the writer must equalise them.
    modes.push_back(
        {1.25 + 3.5 * j, 0.01 + 0.013 * j, synthetic_shape(skeleton, j, std::pow(10.0, 2 - 2 * j))});
  }
  const double amplitude = 0.37;
  const fs::path path = fs::path(dir.path()) / "modes.vtp";
  fw::io::write_modes_vtp(path, skeleton, modes, amplitude);

  auto data = read_vtp(path);
  check_skeleton(data, skeleton);

  vtkFieldData* field = data->GetFieldData();
  vtkDataArray* frequencies = field->GetArray("frequencies_hz");
  vtkDataArray* damping = field->GetArray("damping_ratios");
  vtkDataArray* scales = field->GetArray("modal_scale");
  REQUIRE(frequencies != nullptr);
  REQUIRE(damping != nullptr);
  REQUIRE(scales != nullptr);
  REQUIRE(frequencies->GetNumberOfTuples() == 4);
  REQUIRE(damping->GetNumberOfTuples() == 4);
  REQUIRE(scales->GetNumberOfTuples() == 4);

  const char* names[] = {"mode_01", "mode_02", "mode_03", "mode_04"};
  for (int j = 0; j < 4; ++j) {
    INFO("mode " << names[j]);
    CHECK(frequencies->GetTuple1(j) == modes[std::size_t(j)].frequency_hz);  // binary float64: exact
    CHECK(damping->GetTuple1(j) == modes[std::size_t(j)].damping_ratio);
    const double scale = scales->GetTuple1(j);
    CHECK(scale > 0.0);

    vtkDataArray* shape = data->GetPointData()->GetArray(names[j]);
    REQUIRE(shape != nullptr);
    CHECK(shape->GetDataType() == VTK_DOUBLE);
    REQUIRE(shape->GetNumberOfComponents() == 3);
    REQUIRE(shape->GetNumberOfTuples() == n);

    const Eigen::MatrixX3d& input = modes[std::size_t(j)].displacement;
    double largest = 0.0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d stored(shape->GetComponent(i, 0), shape->GetComponent(i, 1),
                                   shape->GetComponent(i, 2));
      const Eigen::Vector3d original = input.row(i).transpose();
      largest = std::max(largest, stored.norm());
      // modal_scale * input = stored, and so the direction of each nodal vector is kept.
      for (int c = 0; c < 3; ++c) CHECK(stored[c] == scale * original[c]);
      if (original.norm() > 0.0) {
        CHECK(stored.normalized().dot(original.normalized()) == Approx(1.0).epsilon(1e-12));
      } else {
        CHECK(stored.norm() == 0.0);
      }
    }
    CHECK(largest == Approx(amplitude).epsilon(1e-9));
  }
  CHECK(data->GetPointData()->GetArray("mode_05") == nullptr);
  // The first mode is the active vectors array, so Warp By Vector picks it by default.
  REQUIRE(data->GetPointData()->GetVectors() != nullptr);
  CHECK(std::string(data->GetPointData()->GetVectors()->GetName()) == "mode_01");
}

TEST_CASE("write_modes_vtp: the default amplitude is 10% of the skeleton height", "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  REQUIRE(skeleton.height() == 4.0);
  const fs::path path = fs::path(dir.path()) / "modes.vtp";
  const Eigen::MatrixX3d input = synthetic_shape(skeleton, 1, 3.0e-3);
  fw::io::write_modes_vtp(path, skeleton, {{2.0, 0.05, input}});

  auto data = read_vtp(path);
  vtkDataArray* shape = data->GetPointData()->GetArray("mode_01");
  REQUIRE(shape != nullptr);
  double largest = 0.0;
  for (int i = 0; i < skeleton.size(); ++i) {
    double u[3];
    shape->GetTuple(i, u);
    largest = std::max(largest, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
  }
  CHECK(largest == Approx(0.4).epsilon(1e-9));
  CHECK(data->GetFieldData()->GetArray("modal_scale")->GetTuple1(0) ==
        Approx(0.4 / input.rowwise().norm().maxCoeff()).epsilon(1e-12));
}

TEST_CASE("write_modes_vtp: a zero mode gets modal_scale 0 and an all-zero array", "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "modes.vtp";
  std::vector<ModeShape> modes = {{0.0, 0.05, Eigen::MatrixX3d::Zero(skeleton.size(), 3)},
                                  {3.0, 0.02, synthetic_shape(skeleton, 2, 1.0)}};
  fw::io::write_modes_vtp(path, skeleton, modes, 0.5);

  auto data = read_vtp(path);
  vtkDataArray* scales = data->GetFieldData()->GetArray("modal_scale");
  REQUIRE(scales != nullptr);
  CHECK(scales->GetTuple1(0) == 0.0);
  CHECK(scales->GetTuple1(1) > 0.0);
  vtkDataArray* zero = data->GetPointData()->GetArray("mode_01");
  REQUIRE(zero != nullptr);
  for (int i = 0; i < skeleton.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      CHECK(std::isfinite(zero->GetComponent(i, c)));
      CHECK(zero->GetComponent(i, c) == 0.0);
    }
  }
}

TEST_CASE("write_modes_vtp: mode arrays get three-digit names from 100 modes on", "[vtk]") {
  CHECK(fw::io::mode_array_name(0, 1) == "mode_01");
  CHECK(fw::io::mode_array_name(8, 99) == "mode_09");
  CHECK(fw::io::mode_array_name(98, 99) == "mode_99");
  CHECK(fw::io::mode_array_name(0, 100) == "mode_001");
  CHECK(fw::io::mode_array_name(99, 100) == "mode_100");
  CHECK(fw::io::mode_array_name(1233, 1500) == "mode_1234");

  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  std::vector<ModeShape> modes;
  for (int j = 0; j < 100; ++j) modes.push_back({1.0 + j, 0.05, synthetic_shape(skeleton, j, 1.0 + j)});
  const fs::path path = fs::path(dir.path()) / "modes.vtp";
  fw::io::write_modes_vtp(path, skeleton, modes, 0.25);

  auto data = read_vtp(path);
  CHECK(data->GetPointData()->GetArray("mode_001") != nullptr);
  CHECK(data->GetPointData()->GetArray("mode_042") != nullptr);
  CHECK(data->GetPointData()->GetArray("mode_100") != nullptr);
  CHECK(data->GetPointData()->GetArray("mode_01") == nullptr);
  CHECK(data->GetFieldData()->GetArray("frequencies_hz")->GetNumberOfTuples() == 100);
  CHECK(data->GetFieldData()->GetArray("frequencies_hz")->GetTuple1(99) == 100.0);
}

TEST_CASE("write_modes_vtp: a displacement with the wrong row count throws invalid_argument", "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "modes.vtp";
  std::vector<ModeShape> modes = {{1.0, 0.05, synthetic_shape(skeleton, 0, 1.0)},
                                  {2.0, 0.05, Eigen::MatrixX3d::Ones(skeleton.size() - 1, 3)}};
  CHECK_THROWS_MATCHES(fw::io::write_modes_vtp(path, skeleton, modes), std::invalid_argument,
                       Catch::Matchers::Predicate<std::invalid_argument>([](const std::invalid_argument& e) {
                         const std::string what = e.what();
                         return what.rfind("write_modes_vtp: ", 0) == 0 &&
                                what.find("mode_02") != std::string::npos;
                       }));
  // Non-finite shapes and bad amplitudes are rejected too.
  modes[1].displacement = synthetic_shape(skeleton, 1, 1.0);
  modes[1].displacement(2, 1) = std::nan("");
  CHECK_THROWS_AS(fw::io::write_modes_vtp(path, skeleton, modes), std::invalid_argument);
  modes[1].displacement = synthetic_shape(skeleton, 1, 1.0);
  CHECK_THROWS_AS(fw::io::write_modes_vtp(path, skeleton, modes, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(fw::io::write_modes_vtp(path, skeleton, modes, INFINITY), std::invalid_argument);
  CHECK_THROWS_AS(fw::io::write_skeleton_vtp(path, Skeleton()), std::invalid_argument);
  CHECK(entries(dir.path()).empty());
}

TEST_CASE("write_skeleton_vtp: a successful write leaves no temporary file and replaces the old one",
          "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "skeleton.vtp";
  dir.write("skeleton.vtp", "an old, unrelated file");
  fw::io::write_skeleton_vtp(path, skeleton);
  fw::io::write_modes_vtp(fs::path(dir.path()) / "modes.vtp", skeleton,
                          {{1.0, 0.05, synthetic_shape(skeleton, 0, 1.0)}});
  CHECK_FALSE(has_temporary(dir.path()));
  CHECK(entries(dir.path()).size() == 2);
  check_skeleton(read_vtp(path), skeleton);

  // A relative path (no folder part) is written in the current directory.
  const fs::path previous = fs::current_path();
  fs::current_path(dir.path());
  fw::io::write_skeleton_vtp("relative.vtp", skeleton);
  fs::current_path(previous);
  CHECK(fs::is_regular_file(fs::path(dir.path()) / "relative.vtp"));
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("write_skeleton_vtp: a missing folder throws runtime_error naming the path and creates nothing",
          "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "no" / "such" / "skeleton.vtp";
  CHECK_THROWS_MATCHES(
      fw::io::write_skeleton_vtp(path, skeleton), std::runtime_error,
      Catch::Matchers::Message(std::string("write_skeleton_vtp: cannot write ") + path.string() +
                               ": the folder " + path.parent_path().string() + " does not exist"));
  CHECK_THROWS_AS(fw::io::write_modes_vtp(path, skeleton, {}), std::runtime_error);
  CHECK_FALSE(fs::exists(fs::path(dir.path()) / "no"));
  CHECK(entries(dir.path()).empty());

  // A file where the folder should be.
  const std::string file = dir.write("plain", "not a folder");
  const fs::path under_file = fs::path(file) / "skeleton.vtp";
  CHECK_THAT(runtime_error_of([&] { fw::io::write_skeleton_vtp(under_file, skeleton); }),
             Catch::Matchers::Equals("write_skeleton_vtp: cannot write " + under_file.string() + ": " + file +
                                     " is not a folder"));
  CHECK(entries(dir.path()).size() == 1);
}

TEST_CASE("write_skeleton_vtp: a writer failure throws runtime_error naming the path and leaves no file",
          "[vtk]") {
  fw::test::TempDir dir("fw_vtk");
  const Skeleton skeleton = y_tree();
  const fs::path path = fs::path(dir.path()) / "skeleton.vtp";

  SECTION("the temporary cannot be opened: vtkXMLWriter::Write() fails") {
    // A folder where the temporary file should go makes the writer's open fail.
    const fs::path blocker = fs::path(path.string() + ".tmp-" + std::to_string(::getpid()));
    fs::create_directory(blocker);
    const std::string what = runtime_error_of([&] { fw::io::write_skeleton_vtp(path, skeleton); });
    CHECK_THAT(what, Catch::Matchers::StartsWith("write_skeleton_vtp: cannot write " + path.string() + ": "));
    CHECK_FALSE(fs::exists(blocker));  // the temporary (here a folder) is removed
    CHECK_FALSE(fs::exists(path));
  }
  SECTION("the rename onto the target fails: the target is a folder") {
    fs::create_directory(path);
    const std::string what = runtime_error_of([&] { fw::io::write_skeleton_vtp(path, skeleton); });
    CHECK_THAT(what, Catch::Matchers::Contains(path.string()));
    CHECK(fs::is_directory(path));
    CHECK(entries(dir.path()).size() == 1);
  }
  CHECK_FALSE(has_temporary(dir.path()));
}
