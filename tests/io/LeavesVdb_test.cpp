// The points grid "leaves" of the VDB frames (io/VdbWriter, io/writers/WindVdbWriter) read back with OpenVDB.
#include "io/VdbWriter.hpp"

#include "io/writers/WindVdbWriter.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/AttributeArray.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using fw::io::LeafFrame;

namespace {

constexpr double kH = 0.4;  // cell size of the test grid, m

// A 5x4x3 frame, h = 0.4 m, origin (2, -1, 0.5), no solids.
fw::io::WindFrame sample_frame() {
  fw::io::WindFrame frame;
  frame.dims = {5, 4, 3};
  frame.h = kH;
  frame.origin = {2.0, -1.0, 0.5};
  frame.time = 17.25;
  frame.step = 1234;
  frame.velocity.assign(3 * frame.cell_count(), 1.5f);
  return frame;
}

// Five leaves inside the domain (two in one cell, one on a cell's corner) and one outside it, each with
// its own tree id, so that the test can match the points read back whatever their order in the grid.
LeafFrame five_leaves() {
  LeafFrame leaves;
  leaves.position = {{2.1f, -0.9f, 0.6f},  {2.15f, -0.85f, 0.7f},      {2.8f, -0.2f, 1.3f},
                     {3.9f, 0.55f, 1.65f}, {11.0f / 3.0f, 0.1f, 0.9f}, {-5.0f, 30.0f, 100.0f}};
  const float r = 1.0f / std::sqrt(3.0f);
  leaves.normal = {{0.0f, 0.0f, 1.0f},  {r, r, r},           {0.6f, 0.0f, 0.8f},
                   {-1.0f, 0.0f, 0.0f}, {0.0f, -0.8f, 0.6f}, {0.0f, 1.0f, 0.0f}};
  leaves.state = {0, 1, 2, 0, 1, 1};
  leaves.tree_id = {0, 1, 2, 3, 4, 5};
  leaves.side = {0.07f, 0.0316227766f, 0.05f, 0.1f, 0.0625f, 0.04f};
  leaves.counts = {.shed = 4, .flying = 3, .landed = 1, .exited = 0, .attached = 2};
  return leaves;
}

openvdb::GridPtrVecPtr read_grids(const fs::path& path, std::vector<std::string>& names) {
  REQUIRE(fs::is_regular_file(path));
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  names.clear();
  for (auto name = file.beginName(); name != file.endName(); ++name) names.push_back(name.gridName());
  auto grids = file.getGrids();
  file.close();
  return grids;
}

openvdb::points::PointDataGrid::Ptr find_leaves(const openvdb::GridPtrVecPtr& grids) {
  for (const auto& grid : *grids) {
    if (grid->getName() == "leaves") return openvdb::gridPtrCast<openvdb::points::PointDataGrid>(grid);
  }
  return nullptr;
}

// One point of the grid, in world coordinates, with its attributes.
struct Point {
  openvdb::Vec3d position;
  openvdb::Vec3f normal;
  std::int32_t state = -1, tree_id = -1;
  float pscale = 0.0f;
};

std::vector<Point> points_of(const openvdb::points::PointDataGrid& grid) {
  std::vector<Point> points;
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    const openvdb::points::AttributeSet::Descriptor& descriptor = leaf->attributeSet().descriptor();
    // The attribute types of every leaf node: float32 vectors, int32 ids and states, a float pscale.
    CHECK(descriptor.type(descriptor.find("P")) ==
          openvdb::points::TypedAttributeArray<openvdb::Vec3f>::attributeType());
    CHECK(descriptor.type(descriptor.find("N")) ==
          openvdb::points::TypedAttributeArray<openvdb::Vec3f>::attributeType());
    CHECK(descriptor.type(descriptor.find("state")) ==
          openvdb::points::TypedAttributeArray<std::int32_t>::attributeType());
    CHECK(descriptor.type(descriptor.find("tree_id")) ==
          openvdb::points::TypedAttributeArray<std::int32_t>::attributeType());
    CHECK(descriptor.type(descriptor.find("pscale")) ==
          openvdb::points::TypedAttributeArray<float>::attributeType());
    openvdb::points::AttributeHandle<openvdb::Vec3f> p(leaf->constAttributeArray("P"));
    openvdb::points::AttributeHandle<openvdb::Vec3f> n(leaf->constAttributeArray("N"));
    openvdb::points::AttributeHandle<std::int32_t> state(leaf->constAttributeArray("state"));
    openvdb::points::AttributeHandle<std::int32_t> tree_id(leaf->constAttributeArray("tree_id"));
    openvdb::points::AttributeHandle<float> pscale(leaf->constAttributeArray("pscale"));
    for (auto index = leaf->beginIndexOn(); index; ++index) {
      Point point;
      // P is the offset from the voxel's centre, in index space.
      point.position =
          grid.transform().indexToWorld(openvdb::Vec3d(p.get(*index)) + index.getCoord().asVec3d());
      point.normal = n.get(*index);
      point.state = state.get(*index);
      point.tree_id = tree_id.get(*index);
      point.pscale = pscale.get(*index);
      points.push_back(point);
    }
  }
  return points;
}

}  // namespace

TEST_CASE("leaves vdb: a points grid with world positions, N, state, tree_id and pscale per leaf",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();
  const LeafFrame leaves = five_leaves();
  const fs::path path = fs::path(dir.path()) / "wind.0003.vdb";
  fw::io::write_wind_vdb(path, frame, true, true, &leaves);

  std::vector<std::string> names;
  const auto grids = read_grids(path, names);
  // io::File lists names from a sorted index, not in file order.
  CHECK(names == std::vector<std::string>{"leaves", "speed", "vel"});
  const auto grid = find_leaves(grids);
  REQUIRE(grid != nullptr);
  CHECK(grid->metaValue<double>("time_s") == 17.25);
  CHECK(openvdb::points::pointCount(grid->tree()) == leaves.size_written());
  // The wind grids' transform: voxel size h, voxel (i,j,k) on cell (i,j,k).
  // Tolerance: the transform is stored in double; 1e-12 m allows for the scale/translate round trip.
  CHECK(grid->voxelSize().x() == Approx(kH).margin(1e-12));
  CHECK(grid->transform().isLinear());
  const openvdb::Vec3d centre = grid->transform().indexToWorld(openvdb::Coord(1, 2, 0));
  CHECK(centre.x() == Approx(2.0 + kH * 1.5).margin(1e-12));
  CHECK(centre.y() == Approx(-1.0 + kH * 2.5).margin(1e-12));
  CHECK(centre.z() == Approx(0.5 + kH * 0.5).margin(1e-12));

  const std::vector<Point> points = points_of(*grid);
  REQUIRE(points.size() == leaves.size_written());
  std::vector<int> seen(leaves.size_written(), 0);
  for (const Point& point : points) {
    INFO("tree_id " << point.tree_id);
    REQUIRE(point.tree_id >= 0);
    REQUIRE(std::size_t(point.tree_id) < leaves.size_written());
    const std::size_t k = std::size_t(point.tree_id);
    ++seen[k];
    for (int c = 0; c < 3; ++c) {
      // Tolerance: P is a float32 offset within its voxel (|offset| <= h/2, so an ulp is below 3e-8 m),
      // turned back into the world in double; 1e-6 m covers that and the float position itself.
      CHECK(point.position[c] == Approx(double(leaves.position[k][std::size_t(c)])).margin(1e-6));
      // Exact: float32 in, float32 stored.
      CHECK(point.normal[c] == leaves.normal[k][std::size_t(c)]);
    }
    CHECK(point.state == leaves.state[k]);
    // Exact: half of a float is a float.
    CHECK(point.pscale == 0.5f * leaves.side[k]);
  }
  CHECK(seen == std::vector<int>(leaves.size_written(), 1));
}

TEST_CASE("leaves vdb: an empty leaf frame writes an empty grid named leaves, leaves alone are a selection",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();
  const LeafFrame empty;
  const fs::path path = fs::path(dir.path()) / "wind.0000.vdb";
  fw::io::write_wind_vdb(path, frame, true, false, &empty);
  std::vector<std::string> names;
  auto grids = read_grids(path, names);
  CHECK(names == std::vector<std::string>{"leaves", "vel"});
  auto grid = find_leaves(grids);
  REQUIRE(grid != nullptr);
  CHECK(openvdb::points::pointCount(grid->tree()) == 0);
  CHECK(grid->metaValue<double>("time_s") == 17.25);

  const LeafFrame leaves = five_leaves();
  fw::io::write_wind_vdb(path, frame, false, false, &leaves);
  grids = read_grids(path, names);
  CHECK(names == std::vector<std::string>{"leaves"});
  grid = find_leaves(grids);
  REQUIRE(grid != nullptr);
  CHECK(openvdb::points::pointCount(grid->tree()) == leaves.size_written());

  // Without leaves the file is as before, and inconsistent leaves write nothing.
  fw::io::write_wind_vdb(path, frame, true, true);
  read_grids(path, names);
  CHECK(names == std::vector<std::string>{"speed", "vel"});
  CHECK_THROWS_AS(fw::io::write_wind_vdb(path, frame, false, false), std::invalid_argument);
  LeafFrame bad = five_leaves();
  bad.state.pop_back();
  const fs::path other = fs::path(dir.path()) / "wind.0001.vdb";
  CHECK_THROWS_MATCHES(
      fw::io::write_wind_vdb(other, frame, true, true, &bad), std::invalid_argument,
      Catch::Matchers::Message("write_wind_vdb: leaves: state: expected 6 values (one per leaf), got 5"));
  bad = five_leaves();
  bad.side[3] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_AS(fw::io::write_wind_vdb(other, frame, true, true, &bad), std::invalid_argument);
  CHECK_FALSE(fs::exists(other));
}

TEST_CASE("leaves vdb writer: with leaves on every frame holds the leaves grid and needs the leaves",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  fw::fluid::GridSpec spec;
  spec.nx = 5;
  spec.ny = 4;
  spec.nz = 3;
  spec.h = kH;
  spec.origin = {2.0, -1.0, 0.5};
  const fs::path out = fs::path(dir.path()) / "run";

  fw::io::WindVdbWriter plain(out, spec, {}, true, true);
  CHECK(plain.needs().velocity);
  CHECK_FALSE(plain.needs().leaves);
  fw::io::WindVdbWriter with_leaves(out, spec, {}, true, true, /*leaves=*/true);
  CHECK(with_leaves.needs().velocity);
  CHECK(with_leaves.needs().leaves);
  with_leaves.begin();

  fw::io::OutputFrame frame;
  frame.index = 0;
  frame.time = 0.5;
  frame.velocity = fw::fluid::MacVelocity(spec);
  with_leaves.write(frame);  // no leaves yet: an empty grid
  frame.index = 1;
  frame.time = 1.0;
  frame.leaves = five_leaves();
  with_leaves.write(frame);
  frame.index = 2;
  plain.write(frame);

  std::vector<std::string> names;
  auto grids = read_grids(out / "vdb/wind.0000.vdb", names);
  CHECK(names == std::vector<std::string>{"leaves", "speed", "vel"});
  REQUIRE(find_leaves(grids) != nullptr);
  CHECK(openvdb::points::pointCount(find_leaves(grids)->tree()) == 0);
  grids = read_grids(out / "vdb/wind.0001.vdb", names);
  CHECK(names == std::vector<std::string>{"leaves", "speed", "vel"});
  REQUIRE(find_leaves(grids) != nullptr);
  CHECK(openvdb::points::pointCount(find_leaves(grids)->tree()) == frame.leaves.size_written());
  read_grids(out / "vdb/wind.0002.vdb", names);
  CHECK(names == std::vector<std::string>{"speed", "vel"});
}
