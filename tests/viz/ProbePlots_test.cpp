#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "tests/support/Pictures.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/ProbePlots.hpp"
#include "viz/ProbeTable.hpp"

namespace fs = std::filesystem;
using fw::test::bytes;
using fw::test::colour_distance;

namespace {

// A table of `samples` rows at `dt`: probe "mast" blowing speed(t) along x, probe "gap" a steady 3 m/s, and
// tree 0's tip swinging 0.2 m along x.
template <class Speed>
fw::viz::ProbeTable table_of(std::size_t samples, double dt, Speed speed) {
  fw::viz::ProbeTable t;
  t.probes = {{"mast", {}}, {"gap", {}}};
  t.tips = {{"tree0", {}}};
  for (std::size_t n = 0; n < samples; ++n) {
    const double time = n * dt;
    t.time.push_back(time);
    t.probes[0].xyz.push_back({speed(time), 0.0, 0.0});
    t.probes[1].xyz.push_back({3.0, 0.0, 0.0});
    t.tips[0].xyz.push_back({0.2 * std::sin(time), 0.0, 0.0});
  }
  return t;
}

// Anti-aliased lines 1.5 px wide: a pixel on the line is within this many levels of the line's colour.
constexpr int kLineTolerance = 40;

// The topmost pixel of column i (inside `area`) that has the colour c, or -1.
int topmost(const fw::test::Picture& image, const fw::viz::Viewport& area, int i, const fw::viz::Rgb& c) {
  for (int j = int(area.y) + 1; j < int(area.y + area.height); ++j)
    if (colour_distance(image.at(i, j), bytes(c)) <= kLineTolerance) return j;
  return -1;
}

}  // namespace

TEST_CASE("ProbePlots: every panel has its axes, and the lines lie inside them", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  const auto table = table_of(200, 0.1, [](double t) { return 8.0 + std::sin(t); });
  const auto plot = fw::viz::plot_probes(table, {0.0, 5.0, 10.0, 15.0}, "test", {});
  const fs::path png = fs::path(dir.path()) / "probes.png";
  plot.canvas.write_png(png);
  const auto image = fw::test::read_png(png);
  REQUIRE(plot.panels == std::vector<std::string>{"wind", "tips"});
  CHECK(image.width == 1280);
  CHECK(image.height == plot.canvas.height());
  for (const auto& a : plot.plot_areas) {
    // The frame of the axes: dark on all four sides (the 1 px line on a half-pixel straddles two rows).
    auto dark = [&](int i, int j) {
      int darkest = 255;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) darkest = std::min(darkest, image.at(i + di, j + dj)[0]);
      return darkest < 100;
    };
    for (double f : {0.1, 0.5, 0.9}) {
      CHECK(dark(int(a.x), int(a.y + f * a.height)));            // left
      CHECK(dark(int(a.x + a.width), int(a.y + f * a.height)));  // right
      CHECK(dark(int(a.x + f * a.width), int(a.y + a.height)));  // bottom
      CHECK(dark(int(a.x + 0.3 * f * a.width), int(a.y)));       // top, left of the legend
    }
  }
  // The first probe's line crosses the wind panel's first third; the steady probe sits below it.
  const auto& wind = plot.plot_areas[0];
  const int column = int(wind.x + 0.2 * wind.width);
  const int mast = topmost(image, wind, column, fw::viz::series_colour(0));
  const int gap = topmost(image, wind, column, fw::viz::series_colour(1));
  CHECK(mast > 0);
  CHECK(gap > mast);  // 3 m/s is lower in the picture than 7-9 m/s
}

TEST_CASE("ProbePlots: the spectrum of a sine peaks at its frequency on log axes", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  const double f0 = 2.0, dt = 0.05;  // Hz, s: 10 samples a period, Nyquist 10 Hz
  const auto table =
      table_of(1024, dt, [&](double t) { return 10.0 + std::sin(2 * std::numbers::pi * f0 * t); });
  fw::viz::PlotSettings settings;
  settings.spectrum = true;
  const auto plot = fw::viz::plot_probes(table, {}, "test", settings);
  REQUIRE(plot.panels.back() == "spectrum");
  const fs::path png = fs::path(dir.path()) / "spectrum.png";
  plot.canvas.write_png(png);
  const auto image = fw::test::read_png(png);
  const auto& area = plot.plot_areas.back();
  // The highest point of the mast's spectrum: its column maps back to the frequency on the log axis.
  int best_column = -1, best_row = 1 << 30;
  for (int i = int(area.x) + 2; i < int(area.x + 0.85 * area.width); ++i)
    if (const int j = topmost(image, area, i, fw::viz::series_colour(0)); j >= 0 && j < best_row)
      best_row = j, best_column = i;
  REQUIRE(best_column > 0);
  // x axis: df = 1 / (256 dt) (segments of 256 for 1024 samples) to the Nyquist frequency 1 / (2 dt).
  const double lo = 1.0 / (256 * dt), hi = 0.5 / dt;
  const double f = lo * std::pow(hi / lo, (best_column + 0.5 - area.x) / area.width);
  // The peak spreads over the Hann window's main lobe, +-2 bins of df = 0.078 Hz: 8% of 2 Hz.
  CHECK(f == Approx(f0).epsilon(0.08));
}

TEST_CASE("ProbePlots: the damage panel lies under the wind on its time axis and steps at the failures",
          "[viz]") {
  fw::test::TempDir dir("fw_viz");
  auto table = table_of(200, 0.1, [](double t) { return 8.0 + std::sin(t); });  // 0 .. 19.9 s
  // Ten trees: one breaks by 5 s and two more by 12 s; one overturns by 8 s (the rows a run samples).
  fw::viz::DamageCounts counts;
  for (double t : table.time) {
    const int broken = t >= 12.0 - 1e-9 ? 3 : t >= 5.0 - 1e-9 ? 1 : 0, overturned = t >= 8.0 - 1e-9 ? 1 : 0;
    counts.time.push_back(t);
    counts.standing.push_back(10 - broken - overturned);
    counts.broken.push_back(broken);
    counts.overturned.push_back(overturned);
  }
  table.damage = counts;
  const auto plot = fw::viz::plot_probes(table, {}, "test", {});
  REQUIRE(plot.panels == std::vector<std::string>{"wind", "damage", "tips"});
  const auto& wind = plot.plot_areas[0];
  const auto& area = plot.plot_areas[1];
  CHECK(area.x == wind.x);  // the same time axis: 0 .. 19.9 s across the same columns
  CHECK(area.width == wind.width);
  const fs::path png = fs::path(dir.path()) / "damage.png";
  plot.canvas.write_png(png);
  const auto image = fw::test::read_png(png);
  // The y axis runs from a little below 0, so that 0 shows above the axis, to 1.08 x the most failed trees,
  // at least 5.
  const double lo = -0.05 * 1.08 * 5, hi = 1.08 * 5;
  auto column = [&](double t) { return int(area.x + area.width * t / 19.9); };
  auto row = [&](double count) { return area.y + area.height * (hi - count) / (hi - lo); };
  const fw::viz::Rgb broken{0.90, 0.11, 0.09};
  for (const auto& [t, before, after] : {std::tuple{5.0, 0, 1}, std::tuple{12.0, 1, 3}}) {
    INFO("the step at " << t << " s");
    CHECK(topmost(image, area, column(t) - 3, broken) == Approx(row(before)).margin(2));
    CHECK(topmost(image, area, column(t) + 3, broken) == Approx(row(after)).margin(2));
  }
  // And nowhere else: flat between the steps.
  for (double t : {2.0, 9.0, 18.0})
    CHECK(topmost(image, area, column(t), broken) == Approx(row(t < 5 ? 0 : t < 12 ? 1 : 3)).margin(2));
}

TEST_CASE("ProbePlots: spectra need enough samples, and a table needs probes or trees", "[viz]") {
  fw::viz::PlotSettings settings;
  settings.spectrum = true;
  CHECK_THROWS_WITH(fw::viz::plot_probes(table_of(100, 0.1, [](double) { return 5.0; }), {}, "x", settings),
                    Catch::Contains("holds 100 samples per probe; a spectrum needs at least 256"));
  CHECK_THROWS_WITH(fw::viz::plot_probes(fw::viz::ProbeTable{{0.0}, {}, {}}, {}, "x", {}),
                    Catch::Contains("neither probes nor tracked trees"));
}

TEST_CASE("ProbeTable: reads what a run writes and names the line of a bad value", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  const std::string good =
      dir.write("probes.csv",
                "time_s,mast_u,mast_v,mast_w,tree3_tip_dx,tree3_tip_dy,tree3_tip_dz,leaves_shed,"
                "leaves_flying,leaves_landed,leaves_exited\n"
                "0,1,2,2,0.5,0,0,0,0,0,0\n"
                "0.5,3,4,0,nan,0,0,1,1,0,0\n"
                "1.0,9,9");  // a run killed in the middle of a row
  const auto table = fw::viz::read_probe_table(good);
  REQUIRE(table.time == std::vector<double>{0.0, 0.5});
  REQUIRE(table.probes.size() == 1);
  CHECK(table.probes[0].name == "mast");
  CHECK(table.probes[0].magnitude() == std::vector<double>{3.0, 5.0});
  REQUIRE(table.tips.size() == 1);
  CHECK(table.tips[0].name == "tree3");
  CHECK(std::isnan(table.tips[0].xyz[1][0]));
  CHECK_FALSE(table.damage);
  // With storm damage: the tree counts after the leaf counts.
  const auto damaged = fw::viz::read_probe_table(
      dir.write("damaged.csv",
                "time_s,mast_u,mast_v,mast_w,leaves_shed,leaves_flying,leaves_landed,leaves_exited,"
                "trees_standing,trees_broken,trees_overturned\n"
                "0,1,0,0,0,0,0,0,12,0,0\n"
                "0.5,2,0,0,3,1,1,0,10,1,1\n"));
  REQUIRE(damaged.damage);
  CHECK(damaged.damage->time == damaged.time);
  CHECK(damaged.damage->standing == std::vector<int>{12, 10});
  CHECK(damaged.damage->broken == std::vector<int>{0, 1});
  CHECK(damaged.damage->overturned == std::vector<int>{0, 1});
  CHECK_THROWS_WITH(
      fw::viz::read_probe_table(dir.write("counts.csv",
                                          "time_s,mast_u,mast_v,mast_w,trees_standing,trees_broken,"
                                          "trees_overturned\n0,1,0,0,12,0.5,0\n")),
      Catch::Contains("counts.csv:2: trees_broken: expected a whole number >= 0, got '0.5'"));
  const std::string bad = dir.write("bad.csv", "time_s,mast_u,mast_v,mast_w\n0,1,2,3\n0.5,1,x,3\n");
  CHECK_THROWS_WITH(fw::viz::read_probe_table(bad),
                    Catch::Contains("bad.csv:3: mast_v: expected a number, got 'x'"));
  const std::string odd = dir.write("odd.csv", "time_s,mast_u,mast_w\n");
  CHECK_THROWS_WITH(fw::viz::read_probe_table(odd),
                    Catch::Contains("odd.csv:1: mast_u: expected a column triple"));
}
