#include "io/StatsNetcdf.hpp"

#include <fmt/format.h>
#include <netcdf.h>
#include <netcdf_mem.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/AtomicFile.hpp"
#include "fluid/PlaneProfiles.hpp"

namespace fw::io {

namespace {

constexpr const char* kSeriesGroup = "timeseries";
// The in-memory file's first allocation; it grows as needed.
constexpr std::size_t kInitialBytes = 1 << 16;
constexpr const char* kRegionsGroup = "regions";
constexpr const char* kIntervalAttribute = "interval_seconds";
constexpr const char* kAveragingAttribute = "averaging_seconds";
// The profiles: means over the plane's fluid cells and over each record's window.
constexpr const char* kProfileCellMethods = "area: mean time: mean";

// NetCDF's status, as an exception naming the file and what was being done.
void check(int status, const std::filesystem::path& path, const std::string& doing) {
  if (status != NC_NOERR)
    throw std::runtime_error(fmt::format("{}: NetCDF: {}: {}", path.string(), doing, nc_strerror(status)));
}

void put_text(int group, int variable, const char* name, const std::string& value,
              const std::filesystem::path& path) {
  if (value.empty()) return;
  check(nc_put_att_text(group, variable, name, value.size(), value.c_str()), path,
        fmt::format("writing the attribute {}", name));
}

std::string get_text(int group, int variable, const char* name, const std::filesystem::path& path) {
  std::size_t length = 0;
  if (nc_inq_attlen(group, variable, name, &length) != NC_NOERR) return "";
  std::string value(length, '\0');
  check(nc_get_att_text(group, variable, name, value.data()), path,
        fmt::format("reading the attribute {}", name));
  return value;
}

// A coordinate variable `name` over its own dimension of `values`, with CF's attributes.
int define_coordinate(int group, const char* name, std::size_t length, const StatsVariable& about,
                      const char* axis, const std::filesystem::path& path, int* dimension) {
  check(nc_def_dim(group, name, length, dimension), path, fmt::format("defining the dimension {}", name));
  int variable = 0;
  check(nc_def_var(group, name, NC_DOUBLE, 1, dimension, &variable), path,
        fmt::format("defining the coordinate {}", name));
  put_text(group, variable, "units", about.units, path);
  put_text(group, variable, "long_name", about.long_name, path);
  put_text(group, variable, "standard_name", about.standard_name, path);
  put_text(group, variable, "axis", axis, path);
  return variable;
}

int define_variable(int group, const StatsVariable& about, const std::vector<int>& dimensions,
                    const std::filesystem::path& path) {
  int variable = 0;
  check(
      nc_def_var(group, about.name.c_str(), NC_DOUBLE, int(dimensions.size()), dimensions.data(), &variable),
      path, fmt::format("defining {}", about.name));
  put_text(group, variable, "units", about.units, path);
  put_text(group, variable, "long_name", about.long_name, path);
  put_text(group, variable, "standard_name", about.standard_name, path);
  return variable;
}

// Simulated seconds from the run's start: CF's standard name time would need a calendar date as reference.
const StatsVariable kTime{"time", "s", "time since the run started", ""};
const StatsVariable kHeight{"z", "m", "height of the cell centres above the domain origin", "height"};

void require_shapes(const StatsFile& f) {
  const StatsProfiles& p = f.profiles;
  if (p.values.size() != p.time.size())
    throw std::invalid_argument(
        fmt::format("stats.nc: {} profile records for {} times", p.values.size(), p.time.size()));
  for (const auto& record : p.values) {
    if (record.size() != p.variables.size())
      throw std::invalid_argument(fmt::format("stats.nc: a profile record holds {} variables, the file {}",
                                              record.size(), p.variables.size()));
    for (const auto& profile : record)
      if (profile.size() != f.z.size())
        throw std::invalid_argument(
            fmt::format("stats.nc: a profile holds {} heights, the file {}", profile.size(), f.z.size()));
  }
  for (const StatsRegion& region : f.regions) {
    if (region.values.size() != p.time.size())
      throw std::invalid_argument(fmt::format("stats.nc: region {} has {} records for {} times", region.name,
                                              region.values.size(), p.time.size()));
    for (const auto& record : region.values) {
      if (record.size() != p.variables.size())
        throw std::invalid_argument(
            fmt::format("stats.nc: a record of region {} holds {} variables, the file {}", region.name,
                        record.size(), p.variables.size()));
      for (const auto& profile : record)
        if (profile.size() != f.z.size())
          throw std::invalid_argument(
              fmt::format("stats.nc: a profile of region {} holds {} heights, the file {}", region.name,
                          profile.size(), f.z.size()));
    }
  }
  const StatsSeries& s = f.series;
  if (s.values.size() != s.time.size())
    throw std::invalid_argument(
        fmt::format("stats.nc: {} time-series records for {} times", s.values.size(), s.time.size()));
  for (const auto& record : s.values)
    if (record.size() != s.variables.size())
      throw std::invalid_argument(fmt::format("stats.nc: a time-series record holds {} values, the file {}",
                                              record.size(), s.variables.size()));
}

// A group's profiles: its time and z coordinates and a variable of each profile, defined.
struct ProfileGroup {
  int group = 0, time_var = 0, z_var = 0;
  std::vector<int> variables;
};

// Defines the profiles on (time, z) in `group`, time unlimited so that a later writer may append.
ProfileGroup define_profiles(int group, const StatsFile& f, const std::filesystem::path& target) {
  ProfileGroup g;
  g.group = group;
  int time_dim = 0, z_dim = 0;
  g.time_var = define_coordinate(group, "time", NC_UNLIMITED, kTime, "T", target, &time_dim);
  g.z_var = define_coordinate(group, "z", f.z.size(), kHeight, "Z", target, &z_dim);
  put_text(group, g.z_var, "positive", "up", target);
  for (const StatsVariable& v : f.profiles.variables) {
    g.variables.push_back(define_variable(group, v, {time_dim, z_dim}, target));
    put_text(group, g.variables.back(), "cell_methods", kProfileCellMethods, target);
  }
  return g;
}

// Writes the profiles `values` ([record][variable][k]) on the file's times and heights into `g`.
void write_profiles(const ProfileGroup& g, const StatsFile& f,
                    const std::vector<std::vector<std::vector<double>>>& values,
                    const std::filesystem::path& target) {
  if (!f.z.empty()) check(nc_put_var_double(g.group, g.z_var, f.z.data()), target, "writing z");
  for (std::size_t r = 0; r < f.profiles.time.size(); ++r) {
    const std::size_t at[1] = {r}, one[1] = {1};
    check(nc_put_vara_double(g.group, g.time_var, at, one, &f.profiles.time[r]), target, "writing time");
    for (std::size_t n = 0; n < g.variables.size(); ++n) {
      const std::size_t start[2] = {r, 0}, count[2] = {1, f.z.size()};
      check(nc_put_vara_double(g.group, g.variables[n], start, count, values[r][n].data()), target,
            fmt::format("writing {}", f.profiles.variables[n].name));
    }
  }
}

// The whole file, built in memory (NetCDF's in-memory files): the disk sees only write_text_atomically's own
// writes, whose errors say what failed (a full disk: "No space left on device"). On disk, HDF5 met a full
// disk as a generic error and kept the half-written file open, and its clean-up at exit then crashed.
std::string file_bytes(const std::filesystem::path& target, const StatsFile& f) {
  int root = 0;
  check(nc_create_mem(target.filename().c_str(), NC_NETCDF4, kInitialBytes, &root), target,
        "creating the file");
  try {
    put_text(root, NC_GLOBAL, "Conventions", "CF-1.8", target);
    put_text(root, NC_GLOBAL, "title", f.title, target);
    put_text(root, NC_GLOBAL, "source", "forestwind", target);
    put_text(root, NC_GLOBAL, "history", f.history, target);
    check(nc_put_att_double(root, NC_GLOBAL, kIntervalAttribute, NC_DOUBLE, 1, &f.interval), target,
          "writing interval_seconds");
    check(nc_put_att_double(root, NC_GLOBAL, kAveragingAttribute, NC_DOUBLE, 1, &f.averaging), target,
          "writing averaging_seconds");
    const ProfileGroup domain = define_profiles(root, f, target);
    // The time series, in a group of their own with their own times.
    int series = 0, series_time_dim = 0;
    check(nc_def_grp(root, kSeriesGroup, &series), target, "defining the group timeseries");
    const int series_time_var =
        define_coordinate(series, "time", NC_UNLIMITED, kTime, "T", target, &series_time_dim);
    std::vector<int> series_vars;
    for (const StatsVariable& v : f.series.variables)
      series_vars.push_back(define_variable(series, v, {series_time_dim}, target));
    // The regions, a group each below regions/.
    std::vector<ProfileGroup> regions;
    if (!f.regions.empty()) {
      int parent = 0;
      check(nc_def_grp(root, kRegionsGroup, &parent), target, "defining the group regions");
      for (const StatsRegion& region : f.regions) {
        int group = 0;
        check(nc_def_grp(parent, region.name.c_str(), &group), target,
              fmt::format("defining the group regions/{}", region.name));
        check(nc_put_att_double(group, NC_GLOBAL, "region_min", NC_DOUBLE, 2, region.min.data()), target,
              "writing region_min");
        check(nc_put_att_double(group, NC_GLOBAL, "region_max", NC_DOUBLE, 2, region.max.data()), target,
              "writing region_max");
        regions.push_back(define_profiles(group, f, target));
      }
    }
    check(nc_enddef(root), target, "ending the definitions");

    write_profiles(domain, f, f.profiles.values, target);
    for (std::size_t n = 0; n < regions.size(); ++n)
      write_profiles(regions[n], f, f.regions[n].values, target);
    for (std::size_t r = 0; r < f.series.time.size(); ++r) {
      const std::size_t at[1] = {r}, one[1] = {1};
      check(nc_put_vara_double(series, series_time_var, at, one, &f.series.time[r]), target,
            "writing the time series' time");
      for (std::size_t n = 0; n < series_vars.size(); ++n)
        check(nc_put_vara_double(series, series_vars[n], at, one, &f.series.values[r][n]), target,
              fmt::format("writing {}", f.series.variables[n].name));
    }
  } catch (...) {
    nc_abort(root);
    throw;
  }
  NC_memio memory{};
  check(nc_close_memio(root, &memory), target, "closing the file");
  const std::unique_ptr<void, decltype(&std::free)> owned(memory.memory, &std::free);
  return {static_cast<const char*>(memory.memory), memory.size};
}

// The variables of `group` other than its coordinates, in the order they were defined, with their values:
// per variable, every value in the file's order (record-major).
std::vector<std::pair<StatsVariable, std::vector<double>>> read_variables(int group,
                                                                          const std::filesystem::path& path) {
  int count = 0;
  check(nc_inq_varids(group, &count, nullptr), path, "listing the variables");
  std::vector<int> ids(std::size_t(count), 0);
  check(nc_inq_varids(group, &count, ids.data()), path, "listing the variables");
  std::vector<std::pair<StatsVariable, std::vector<double>>> out;
  for (const int id : ids) {
    char name[NC_MAX_NAME + 1] = {};
    int dims = 0;
    check(nc_inq_var(group, id, name, nullptr, &dims, nullptr, nullptr), path, "reading a variable");
    std::vector<int> dim_ids(std::size_t(dims), 0);
    check(nc_inq_vardimid(group, id, dim_ids.data()), path, fmt::format("reading {}'s dimensions", name));
    std::size_t values = 1;
    for (const int d : dim_ids) {
      std::size_t length = 0;
      check(nc_inq_dimlen(group, d, &length), path, fmt::format("reading {}'s dimensions", name));
      values *= length;
    }
    std::vector<double> data(values, 0.0);
    if (values > 0) check(nc_get_var_double(group, id, data.data()), path, fmt::format("reading {}", name));
    out.push_back({{name, get_text(group, id, "units", path), get_text(group, id, "long_name", path),
                    get_text(group, id, "standard_name", path)},
                   std::move(data)});
  }
  return out;
}

// A group's profiles ([record][variable][k]), with its times, heights and variables.
std::vector<std::vector<std::vector<double>>> read_profiles(int group, const std::filesystem::path& path,
                                                            std::vector<double>* time, std::vector<double>* z,
                                                            std::vector<StatsVariable>* variables) {
  std::vector<std::vector<std::vector<double>>> values;
  const auto read = read_variables(group, path);
  for (const auto& [about, data] : read) {
    if (about.name == "time") *time = data;
    if (about.name == "z") *z = data;
  }
  values.resize(time->size(), {});
  for (const auto& [about, data] : read) {
    if (about.name == "time" || about.name == "z") continue;
    variables->push_back(about);
    for (std::size_t r = 0; r < time->size(); ++r)
      values[r].emplace_back(data.begin() + long(r * z->size()), data.begin() + long((r + 1) * z->size()));
  }
  return values;
}

}  // namespace

StatsFile read_stats_netcdf(const std::filesystem::path& path) {
  int root = 0;
  check(nc_open(path.c_str(), NC_NOWRITE, &root), path, "opening the file");
  StatsFile f;
  try {
    f.title = get_text(root, NC_GLOBAL, "title", path);
    f.history = get_text(root, NC_GLOBAL, "history", path);
    // A file without them reads as 0: not given.
    nc_get_att_double(root, NC_GLOBAL, kIntervalAttribute, &f.interval);
    nc_get_att_double(root, NC_GLOBAL, kAveragingAttribute, &f.averaging);
    f.profiles.values = read_profiles(root, path, &f.profiles.time, &f.z, &f.profiles.variables);
    int regions = 0;
    if (nc_inq_ncid(root, kRegionsGroup, &regions) == NC_NOERR) {
      int count = 0;
      check(nc_inq_grps(regions, &count, nullptr), path, "listing the regions");
      std::vector<int> groups(std::size_t(count), 0);
      check(nc_inq_grps(regions, &count, groups.data()), path, "listing the regions");
      for (const int group : groups) {
        StatsRegion region;
        char name[NC_MAX_NAME + 1] = {};
        check(nc_inq_grpname(group, name), path, "reading a region's name");
        region.name = name;
        check(nc_get_att_double(group, NC_GLOBAL, "region_min", region.min.data()), path,
              fmt::format("reading region {}'s region_min", region.name));
        check(nc_get_att_double(group, NC_GLOBAL, "region_max", region.max.data()), path,
              fmt::format("reading region {}'s region_max", region.name));
        std::vector<double> time, z;
        std::vector<StatsVariable> variables;
        const auto values = read_profiles(group, path, &time, &z, &variables);
        // Its variables in the domain's order, by name (the root group lists them by name, a group in the
        // order they were made).
        std::vector<std::size_t> at;
        for (const StatsVariable& v : f.profiles.variables)
          at.push_back(std::size_t(std::find(variables.begin(), variables.end(), v) - variables.begin()));
        const bool same =
            time == f.profiles.time && z == f.z && variables.size() == at.size() &&
            std::all_of(at.begin(), at.end(), [&](std::size_t n) { return n < variables.size(); });
        if (!same)
          throw std::runtime_error(
              fmt::format("{}: region {} has other times, heights or variables than the domain's",
                          path.string(), region.name));
        for (const auto& record : values) {
          std::vector<std::vector<double>> ours;
          for (const std::size_t n : at) ours.push_back(record[n]);
          region.values.push_back(std::move(ours));
        }
        f.regions.push_back(std::move(region));
      }
    }
    int series = 0;
    check(nc_inq_ncid(root, kSeriesGroup, &series), path, "finding the group timeseries");
    const auto read = read_variables(series, path);
    for (const auto& [about, data] : read)
      if (about.name == "time") f.series.time = data;
    f.series.values.resize(f.series.time.size(), {});
    for (const auto& [about, data] : read) {
      if (about.name == "time") continue;
      f.series.variables.push_back(about);
      for (std::size_t r = 0; r < f.series.time.size(); ++r) f.series.values[r].push_back(data[r]);
    }
  } catch (...) {
    nc_close(root);
    throw;
  }
  check(nc_close(root), path, "closing the file");
  return f;
}

std::vector<StatsVariable> profile_columns() {
  std::vector<StatsVariable> columns;
  for (const fluid::ProfileVariable& v : fluid::profile_variables())
    columns.push_back({v.name, v.units, v.long_name, v.standard_name});
  return columns;
}

void write_stats_netcdf(const std::filesystem::path& path, const StatsFile& file) {
  require_shapes(file);
  base::write_text_atomically("write_stats_netcdf", path, file_bytes(path, file));
}

}  // namespace fw::io
