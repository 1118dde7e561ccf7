// check_frames DIR [STATS_INTERVAL]: whether every frame a run folder lists opens (tests/cli/kill_run.sh,
// disk_full.sh). Each file that wind.pvd, trees.pvd and leaves.pvd list is read back through VTK's XML
// readers (viz/RunFolder), and each VDB frame under vdb/ through OpenVDB, every grid with its voxels: not
// merely present, whole. With STATS_INTERVAL (s, output.statistics.interval), stats.nc must read back
// (io/StatsNetcdf) and hold a record at each multiple of it up to the last frame wind.pvd lists: stats.nc
// is written at each record, before the frames of that time are listed, so a kill loses none of those.
// Prints "N files read" and exits 0; exits 1 naming the first file that does not read. A folder whose
// collections are missing or list no frame (a run killed before its first frame) reads as 0 files.
#include <fmt/format.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "io/PvdCollection.hpp"
#include "io/StatsNetcdf.hpp"
#include "viz/RunFolder.hpp"

namespace {

namespace fs = std::filesystem;

// Reads every file that the folder's collections list; returns how many.
int read_listed(const fs::path& folder) {
  const bool any = fs::exists(folder / "wind.pvd") || fs::exists(folder / "trees.pvd");
  if (!any) return 0;
  std::optional<fw::viz::RunFolder> run;
  try {
    run.emplace(folder);
  } catch (const std::invalid_argument&) {
    // Collections that list no frame yet: the run stopped before its first frame was complete.
    for (const char* name : {"wind.pvd", "trees.pvd"})
      if (fs::exists(folder / name) && !fw::io::read_pvd(folder / name).empty()) throw;
    return 0;
  }
  int files = 0;
  for (const char* name : {"wind.pvd", "trees.pvd", "leaves.pvd"}) {
    if (!fs::exists(folder / name)) continue;
    for (const fw::io::PvdCollection::Entry& entry : fw::io::read_pvd(folder / name)) {
      fw::viz::RunFolder::Frame frame;  // this one file alone
      frame.time = entry.time;
      fs::path& slot = name[0] == 'w' ? frame.wind : name[0] == 't' ? frame.trees : frame.leaves;
      slot = folder / entry.file;
      static_cast<void>(run->load(frame));
      ++files;
    }
  }
  return files;
}

// Reads every grid of every VDB frame; returns how many files.
int read_vdb(const fs::path& folder) {
  if (!fs::is_directory(folder / "vdb")) return 0;
  openvdb::initialize();
  int files = 0;
  for (const auto& entry : fs::directory_iterator(folder / "vdb")) {
    if (entry.path().extension() != ".vdb") continue;  // a killed run's temporaries are not frames
    try {
      openvdb::io::File file(entry.path().string());
      file.open(/*delayLoad=*/false);
      const openvdb::GridPtrVecPtr grids = file.getGrids();
      file.close();
      if (!grids || grids->empty()) throw std::runtime_error("no grids");
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("{}: does not read: {}", entry.path().string(), e.what()));
    }
    ++files;
  }
  return files;
}

// Checks stats.nc against the frames wind.pvd lists (see above); returns its records.
std::size_t read_statistics(const fs::path& folder, double interval) {
  // Sums of float dt land within this fraction of an interval of its multiples (host/app/Schedule.hpp).
  constexpr double kTolerance = 1e-6;
  double last_frame = 0.0;
  if (fs::exists(folder / "wind.pvd"))
    if (const auto listed = fw::io::read_pvd(folder / "wind.pvd"); !listed.empty())
      last_frame = listed.back().time;
  const auto due = std::size_t(std::floor(last_frame / interval + kTolerance));
  if (!fs::exists(folder / "stats.nc")) {
    if (due > 0)
      throw std::runtime_error(fmt::format("no stats.nc, but a frame at {} s is listed", last_frame));
    return 0;
  }
  const fw::io::StatsFile stats = fw::io::read_stats_netcdf(folder / "stats.nc");
  const std::vector<double>& times = stats.profiles.time;
  for (std::size_t n = 0; n < times.size(); ++n)
    if (std::abs(times[n] - double(n + 1) * interval) > kTolerance * interval + 0.5 * interval)
      throw std::runtime_error(
          fmt::format("stats.nc: record {} at {} s, not near {} s", n, times[n], double(n + 1) * interval));
  if (times.size() < due)
    throw std::runtime_error(
        fmt::format("stats.nc holds {} records, but a frame at {} s is listed: {} are due", times.size(),
                    last_frame, due));
  return times.size();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: check_frames DIR [STATS_INTERVAL]\n";
    return 2;
  }
  try {
    const int files = read_listed(argv[1]) + read_vdb(argv[1]);
    if (argc == 3) {
      const std::size_t records = read_statistics(argv[1], std::stod(argv[2]));
      std::cout << fmt::format("{} files read, {} statistics records\n", files, records);
      return 0;
    }
    std::cout << fmt::format("{} files read\n", files);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "check_frames: " << e.what() << "\n";
    return 1;
  }
}
