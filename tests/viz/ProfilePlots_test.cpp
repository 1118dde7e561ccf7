// viz/ProfilePlots: stats.nc's profiles as a picture: the panels a file calls for, the last record's lines
// where its values put them, and the errors `plot --profiles` reports.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>

#include "tests/support/Pictures.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/ProfilePlots.hpp"

namespace fs = std::filesystem;
using fw::test::bytes;
using fw::test::colour_distance;

namespace {

// Two records on 8 heights of 2 m: u = 2 + z / 4 in the last, everything else 0 but u_2 = 0.25, and lad
// below 6 m when `canopy`.
fw::io::StatsFile two_records(bool canopy) {
  fw::io::StatsFile f;
  f.title = "profiles";
  f.averaging = 10.0;
  for (int k = 0; k < 8; ++k) f.z.push_back(1.0 + 2.0 * k);
  f.profiles.variables = fw::io::profile_columns();
  f.profiles.time = {10.0, 20.0};
  for (int r = 0; r < 2; ++r) {
    std::vector<std::vector<double>> record(f.profiles.variables.size(), std::vector<double>(8, 0.0));
    for (std::size_t n = 0; n < f.profiles.variables.size(); ++n)
      for (int k = 0; k < 8; ++k) {
        const std::string& name = f.profiles.variables[n].name;
        if (name == "u") record[n][std::size_t(k)] = (r == 1 ? 2.0 : 1.0) + f.z[std::size_t(k)] / 4.0;
        if (name == "u_2") record[n][std::size_t(k)] = 0.25;
        if (name == "area") record[n][std::size_t(k)] = 1.0;
        if (name == "lad" && canopy && f.z[std::size_t(k)] < 6.0) record[n][std::size_t(k)] = 0.3;
      }
    f.profiles.values.push_back(record);
  }
  f.regions.push_back({"gap", {0, 0}, {10, 10}, f.profiles.values});
  return f;
}

// Anti-aliased lines 1.8 px wide: a pixel on the line is within this many levels of the line's colour.
constexpr int kLineTolerance = 40;

}  // namespace

TEST_CASE("ProfilePlots: four panels against height, a fifth with a canopy, and u's line where u lies",
          "[viz]") {
  fw::test::TempDir dir("fw_viz_profiles");
  const auto plot = fw::viz::plot_profiles(two_records(false), "");
  CHECK(plot.panels == std::vector<std::string>{"mean", "flux", "variance", "skewness"});
  CHECK(fw::viz::plot_profiles(two_records(true), "").panels.back() == "canopy");
  CHECK(fw::viz::plot_profiles(two_records(true), "gap").panels.size() == 5);
  const fs::path png = fs::path(dir.path()) / "profiles.png";
  plot.canvas.write_png(png);
  const auto image = fw::test::read_png(png);
  // In the mean panel, u's colour (series 0) crosses the row of each height's pixel somewhere; its column
  // moves right with height (u grows with z), and the grey of the earlier record lies left of it.
  const fw::viz::Viewport& area = plot.plot_areas[0];
  const auto column_of = [&](int row, const fw::viz::Rgb& colour) {
    for (int i = int(area.x) + 2; i < int(area.x + area.width) - 2; ++i)
      if (colour_distance(image.at(i, row), bytes(colour)) <= kLineTolerance) return i;
    return -1;
  };
  const int low = int(area.y + 0.85 * area.height), high = int(area.y + 0.15 * area.height);
  const int u_low = column_of(low, fw::viz::series_colour(0)),
            u_high = column_of(high, fw::viz::series_colour(0));
  REQUIRE(u_low > 0);
  REQUIRE(u_high > 0);
  CHECK(u_high > u_low);
}

TEST_CASE("ProfilePlots: no record, or no such region, is refused naming what there is", "[viz]") {
  fw::io::StatsFile empty = two_records(false);
  empty.profiles.time.clear();
  empty.profiles.values.clear();
  CHECK_THROWS_WITH(fw::viz::plot_profiles(empty, ""), Catch::Contains("no profile record yet"));
  CHECK_THROWS_WITH(fw::viz::plot_profiles(two_records(false), "lee"),
                    Catch::Contains("no such region") && Catch::Contains("gap"));
}
