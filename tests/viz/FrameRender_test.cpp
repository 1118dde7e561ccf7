#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/support/Pictures.hpp"
#include "tests/support/RunFolders.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/FrameRender.hpp"
#include "viz/RunFolder.hpp"

namespace fs = std::filesystem;
using fw::test::bytes;
using fw::test::colour_distance;

namespace {

// The PNG holds our 8-bit rounding of the map's colour exactly (lossless), and a cell drawn as a sharp
// block has no anti-aliasing inside it: one level per channel allows for the rounding only.
constexpr int kColourTolerance = 1;

fw::viz::FrameRender render(const fs::path& folder, fw::viz::RenderSettings settings, const fs::path& png) {
  const fw::viz::RunFolder run(folder);
  fw::viz::FrameRender picture(run.load(run.select(std::nullopt, std::nullopt)), run.scenario_name(),
                               settings);
  picture.canvas().write_png(png);
  return picture;
}

}  // namespace

TEST_CASE("FrameRender: the inflow of a uniform wind has the colour map's colour for its speed", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::UniformWind wind;                                // 6 m/s, 40 x 20 x 10 cells of 1 m
  wind.slow_x0 = 28, wind.slow_x1 = 40, wind.slow_u = 2.0f;  // a slow wake in the east
  fw::test::write_run(dir.path(), wind, {}, 2, 0.5);
  fw::viz::RenderSettings settings;
  settings.height = 5.2;
  settings.range = std::array<double, 2>{0.0, 10.0};
  const fs::path png = fs::path(dir.path()) / "top.png";
  const auto picture = render(dir.path(), settings, png);
  const auto image = fw::test::read_png(png);
  CHECK(image.width == settings.width);
  CHECK(image.height == settings.height_px);
  CHECK(picture.slice_layer() == 5);

  const fw::viz::ColourMap& map = fw::viz::ColourMap::named("wind");
  // Cell centres of the inflow region (x < 28 m) and of the wake, well inside their regions.
  for (double x : {0.5, 3.5, 12.5, 25.5})
    for (double y : {0.5, 9.5, 18.5}) {
      const auto p = picture.camera().to_pixel({x, y, 5.5});
      INFO("x " << x << " y " << y);
      CHECK(colour_distance(image.at(int(p.x), int(p.y)), bytes(map.colour(6.0, 0.0, 10.0))) <=
            kColourTolerance);
    }
  for (double x : {30.5, 38.5}) {
    const auto p = picture.camera().to_pixel({x, 10.5, 5.5});
    CHECK(colour_distance(image.at(int(p.x), int(p.y)), bytes(map.colour(2.0, 0.0, 10.0))) <=
          kColourTolerance);
  }
  // The default range is 0 to the slice's fastest wind: the inflow is then the top of the map.
  settings.range.reset();
  const auto fitted = render(dir.path(), settings, png);
  CHECK(fitted.range() == std::array<double, 2>{0.0, 6.0});
  const auto p = fitted.camera().to_pixel({10.5, 10.5, 5.5});
  CHECK(colour_distance(fw::test::read_png(png).at(int(p.x), int(p.y)), bytes(map.colour(1.0))) <=
        kColourTolerance);
}

TEST_CASE("FrameRender: a tree is drawn where it stands and nowhere else", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::UniformWind wind;
  // A trunk 8 m tall at (12, 10), 0.4 m in radius, its top swayed 1 m downwind.
  fw::test::write_run(dir.path(), wind, {fw::test::trunk(12.0, 10.0, 8.0, 0.4, 9, 1.0)}, 1, 0.5);
  const fw::viz::Rgb slice_colour = fw::viz::ColourMap::named("wind").colour(1.0);
  for (const auto view : {fw::viz::ViewKind::top, fw::viz::ViewKind::side}) {
    fw::viz::RenderSettings settings;
    settings.view = view;
    const fs::path png = fs::path(dir.path()) / "trees.png";
    const auto picture = render(dir.path(), settings, png);
    const auto image = fw::test::read_png(png);
    CHECK(picture.displacement_range() == Approx(1.0).epsilon(1e-6));  // the top's sway, float32 files
    auto pixel = [&](double x, double y, double z) {
      const auto p = picture.camera().to_pixel({x, y, z});
      return image.at(int(p.x), int(p.y));
    };
    // On the trunk: its colour or its dark edge, far from the wind's colour (the map's top is a light
    // yellow, every tree colour at least 60 levels away in some channel).
    const std::vector<std::array<double, 3>> on_tree =
        view == fw::viz::ViewKind::top
            ? std::vector<std::array<double, 3>>{{12.0, 10.0, 4.0}, {12.9, 10.0, 8.0}}
            : std::vector<std::array<double, 3>>{{12.1, 10.0, 1.0}, {12.5, 10.0, 4.0}, {12.85, 10.0, 7.0}};
    for (const auto& q : on_tree) {
      INFO("view " << int(view) << " at " << q[0] << ", " << q[1] << ", " << q[2]);
      CHECK(colour_distance(pixel(q[0], q[1], q[2]), bytes(slice_colour)) > 60);
    }
    // Away from it (3 m and more, beyond its radius and its 1 m sway): the slice alone.
    const std::vector<std::array<double, 3>> off_tree =
        view == fw::viz::ViewKind::top
            ? std::vector<std::array<double, 3>>{{8.5, 10.5, 5},
                                                 {16.5, 10.5, 5},
                                                 {12.5, 14.5, 5},
                                                 {12.5, 5.5, 5}}
            : std::vector<std::array<double, 3>>{
                  {8.5, 10, 4.5}, {16.5, 10, 4.5}, {12.5, 10, 9.5}, {30.5, 10, 2.5}};
    for (const auto& q : off_tree) {
      INFO("view " << int(view) << " away at " << q[0] << ", " << q[1] << ", " << q[2]);
      CHECK(colour_distance(pixel(q[0], q[1], q[2]), bytes(slice_colour)) <= kColourTolerance);
    }
  }
}

TEST_CASE("FrameRender: solid cells are grey and outlined, not coloured as wind", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::UniformWind wind;
  wind.solid_box = {18, 24, 6, 14, 0, 8};  // a building 8 m high
  fw::test::write_run(dir.path(), wind, {}, 1, 0.5);
  fw::viz::RenderSettings settings;
  settings.height = 4.5;
  const fs::path png = fs::path(dir.path()) / "solid.png";
  const auto picture = render(dir.path(), settings, png);
  const auto image = fw::test::read_png(png);
  const auto inside = picture.camera().to_pixel({21.0, 10.0, 4.5});
  const auto grey = image.at(int(inside.x), int(inside.y));
  CHECK(grey[0] == grey[1]);
  CHECK(grey[1] == grey[2]);
  CHECK(grey[0] > 100);  // the light grey fill
  // The outline along the building's west wall (x = 18 m) is dark.
  const auto edge = picture.camera().to_pixel({18.0, 10.0, 4.5});
  int darkest = 255;  // the 1.4 px line straddles the cell boundary: look at the pixels on either side
  for (int i = int(edge.x) - 1; i <= int(edge.x) + 1; ++i)
    darkest = std::min(darkest, image.at(i, int(edge.y))[0]);
  CHECK(darkest < 90);
}

TEST_CASE("RunFolder: a bad frame number or field name is refused with what there is", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {}, 3, 0.5);
  const fw::viz::RunFolder run(dir.path());
  REQUIRE(run.frames().size() == 3);
  CHECK_THROWS_WITH(run.select(3, std::nullopt), Catch::Contains("frames 0..2 (t = 0 .. 1 s)"));
  CHECK_THROWS_WITH(run.select(-1, std::nullopt), Catch::Contains("frames 0..2"));
  CHECK_THROWS_WITH(run.select(std::nullopt, 7.0), Catch::Contains("--time 7"));
  CHECK(run.select(std::nullopt, 0.6).index == 1);  // the nearest frame
  const auto data = run.load(run.select(0, std::nullopt));
  CHECK_THROWS_WITH(data.wind->field("vorticity"),
                    Catch::Contains("choose one of velocity, velocity_x, velocity_y, velocity_z, speed"));
  CHECK_THROWS_AS(fw::viz::FrameRender(data, "x",
                                       [] {
                                         fw::viz::RenderSettings s;
                                         s.field = "temperature";
                                         return s;
                                       }()),
                  std::invalid_argument);
  CHECK_THROWS_WITH(fw::viz::RunFolder(fs::path(dir.path()) / "nothing"), Catch::Contains("output folder"));
}

TEST_CASE("RunFolder: a folder whose last listed frame does not read renders the one before", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {fw::test::trunk(12, 10, 8, 0.4, 5, 0.5)}, 3, 0.5);
  // A run killed while a copy of the folder was taken: the last frame's wind file is cut short.
  const fs::path last = fs::path(dir.path()) / "wind" / "wind_000002.vti";
  fs::resize_file(last, fs::file_size(last) / 2);
  const fw::viz::RunFolder run(dir.path());
  std::string note;
  const auto data = run.load_last_complete(run.select(std::nullopt, std::nullopt), &note);
  CHECK(data.index == 1);
  CHECK(data.time == 0.5);
  CHECK_THAT(note, Catch::Contains("frame 2 does not read") && Catch::Contains("rendering frame 1"));
  CHECK_THROWS_WITH(run.load(run.select(2, std::nullopt)), Catch::Contains("wind_000002.vti"));
  // And a frame whose trees file is gone.
  fs::remove(fs::path(dir.path()) / "trees" / "trees_000001.vtp");
  CHECK(run.load_last_complete(run.select(std::nullopt, std::nullopt)).index == 0);
}

TEST_CASE("RunFolder: trees written every N-th frame hold still between their frames", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {fw::test::trunk(12, 10, 8, 0.4, 5, 0.5)}, 4, 0.5);
  // As output.vtk.trees_every: 2 writes them: trees.pvd lists frames 0 and 2 only.
  fw::io::PvdCollection trees(fs::path(dir.path()) / "trees.pvd");
  trees.add(0.0, "trees/trees_000000.vtp");
  trees.add(1.0, "trees/trees_000002.vtp");
  const fw::viz::RunFolder run(dir.path());
  REQUIRE(run.frames().size() == 4);
  CHECK(run.frames()[1].trees.filename() == "trees_000000.vtp");
  CHECK(run.frames()[2].trees.filename() == "trees_000002.vtp");
  CHECK(run.frames()[3].trees.filename() == "trees_000002.vtp");
  CHECK(run.load(run.frames()[3]).trees.has_value());
}

TEST_CASE("RunFolder: the scenario's name is read from run.json however long, escapes undone", "[viz]") {
  // A std::regex over the value recursed once a character and overflowed the stack on a long one.
  fw::test::TempDir dir("fw_viz");
  const std::string name(std::size_t(8) << 20, 'n');
  std::ofstream(fs::path(dir.path()) / "run.json")
      << "{\"scenario_file\": \"x.yaml\", \"scenario\" :\n \"" << name << "\\\"q\\\\\"}";
  CHECK(fw::viz::scenario_name_of(dir.path()) == name + "\"q\\");
  std::ofstream(fs::path(dir.path()) / "run.json") << "{\"scenario\": \"unclosed\\\"}";
  CHECK(fw::viz::scenario_name_of(dir.path()) == fs::path(dir.path()).filename().string());
}
