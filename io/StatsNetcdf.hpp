// stats.nc: profiles against height and time series, as NetCDF-4 with CF-1.8 attributes, the file LES users
// open in xarray (docs/statistics.md). This is the file's layout and its writer; what fills it is the run's.
//
//   fw::io::StatsFile file;
//   file.title = "storm";
//   file.z = {1.0, 3.0, 5.0};                                  // m, the cell centres
//   file.profiles.variables = fw::io::profile_columns();       // fluid::profile_variables(), in order
//   file.profiles.time = {60.0};                               // s, the end of each averaging window
//   file.profiles.values = {{{...nz values...}, ...}};         // [record][variable][k]
//   fw::io::write_stats_netcdf("out/storm/stats.nc", file);   // the whole file, under a temporary name
//
// The root group holds the whole domain's profiles on the dimensions (time, z); the group "timeseries" holds
// the time series on its own dimension time; the group "regions/NAME" holds a region's profiles, with copies
// of time and z so that xarray opens it alone, and the box in the attributes region_min and region_max. Every
// variable carries units and long_name, and standard_name where CF has one; the coordinates carry axis,
// positive and standard_name. The file is written whole under a temporary name and renamed (base/AtomicFile):
// a run killed while writing it leaves the last complete file. It is built in memory and written with POSIX
// writes, so a full disk reads "No space left on device" and leaves nothing behind. The root group lists
// its variables by name (an in-memory file keeps no order of creation there), so a reader finds them by name.
// The profiles carry CF's cell_methods "area: mean time: mean", and the root the records' interval and
// averaging time in seconds (the attributes interval_seconds and averaging_seconds).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace fw::io {

/// A variable of stats.nc: its name, units (UDUNITS), long name and CF standard name ("" where none).
struct StatsVariable {
  std::string name, units, long_name, standard_name;
  bool operator==(const StatsVariable&) const = default;
};

/// Profiles against height: values[record][variable][k], one record per time.
struct StatsProfiles {
  std::vector<StatsVariable> variables;
  std::vector<double> time;                              // s
  std::vector<std::vector<std::vector<double>>> values;  // [record][variable][k]
};

/// Time series: values[record][variable], one record per time.
struct StatsSeries {
  std::vector<StatsVariable> variables;
  std::vector<double> time;                 // s
  std::vector<std::vector<double>> values;  // [record][variable]
};

/// The profiles of a horizontal part of the domain, on the whole domain's times, heights and variables.
struct StatsRegion {
  std::string name;                                      // the group's: regions/NAME
  std::array<double, 2> min{}, max{};                    // m: the box the averaged cells fill (x, y)
  std::vector<std::vector<std::vector<double>>> values;  // [record][variable][k]
};

struct StatsFile {
  std::string title;       // the scenario's name
  std::string history;     // what wrote it: "forestwind run SCENARIO"
  std::vector<double> z;   // m, the heights of the profiles
  double interval = 0.0;   // s between profile records (attribute interval_seconds; 0: not given)
  double averaging = 0.0;  // s each record averages over, up to its time (attribute averaging_seconds)
  StatsProfiles profiles;
  StatsSeries series;
  std::vector<StatsRegion> regions;  // each in the group regions/NAME, with its own copies of time and z
};

/// The profile variables of fluid/PlaneProfiles, in its order.
std::vector<StatsVariable> profile_columns();

/// Reads a stats.nc that write_stats_netcdf wrote (a resumed run goes on from its records). Its variables
/// come in the root group's order, which is by name (the in-memory file the writer builds keeps no order
/// of creation there): find them by name. A region's come in the same order. Throws
/// std::runtime_error naming the path and NetCDF's message when it does not read as one.
StatsFile read_stats_netcdf(const std::filesystem::path& path);

/// Writes `file` to `path` whole (under "<path>.tmp-<pid>", then renamed). Throws std::invalid_argument when
/// a record's shape is not the file's (values per variable, heights), std::runtime_error naming the path and
/// NetCDF's message when the library fails.
void write_stats_netcdf(const std::filesystem::path& path, const StatsFile& file);

}  // namespace fw::io
