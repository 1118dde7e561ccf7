#include "io/VdbWriter.hpp"

#include "base/AtomicFile.hpp"
#include "io/LeavesVtk.hpp"

#include <fmt/format.h>

#include <openvdb/io/Archive.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointAttribute.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/PointIndexGrid.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fw::io {
namespace {

// openvdb::io::File::write as it is (a seekable archive on an ofstream), but with the stream's state checked
// after its close: OpenVDB 10 ignores it, so a full disk would leave a truncated file that reads as a frame.
class CheckedVdbArchive : public openvdb::io::Archive {
 public:
  /// Writes the grids to `path`; returns 0, or the errno of the failure (EIO when the stream gives none).
  int write_file(const std::filesystem::path& path, const openvdb::GridPtrVec& grids,
                 const openvdb::MetaMap& meta) const {
    std::ofstream out(path, std::ios_base::out | std::ios_base::binary | std::ios_base::trunc);
    if (!out) return errno != 0 ? errno : EIO;
    errno = 0;
    Archive::write(out, grids, /*seekable=*/true, meta);
    out.close();
    if (out.fail()) return errno != 0 ? errno : EIO;
    return 0;
  }
};

void initialize_openvdb() {
  // openvdb::initialize registers grid and metadata types in global tables; once per process is enough.
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

openvdb::math::Transform::Ptr cell_centred_transform(const WindFrame& frame) {
  // Index space puts voxel (i,j,k)'s centre at (i,j,k); scale by h, then shift by origin + h/2 so that the
  // centre lands on the cell's centre.
  auto transform = openvdb::math::Transform::createLinearTransform(frame.h);
  transform->postTranslate(openvdb::Vec3d(frame.origin[0] + 0.5 * frame.h, frame.origin[1] + 0.5 * frame.h,
                                          frame.origin[2] + 0.5 * frame.h));
  return transform;
}

// Adds attribute `name` to every leaf node of `points` and fills it from `values` (one per point, input
// order), looked up through the index grid the points were partitioned with.
template <typename T>
void add_point_attribute(openvdb::points::PointDataTree& points, const openvdb::tools::PointIndexTree& index,
                         const std::string& name, const std::vector<T>& values) {
  openvdb::points::appendAttribute<T>(points, name);
  openvdb::points::populateAttribute(points, index, name, openvdb::points::PointAttributeVector<T>(values));
}

openvdb::points::PointDataGrid::Ptr leaves_grid(const LeafFrame& leaves,
                                                const openvdb::math::Transform& transform, double time) {
  const std::size_t n = leaves.size_written();
  std::vector<openvdb::Vec3d> position(n);
  std::vector<openvdb::Vec3f> normal(n);
  std::vector<std::int32_t> state(n);
  std::vector<float> pscale(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = leaves.position[k];
    const auto& v = leaves.normal[k];
    position[k] = openvdb::Vec3d(p[0], p[1], p[2]);
    normal[k] = openvdb::Vec3f(v[0], v[1], v[2]);
    state[k] = leaves.state[k];
    // Houdini's pscale is a point's radius: half the blade side.
    pscale[k] = 0.5f * leaves.side[k];
  }
  // P is stored as float32 offsets within each voxel (NullCodec: no quantisation), so a position keeps
  // float precision relative to its cell rather than to the world origin.
  const openvdb::points::PointAttributeVector<openvdb::Vec3d> positions(position);
  const auto index =
      openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(positions, transform);
  auto grid =
      openvdb::points::createPointDataGrid<openvdb::points::NullCodec, openvdb::points::PointDataGrid>(
          *index, positions, transform);
  add_point_attribute(grid->tree(), index->tree(), "N", normal);
  add_point_attribute(grid->tree(), index->tree(), "state", state);
  add_point_attribute(grid->tree(), index->tree(), "tree_id", leaves.tree_id);
  add_point_attribute(grid->tree(), index->tree(), "pscale", pscale);
  grid->setName("leaves");
  grid->insertMeta("time_s", openvdb::DoubleMetadata(time));
  return grid;
}

}  // namespace

void write_wind_vdb(const std::filesystem::path& path, const WindFrame& frame, bool vel, bool speed,
                    const LeafFrame* leaves) {
  if (!vel && !speed && !leaves) {
    throw std::invalid_argument(fmt::format(
        "write_wind_vdb: {}: no grid selected (expected vel, speed, leaves or several)", path.string()));
  }
  try {
    frame.validate();
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("write_wind_vdb: ") + error.what());
  }
  if (leaves) validate_leaf_frame("write_wind_vdb", *leaves);
  base::require_output_folder("write_wind_vdb", path);
  initialize_openvdb();

  const auto transform = cell_centred_transform(frame);
  openvdb::Vec3SGrid::Ptr vel_grid;
  openvdb::FloatGrid::Ptr speed_grid;
  if (vel) {
    vel_grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    vel_grid->setName("vel");
    vel_grid->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    vel_grid->setGridClass(openvdb::GRID_UNKNOWN);
    vel_grid->setTransform(transform->copy());
    vel_grid->insertMeta("time_s", openvdb::DoubleMetadata(frame.time));
    vel_grid->setSaveFloatAsHalf(false);
  }
  if (speed) {
    speed_grid = openvdb::FloatGrid::create(0.0f);
    speed_grid->setName("speed");
    speed_grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    speed_grid->setTransform(transform->copy());
    speed_grid->insertMeta("time_s", openvdb::DoubleMetadata(frame.time));
    speed_grid->setSaveFloatAsHalf(false);
  }

  {
    // Accessors cache the path to the last leaf, which makes the x-fastest sweep cheap.
    std::optional<openvdb::Vec3SGrid::Accessor> vel_at;
    std::optional<openvdb::FloatGrid::Accessor> speed_at;
    if (vel_grid) vel_at.emplace(vel_grid->getAccessor());
    if (speed_grid) speed_at.emplace(speed_grid->getAccessor());
    for (int k = 0; k < frame.dims[2]; ++k) {
      for (int j = 0; j < frame.dims[1]; ++j) {
        for (int i = 0; i < frame.dims[0]; ++i) {
          const std::size_t cell = frame.cell_index(i, j, k);
          if (frame.is_solid(cell)) continue;  // stays inactive: background 0
          const openvdb::Coord ijk(i, j, k);
          const float* v = &frame.velocity[3 * cell];
          if (vel_at) vel_at->setValueOn(ijk, openvdb::Vec3s(v[0], v[1], v[2]));
          if (speed_at) {
            const double x = v[0], y = v[1], z = v[2];
            speed_at->setValueOn(ijk, float(std::sqrt(x * x + y * y + z * z)));
          }
        }
      }
    }
  }

  openvdb::GridPtrVec grids;
  if (vel_grid) grids.push_back(vel_grid);
  if (speed_grid) grids.push_back(speed_grid);
  if (leaves) grids.push_back(leaves_grid(*leaves, *transform, frame.time));
  openvdb::MetaMap file_meta;
  file_meta.insertMeta("time_s", openvdb::DoubleMetadata(frame.time));
  file_meta.insertMeta("step", openvdb::Int64Metadata(frame.step));
  if (frame.site) {
    // The site (docs/gis.md): origin + a local position is the position in the CRS.
    const auto& o = frame.site->origin;
    file_meta.insertMeta("site_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(o[0], o[1], o[2])));
    const auto& crs = frame.site->crs;
    file_meta.insertMeta("site_epsg", openvdb::Int32Metadata(crs && crs->epsg ? *crs->epsg : 0));
    if (crs) file_meta.insertMeta("site_crs", openvdb::StringMetadata(crs->wkt));
  }

  base::AtomicFile file(path);
  try {
    if (const int error = CheckedVdbArchive().write_file(file.temporary_path(), grids, file_meta))
      throw std::runtime_error(std::strerror(error));
  } catch (const openvdb::Exception& error) {
    throw std::runtime_error(fmt::format("write_wind_vdb: cannot write {}: {}", path.string(), error.what()));
  } catch (const std::exception& error) {
    // Boost iostreams and the standard library may throw their own exceptions from inside OpenVDB's writer.
    throw std::runtime_error(fmt::format("write_wind_vdb: cannot write {}: {}", path.string(), error.what()));
  }
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("write_wind_vdb: cannot write {}: {}", path.string(), error.what()));
  }
}

}  // namespace fw::io
