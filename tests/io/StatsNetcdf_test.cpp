// io/StatsNetcdf: stats.nc written and read back, its CF attributes, ncdump's view of it, and bad shapes.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "fluid/PlaneProfiles.hpp"
#include "io/StatsNetcdf.hpp"

using namespace fw;

namespace {

std::filesystem::path fresh_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("fw_stats_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

// Two profile records of every profile variable on three heights, and three time-series records.
io::StatsFile two_records() {
  io::StatsFile f;
  f.title = "periodic_canopy";
  f.history = "forestwind run canopy.yaml";
  f.z = {1.0, 3.0, 5.0};
  f.interval = 60.0;
  f.averaging = 30.0;
  f.profiles.variables = io::profile_columns();
  f.profiles.time = {60.0, 120.0};
  for (std::size_t r = 0; r < 2; ++r) {
    std::vector<std::vector<double>> record;
    for (std::size_t n = 0; n < f.profiles.variables.size(); ++n)
      record.push_back({100.0 * r + n, 100.0 * r + n + 0.25, 100.0 * r + n + 0.5});
    f.profiles.values.push_back(record);
  }
  f.series.variables = {{"ustar", "m s-1", "friction velocity at the ground", ""},
                        {"dt", "s", "time step", ""}};
  f.series.time = {0.5, 1.0, 1.5};
  f.series.values = {{0.31, 0.5}, {0.32, 0.5}, {0.33, 0.5}};
  // A region: the domain's values plus 1000.
  io::StatsRegion gap{"gap", {10.0, 20.0}, {30.0, 44.0}, f.profiles.values};
  for (auto& record : gap.values)
    for (auto& profile : record)
      for (double& value : profile) value += 1000.0;
  f.regions = {gap};
  return f;
}

// What a shell command prints on stdout.
std::string output_of(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  REQUIRE(pipe);
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof(buffer), pipe.get())) out.append(buffer, n);
  return out;
}

}  // namespace

TEST_CASE("stats.nc: profiles and time series read back as written, with their units and names", "[stats]") {
  const auto path = fresh_folder("round_trip") / "stats.nc";
  const io::StatsFile written = two_records();
  io::write_stats_netcdf(path, written);
  const io::StatsFile read = io::read_stats_netcdf(path);
  CHECK(read.title == written.title);
  CHECK(read.history == written.history);
  CHECK(read.z == written.z);
  CHECK(read.interval == 60.0);
  CHECK(read.averaging == 30.0);
  CHECK(read.profiles.time == written.profiles.time);
  // The file lists its variables by name: each written one is found there, with its attributes and values.
  REQUIRE(read.profiles.variables.size() == written.profiles.variables.size());
  const auto find_in = [](const std::vector<io::StatsVariable>& list, const std::string& name) {
    for (std::size_t n = 0; n < list.size(); ++n)
      if (list[n].name == name) return n;
    return list.size();
  };
  for (std::size_t n = 0; n < written.profiles.variables.size(); ++n) {
    const io::StatsVariable& v = written.profiles.variables[n];
    INFO(v.name);
    const std::size_t at = find_in(read.profiles.variables, v.name);
    REQUIRE(at < read.profiles.variables.size());
    CHECK(read.profiles.variables[at] == v);
    for (std::size_t r = 0; r < written.profiles.time.size(); ++r) {
      CHECK(read.profiles.values[r][at] == written.profiles.values[r][n]);  // doubles as doubles: bit for bit
      CHECK(read.regions.at(0).values[r][at] == written.regions[0].values[r][n]);
    }
  }
  CHECK(read.series.time == written.series.time);
  REQUIRE(read.regions.size() == 1);
  CHECK(read.regions[0].name == "gap");
  CHECK(read.regions[0].min == written.regions[0].min);
  CHECK(read.regions[0].max == written.regions[0].max);
  REQUIRE(read.series.variables.size() == 2);
  const std::size_t ustar = find_in(read.series.variables, "ustar");
  REQUIRE(ustar < 2);
  CHECK(read.series.variables[ustar].units == "m s-1");
  for (std::size_t r = 0; r < 3; ++r) CHECK(read.series.values[r][ustar] == written.series.values[r][0]);
  // No temporary is left beside it.
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path()))
    CHECK(entry.path().filename() == "stats.nc");
}

TEST_CASE("stats.nc: ncdump -h shows CF-1.8, the dimensions time and z, and each variable's attributes",
          "[stats]") {
  const auto path = fresh_folder("ncdump") / "stats.nc";
  io::write_stats_netcdf(path, two_records());
  const std::string header = output_of("ncdump -h " + path.string() + " 2>&1");
  INFO(header);
  for (const char* text :
       {"netcdf stats {", "time = UNLIMITED ; // (2 currently)", "z = 3 ;", ":Conventions = \"CF-1.8\" ;",
        "double u_w(time, z) ;", "u_w:units = \"m2 s-2\" ;", "u:standard_name = \"eastward_wind\" ;",
        "z:positive = \"up\" ;", "z:axis = \"Z\" ;", "group: timeseries {", "double ustar(time) ;",
        "group: regions {", "group: gap {", ":region_min = 10., 20. ;",
        "u:cell_methods = \"area: mean time: mean\" ;", ":averaging_seconds = 30. ;"})
    CHECK(header.find(text) != std::string::npos);
}

TEST_CASE("stats.nc: xarray opens it, the profiles on (time, z) and the time series in their group",
          "[stats]") {
  // Debian's Python, where python3-xarray and python3-netcdf4 install (scripts/install-deps.sh), whatever
  // python3 comes first on the PATH.
  const auto path = fresh_folder("xarray") / "stats.nc";
  io::write_stats_netcdf(path, two_records());
  const std::string script =
      "import xarray as xr\n"
      "ds = xr.open_dataset('" +
      path.string() +
      "')\n"
      "ts = xr.open_dataset('" +
      path.string() +
      "', group='timeseries')\n"
      "print(ds['u_w'].dims, float(ds['u_w'][1, 2]), ds['u'].attrs['standard_name'], "
      "list(ds['time'].values))\n"
      "print(ts['ustar'].dims, float(ts['ustar'][2]))\n"
      "gap = xr.open_dataset('" +
      path.string() +
      "', group='regions/gap')\n"
      "print('gap', float(gap['u_w'][1, 2]), list(gap['z'].values))\n";
  const std::string out = output_of("/usr/bin/python3 -c \"" + script + "\" 2>&1");
  INFO(out);
  // u_w is variable 9: its record 1 at height 2 holds 100 + 9 + 0.5.
  CHECK(out.find("('time', 'z') 109.5 eastward_wind [60.0, 120.0]") != std::string::npos);
  CHECK(out.find("('time',) 0.33") != std::string::npos);
  CHECK(out.find("gap 1109.5 [1.0, 3.0, 5.0]") != std::string::npos);
}

TEST_CASE("stats.nc: a record of the wrong shape is refused and nothing is written", "[stats]") {
  const auto folder = fresh_folder("bad_shape");
  io::StatsFile f = two_records();
  f.profiles.values[1][3].pop_back();  // one height short
  CHECK_THROWS_AS(io::write_stats_netcdf(folder / "stats.nc", f), std::invalid_argument);
  f = two_records();
  f.series.time.push_back(2.0);  // a time without its record
  CHECK_THROWS_AS(io::write_stats_netcdf(folder / "stats.nc", f), std::invalid_argument);
  f = two_records();
  f.regions[0].values.pop_back();  // a region a record short
  CHECK_THROWS_AS(io::write_stats_netcdf(folder / "stats.nc", f), std::invalid_argument);
  CHECK(std::filesystem::is_empty(folder));
  CHECK_THROWS_AS(io::read_stats_netcdf(folder / "missing.nc"), std::runtime_error);
}
