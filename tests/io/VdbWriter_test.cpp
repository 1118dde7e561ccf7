#include "io/VdbWriter.hpp"

#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using fw::test::has_temporary;

// A 5x4x3 frame, h = 0.4 m, origin (2, -1, 0.5), with cells (1,2,0) and (4,0,2) solid.
fw::io::WindFrame sample_frame() {
  fw::io::WindFrame frame;
  frame.dims = {5, 4, 3};
  frame.h = 0.4;
  frame.origin = {2.0, -1.0, 0.5};
  frame.time = 17.25;
  frame.step = 1234;
  const std::size_t cells = frame.cell_count();
  frame.velocity.resize(3 * cells);
  for (std::size_t c = 0; c < 3 * cells; ++c)
    frame.velocity[c] = float(std::cos(0.21 * double(c)) * 7.0 + 0.5);
  frame.solid.assign(cells, 0);
  frame.solid[frame.cell_index(1, 2, 0)] = 1;
  frame.solid[frame.cell_index(4, 0, 2)] = 1;
  return frame;
}

struct ReadBack {
  std::vector<std::string> names;
  openvdb::MetaMap::Ptr meta;
  openvdb::GridPtrVecPtr grids;
};

ReadBack read_vdb(const fs::path& path) {
  REQUIRE(fs::is_regular_file(path));
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  ReadBack out;
  for (auto name = file.beginName(); name != file.endName(); ++name) out.names.push_back(name.gridName());
  out.meta = file.getMetadata();
  out.grids = file.getGrids();
  file.close();
  return out;
}

template <typename GridT>
typename GridT::Ptr find_grid(const ReadBack& vdb, const std::string& name) {
  for (const auto& grid : *vdb.grids) {
    if (grid->getName() == name) return openvdb::gridPtrCast<GridT>(grid);
  }
  return nullptr;
}

}  // namespace

TEST_CASE("write_wind_vdb: grids vel and speed with cell-centred transform, values, inactive solids, time_s",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();
  const fs::path path = fs::path(dir.path()) / "wind.0007.vdb";
  fw::io::write_wind_vdb(path, frame, true, true);
  CHECK_FALSE(has_temporary(dir.path()));

  const ReadBack vdb = read_vdb(path);
  // io::File lists names from a sorted index, not in file order.
  CHECK(vdb.names == std::vector<std::string>{"speed", "vel"});
  REQUIRE(vdb.meta != nullptr);
  CHECK(vdb.meta->metaValue<double>("time_s") == 17.25);
  CHECK(vdb.meta->metaValue<openvdb::Int64>("step") == 1234);

  const auto vel = find_grid<openvdb::Vec3SGrid>(vdb, "vel");
  const auto speed = find_grid<openvdb::FloatGrid>(vdb, "speed");
  REQUIRE(vel != nullptr);
  REQUIRE(speed != nullptr);
  CHECK(vel->getVectorType() == openvdb::VEC_CONTRAVARIANT_RELATIVE);
  CHECK(vel->getGridClass() == openvdb::GRID_UNKNOWN);
  CHECK(speed->getGridClass() == openvdb::GRID_FOG_VOLUME);
  CHECK(vel->metaValue<double>("time_s") == 17.25);
  CHECK(speed->metaValue<double>("time_s") == 17.25);

  for (const auto* grid : {static_cast<const openvdb::GridBase*>(vel.get()),
                           static_cast<const openvdb::GridBase*>(speed.get())}) {
    INFO("grid " << grid->getName());
    const openvdb::Vec3d size = grid->voxelSize();
    // Tolerance: the transform is stored in double; 1e-12 m allows for the scale/translate round trip.
    CHECK(size.x() == Approx(0.4).margin(1e-12));
    CHECK(size.y() == Approx(0.4).margin(1e-12));
    CHECK(size.z() == Approx(0.4).margin(1e-12));
    CHECK(grid->transform().isLinear());
    // Voxel (i,j,k)'s centre is the cell's centre: origin + h (i+1/2, j+1/2, k+1/2).
    for (const auto& ijk : {openvdb::Coord(0, 0, 0), openvdb::Coord(3, 1, 2), openvdb::Coord(4, 3, 2)}) {
      const openvdb::Vec3d world = grid->transform().indexToWorld(ijk);
      CHECK(world.x() == Approx(2.0 + 0.4 * (ijk.x() + 0.5)).margin(1e-12));
      CHECK(world.y() == Approx(-1.0 + 0.4 * (ijk.y() + 0.5)).margin(1e-12));
      CHECK(world.z() == Approx(0.5 + 0.4 * (ijk.z() + 0.5)).margin(1e-12));
    }
    // And the domain's minimum corner is the corner of voxel (0,0,0).
    const openvdb::Vec3d corner = grid->transform().worldToIndex(openvdb::Vec3d(2.0, -1.0, 0.5));
    CHECK(corner.x() == Approx(-0.5).margin(1e-12));
    CHECK(corner.z() == Approx(-0.5).margin(1e-12));
    CHECK(grid->activeVoxelCount() == frame.cell_count() - 2);
  }

  const auto vel_at = vel->getConstAccessor();
  const auto speed_at = speed->getConstAccessor();
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 5; ++i) {
        INFO("cell " << i << "," << j << "," << k);
        const openvdb::Coord ijk(i, j, k);
        const std::size_t cell = frame.cell_index(i, j, k);
        if (frame.is_solid(cell)) {
          CHECK_FALSE(vel_at.isValueOn(ijk));
          CHECK_FALSE(speed_at.isValueOn(ijk));
          CHECK(vel_at.getValue(ijk) == openvdb::Vec3s(0.0f));
          CHECK(speed_at.getValue(ijk) == 0.0f);
          continue;
        }
        CHECK(vel_at.isValueOn(ijk));
        CHECK(speed_at.isValueOn(ijk));
        const openvdb::Vec3s v = vel_at.getValue(ijk);
        // Exact: float32 values, saved as float (not half).
        CHECK(v.x() == frame.velocity[3 * cell + 0]);
        CHECK(v.y() == frame.velocity[3 * cell + 1]);
        CHECK(v.z() == frame.velocity[3 * cell + 2]);
        // Tolerance: speed computed in double, rounded to float (1 ulp).
        CHECK(speed_at.getValue(ijk) ==
              Approx(std::sqrt(double(v.x()) * v.x() + double(v.y()) * v.y() + double(v.z()) * v.z()))
                  .epsilon(1e-6));
      }
    }
  }
  CHECK_FALSE(vel_at.isValueOn(openvdb::Coord(5, 0, 0)));  // outside the domain
}

TEST_CASE("write_wind_vdb: a run's site goes into the file's metadata: origin, EPSG code and WKT",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  fw::io::WindFrame frame = sample_frame();
  fw::io::SiteSettings site;
  site.origin = {512040.25, 5401040.5, 421.0};
  site.crs.emplace().wkt = "PROJCRS[\"WGS 84 / UTM zone 32N\"]";
  site.crs->epsg = 32632;
  frame.site = &site;
  const fs::path path = fs::path(dir.path()) / "wind.0001.vdb";
  fw::io::write_wind_vdb(path, frame, true, false);
  const ReadBack vdb = read_vdb(path);
  REQUIRE(vdb.meta != nullptr);
  CHECK(vdb.meta->metaValue<openvdb::Vec3d>("site_origin") == openvdb::Vec3d(512040.25, 5401040.5, 421.0));
  CHECK(vdb.meta->metaValue<openvdb::Int32>("site_epsg") == 32632);
  CHECK(vdb.meta->metaValue<std::string>("site_crs") == site.crs->wkt);
  // Without a site: none of them.
  frame.site = nullptr;
  fw::io::write_wind_vdb(path, frame, true, false);
  CHECK_FALSE(read_vdb(path).meta->operator[]("site_origin"));
}

TEST_CASE("write_wind_vdb: only the selected grids are written and selecting none is an error", "[output]") {
  fw::test::TempDir dir("fw_out");
  fw::io::WindFrame frame = sample_frame();
  frame.solid.clear();  // no solids: every cell active
  const fs::path path = fs::path(dir.path()) / "speed.vdb";
  fw::io::write_wind_vdb(path, frame, false, true);
  const ReadBack vdb = read_vdb(path);
  CHECK(vdb.names == std::vector<std::string>{"speed"});
  CHECK(vdb.grids->front()->activeVoxelCount() == frame.cell_count());

  CHECK_THROWS_AS(fw::io::write_wind_vdb(path, frame, false, false), std::invalid_argument);
  frame.velocity.resize(3);
  CHECK_THROWS_AS(fw::io::write_wind_vdb(path, frame, true, false), std::invalid_argument);
}

TEST_CASE("write_wind_vdb: a missing folder or unwritable temporary throws runtime_error naming the path",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();
  const fs::path missing = fs::path(dir.path()) / "vdb" / "wind.0000.vdb";
  CHECK_THROWS_MATCHES(
      fw::io::write_wind_vdb(missing, frame, true, true), std::runtime_error,
      Catch::Matchers::Message("write_wind_vdb: cannot write " + missing.string() + ": the folder " +
                               missing.parent_path().string() + " does not exist"));

  // A folder nobody may create files in, root included.
  if (fs::is_directory("/proc")) {
    const fs::path target = "/proc/fw_wind_test.vdb";
    CHECK_THROWS_WITH(fw::io::write_wind_vdb(target, frame, true, true),
                      Catch::Matchers::StartsWith("write_wind_vdb: cannot write " + target.string() + ": "));
  }

  const fs::path path = fs::path(dir.path()) / "wind.0000.vdb";
  fs::create_directory(fs::path(path.string() + ".tmp-" + std::to_string(::getpid())));
  CHECK_THROWS_WITH(fw::io::write_wind_vdb(path, frame, true, true),
                    Catch::Matchers::StartsWith("write_wind_vdb: cannot write " + path.string() + ": "));
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(has_temporary(dir.path()));
}
