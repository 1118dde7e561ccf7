// host/app/StatisticsRecorder: a run's stats.nc, end to end (scenario -> plan -> Simulation -> file), on a
// flow whose statistics are known exactly.
#include "host/app/StatisticsRecorder.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "host/app/Simulation.hpp"
#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "io/StatsNetcdf.hpp"
#include "tests/support/TempDir.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;

namespace {

// A uniform 6 m/s wind from the west through a box periodic in x and y between slip ground and lid: it
// stays uniform, so every record holds u = 6 m/s, v = w = 0 and no variance, at every height. A stand-alone
// region ("east") and 0.1 s steps: records at 0.5, 1.0, 1.5 and 2.0 s, a time-series row every step.
const char* kUniform = R"(scenario: uniform_box
time: {end: 2.0, dt: 0.1}
domain: {origin: [0, 0, 10], size: [32, 16, 12], cell_size: 2.0}
boundaries: {west: periodic, east: periodic, south: periodic, north: periodic, ground: slip, top: slip}
wind: {speed: 6.0, direction: 270.0, profile: {type: uniform}}
output:
  directory: out
  interval: 1.0
  vtk: {wind: false, trees: false}
  statistics:
    interval: 0.5
    averaging: 0.3
    regions:
      - {name: east, min: [16, 0], max: [32, 16]}
)";

// Float faces of 6 m/s: exact in float and in the sums; a few roundings of the raw moments' algebra.
constexpr double kRounding = 1e-12;

}  // namespace

TEST_CASE("StatisticsRecorder: a run's stats.nc holds a uniform wind's records, regions and time series",
          "[simulation][statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const test::TempDir dir("fw_stats_run");
  const io::Scenario scenario = io::load_scenario(dir.write("uniform.yaml", kUniform));
  const auto out = std::filesystem::path(dir.path()) / "out";
  host::Simulation sim(*cc, host::plan_simulation(scenario, nullptr, nullptr), out);
  const host::RunSummary summary = sim.run(host::RunOptions{});
  CHECK(summary.stage_ms.count("statistics") == 1);

  const io::StatsFile stats = io::read_stats_netcdf(out / "stats.nc");
  CHECK(stats.title == "uniform_box");
  CHECK(stats.history == "forestwind run uniform.yaml");
  // Heights: the cell centres above the domain's origin (10 m): absolute.
  REQUIRE(stats.z.size() == 6);
  CHECK(stats.z.front() == Approx(11.0));
  CHECK(stats.z.back() == Approx(21.0));
  REQUIRE(stats.profiles.time.size() == 4);
  for (std::size_t r = 0; r < 4; ++r)
    CHECK(stats.profiles.time[r] == Approx(0.5 * double(r + 1)).margin(1e-9));
  REQUIRE(stats.regions.size() == 1);
  CHECK(stats.regions[0].name == "east");
  CHECK(stats.regions[0].min == std::array<double, 2>{16.0, 0.0});
  CHECK(stats.regions[0].max == std::array<double, 2>{32.0, 16.0});
  const auto column = [&](const std::string& name) {
    for (std::size_t n = 0; n < stats.profiles.variables.size(); ++n)
      if (stats.profiles.variables[n].name == name) return n;
    FAIL("no variable " << name);
    return std::size_t(0);
  };
  for (const auto* values : {&stats.profiles.values, &stats.regions[0].values})
    for (const auto& record : *values)
      for (std::size_t k = 0; k < stats.z.size(); ++k) {
        INFO("height " << k);
        CHECK(record[column("area")][k] == 1.0);
        CHECK(record[column("u")][k] == Approx(6.0).margin(kRounding));
        CHECK(std::abs(record[column("v")][k]) < kRounding);
        CHECK(std::abs(record[column("w")][k]) < kRounding);
        CHECK(std::abs(record[column("u_2")][k]) < kRounding);
        CHECK(std::abs(record[column("u_3")][k]) < kRounding);
        CHECK(std::abs(record[column("u_flux")][k]) < kRounding);
        CHECK(record[column("lad")][k] == 0.0);
      }

  // A row a step: 20 steps of 0.1 s.
  REQUIRE(stats.series.time.size() == 20);
  REQUIRE(stats.series.variables == host::series_columns());
  for (std::size_t r = 0; r < 20; ++r) {
    INFO("row " << r);
    const std::vector<double>& row = stats.series.values[r];
    CHECK(stats.series.time[r] == Approx(0.1 * double(r + 1)).margin(1e-9));
    CHECK(row[0] == Approx(0.0).margin(1e-6));     // u*: no flux at a slip ground
    CHECK(row[1] == Approx(18.0).epsilon(1e-12));  // |u|^2 / 2
    CHECK(row[2] == Approx(6.0).epsilon(1e-12));   // the largest speed
    CHECK(row[3] == Approx(0.1).epsilon(1e-12));   // dt
    CHECK(row[5] >= 0.0);                          // pressure iterations
    CHECK(row[6] == 0.0);                          // no leaves, no trees
    CHECK(row[8] == 0.0);
  }
}
