#include <catch2/catch.hpp>

#include <filesystem>

#include "tests/support/Pictures.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/ColourMap.hpp"
#include "viz/ModeShapes.hpp"

namespace fs = std::filesystem;

TEST_CASE("ModeShapes: each mode's panel shows the exaggerated shape beside the rest shape", "[viz]") {
  // A vertical pole 10 m tall, 11 nodes; mode 1 sways along x (linear in height), mode 2 along y.
  std::vector<fw::trees::SkeletonNode> nodes;
  for (int n = 0; n <= 10; ++n) nodes.push_back({n - 1, Eigen::Vector3d(0, 0, n), 0.1});
  const auto pole = fw::trees::Skeleton::from_nodes(nodes);
  fw::io::ModeShape sway_x{0.5, 0.02, Eigen::MatrixX3d::Zero(11, 3)},
      sway_y{0.7, 0.02, Eigen::MatrixX3d::Zero(11, 3)};
  for (int n = 0; n <= 10; ++n) sway_x.displacement(n, 0) = 0.01 * n, sway_y.displacement(n, 1) = -0.03 * n;
  const fw::viz::Canvas picture = fw::viz::draw_mode_shapes(pole, {sway_x, sway_y}, "pole");
  fw::test::TempDir dir("fw_viz");
  const fs::path png = fs::path(dir.path()) / "modes.png";
  picture.write_png(png);
  const auto image = fw::test::read_png(png);
  CHECK(image.width == 2 * 300);  // one panel per mode
  // In each panel the pole's top is drawn kExaggeration * 10 m = 1.5 m to the side of the rest pole (to
  // +x in mode 1, -y in mode 2) in the map's lightest colour; the rest pole stands in light grey.
  const auto lightest = fw::test::bytes(fw::viz::ColourMap::named("displacement").colour(1.0));
  const auto rest_grey = fw::test::bytes({0.8, 0.8, 0.8});
  for (int panel = 0; panel < 2; ++panel) {
    // Find the rows of the rest pole's top and the swayed top by scanning the panel for their colours.
    int rest_column = -1, swayed_column = -1, rest_top = 1 << 30, swayed_top = 1 << 30;
    for (int j = 44; j < image.height - 44; ++j)
      for (int i = panel * 300 + 6; i < (panel + 1) * 300 - 6; ++i) {
        const auto c = image.at(i, j);
        if (fw::test::colour_distance(c, rest_grey) <= 8 && j < rest_top) rest_top = j, rest_column = i;
        if (fw::test::colour_distance(c, lightest) <= 8 && j < swayed_top) swayed_top = j, swayed_column = i;
      }
    INFO("panel " << panel);
    REQUIRE(rest_column > 0);
    REQUIRE(swayed_column > 0);
    if (panel == 0) CHECK(swayed_column > rest_column + 10);  // swayed to +x, right in the x-z view
    if (panel == 1) CHECK(swayed_column < rest_column - 10);  // swayed to -y, left in the y-z view
  }
  CHECK_THROWS_WITH(fw::viz::draw_mode_shapes(pole, {}, "pole"), Catch::Contains("at least one mode"));
}
