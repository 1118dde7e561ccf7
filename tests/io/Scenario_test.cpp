#include "io/Scenario.hpp"

#include "fluid/TurbulenceBox.hpp"
#include "kernels/shared_types.h"
#include "tests/support/ScenarioErrors.hpp"
#include "tests/support/TempDir.hpp"
#include "trees/StandDensity.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <variant>

namespace fs = std::filesystem;

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using fw::fluid::BoundaryType;
using fw::io::BoundaryChoice;
using fw::io::Expression;
using fw::io::Scenario;

namespace {

// The reference example of docs/design.md ("File formats"), verbatim but for one value: its reference_height
// of 10 m lies below displacement_height + roughness_length = 12.8 m, where the log law gives no wind, which
// the loader rejects (see "a log profile whose reference height..." below), so it reads 20 m here. Its
// heightmap hills.pgm is written next to it by the test, and its skeleton is generated, so it needs no
// other file.
const std::string kDesignExample =
    R"yaml(# SI units; x east, y north, z up; directions in degrees the wind blows FROM, clockwise from north
scenario: storm_over_forest
seed: 7
time: {end: 120.0, dt: auto, cfl: 0.8}                 # dt: seconds or auto
domain: {origin: [0, 0, 0], size: [480, 240, 96], cell_size: 2.0}
boundaries: {west: auto, east: auto, south: auto, north: auto, ground: no_slip, top: slip}
  # auto: inflow where the ambient wind enters the domain, outflow where it leaves; also inflow|outflow|slip|no_slip|periodic
wind:
  speed: "12 + 10*min(1, max(0, (t-20)/40))"          # m/s at reference_height
  direction: "250 + 20*min(1, max(0, (t-20)/40))"
  reference_height: 20.0
  profile: {type: log, roughness_length: 0.8, displacement_height: 12.0}   # or {type: power, alpha: 0.2} | {type: uniform}
events:
  - gust: {start: 70.0, duration: 6.0, peak_speed: 14.0, center: [120, 120, 30], radius: 60.0, travel: with_wind}
obstacles:
  - box: {name: barn, center: [300, 100, 6], size: [30, 15, 12], yaw: 15.0}
  - cylinder: {name: silo, base: [340, 60, 0], radius: 4.0, height: 20.0}
  - sphere: {name: dome, center: [420, 40, 0], radius: 10.0}
terrain: {heightmap: hills.pgm, cell_size: 4.0, max_height: 20.0}   # optional; a PGM, or a raster
forest:
  two_way_coupling: true
  species:
    - name: pine
      skeleton: {generate: {preset: conifer, height: 18.0, seed: 3}}  # or {file: pine.tree} or {qsm: pine_qsm.txt}
      material: {youngs_modulus: 1.0e10, shear_modulus: 3.85e9, density: 900}
      modes: {count: 20, damping_ratio: 0.05, wind_samples: 3}
      drag_coefficient: 1.2
      canopy: {leaf_area_index: 3.5, drag_coefficient: 0.2}
  stands:
    - {species: pine, region: {min: [60, 20], max: [260, 220]}, layout: poisson, spacing: 6.0,
       scale: {min: 0.85, max: 1.15}, seed: 11}                      # layout: poisson | grid
  trees:
    - {species: pine, position: [400, 200], yaw: 30.0, scale: 1.0}
solver: {pressure: multigrid, tolerance: 1.0e-4, max_iterations: 100, advection: maccormack, vorticity_confinement: 0.0}
  # pressure: multigrid | cg | jacobi (jacobi_iterations: N); advection: semi_lagrangian | maccormack
output:
  directory: out/storm
  interval: 0.5                                       # seconds of simulated time between frames
  vtk: {wind: true, trees: true, fields: [velocity, pressure, speed, vorticity, solid, canopy_density]}
  vdb: {enabled: true, grids: [vel, speed]}
  probes:
    - {name: mast, position: [40, 120, 10]}
)yaml";

// A P2 heightmap `columns` wide and `rows` high that rises linearly to the east: pixel (c, r) = c, maxval
// columns - 1, so the height is (x / cell_size - 0.5) / (columns - 1) * max_height between the pixel centres.
std::string ramp_pgm(int columns, int rows) {
  std::string text = fmt::format("P2\n# rises to the east\n{} {}\n{}\n", columns, rows, columns - 1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) text += fmt::format("{}{}", c, c + 1 < columns ? " " : "\n");
  }
  return text;
}

const std::string kTreeFile = "# a stick\n0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n";
const std::string kQsmFile = "0.1 1.0 0 0 0 0 0 1 0\n0.05 1.0 0 0 1 0 0 1 1\n";

// The first four lines of every error case below: a valid scenario the cases add to or change.
const std::string kBase =
    "scenario: errors\n"                              // 1
    "time: {end: 10.0}\n"                             // 2
    "domain: {size: [40, 20, 10], cell_size: 2.0}\n"  // 3
    "wind: {speed: 4.0, direction: 270}\n";           // 4

using fw::test::expect_scenario_error;

void check_vector(const std::array<double, 3>& actual, const std::array<double, 3>& expected, double margin) {
  INFO("actual [" << actual[0] << ", " << actual[1] << ", " << actual[2] << "], expected [" << expected[0]
                  << ", " << expected[1] << ", " << expected[2] << "]");
  for (int i = 0; i < 3; ++i)
    CHECK(actual[std::size_t(i)] == Approx(expected[std::size_t(i)]).margin(margin));
}

// A scenario built in memory for wind_vector and grid_spec: speed and direction as expressions of t.
Scenario wind_only(const std::string& speed, const std::string& direction) {
  Scenario scenario;
  scenario.domain.size = {40, 20, 10};
  scenario.domain.cell_size = 2.0;
  scenario.domain.cells = {20, 10, 5};
  scenario.wind.speed = Expression::parse(speed);
  scenario.wind.direction = Expression::parse(direction);
  return scenario;
}

// Changes the working directory for its lifetime.
class WorkingDirectory {
 public:
  explicit WorkingDirectory(const fs::path& folder) : previous_(fs::current_path()) {
    fs::current_path(folder);
  }
  ~WorkingDirectory() {
    std::error_code ignored;
    fs::current_path(previous_, ignored);
  }
  WorkingDirectory(const WorkingDirectory&) = delete;
  WorkingDirectory& operator=(const WorkingDirectory&) = delete;

 private:
  fs::path previous_;
};

}  // namespace

TEST_CASE(
    "load_scenario: the reference example of docs/design.md parses and every field lands where expected",
    "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  dir.write("hills.pgm", ramp_pgm(121, 2));
  const std::string path = dir.write("storm.yaml", kDesignExample);
  const Scenario s = fw::io::load_scenario(path);

  CHECK(s.file.string() == path);
  CHECK(fs::equivalent(s.folder, dir.path()));
  CHECK(s.text == kDesignExample);
  CHECK(s.name == "storm_over_forest");
  CHECK(s.seed == 7);

  CHECK(s.time.end == 120.0);
  CHECK_FALSE(s.time.dt.has_value());  // auto
  CHECK(s.time.cfl == 0.8);

  CHECK(s.domain.origin == std::array<double, 3>{0, 0, 0});
  CHECK(s.domain.size == std::array<double, 3>{480, 240, 96});
  CHECK(s.domain.cell_size == 2.0);
  CHECK(s.domain.cells == std::array<int, 3>{240, 120, 48});  // size / cell_size
  CHECK(s.domain.max_corner() == std::array<double, 3>{480, 240, 96});

  CHECK(s.boundaries == std::array<BoundaryChoice, 6>{BoundaryChoice::automatic, BoundaryChoice::automatic,
                                                      BoundaryChoice::automatic, BoundaryChoice::automatic,
                                                      BoundaryChoice::no_slip, BoundaryChoice::slip});

  // Wind: the ramp from 12 to 22 m/s veering from 250 to 270 degrees between t = 20 and 60 s.
  CHECK(s.wind.speed.text() == "12 + 10*min(1, max(0, (t-20)/40))");
  CHECK(s.wind.direction.text() == "250 + 20*min(1, max(0, (t-20)/40))");
  CHECK_FALSE(s.wind.speed.is_constant());
  CHECK(s.wind.speed(0.0) == 12.0);
  CHECK(s.wind.speed(40.0) == 17.0);
  CHECK(s.wind.speed(60.0) == 22.0);
  CHECK(s.wind.direction(0.0) == 250.0);
  CHECK(s.wind.direction(40.0) == 260.0);
  CHECK(s.wind.direction(90.0) == 270.0);
  CHECK(s.wind.reference_height == 20.0);
  CHECK(s.wind.profile.type == fw::fluid::InflowProfile::Type::log);
  CHECK(s.wind.profile.roughness_length == 0.8);
  CHECK(s.wind.profile.displacement_height == 12.0);
  CHECK(s.wind.profile.reference_height == 20.0);
  // Tolerance: sin and cos of 250 degrees to 1e-12. From 250 degrees at 12 m/s the wind blows toward 70
  // degrees: 12 * (sin 70, cos 70) = (11.27631145, 4.10424172).
  check_vector(s.wind_vector(0.0), {11.27631145, 4.10424172, 0.0}, 1e-8);

  // The gust travels with the wind at its start (t = 70 s: 22 m/s from 270 degrees, toward +x).
  REQUIRE(s.events.size() == 1);
  const fw::io::GustEvent& gust = s.events[0];
  CHECK(gust.start == 70.0);
  CHECK(gust.duration == 6.0);
  CHECK(gust.peak_speed == 14.0);
  CHECK(gust.center == std::array<double, 3>{120, 120, 30});
  CHECK(gust.radius == 60.0);
  CHECK(gust.travel_with_wind);
  // Tolerance: 22 m/s times sin/cos rounding, 1e-12.
  check_vector(gust.travel, {22.0, 0.0, 0.0}, 1e-12);
  CHECK(gust.travel == s.wind_vector(70.0));

  REQUIRE(s.obstacles.size() == 3);
  const auto* barn = std::get_if<fw::fluid::SolidBox>(&s.obstacles[0]);
  REQUIRE(barn != nullptr);
  CHECK(barn->name == "barn");
  CHECK(barn->center == std::array<double, 3>{300, 100, 6});
  CHECK(barn->size == std::array<double, 3>{30, 15, 12});
  CHECK(barn->yaw_rad == fw::io::radians(15.0));  // the file gives degrees
  const auto* silo = std::get_if<fw::fluid::SolidCylinder>(&s.obstacles[1]);
  REQUIRE(silo != nullptr);
  CHECK(silo->name == "silo");
  CHECK(silo->base == std::array<double, 3>{340, 60, 0});
  CHECK(silo->radius == 4.0);
  CHECK(silo->height == 20.0);
  const auto* dome = std::get_if<fw::fluid::SolidSphere>(&s.obstacles[2]);
  REQUIRE(dome != nullptr);
  CHECK(dome->name == "dome");
  CHECK(dome->center == std::array<double, 3>{420, 40, 0});
  CHECK(dome->radius == 10.0);

  REQUIRE(s.terrain.has_value());
  CHECK(fs::equivalent(s.terrain->heightmap, fs::path(dir.path()) / "hills.pgm"));
  CHECK(s.terrain->heightmap.is_absolute());
  CHECK(s.terrain->cell_size == 4.0);
  CHECK(s.terrain->max_height == 20.0);
  REQUIRE(s.terrain->map.has_value());
  CHECK(s.terrain->map->columns() == 121);
  CHECK(s.terrain->map->rows() == 2);
  CHECK(s.terrain->map->cell_size() == 4.0);
  CHECK(s.terrain->map->max_height() == 20.0);  // the east column is maxval

  const fw::io::ForestSettings& forest = s.forest;
  CHECK(forest.two_way_coupling);
  REQUIRE(forest.species.size() == 1);
  const fw::io::Species& pine = forest.species[0];
  CHECK(pine.name == "pine");
  CHECK(pine.skeleton.kind == fw::io::SkeletonSource::Kind::generate);
  CHECK(pine.skeleton.generate.preset == "conifer");
  CHECK(pine.skeleton.generate.height == 18.0);
  CHECK(pine.skeleton.generate.seed == 3);
  CHECK(pine.material.youngs_modulus == 1.0e10);
  CHECK(pine.material.shear_modulus == 3.85e9);
  CHECK(pine.material.density == 900.0);
  CHECK(pine.modes.count == 20);
  CHECK(pine.modes.damping_ratio == 0.05);
  CHECK(pine.modes.wind_samples == 3);
  CHECK(pine.drag_coefficient == 1.2);
  CHECK(pine.canopy.leaf_area_index == 3.5);
  CHECK(pine.canopy.drag_coefficient == 0.2);

  REQUIRE(forest.stands.size() == 1);
  const fw::io::Stand& stand = forest.stands[0];
  CHECK(stand.species == "pine");
  CHECK(stand.layout.species == 0);
  CHECK(stand.layout.min.x() == 60.0);
  CHECK(stand.layout.min.y() == 20.0);
  CHECK(stand.layout.max.x() == 260.0);
  CHECK(stand.layout.max.y() == 220.0);
  CHECK(stand.layout.layout == fw::trees::StandLayout::poisson);
  CHECK(stand.layout.spacing == 6.0);
  CHECK(stand.layout.scale_min == 0.85);
  CHECK(stand.layout.scale_max == 1.15);
  CHECK(stand.layout.seed == 11);

  REQUIRE(forest.trees.size() == 1);
  const fw::io::PlacedTreeSettings& tree = forest.trees[0];
  CHECK(tree.species == "pine");
  CHECK(tree.species_index == 0);
  CHECK(tree.position[0] == 400.0);
  CHECK(tree.position[1] == 200.0);
  CHECK_FALSE(tree.height_given);
  // On the ground: x = 400 m is pixel column 99.5 of the ramp, 99.5 / 120 * 20 m = 16.58333 m.
  // Tolerance: bilinear interpolation in doubles, 1e-9 m.
  CHECK(tree.position[2] == Approx(99.5 / 120.0 * 20.0).margin(1e-9));
  CHECK(tree.yaw_rad == Approx(std::numbers::pi / 6).epsilon(1e-15));  // 30 degrees
  CHECK(tree.scale == 1.0);

  CHECK(s.solver.pressure == fw::fluid::PressureSolverType::multigrid);
  CHECK(s.solver.tolerance == 1.0e-4);
  CHECK(s.solver.max_iterations == 100);
  CHECK(s.solver.jacobi_iterations == 40);  // not given: the default
  CHECK(s.solver.advection == fw::fluid::AdvectionScheme::maccormack);
  CHECK(s.solver.vorticity_confinement == 0.0);
  const fw::fluid::WindSettings settings = s.wind_settings();
  CHECK(settings.advection == fw::fluid::AdvectionScheme::maccormack);
  CHECK(settings.pressure.solver == fw::fluid::PressureSolverType::multigrid);
  CHECK(settings.pressure.tolerance == 1.0e-4);
  CHECK(settings.pressure.max_iterations == 100);
  CHECK(settings.cfl == 0.8);  // auto dt

  // The output directory resolves against the working directory, not the scenario folder.
  CHECK(s.output.directory.string() == fs::absolute("out/storm").lexically_normal().string());
  CHECK(s.output.interval == 0.5);
  CHECK(s.output.vtk_wind);
  CHECK(s.output.vtk_trees);
  CHECK(s.output.vtk_fields ==
        std::vector<std::string>{"velocity", "pressure", "speed", "vorticity", "solid", "canopy_density"});
  CHECK(s.output.vdb_enabled);
  CHECK(s.output.vdb_grids == std::vector<std::string>{"vel", "speed"});
  REQUIRE(s.output.probes.size() == 1);
  CHECK(s.output.probes[0].name == "mast");
  CHECK(s.output.probes[0].position == std::array<double, 3>{40, 120, 10});
}

TEST_CASE("load_scenario: values other than the defaults are read for every optional key", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  // A PGM at the domain's corner (-10, 0), 10 m pixels: centres x = -5, 5, 15, 25, heights 0, 1, 2, 3 m.
  dir.write("ground.pgm", ramp_pgm(4, 2));
  dir.write("willow.tree", kTreeFile);
  dir.write("birch_qsm.txt", kQsmFile);
  const fs::path results = fs::path(dir.path()) / "results";
  const std::string text = fmt::format(R"(scenario: all_keys
seed: 18446744073709551615
time: {{end: 5.0, dt: 0.01, cfl: 0.5, spin_up: 2.5}}
domain: {{origin: [-10, 0, 5], size: [40, 20, 12], cell_size: 0.5}}
boundaries: {{west: inflow, east: outflow, south: periodic, north: periodic, ground: slip, top: no_slip}}
wind:
  speed: "3 + t"
  direction: 180
  reference_height: 25
  profile: {{type: power, alpha: 0.3}}
events:
  - gust: {{start: 0, duration: 1.5, peak_speed: 0, center: [-10, 0, 5], radius: 2.5, travel: [1, -2, 0.5]}}
  - gust: {{start: 2, duration: 1, peak_speed: 3, center: [0, 10, 8], radius: 1}}
obstacles:
  - sphere: {{name: boulder, center: [0, 5, 5], radius: 1.5}}
  - box: {{name: shed, center: [5, 5, 6], size: [2, 3, 2]}}
terrain: {{heightmap: ground.pgm, cell_size: 10, max_height: 3}}
forest:
  two_way_coupling: false
  integrator: semi_implicit
  species:
    - name: willow
      skeleton: {{file: willow.tree}}
      material: {{youngs_modulus: 8e9, shear_modulus: 2.5e9, density: 650}}
      modes: {{count: 5, damping_ratio: 0.1, wind_samples: 16}}
      drag_coefficient: 0.9
      canopy: {{leaf_area_index: 2.5, drag_coefficient: 0.15}}
    - name: birch
      skeleton: {{qsm: birch_qsm.txt}}
  stands:
    - {{species: birch, region: {{min: [-10, 0], max: [0, 10]}}, layout: grid, spacing: 2.5, scale: {{min: 0.5}},
       seed: 99}}
  trees:
    - {{species: willow, position: [15, 10]}}
    - {{species: birch, position: [20, 15, 9.5], yaw: -45, scale: 1.25}}
solver: {{pressure: jacobi, jacobi_iterations: 7, tolerance: 0.5, max_iterations: 3, vorticity_confinement: 0.25}}
output:
  directory: {}
  interval: 0.25
  vtk: {{wind: false, trees: false, fields: [speed, velocity]}}
  vdb: {{enabled: false, grids: [speed]}}
  probes:
    - {{name: a_1, position: [-10, 0, 5]}}
    - {{name: B2, position: [30, 20, 17]}}
)",
                                       results.string());
  const Scenario s = fw::io::load_scenario(dir.write("all_keys.yaml", text));

  CHECK(s.seed == 18446744073709551615ULL);
  REQUIRE(s.time.dt.has_value());
  CHECK(*s.time.dt == 0.01);
  CHECK(s.time.cfl == 0.5);
  CHECK(s.time.spin_up == 2.5);
  CHECK(s.domain.origin == std::array<double, 3>{-10, 0, 5});
  CHECK(s.domain.cells == std::array<int, 3>{80, 40, 24});
  CHECK(s.domain.max_corner() == std::array<double, 3>{30, 20, 17});
  CHECK(s.boundaries == std::array<BoundaryChoice, 6>{BoundaryChoice::inflow, BoundaryChoice::outflow,
                                                      BoundaryChoice::periodic, BoundaryChoice::periodic,
                                                      BoundaryChoice::slip, BoundaryChoice::no_slip});

  CHECK(s.wind.speed(2.0) == 5.0);
  CHECK(s.wind.direction.is_constant());
  CHECK(s.wind.direction(0.0) == 180.0);
  CHECK(s.wind.reference_height == 25.0);
  CHECK(s.wind.profile.type == fw::fluid::InflowProfile::Type::power);
  CHECK(s.wind.profile.alpha == 0.3);
  CHECK(s.wind.profile.reference_height == 25.0);  // follows reference_height

  REQUIRE(s.events.size() == 2);
  CHECK(s.events[0].start == 0.0);
  CHECK(s.events[0].duration == 1.5);
  CHECK(s.events[0].peak_speed == 0.0);
  CHECK(s.events[0].radius == 2.5);
  CHECK_FALSE(s.events[0].travel_with_wind);
  CHECK(s.events[0].travel == std::array<double, 3>{1, -2, 0.5});
  // No travel key: with the wind at t = 2 s, 5 m/s from the south, toward +y. Tolerance 1e-12 m/s.
  CHECK(s.events[1].travel_with_wind);
  check_vector(s.events[1].travel, {0.0, 5.0, 0.0}, 1e-12);

  REQUIRE(s.obstacles.size() == 2);
  const auto* boulder = std::get_if<fw::fluid::SolidSphere>(&s.obstacles[0]);
  REQUIRE(boulder != nullptr);
  CHECK(boulder->name == "boulder");
  CHECK(boulder->radius == 1.5);
  const auto* shed = std::get_if<fw::fluid::SolidBox>(&s.obstacles[1]);
  REQUIRE(shed != nullptr);
  CHECK(shed->size == std::array<double, 3>{2, 3, 2});
  CHECK(shed->yaw_rad == 0.0);  // not given

  REQUIRE(s.terrain.has_value());
  CHECK(s.terrain->cell_size == 10.0);
  CHECK(s.terrain->map->columns() == 4);
  CHECK_FALSE(s.terrain->site.has_value());  // an image places no site

  const fw::io::ForestSettings& forest = s.forest;
  CHECK_FALSE(forest.two_way_coupling);
  CHECK(forest.integrator == fw::trees::ModalIntegrator::semi_implicit);
  REQUIRE(forest.species.size() == 2);
  const fw::io::Species& willow = forest.species[0];
  CHECK(willow.skeleton.kind == fw::io::SkeletonSource::Kind::file);
  CHECK(fs::equivalent(willow.skeleton.path, fs::path(dir.path()) / "willow.tree"));
  CHECK(willow.material.youngs_modulus == 8e9);
  CHECK(willow.material.shear_modulus == 2.5e9);
  CHECK(willow.material.density == 650.0);
  CHECK(willow.modes.count == 5);
  CHECK(willow.modes.damping_ratio == 0.1);
  CHECK(willow.modes.wind_samples == FW_MAX_TREE_SAMPLES);
  CHECK(willow.drag_coefficient == 0.9);
  CHECK(willow.canopy.leaf_area_index == 2.5);
  CHECK(willow.canopy.drag_coefficient == 0.15);
  const fw::io::Species& birch = forest.species[1];
  CHECK(birch.skeleton.kind == fw::io::SkeletonSource::Kind::qsm);
  CHECK(fs::equivalent(birch.skeleton.path, fs::path(dir.path()) / "birch_qsm.txt"));

  REQUIRE(forest.stands.size() == 1);
  const fw::io::Stand& stand = forest.stands[0];
  CHECK(stand.species == "birch");
  CHECK(stand.layout.species == 1);
  CHECK(stand.layout.layout == fw::trees::StandLayout::grid);
  CHECK(stand.layout.spacing == 2.5);
  CHECK(stand.layout.scale_min == 0.5);
  CHECK(stand.layout.scale_max == 1.0);  // max not given
  CHECK(stand.layout.seed == 99);

  REQUIRE(forest.trees.size() == 2);
  // On the ramp: x = 15 is column 2, 2 m, and the terrain counts from the domain floor z = 5. Tolerance:
  // bilinear in doubles, 1e-12 m.
  CHECK_FALSE(forest.trees[0].height_given);
  CHECK(forest.trees[0].species_index == 0);
  CHECK(forest.trees[0].position[2] == Approx(5.0 + 2.0).margin(1e-12));
  CHECK(forest.trees[1].species == "birch");
  CHECK(forest.trees[1].species_index == 1);
  CHECK(forest.trees[1].height_given);
  CHECK(forest.trees[1].position == std::array<double, 3>{20, 15, 9.5});
  CHECK(forest.trees[1].yaw_rad == Approx(-std::numbers::pi / 4).epsilon(1e-15));  // -45 degrees
  CHECK(forest.trees[1].scale == 1.25);

  CHECK(s.solver.pressure == fw::fluid::PressureSolverType::jacobi);
  CHECK(s.solver.jacobi_iterations == 7);
  CHECK(s.solver.tolerance == 0.5);
  CHECK(s.solver.max_iterations == 3);
  CHECK(s.solver.advection == fw::fluid::AdvectionScheme::semi_lagrangian);
  CHECK(s.solver.vorticity_confinement == 0.25);
  const fw::fluid::WindSettings settings = s.wind_settings();
  CHECK(settings.dt == 0.01);
  CHECK(settings.cfl == 0.0);  // fixed dt
  CHECK(settings.pressure.solver == fw::fluid::PressureSolverType::jacobi);
  CHECK(settings.pressure.jacobi_iterations == 7);
  CHECK(settings.vorticity_confinement == 0.25);

  // Explicit faces pass through grid_spec unchanged.
  const fw::fluid::GridSpec grid = s.grid_spec(0.0);
  CHECK(grid.nx == 80);
  CHECK(grid.ny == 40);
  CHECK(grid.nz == 24);
  CHECK(grid.h == 0.5);
  CHECK(grid.origin == std::array<double, 3>{-10, 0, 5});
  CHECK(grid.boundary == std::array<BoundaryType, 6>{BoundaryType::inflow, BoundaryType::outflow,
                                                     BoundaryType::periodic, BoundaryType::periodic,
                                                     BoundaryType::slip, BoundaryType::no_slip});

  CHECK(s.output.directory.string() == results.string());
  CHECK(s.output.interval == 0.25);
  CHECK_FALSE(s.output.vtk_wind);
  CHECK_FALSE(s.output.vtk_trees);
  CHECK(s.output.vtk_fields == std::vector<std::string>{"speed", "velocity"});  // the file's order
  CHECK_FALSE(s.output.vdb_enabled);
  CHECK(s.output.vdb_grids == std::vector<std::string>{"speed"});
  REQUIRE(s.output.probes.size() == 2);
  CHECK(s.output.probes[0].name == "a_1");
  CHECK(s.output.probes[1].name == "B2");
  CHECK(s.output.probes[1].position == std::array<double, 3>{30, 20, 17});  // the far corner: faces count
}

TEST_CASE("load_scenario: a minimal scenario gets the documented defaults", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("minimal.yaml", R"(scenario: minimal
time: {end: 10.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
wind: {speed: 4.0, direction: 270}
events:
  - gust: {start: 1.0, duration: 2.0, peak_speed: 3.0, center: [10, 10, 5], radius: 4.0}
forest:
  species:
    - name: oak
      skeleton: {generate: {preset: broadleaf}}
  stands:
    - {species: oak, region: {min: [5, 5], max: [15, 15]}, spacing: 4.0}
  trees:
    - {species: oak, position: [30, 10]}
)"));
  CHECK(s.name == "minimal");
  CHECK(s.seed == 0);
  CHECK(s.time.end == 10.0);
  CHECK_FALSE(s.time.dt.has_value());
  CHECK(s.time.cfl == 0.8);
  CHECK(s.time.spin_up == 0.0);  // no spin-up: the trees start in equilibrium with the inflow profile
  CHECK(s.domain.origin == std::array<double, 3>{0, 0, 0});
  CHECK(s.domain.cells == std::array<int, 3>{20, 10, 5});
  CHECK_FALSE(s.domain.decomposition.has_value());  // chosen from the ranks
  CHECK(s.boundaries == std::array<BoundaryChoice, 6>{BoundaryChoice::automatic, BoundaryChoice::automatic,
                                                      BoundaryChoice::automatic, BoundaryChoice::automatic,
                                                      BoundaryChoice::no_slip, BoundaryChoice::slip});
  CHECK(s.wind.speed.is_constant());
  CHECK(s.wind.speed.text() == "4.0");
  CHECK(s.wind.reference_height == 10.0);
  CHECK(s.wind.profile.type == fw::fluid::InflowProfile::Type::uniform);
  CHECK(s.wind.profile.alpha == 0.2);
  CHECK(s.wind.profile.displacement_height == 0.0);
  CHECK(s.wind.profile.reference_height == 10.0);

  // travel defaults to with_wind: 4 m/s from the west at t = 1 s. Tolerance 1e-12 m/s.
  REQUIRE(s.events.size() == 1);
  CHECK(s.events[0].travel_with_wind);
  check_vector(s.events[0].travel, {4.0, 0.0, 0.0}, 1e-12);
  CHECK(s.obstacles.empty());
  CHECK_FALSE(s.terrain.has_value());

  CHECK(s.forest.two_way_coupling);
  CHECK(s.forest.integrator == fw::trees::ModalIntegrator::exact);
  REQUIRE(s.forest.species.size() == 1);
  const fw::io::Species& oak = s.forest.species[0];
  CHECK(oak.skeleton.generate.preset == "broadleaf");
  CHECK(oak.skeleton.generate.height == 0.0);  // the preset's default height
  CHECK(oak.material.youngs_modulus == 1.0e10);
  CHECK(oak.material.shear_modulus == 3.85e9);
  CHECK(oak.material.density == 900.0);
  CHECK(oak.modes.count == 20);
  CHECK(oak.modes.damping_ratio == 0.05);
  CHECK(oak.modes.wind_samples == 3);
  CHECK(oak.drag_coefficient == 1.2);
  CHECK(oak.canopy.leaf_area_index == 0.0);
  CHECK(oak.canopy.drag_coefficient == 0.4);  // per one-sided leaf area: 1/2 C_D = 0.2, canopy LES's C_d
  // No `leaves`: no single leaves, so the run is the one without them.
  CHECK(oak.leaves.model == fw::trees::FlutterModel::none);
  CHECK_FALSE(oak.leaves.has_leaves());
  REQUIRE(s.forest.stands.size() == 1);
  CHECK(s.forest.stands[0].layout.layout == fw::trees::StandLayout::poisson);
  CHECK(s.forest.stands[0].layout.scale_min == 1.0);
  CHECK(s.forest.stands[0].layout.scale_max == 1.0);
  CHECK(s.forest.stands[0].layout.seed == 0);
  REQUIRE(s.forest.trees.size() == 1);
  CHECK(s.forest.trees[0].position == std::array<double, 3>{30, 10, 0});  // no terrain: the domain floor
  CHECK(s.forest.trees[0].yaw_rad == 0.0);
  CHECK(s.forest.trees[0].scale == 1.0);

  CHECK(s.solver.pressure == fw::fluid::PressureSolverType::cg);
  CHECK(s.solver.tolerance == 1e-3);
  CHECK(s.solver.max_iterations == 100);
  CHECK(s.solver.jacobi_iterations == 40);
  CHECK(s.solver.advection == fw::fluid::AdvectionScheme::semi_lagrangian);
  CHECK(s.solver.stage_projection == fw::fluid::StageProjection::final_stage);
  CHECK(s.solver.vorticity_confinement == 0.0);

  CHECK(s.output.directory.string() == (fs::current_path() / "out" / "minimal").lexically_normal().string());
  CHECK(s.output.interval == 1.0);
  CHECK(s.output.vtk_wind);
  CHECK(s.output.vtk_trees);
  CHECK(s.output.vtk_fields ==
        std::vector<std::string>{"velocity", "pressure", "speed", "vorticity", "solid", "canopy_density"});
  CHECK_FALSE(s.output.vdb_enabled);
  CHECK(s.output.vdb_grids == std::vector<std::string>{"vel", "speed", "leaves"});
  CHECK(s.output.vtk_leaves);
  CHECK(s.output.leaves_attached_stride == 1);  // all
  CHECK(s.output.probes.empty());

  // The turbulence keys' defaults: a laminar wind, no forcing, a smooth ground, no eddy viscosity.
  CHECK_FALSE(s.wind.turbulence.has_value());
  CHECK_FALSE(s.wind.forcing.has_value());
  CHECK(s.ground_roughness_length == 0.0);
  CHECK(s.solver.smagorinsky_constant == 0.0);
  CHECK_FALSE(s.output.probe_interval.has_value());                  // auto
  CHECK(s.resolved_probe_interval() == std::optional<double>(1.0));  // without turbulence: output.interval
  CHECK(s.forest.strong_wind_correction);
}

TEST_CASE("Scenario::wind_vector: directions are where the wind comes from, clockwise from north",
          "[scenario]") {
  struct Case {
    double direction;
    std::array<double, 3> expected;  // m/s for 5 m/s
  };
  const double diagonal = 5.0 / std::sqrt(2.0);
  const Case cases[] = {
      {0.0, {0.0, -5.0, 0.0}},    // from the north, toward -y
      {90.0, {-5.0, 0.0, 0.0}},   // from the east, toward -x
      {180.0, {0.0, 5.0, 0.0}},   // from the south, toward +y
      {270.0, {5.0, 0.0, 0.0}},   // from the west, toward +x
      {360.0, {0.0, -5.0, 0.0}},  // a full turn is north again
      {-90.0, {5.0, 0.0, 0.0}},   // -90 is 270
      {225.0, {diagonal, diagonal, 0.0}},
      {250.0, {5.0 * 0.9396926208, 5.0 * 0.3420201433, 0.0}},  // toward 70 degrees: 5 (sin 70, cos 70)
  };
  for (const Case& c : cases) {
    INFO("direction " << c.direction);
    // Tolerance: sin and cos in doubles, and 10 digits in the 250-degree case: 1e-9 m/s.
    check_vector(wind_only("5", fmt::format("{}", c.direction)).wind_vector(0.0), c.expected, 1e-9);
  }
}

TEST_CASE("Scenario::wind_vector: speed and direction follow their expressions of t", "[scenario]") {
  // Speed 2t m/s; direction veering from 270 to 180 degrees over the first 10 s.
  const Scenario s = wind_only("2*t", "270 - 90*min(1, t/10)");
  const double diagonal = 10.0 / std::sqrt(2.0);
  // Tolerance: 1e-9 m/s.
  check_vector(s.wind_vector(0.0), {0.0, 0.0, 0.0}, 1e-9);            // calm at t = 0
  check_vector(s.wind_vector(5.0), {diagonal, diagonal, 0.0}, 1e-9);  // 10 m/s from 225: toward north-east
  check_vector(s.wind_vector(10.0), {0.0, 20.0, 0.0}, 1e-9);          // 20 m/s from the south
  check_vector(s.wind_vector(20.0), {0.0, 40.0, 0.0}, 1e-9);          // 40 m/s, still from the south
}

TEST_CASE("Scenario::grid_spec: auto faces are inflow upwind and outflow downwind and alongside",
          "[scenario]") {
  using B = BoundaryType;
  struct Case {
    const char* direction;
    std::array<B, 6> expected;  // west, east, south, north, ground, top
  };
  const Case cases[] = {
      {"270", {B::inflow, B::outflow, B::outflow, B::outflow, B::no_slip, B::slip}},  // westerly
      {"90", {B::outflow, B::inflow, B::outflow, B::outflow, B::no_slip, B::slip}},   // easterly
      {"180", {B::outflow, B::outflow, B::inflow, B::outflow, B::no_slip, B::slip}},  // southerly
      {"0", {B::outflow, B::outflow, B::outflow, B::inflow, B::no_slip, B::slip}},    // northerly
      {"225", {B::inflow, B::outflow, B::inflow, B::outflow, B::no_slip, B::slip}},   // from the south-west
      {"45", {B::outflow, B::inflow, B::outflow, B::inflow, B::no_slip, B::slip}},    // from the north-east
  };
  for (const Case& c : cases) {
    INFO("direction " << c.direction);
    const fw::fluid::GridSpec grid = wind_only("5", c.direction).grid_spec(0.0);
    CHECK(grid.boundary == c.expected);
    CHECK(grid.nx == 20);
    CHECK(grid.ny == 10);
    CHECK(grid.nz == 5);
    CHECK(grid.h == 2.0);
  }

  // The faces follow the wind at the time asked for: westerly until t = 10 s, easterly after.
  const Scenario turning = wind_only("5", "t < 10 ? 270 : 90");
  CHECK(turning.grid_spec(0.0).boundary[FW_FACE_WEST] == B::inflow);
  CHECK(turning.grid_spec(0.0).boundary[FW_FACE_EAST] == B::outflow);
  CHECK(turning.grid_spec(10.0).boundary[FW_FACE_WEST] == B::outflow);
  CHECK(turning.grid_spec(10.0).boundary[FW_FACE_EAST] == B::inflow);

  // No wind enters anywhere in a calm.
  const fw::fluid::GridSpec calm = wind_only("0", "270").grid_spec(0.0);
  for (int face = 0; face < 4; ++face) CHECK(calm.boundary[std::size_t(face)] == B::outflow);

  // Faces given explicitly are kept, whatever the wind.
  Scenario fixed = wind_only("5", "270");
  fixed.boundaries[FW_FACE_WEST] = BoundaryChoice::slip;
  fixed.boundaries[FW_FACE_EAST] = BoundaryChoice::inflow;
  fixed.boundaries[FW_FACE_SOUTH] = BoundaryChoice::periodic;
  fixed.boundaries[FW_FACE_NORTH] = BoundaryChoice::periodic;
  CHECK(fixed.grid_spec(0.0).boundary ==
        std::array<B, 6>{B::slip, B::inflow, B::periodic, B::periodic, B::no_slip, B::slip});
}

TEST_CASE("load_scenario: relative paths resolve against the scenario's folder, the output against the cwd",
          "[scenario]") {
  fw::test::TempDir root("fw_scenario");
  const fs::path base = root.path();
  fs::create_directories(base / "scenarios" / "trees");
  fs::create_directories(base / "shared");
  fs::create_directories(base / "run");
  root.write("scenarios/hills.pgm", ramp_pgm(11, 6));
  root.write("scenarios/trees/pine.tree", kTreeFile);
  root.write("shared/birch_qsm.txt", kQsmFile);
  // A decoy next to the working directory that must not be the one found.
  root.write("run/hills.pgm", "not a heightmap");
  const std::string text = R"(scenario: paths
time: {end: 1.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
wind: {speed: 4.0, direction: 270}
terrain: {heightmap: hills.pgm, cell_size: 4.0, max_height: 10.0}
forest:
  species:
    - name: pine
      skeleton: {file: trees/pine.tree}
    - name: birch
      skeleton: {qsm: ../shared/birch_qsm.txt}
)";
  root.write("scenarios/paths.yaml", text);

  const WorkingDirectory cwd(base / "run");
  const Scenario s = fw::io::load_scenario("../scenarios/paths.yaml");
  CHECK(s.file.string() == "../scenarios/paths.yaml");
  CHECK(s.folder.is_absolute());
  CHECK(fs::equivalent(s.folder, base / "scenarios"));
  REQUIRE(s.terrain.has_value());
  CHECK(s.terrain->heightmap.is_absolute());
  CHECK(fs::equivalent(s.terrain->heightmap, base / "scenarios" / "hills.pgm"));
  CHECK(s.terrain->map->columns() == 11);  // the real heightmap, not the decoy
  REQUIRE(s.forest.species.size() == 2);
  CHECK(fs::equivalent(s.forest.species[0].skeleton.path, base / "scenarios" / "trees" / "pine.tree"));
  CHECK(fs::equivalent(s.forest.species[1].skeleton.path, base / "shared" / "birch_qsm.txt"));
  CHECK(s.forest.species[1].skeleton.path.lexically_normal().string() ==
        s.forest.species[1].skeleton.path.string());  // no ".." left
  // The default output directory is out/<scenario> under the working directory.
  CHECK(s.output.directory.string() == (fs::current_path() / "out" / "paths").string());

  // A file that exists only next to the working directory is not found.
  root.write("run/only_here.tree", kTreeFile);
  std::string only_here = text;
  only_here.replace(only_here.find("trees/pine.tree"), std::string("trees/pine.tree").size(),
                    "only_here.tree");
  root.write("scenarios/only_here.yaml", only_here);
  try {
    fw::io::load_scenario("../scenarios/only_here.yaml");
    FAIL("a skeleton next to the working directory was accepted");
  } catch (const fw::io::ScenarioError& error) {
    CHECK(error.line() == 9);
    CHECK(error.key() == "forest.species[0].skeleton.file");
    CHECK_THAT(std::string(error.what()), Contains("no such file"));
  }
}

TEST_CASE("load_scenario: unknown key names file, line and dotted key", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "nested",
                        kBase +
                            "forest:\n"                                          // 5
                            "  species:\n"                                       // 6
                            "    - name: oak\n"                                  // 7
                            "      skeleton: {generate: {preset: broadleaf}}\n"  // 8
                            "      modes:\n"                                     // 9
                            "        count: 8\n"                                 // 10
                            "        damping: 0.05\n",                           // 11
                        11, "forest.species[0].modes.damping",
                        "one of the keys count, damping_ratio, wind_samples expected, got 'damping'");
  expect_scenario_error(dir, "top_level", kBase + "gusts: []\n", 5, "gusts", "got 'gusts'");
  expect_scenario_error(
      dir, "in_event",
      kBase +
          "events:\n  - gust: {start: 1, duration: 2, peak_speed: 3, center: [1, 1, 1], radius: 2,\n"
          "            spin: 4}\n",
      7, "events[0].gust.spin", "one of the keys start, duration, peak_speed, center, radius, travel");
  // The profile's keys depend on its type: alpha belongs to power only.
  expect_scenario_error(
      dir, "profile_key",
      "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
      "wind:\n  speed: 4\n  direction: 270\n  profile: {type: log, roughness_length: 0.1, alpha: 0.2}\n",
      7, "wind.profile.alpha", "got 'alpha'");
}

TEST_CASE("load_scenario: duplicate key names its second line and the first", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "duplicate",
                        "scenario: errors\n"
                        "time: {end: 10.0}\n"
                        "domain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n"
                        "  speed: 4.0\n"  // 5
                        "  direction: 270\n"
                        "  speed: 6.0\n",  // 7
                        7, "wind.speed", "each key once expected, got 'speed' again (first on line 5)");
  expect_scenario_error(dir, "duplicate_top", kBase + "time: {end: 20.0}\n", 5, "time", "(first on line 2)");
}

TEST_CASE("load_scenario: wrong type names the key and shows the value", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "end_word",
                        "scenario: errors\ntime: {end: soon}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind: {speed: 4.0, direction: 270}\n",
                        2, "time.end", "a number > 0 and <= 1e9 (s) expected, got 'soon'");
  expect_scenario_error(dir, "spin_up_word",
                        "scenario: errors\ntime:\n  end: 10.0\n  spin_up: long\n"
                        "domain: {size: [40, 20, 10], cell_size: 2.0}\nwind: {speed: 4.0, direction: 270}\n",
                        4, "time.spin_up", "a number >= 0 and <= 1e9 (s) expected, got 'long'");
  expect_scenario_error(dir, "spin_up_list",
                        "scenario: errors\ntime: {end: 10.0, spin_up: [5]}\n"
                        "domain: {size: [40, 20, 10], cell_size: 2.0}\nwind: {speed: 4.0, direction: 270}\n",
                        2, "time.spin_up", "a number >= 0 and <= 1e9 (s) expected, got '[5]'");
  expect_scenario_error(dir, "coupling", kBase + "forest:\n  two_way_coupling: maybe\n", 6,
                        "forest.two_way_coupling", "true or false expected, got 'maybe'");
  expect_scenario_error(dir, "cell_list",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: [2]}\n"
                        "wind: {speed: 4.0, direction: 270}\n",
                        3, "domain.cell_size", "got '[2]'");
  expect_scenario_error(dir, "probes_map", kBase + "output:\n  probes: {name: mast}\n", 6, "output.probes",
                        "a list of probes expected, got a map");
  expect_scenario_error(
      dir, "size_two",
      "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20], cell_size: 2}\n"
      "wind: {speed: 4.0, direction: 270}\n",
      3, "domain.size",
      "a list of 3 numbers [x, y, z], each > 0 and <= 40075017 (m) expected, got '[40, 20]'");
  expect_scenario_error(dir, "root_list", "- scenario: errors\n", 1, "(top level)", "a map of scenario keys");
  expect_scenario_error(dir, "empty", "", 1, "(top level)",
                        "a map of scenario keys (scenario, time, domain, wind, ...) "
                        "expected, got nothing");
}

TEST_CASE("load_scenario: missing required key names the map that lacks it", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "no_speed",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n"
                        "  direction: 270\n"  // 5: the map starts here
                        "  reference_height: 10\n",
                        5, "wind.speed", "(required), got nothing");
  expect_scenario_error(dir, "no_time",
                        "scenario: errors\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind: {speed: 4.0, direction: 270}\n",
                        1, "time", "a map {end, dt, cfl, spin_up} expected (required), got nothing");
  expect_scenario_error(
      dir, "no_radius",
      kBase + "events:\n  - gust: {start: 1, duration: 2, peak_speed: 3, center: [1, 1, 1]}\n", 6,
      "events[0].gust.radius", "a number > 0 and <= 40075017 (m) expected (required)");
  expect_scenario_error(dir, "no_roughness",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n  speed: 4\n  direction: 270\n  profile: {type: log}\n",
                        7, "wind.profile.roughness_length", "(required)");
  expect_scenario_error(dir, "no_skeleton", kBase + "forest:\n  species:\n    - name: oak\n", 7,
                        "forest.species[0].skeleton", "(required)");
}

TEST_CASE("load_scenario: out-of-range numbers name the key and the allowed range", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string species = kBase +
                              "forest:\n"
                              "  species:\n"
                              "    - name: oak\n"
                              "      skeleton: {generate: {preset: broadleaf}}\n";  // 8
  expect_scenario_error(dir, "samples", species + "      modes: {wind_samples: 17}\n", 9,
                        "forest.species[0].modes.wind_samples", "an integer 1..16 expected, got '17'");
  expect_scenario_error(dir, "count", species + "      modes: {count: 0}\n", 9,
                        "forest.species[0].modes.count", "an integer 1..1000 expected, got '0'");
  expect_scenario_error(dir, "damping", species + "      modes: {damping_ratio: -0.1}\n", 9,
                        "forest.species[0].modes.damping_ratio",
                        "a number >= 0 and <= 10 expected, got '-0.1'");
  expect_scenario_error(dir, "density", species + "      material: {density: 0}\n", 9,
                        "forest.species[0].material.density",
                        "a number >= 1.2 and <= 22590 (kg/m^3) expected, got '0'");
  expect_scenario_error(
      dir, "gust_zero",
      kBase + "events:\n  - gust: {start: 1, duration: 0, peak_speed: 3, center: [1, 1, 1], radius: 2}\n", 6,
      "events[0].gust.duration", "a number > 0 and <= 1e9 (s) expected, got '0'");
  expect_scenario_error(dir, "drag_law", kBase + "forest: {drag_law: {exponent: -2}}\n", 5,
                        "forest.drag_law.exponent",
                        "a number >= -1.3333333333333333 and <= 0 expected, got '-2'");
  expect_scenario_error(dir, "seed", kBase + "seed: -1\n", 5, "seed",
                        "an integer 0..18446744073709551615 expected, got '-1'");
  expect_scenario_error(
      dir, "cfl",
      "scenario: errors\ntime: {end: 10.0, cfl: 0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
      "wind: {speed: 4.0, direction: 270}\n",
      2, "time.cfl", "a number > 0 and <= 5 expected, got '0'");
  expect_scenario_error(
      dir, "dt",
      "scenario: errors\ntime: {end: 10.0, dt: -0.5}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
      "wind: {speed: 4.0, direction: 270}\n",
      2, "time.dt", "a number > 0 and <= 3600 (s) or auto expected, got '-0.5'");
  expect_scenario_error(
      dir, "spin_up_negative",
      "scenario: errors\ntime: {end: 10.0, spin_up: -1}\ndomain: {size: [40, 20, 10], cell_size: "
      "2.0}\nwind: {speed: 4.0, direction: 270}\n",
      2, "time.spin_up", "a number >= 0 and <= 1e9 (s) expected, got '-1'");
  expect_scenario_error(dir, "scale",
                        species +
                            "  stands:\n    - {species: oak, region: {min: [5, 5], max: [15, 15]}, "
                            "spacing: 4, scale: {min: 1.2, max: 1.1}}\n",
                        10, "forest.stands[0].scale.max", "a number >= scale.min (1.2)");
}

TEST_CASE("load_scenario: a number past what a scenario can mean is refused, naming the key (issue 44)",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string species = kBase +
                              "forest:\n"
                              "  species:\n"
                              "    - name: oak\n";  // 7
  // The mutants of the issue: a tree taller than any tree, an end time past any run.
  expect_scenario_error(
      dir, "tree_height", species + "      skeleton: {generate: {preset: broadleaf, height: 1e30}}\n", 8,
      "forest.species[0].skeleton.generate.height", "a number >= 0 and <= 150 (m) expected, got '1e30'");
  expect_scenario_error(dir, "tree_too_small",
                        species + "      skeleton: {generate: {preset: broadleaf, height: 1e-3}}\n", 8,
                        "forest.species[0].skeleton.generate.height",
                        "0 (the preset's height) or at least 0.01 m expected, got '1e-3'");
  expect_scenario_error(
      dir, "end",
      "scenario: errors\ntime: {end: 1e30, cfl: 3.5}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
      "wind: {speed: 4.0, direction: 270}\n",
      2, "time.end", "a number > 0 and <= 1e9 (s) expected, got '1e30'");
  // An expression is held to its key's range at every time it is sampled.
  expect_scenario_error(dir, "speed_past_any_wind",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind: {speed: '100 + 10*t', direction: 270}\n",
                        4, "wind.speed",
                        "a finite value >= 0 and <= 150 (m/s) for 0 <= t <= 10 s (it gives 150.1");
  // A domain as tall as the troposphere, however wide.
  expect_scenario_error(
      dir, "domain_height",
      "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 32000], cell_size: 2.0}\n"
      "wind: {speed: 4.0, direction: 270}\n",
      3, "domain.size[2]", "the height at most 20000 m expected, got '32000'");
  // A yaw past a turn, whose radians would overflow at 1e308.
  expect_scenario_error(dir, "yaw",
                        species +
                            "      skeleton: {generate: {preset: broadleaf}}\n  trees:\n"
                            "    - {species: oak, position: [10, 10], yaw: 1e308}\n",
                        10, "forest.trees[0].yaw",
                        "a number >= -360 and <= 360 (degrees) expected, got '1e308'");
  // Frames, probe rows and checkpoints: at most one a step, and at most 10^9 steps.
  const std::string long_run =
      "scenario: errors\ntime: {end: 1e9}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
      "wind: {speed: 4.0, direction: 270}\n";
  expect_scenario_error(
      dir, "frames", long_run + "output: {interval: 0.5}\n", 5, "output.interval",
      "and at least time.end / 1e9 = 1 s (a run writes at most one a step, and takes at most 1e9 "
      "steps) expected, got '0.5'");
  expect_scenario_error(dir, "probe_rows", long_run + "output: {probe_interval: 0.5}\n", 5,
                        "output.probe_interval", "at least time.end / 1e9 = 1 s");
  expect_scenario_error(dir, "checkpoints", long_run + "output: {checkpoint: {interval: 0.5}}\n", 5,
                        "output.checkpoint.interval", "at least time.end / 1e9 = 1 s");
  CHECK_NOTHROW(fw::io::load_scenario(dir.write("every_second.yaml", long_run + "output: {interval: 1}\n")));
}

TEST_CASE("load_scenario: unknown enum word lists the allowed words", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "pressure", kBase + "solver: {pressure: sor}\n", 5, "solver.pressure",
                        "one of multigrid | cg | jacobi expected, got 'sor'");
  // auto follows the horizontal wind, so the ground and the top do not take it.
  expect_scenario_error(dir, "ground_auto", kBase + "boundaries: {ground: auto}\n", 5, "boundaries.ground",
                        "one of inflow | outflow | slip | no_slip | periodic | rough expected, got 'auto'");
  expect_scenario_error(dir, "profile",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n  speed: 4\n  direction: 270\n  profile: {type: exponential}\n",
                        7, "wind.profile.type", "one of uniform | power | log expected, got 'exponential'");
  expect_scenario_error(dir, "field", kBase + "output:\n  vtk: {fields: [velocity, temperature]}\n", 6,
                        "output.vtk.fields[1]", "got 'temperature'");
  expect_scenario_error(
      dir, "preset",
      kBase + "forest:\n  species:\n    - name: oak\n      skeleton: {generate: {preset: baobab}}\n", 8,
      "forest.species[0].skeleton.generate.preset", "got 'baobab'");
}

TEST_CASE("load_scenario: a size that is not a whole multiple of cell_size names the axis", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "odd_z",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 15], cell_size: 2.0}\n"
                        "wind: {speed: 4.0, direction: 270}\n",
                        3, "domain.size[2]",
                        "a whole multiple of cell_size (2 m) along z expected, got '15'");
  expect_scenario_error(dir, "too_small",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 1, 10], cell_size: 2.0}\n"
                        "wind: {speed: 4.0, direction: 270}\n",
                        3, "domain.size[1]", "along y");
  // Periodic faces come in pairs, along an axis with an even cell count.
  expect_scenario_error(dir, "periodic_pair", kBase + "boundaries: {west: periodic}\n", 5, "boundaries.west",
                        "periodic on both west and east (a pair), or neither; east is 'auto'");
  expect_scenario_error(dir, "periodic_odd",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [42, 20, 10], cell_size: 2.0}\n"
                        "wind: {speed: 4.0, direction: 270}\nboundaries: {west: periodic, east: periodic}\n",
                        5, "boundaries.west", "an even cell count; x has 21 cells");
}

TEST_CASE("load_scenario: a grid is as large as fluid::GridSpec allows, and no larger", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const auto cube = [](int cells) {
    return fmt::format(
        "scenario: big\ntime: {{end: 1.0}}\ndomain: {{size: [{0}, {0}, {0}], cell_size: 1.0}}\n"
        "wind: {{speed: 4.0, direction: 270}}\n",
        cells);
  };
  // 1289^3 cells have 1290^3 = 2.1467e9 faces, within GridSpec::kMaxFaces = 2^31 - 1; 1290^3 cells have
  // 1291^3 = 2.1517e9, beyond it. The loader computes nothing per cell, so both are quick.
  const Scenario largest = fw::io::load_scenario(dir.write("largest.yaml", cube(1289)));
  CHECK_NOTHROW(largest.grid_spec(0.0).validate());
  CHECK_THROWS(fw::fluid::GridSpec{1290, 1290, 1290, 1.0}.validate());
  expect_scenario_error(
      dir, "too_large", cube(1290), 3, "domain.cell_size",
      "a cell size giving (nx + 1)(ny + 1)(nz + 1) <= 2147483647 (size / cell_size gives 2.15e+09 "
      "cells) expected, got '1.0'");
}

TEST_CASE("load_scenario: positions outside the domain name the position's key", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string species = kBase +
                              "forest:\n"
                              "  species:\n"
                              "    - name: oak\n"
                              "      skeleton: {generate: {preset: broadleaf}}\n";  // 8
  expect_scenario_error(dir, "tree_west", species + "  trees:\n    - {species: oak, position: [-1, 10]}\n",
                        10, "forest.trees[0].position",
                        "inside the domain's horizontal extent [0, 40] x [0, 20] m");
  expect_scenario_error(
      dir, "stand_corner",
      species + "  stands:\n    - {species: oak, spacing: 4,\n       region: {min: [5, 5], max: [50, 15]}}\n",
      11, "forest.stands[0].region.max", "a point [x, y] inside the domain's horizontal extent");
  expect_scenario_error(
      dir, "probe_high", kBase + "output:\n  probes:\n    - {name: mast, position: [10, 10, 10.5]}\n", 7,
      "output.probes[0].position", "a position inside the domain [0, 40] x [0, 20] x [0, 10] m");
  expect_scenario_error(dir, "probe_name",
                        kBase + "output:\n  probes:\n    - {name: wind-mast, position: [10, 10, 5]}\n", 7,
                        "output.probes[0].name", "a probe name of letters, digits and _");
  expect_scenario_error(dir, "unknown_species",
                        species + "  trees:\n    - {species: elm, position: [10, 10]}\n", 10,
                        "forest.trees[0].species", "a species name, one of oak expected, got 'elm'");
  expect_scenario_error(dir, "species_twice",
                        species + "    - name: oak\n      skeleton: {generate: {preset: conifer}}\n", 9,
                        "forest.species[1].name", "a species name not used before");
}

TEST_CASE("load_scenario: a bad expression, or one that goes negative or infinite, names the key",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "unknown_function",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n  speed: 4\n  direction: \"270 + wobble(t)\"\n",
                        6, "wind.direction", "unknown variable or function \"wobble\"");
  // A valid formula that gives a negative speed during the run: sampled over [0, end].
  expect_scenario_error(dir, "negative_speed",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n  speed: \"5 - t\"\n  direction: 270\n",
                        5, "wind.speed", "a finite value >= 0 and <= 150 (m/s) for 0 <= t <= 10 s");
  // Beyond the end of the run the formula is never used.
  CHECK_NOTHROW(fw::io::load_scenario(
      dir.write("late.yaml",
                "scenario: late\ntime: {end: 4.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                "wind:\n  speed: \"5 - t\"\n  direction: 270\n")));
  expect_scenario_error(dir, "infinite_direction",
                        "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0}\n"
                        "wind:\n  speed: 4\n  direction: \"270 + 1/(t-5)\"\n",
                        6, "wind.direction",
                        "a finite value >= -3.6e8 and <= 3.6e8 (degrees) for 0 <= t <= 10 s");
}

TEST_CASE("load_scenario: a missing heightmap names the heightmap key's line", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "no_heightmap",
                        kBase + "terrain:\n  cell_size: 4\n  heightmap: nowhere.pgm\n  max_height: 10\n", 7,
                        "terrain.heightmap", "no such file");
  // A PGM needs cell_size and max_height; the error points at the terrain map.
  dir.write("hills.pgm", ramp_pgm(5, 5));
  expect_scenario_error(dir, "no_max_height", kBase + "terrain:\n  heightmap: hills.pgm\n  cell_size: 4\n", 6,
                        "terrain.max_height", "needed for a PGM heightmap");
  // A file that is not a PGM.
  dir.write("notes.txt", "hills to the east\n");
  expect_scenario_error(dir, "not_a_heightmap", kBase + "terrain: {heightmap: notes.txt}\n", 5,
                        "terrain.heightmap", "a PGM image");
}

TEST_CASE("load_scenario: a YAML syntax error reports key (yaml) and its line", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "indent", kBase + "seed: 3\n  extra: 4\n", 6, "(yaml)",
                        "valid YAML expected, got a syntax error");
  expect_scenario_error(dir, "two_documents", kBase + "---\nscenario: again\n", 6, "(yaml)",
                        "one YAML document expected, got 2");
}

TEST_CASE("load_scenario: a file that cannot be read reports line 0 and key (file)", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string missing = (fs::path(dir.path()) / "missing.yaml").string();
  try {
    fw::io::load_scenario(missing);
    FAIL("a missing file was accepted");
  } catch (const fw::io::ScenarioError& error) {
    CHECK(error.file() == missing);
    CHECK(error.line() == 0);
    CHECK(error.key() == "(file)");
    CHECK_THAT(std::string(error.what()), StartsWith(missing + ":0: (file): ") && Contains("no such file"));
  }
  try {
    fw::io::load_scenario(dir.path());
    FAIL("a directory was accepted");
  } catch (const fw::io::ScenarioError& error) {
    CHECK(error.line() == 0);
    CHECK(error.key() == "(file)");
    CHECK_THAT(std::string(error.what()), Contains("got a directory"));
  }
}

TEST_CASE("load_scenario: a log profile whose reference height is not above d + z0 names the profile key",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  // docs/design.md's own combination: 10 m reference, d = 12 m, z0 = 0.8 m.
  expect_scenario_error(dir, "log_below_displacement",
                        "scenario: errors\n"
                        "time: {end: 10.0}\n"
                        "domain: {size: [40, 20, 30], cell_size: 2.0}\n"
                        "wind:\n"
                        "  speed: 4.0\n"
                        "  direction: 270\n"
                        "  reference_height: 10.0\n"
                        "  profile: {type: log, roughness_length: 0.8, displacement_height: 12.0}\n",
                        8, "wind.profile.displacement_height",
                        "(now 12.8 m) below wind.reference_height (10 m)");
  // Without a displacement height the roughness length alone is checked, and named.
  expect_scenario_error(dir, "log_rough",
                        "scenario: errors\n"
                        "time: {end: 10.0}\n"
                        "domain: {size: [40, 20, 30], cell_size: 2.0}\n"
                        "wind:\n"
                        "  speed: 4.0\n"
                        "  direction: 270\n"
                        "  reference_height: 2.0\n"
                        "  profile:\n"
                        "    type: log\n"
                        "    roughness_length: 3.0\n",
                        10, "wind.profile.roughness_length", "(now 3 m) below wind.reference_height (2 m)");
}

TEST_CASE("load_scenario: a tree's height outside the domain names position[2]", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "tree_above",
                        kBase +
                            "forest:\n"
                            "  species:\n"
                            "    - {name: stick, skeleton: {generate: {preset: palm}}}\n"
                            "  trees:\n"
                            "    - {species: stick, position: [10, 10, 12]}\n",
                        9, "forest.trees[0].position[2]", "a height inside the domain's [0, 10] m");
}

TEST_CASE("load_scenario: stands and generated skeletons take their default seeds from the global seed",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  auto forest = [](const std::string& seed_line) {
    return seed_line + kBase.substr(kBase.find('\n') + 1) +
           "forest:\n"
           "  species:\n"
           "    - {name: a, skeleton: {generate: {preset: palm}}}\n"
           "    - {name: b, skeleton: {generate: {preset: palm, seed: 99}}}\n"
           "  stands:\n"
           "    - {species: a, region: {min: [0, 0], max: [40, 20]}, spacing: 8.0}\n"
           "    - {species: b, region: {min: [0, 0], max: [40, 20]}, spacing: 8.0, seed: 5}\n"
           "    - {species: b, region: {min: [0, 0], max: [40, 20]}, spacing: 8.0}\n";
  };
  const Scenario unseeded = fw::io::load_scenario(dir.write("unseeded.yaml", "scenario: s0\n" + forest("")));
  const Scenario seeded =
      fw::io::load_scenario(dir.write("seeded.yaml", "scenario: s7\nseed: 7\n" + forest("")));
  // Without a global seed (0): species k generates with seed 1 + k, stand k is laid out with seed k.
  CHECK(unseeded.forest.species[0].skeleton.generate.seed == 1);
  CHECK(unseeded.forest.stands[0].layout.seed == 0);
  CHECK(unseeded.forest.stands[2].layout.seed == 2);
  // With seed 7 every default moves with it; seeds the file gives stay as written.
  CHECK(seeded.forest.species[0].skeleton.generate.seed == 8);
  CHECK(seeded.forest.species[1].skeleton.generate.seed == 99);
  CHECK(seeded.forest.stands[0].layout.seed == 7);
  CHECK(seeded.forest.stands[1].layout.seed == 5);
  CHECK(seeded.forest.stands[2].layout.seed == 9);
}

TEST_CASE("load_scenario: a stand's own leaf_area_index is read with its line, and a bad one is refused",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string forest =
      kBase +
      "forest:\n"
      "  species:\n"
      "    - {name: oak, skeleton: {generate: {preset: broadleaf}}, canopy: {leaf_area_index: 3}}\n"
      "  stands:\n"
      "    - {species: oak, region: {min: [0, 0], max: [40, 20]}, spacing: 8.0}\n";  // 9
  auto with = [&](const std::string& value) {
    return forest +
           "    - {species: oak, region: {min: [0, 0], max: [40, 20]}, spacing: 8.0,\n"  // 10
           "       leaf_area_index: " +
           value + "}\n";  // 11
  };
  const Scenario scenario = fw::io::load_scenario(dir.write("given.yaml", with("4.5")));
  REQUIRE(scenario.forest.stands.size() == 2);
  // Left out: the species' canopy.leaf_area_index stays on every crown of the stand.
  CHECK_FALSE(scenario.forest.stands[0].leaf_area_index);
  CHECK(scenario.forest.stands[0].line == 9);
  CHECK(scenario.forest.stands[0].leaf_area_index_line == 9);
  CHECK(scenario.forest.stands[1].leaf_area_index == 4.5);
  CHECK(scenario.forest.stands[1].line == 10);
  CHECK(scenario.forest.stands[1].leaf_area_index_line == 11);
  CHECK(scenario.forest.species[0].canopy.leaf_area_index == 3.0);  // both given: each keeps its own
  // The upper limit is the forests' own (trees::StandDensity), and it is allowed.
  const std::string most = fmt::format("{}", fw::trees::StandDensity::kMaxLeafAreaIndex);
  CHECK(fw::io::load_scenario(dir.write("most.yaml", with(most))).forest.stands[1].leaf_area_index ==
        fw::trees::StandDensity::kMaxLeafAreaIndex);

  const std::string key = "forest.stands[1].leaf_area_index";
  const std::string range = "a number > 0 and <= " + most + " (m^2/m^2) expected";
  expect_scenario_error(dir, "lai_zero", with("0"), 11, key, range + ", got '0'");
  expect_scenario_error(dir, "lai_negative", with("-2"), 11, key, range + ", got '-2'");
  expect_scenario_error(dir, "lai_above", with("19"), 11, key, range + ", got '19'");
  expect_scenario_error(dir, "lai_infinite", with(".inf"), 11, key, range + ", got '.inf'");
  expect_scenario_error(dir, "lai_nan", with(".nan"), 11, key, range + ", got '.nan'");
  expect_scenario_error(dir, "lai_word", with("dense"), 11, key, range + ", got 'dense'");
}

TEST_CASE("check_species_skeleton: more modes than the skeleton has DOFs names modes.count's line",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string text = kBase +
                           "forest:\n"                                                     // 5
                           "  species:\n"                                                  // 6
                           "    - name: stick\n"                                           // 7
                           "      skeleton: {generate: {preset: palm}}\n"                  // 8
                           "      modes:\n"                                                // 9
                           "        count: 12\n"                                           // 10
                           "    - {name: plain, skeleton: {generate: {preset: palm}}}\n";  // 11
  const std::string path = dir.write("modes.yaml", text);
  const Scenario s = fw::io::load_scenario(path);
  // 3 nodes, root clamped: 12 DOFs, so at most 11 modes.
  try {
    fw::io::check_species_skeleton(s, 0, 3);
    FAIL("check_species_skeleton accepted 12 modes for 12 DOFs");
  } catch (const fw::io::ScenarioError& error) {
    CHECK(error.line() == 10);
    CHECK(error.key() == "forest.species[0].modes.count");
    CHECK_THAT(std::string(error.what()),
               Contains("at most 11 modes for this skeleton of 3 nodes (12 DOFs)"));
  }
  CHECK_NOTHROW(fw::io::check_species_skeleton(s, 0, 4));
  // The default count (20) with no modes key: the species entry's line.
  try {
    fw::io::check_species_skeleton(s, 1, 3);
    FAIL("check_species_skeleton accepted 20 modes for 12 DOFs");
  } catch (const fw::io::ScenarioError& error) {
    CHECK(error.line() == 11);
  }
}

TEST_CASE("load_scenario: a PGM heightmap's south-west corner sits at the domain's origin", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  // 11 columns rising east, 6 rows, 4 m pixels: height (x' / 4 - 0.5) / 10 * 10 m at x' = x - origin x.
  dir.write("ramp.pgm", ramp_pgm(11, 6));
  const Scenario s = fw::io::load_scenario(dir.write("shifted.yaml",
                                                     "scenario: shifted\n"
                                                     "time: {end: 1.0}\n"
                                                     "domain: {origin: [-100, 50, 3], size: [44, 24, 20], "
                                                     "cell_size: 2.0}\n"
                                                     "wind: {speed: 1.0, direction: 270}\n"
                                                     "terrain: {heightmap: ramp.pgm, cell_size: 4.0, "
                                                     "max_height: 10.0}\n"));
  REQUIRE(s.terrain.has_value());
  const fw::fluid::Heightmap& map = *s.terrain->map;
  CHECK(map.sw_centre() == std::array<double, 2>{-98.0, 52.0});  // origin + half a pixel
  // Tolerance: bilinear interpolation in doubles, 1e-12 m.
  CHECK(map.height_at(-98.0, 60.0) == Approx(0.0).margin(1e-12));   // first pixel centre
  CHECK(map.height_at(-78.0, 60.0) == Approx(5.0).margin(1e-12));   // column 5 of 0..10
  CHECK(map.height_at(-58.0, 60.0) == Approx(10.0).margin(1e-12));  // the east column
}

namespace {

// The first six lines of the turbulence error cases: a valid scenario with a block `wind` map to add to.
const std::string kWindBase =
    "scenario: errors\n"                              // 1
    "time: {end: 10.0}\n"                             // 2
    "domain: {size: [40, 20, 10], cell_size: 2.0}\n"  // 3
    "wind:\n"                                         // 4
    "  speed: 4.0\n"                                  // 5
    "  direction: 270\n";                             // 6

}  // namespace

TEST_CASE("load_scenario: turbulence, a rough ground, the eddy viscosity and the probe interval are read",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("turbulent.yaml", R"(scenario: turbulent
seed: 5
time: {end: 10.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
boundaries: {ground: rough, roughness_length: 0.3}
wind:
  speed: "4 + t"
  direction: 270
  turbulence: {model: von_karman, intensity: 0.15, length_scale: 10, box_size: [50, 30, 7], seed: 9,
               unresolved: false, cutoff_cells: 4}
forest: {strong_wind_correction: false, drag_law: {exponent: -0.5, reference_speed: 4.0}}
solver: {smagorinsky_constant: 0.17, advection: upwind5, stage_projection: every_stage}
output: {interval: 0.5, probe_interval: 0.05}
)"));
  REQUIRE(s.wind.turbulence.has_value());
  const fw::io::TurbulenceSettings& turbulence = *s.wind.turbulence;
  CHECK(turbulence.model == fw::io::TurbulenceModel::von_karman);
  CHECK(turbulence.intensity == std::optional<double>(0.15));
  CHECK_FALSE(turbulence.sigma.has_value());
  CHECK(turbulence.length_scale == 10.0);
  // 25, 15 and 3.5 cells of 2 m, rounded to whole even counts of at least 4.
  CHECK(turbulence.box_cells == std::array<int, 3>{26, 16, 4});
  CHECK(turbulence.box_size == std::array<double, 3>{52, 32, 8});
  CHECK(turbulence.box_size_given);
  CHECK(turbulence.seed == 9);
  CHECK_FALSE(turbulence.unresolved);
  CHECK(turbulence.cutoff_cells == 4.0);
  // sigma_u = I U follows the speed, 6 m/s at t = 2 s; isotropic. Tolerance: one multiplication, 1e-12 m/s.
  check_vector(turbulence.standard_deviations(s.wind.speed(2.0)), {0.9, 0.9, 0.9}, 1e-12);

  CHECK(s.boundaries[FW_FACE_GROUND] == BoundaryChoice::rough);
  CHECK(fw::io::to_string(BoundaryChoice::rough) == "rough");
  CHECK(s.ground_roughness_length == 0.3);
  // A rough ground is a slip wall to the grid; the wall stress is a stage of its own.
  CHECK(s.grid_spec(0.0).boundary[FW_FACE_GROUND] == BoundaryType::slip);
  CHECK_FALSE(s.wind.forcing.has_value());  // the sides are not periodic

  CHECK_FALSE(s.forest.strong_wind_correction);
  CHECK(s.forest.drag_law.exponent == -0.5);
  CHECK(s.forest.drag_law.reference_speed == 4.0);
  CHECK(s.solver.smagorinsky_constant == 0.17);
  CHECK(s.solver.subgrid == fw::fluid::SubgridModel::smagorinsky);  // the default
  CHECK(s.solver.advection == fw::fluid::AdvectionScheme::upwind5);
  CHECK(s.wind_settings().stage_projection == fw::fluid::StageProjection::every_stage);
  CHECK(s.output.probe_interval == std::optional<double>(0.05));
  CHECK(s.resolved_probe_interval() == std::optional<double>(0.05));
}

TEST_CASE("load_scenario: solver.subgrid tke reaches the wind settings, without a Smagorinsky constant",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("tke.yaml", kBase + "solver: {subgrid: tke}\n"));
  CHECK(s.solver.subgrid == fw::fluid::SubgridModel::tke);
  const auto settings = s.wind_settings();
  CHECK(settings.subgrid == fw::fluid::SubgridModel::tke);
  CHECK(settings.smagorinsky_constant == 0.0);
  CHECK_NOTHROW(settings.validate());
}

TEST_CASE("load_scenario: upwind5 gets the measured Smagorinsky constant unless the file names one",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const auto constant = [&](const std::string& name, const std::string& solver) {
    return fw::io::load_scenario(dir.write(name + ".yaml", kBase + "solver: " + solver + "\n"))
        .wind_settings()
        .smagorinsky_constant;
  };
  CHECK(constant("upwind5", "{advection: upwind5}") == fw::fluid::WindSettings::kUpwind5SmagorinskyConstant);
  CHECK(fw::fluid::WindSettings::kUpwind5SmagorinskyConstant == 0.16);  // as docs/scenario.md says
  CHECK(constant("upwind5_named", "{advection: upwind5, smagorinsky_constant: 0.12}") == 0.12);
  CHECK(constant("upwind5_off", "{advection: upwind5, smagorinsky_constant: 0}") == 0.0);
  CHECK(constant("upwind5_tke", "{advection: upwind5, subgrid: tke}") == 0.0);
  // The dissipative schemes drain the cascade themselves: off unless named.
  CHECK(constant("maccormack", "{advection: maccormack}") == 0.0);
  CHECK(constant("semi_lagrangian", "{advection: semi_lagrangian}") == 0.0);
}

TEST_CASE("load_scenario: turbulence and a rough ground get the documented defaults", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("defaults.yaml", R"(scenario: turbulent_defaults
seed: 5
time: {end: 10.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
boundaries: {ground: rough}
wind:
  speed: 4
  direction: 270
  profile: {type: log, roughness_length: 0.05}
  turbulence: {sigma: [1.2, 0.9, 0.6], length_scale: 10}
)"));
  REQUIRE(s.wind.turbulence.has_value());
  const fw::io::TurbulenceSettings& turbulence = *s.wind.turbulence;
  CHECK(turbulence.model == fw::io::TurbulenceModel::von_karman);
  CHECK_FALSE(turbulence.intensity.has_value());
  CHECK(turbulence.sigma == std::optional<std::array<double, 3>>({1.2, 0.9, 0.6}));
  CHECK(turbulence.standard_deviations(20.0) == std::array<double, 3>{1.2, 0.9, 0.6});  // fixed over time
  // 20 x 10 x 5 cells; 8 length scales are 40 cells: x and y the power of two above 40, z the one above 5.
  CHECK(turbulence.box_cells == std::array<int, 3>{64, 64, 8});
  CHECK(turbulence.box_size == std::array<double, 3>{128, 128, 16});
  CHECK_FALSE(turbulence.box_size_given);
  CHECK(turbulence.seed == 5);  // the global seed
  CHECK(turbulence.unresolved);
  CHECK(turbulence.cutoff_cells == 2.0);
  // The rough ground takes the log profile's roughness length.
  CHECK(s.ground_roughness_length == 0.05);
  // With turbulence, auto samples the probes at every solver step.
  CHECK_FALSE(s.output.probe_interval.has_value());
  CHECK_FALSE(s.resolved_probe_interval().has_value());

  // A domain wider than 8 length scales: the box covers the domain (80 cells along x -> 128); a domain
  // only 2 cells deep still gets 4 along z. Without a log profile the roughness length is 0.1 m.
  const Scenario wide = fw::io::load_scenario(dir.write("wide.yaml", R"(scenario: wide
time: {end: 10.0}
domain: {size: [160, 20, 4], cell_size: 2.0}
boundaries: {ground: rough}
wind: {speed: 4, direction: 270, turbulence: {intensity: 0.2, length_scale: 1}}
)"));
  REQUIRE(wide.wind.turbulence.has_value());
  CHECK(wide.wind.turbulence->box_cells == std::array<int, 3>{128, 16, 4});
  CHECK(wide.wind.turbulence->seed == 0);
  CHECK(wide.ground_roughness_length == 0.1);
  // A given size below 4 cells becomes 4 cells.
  const Scenario tiny = fw::io::load_scenario(dir.write(
      "tiny.yaml", kWindBase + "  turbulence: {intensity: 0.2, length_scale: 1, box_size: [1, 2, 3]}\n"));
  REQUIRE(tiny.wind.turbulence.has_value());
  CHECK(tiny.wind.turbulence->box_cells == std::array<int, 3>{4, 4, 4});
}

TEST_CASE("load_scenario: four periodic sides switch the mean forcing on, with or without wind.forcing",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string periodic =
      "boundaries: {west: periodic, east: periodic, south: periodic, north: periodic}\n";
  const Scenario plain = fw::io::load_scenario(dir.write("plain.yaml", kWindBase + periodic));
  REQUIRE(plain.wind.forcing.has_value());
  CHECK(plain.wind.forcing->relaxation_time == 10.0);
  const Scenario given = fw::io::load_scenario(
      dir.write("given.yaml", kWindBase + "  forcing: {relaxation_time: 30}\n" + periodic));
  REQUIRE(given.wind.forcing.has_value());
  CHECK(given.wind.forcing->relaxation_time == 30.0);
  // Two periodic sides leave inflow faces: no forcing.
  const Scenario channel = fw::io::load_scenario(
      dir.write("channel.yaml", kWindBase + "boundaries: {south: periodic, north: periodic}\n"));
  CHECK_FALSE(channel.wind.forcing.has_value());
}

TEST_CASE("load_scenario: bad turbulence keys name the key and say what is expected", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  expect_scenario_error(dir, "negative_intensity",
                        kWindBase + "  turbulence: {intensity: -0.1, length_scale: 10}\n", 7,
                        "wind.turbulence.intensity", "a number >= 0 and <= 2 expected, got '-0.1'");
  expect_scenario_error(dir, "both",
                        kWindBase +
                            "  turbulence:\n"          // 7
                            "    intensity: 0.1\n"     // 8
                            "    sigma: [1, 1, 1]\n"   // 9
                            "    length_scale: 10\n",  // 10
                        9, "wind.turbulence.sigma",
                        "exactly one of intensity and sigma expected, got both (intensity on line 8)");
  expect_scenario_error(
      dir, "neither", kWindBase + "  turbulence: {length_scale: 10}\n", 7, "wind.turbulence.intensity",
      "a number >= 0 and <= 2, or sigma (exactly one of intensity and sigma) expected (required), "
      "got nothing");
  expect_scenario_error(dir, "no_length_scale", kWindBase + "  turbulence: {intensity: 0.1}\n", 7,
                        "wind.turbulence.length_scale",
                        "a number >= 1e-3 and <= 10000 (m) expected (required), got nothing");
  expect_scenario_error(dir, "zero_sigma", kWindBase + "  turbulence: {sigma: [1, 0, 1], length_scale: 10}\n",
                        7, "wind.turbulence.sigma[1]", "a number > 0 and <= 150 (m/s) expected, got '0'");
  expect_scenario_error(
      dir, "sigma_pair", kWindBase + "  turbulence: {sigma: [1, 1], length_scale: 10}\n", 7,
      "wind.turbulence.sigma",
      "a list of 3 numbers [sigma_u, sigma_v, sigma_w], each > 0 and <= 150 (m/s) expected, got '[1, 1]'");
  expect_scenario_error(
      dir, "unknown_key", kWindBase + "  turbulence: {intensity: 0.1, length_scale: 10, spectrum: kaimal}\n",
      7, "wind.turbulence.spectrum",
      "one of the keys model, intensity, sigma, length_scale, box_size, seed, unresolved, cutoff_cells "
      "expected, got 'spectrum'");
  expect_scenario_error(dir, "model",
                        kWindBase + "  turbulence: {model: mann, intensity: 0.1, length_scale: 10}\n", 7,
                        "wind.turbulence.model", "one of von_karman expected, got 'mann'");
  expect_scenario_error(dir, "cutoff",
                        kWindBase + "  turbulence: {intensity: 0.1, length_scale: 10, cutoff_cells: 0}\n", 7,
                        "wind.turbulence.cutoff_cells", "a number > 0 and <= 2147483647 expected, got '0'");
  expect_scenario_error(dir, "unresolved",
                        kWindBase + "  turbulence: {intensity: 0.1, length_scale: 10, unresolved: 1}\n", 7,
                        "wind.turbulence.unresolved", "true or false expected, got '1'");
  expect_scenario_error(
      dir, "box_negative",
      kWindBase + "  turbulence: {intensity: 0.1, length_scale: 10, box_size: [64, -2, 8]}\n", 7,
      "wind.turbulence.box_size[1]", "a number > 0 and <= 40075017 (m) expected, got '-2'");
  // 8 length scales of a million metres in cells of 2 m: 2^22 cells along x and y is far too many.
  expect_scenario_error(
      dir, "default_box_too_big", kWindBase + "  turbulence: {intensity: 0.1, length_scale: 1.0e4}\n", 7,
      "wind.turbulence.box_size",
      "of at most 715827882 points in all, 2 per cell along each axis expected (required here: the "
      "default box, 8 length_scale along x and y, is 65536 x 65536 x 8 cells of 2 m");
  expect_scenario_error(
      dir, "box_too_big",
      kWindBase + "  turbulence: {intensity: 0.1, length_scale: 10, box_size: [1.0e5, 1.0e5, 1000]}\n", 7,
      "wind.turbulence.box_size",
      "2 per cell along each axis (this box is 50000 x 50000 x 500 cells of 2 m, 1e+13 points)");
}

TEST_CASE("load_scenario: the turbulence box's limit counts the points fluid::TurbulenceBox allocates",
          "[scenario]") {
  // check and run agree: the box the loader accepts at the limit is one TurbulenceBoxSpec::validate takes
  // (without allocating it), and one more cell is refused by both, the loader naming file, line and key.
  // Cells of 2 m, 4 x 4 along y and z: 5592404 cells along x are 2^3 * 16 * 5592404 = 715827712 points,
  // within kMaxPoints = 715827882; 5592406 cells are 715827968 points, beyond it.
  fw::test::TempDir dir("fw_scenario");
  const auto box = [](long cells_x) {
    return fmt::format("{}  turbulence: {{intensity: 0.1, length_scale: 10, box_size: [{}, 8, 8]}}\n",
                       kWindBase, 2 * cells_x);
  };
  const auto spec_of = [](const std::array<int, 3>& cells) {
    // As host::inflow_turbulence_spec builds it.
    fw::fluid::TurbulenceBoxSpec spec;
    for (std::size_t a = 0; a < 3; ++a) spec.cells[a] = fw::fluid::kTurbulencePointsPerCell * cells[a];
    spec.spacing = 2.0 / fw::fluid::kTurbulencePointsPerCell;
    spec.spectrum = {1.0, 10.0};
    return spec;
  };
  const Scenario largest = fw::io::load_scenario(dir.write("largest.yaml", box(5592404)));
  REQUIRE(largest.wind.turbulence.has_value());
  CHECK(largest.wind.turbulence->box_cells == std::array<int, 3>{5592404, 4, 4});
  CHECK(spec_of(largest.wind.turbulence->box_cells).point_count() == 715827712);
  CHECK_NOTHROW(spec_of(largest.wind.turbulence->box_cells).validate());

  CHECK_THROWS_WITH(spec_of({5592406, 4, 4}).validate(), Contains("exceed the limit of 715827882"));
  expect_scenario_error(
      dir, "one_cell_more", box(5592406), 7, "wind.turbulence.box_size",
      "a list of 3 numbers [x, y, z], each > 0 and <= 40075017 (m) of at most 715827882 points in "
      "all, 2 per cell along each axis (this box is 5592406 x 4 x 4 cells of 2 m, 7.16e+08 points) "
      "expected, got '[11184812, 8, 8]'");
}

TEST_CASE("load_scenario: bad rough-ground, forcing, Smagorinsky and probe keys name the key", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  // rough is a ground condition: a side or the top is told so.
  expect_scenario_error(
      dir, "rough_side", kBase + "boundaries: {west: rough}\n", 5, "boundaries.west",
      "one of auto | inflow | outflow | slip | no_slip | periodic (rough is for the ground only) expected, "
      "got 'rough'");
  expect_scenario_error(
      dir, "rough_top", kBase + "boundaries: {top: rough}\n", 5, "boundaries.top",
      "one of inflow | outflow | slip | no_slip | periodic (rough is for the ground only) expected");
  expect_scenario_error(dir, "roughness_smooth", kBase + "boundaries: {roughness_length: 0.1}\n", 5,
                        "boundaries.roughness_length",
                        "nothing unless boundaries.ground is rough (it is 'no_slip') expected, got '0.1'");
  expect_scenario_error(
      dir, "roughness_high", kBase + "boundaries: {ground: rough, roughness_length: 1.0}\n", 5,
      "boundaries.roughness_length",
      "a number > 0 and <= 10 (m) below cell_size / 2 = 1 m (the log law is evaluated at the first "
      "cell centre) expected, got '1.0'");
  expect_scenario_error(dir, "roughness_zero", kBase + "boundaries: {ground: rough, roughness_length: 0}\n",
                        5, "boundaries.roughness_length", "a number > 0 and <= 10 (m) expected, got '0'");
  // The default from the log profile is checked too, and blamed on the missing key at the boundaries' line.
  expect_scenario_error(
      dir, "roughness_default",
      kWindBase + "  profile: {type: log, roughness_length: 1.5}\nboundaries: {ground: rough}\n", 8,
      "boundaries.roughness_length",
      "a number > 0 and <= 10 (m) below cell_size / 2 = 1 m expected (required here: the default, "
      "wind.profile.roughness_length, is 1.5 m), got nothing");
  expect_scenario_error(
      dir, "forcing_open", kWindBase + "  forcing: {relaxation_time: 5}\n", 7, "wind.forcing",
      "forcing only in a domain whose west, east, south and north are all periodic (boundaries.west is "
      "'auto') expected, got a map");
  expect_scenario_error(
      dir, "forcing_channel",
      kWindBase + "  forcing: {}\nboundaries: {west: periodic, east: periodic, south: slip, north: slip}\n",
      7, "wind.forcing", "(boundaries.south is 'slip') expected, got a map");
  expect_scenario_error(
      dir, "forcing_zero",
      kWindBase + "  forcing: {relaxation_time: 0}\n" +
          "boundaries: {west: periodic, east: periodic, south: periodic, north: periodic}\n",
      7, "wind.forcing.relaxation_time", "a number > 0 and <= 1e9 (s) expected, got '0'");
  expect_scenario_error(dir, "smagorinsky_one", kBase + "solver: {smagorinsky_constant: 1}\n", 5,
                        "solver.smagorinsky_constant", "a number >= 0 and < 1 expected, got '1'");
  expect_scenario_error(dir, "smagorinsky_negative", kBase + "solver: {smagorinsky_constant: -0.1}\n", 5,
                        "solver.smagorinsky_constant", "a number >= 0 and < 1 expected, got '-0.1'");
  expect_scenario_error(dir, "subgrid_word", kBase + "solver: {subgrid: deardorff}\n", 5, "solver.subgrid",
                        "one of smagorinsky | tke expected, got 'deardorff'");
  // Strict: the tke model takes no Smagorinsky constant, whichever key comes first in the map.
  expect_scenario_error(
      dir, "subgrid_constant", kBase + "solver:\n  smagorinsky_constant: 0.17\n  subgrid: tke\n", 6,
      "solver.smagorinsky_constant",
      "nothing unless solver.subgrid is smagorinsky (it is 'tke': its eddy viscosity comes from the "
      "subgrid energy) expected, got '0.17'");
  expect_scenario_error(dir, "probe_zero", kBase + "output: {probe_interval: 0}\n", 5,
                        "output.probe_interval", "a number > 0 and <= 1e9 (s) or auto expected, got '0'");
  expect_scenario_error(dir, "probe_negative", kBase + "output: {probe_interval: -0.5}\n", 5,
                        "output.probe_interval", "a number > 0 and <= 1e9 (s) or auto expected, got '-0.5'");
  expect_scenario_error(dir, "probe_word", kBase + "output: {probe_interval: often}\n", 5,
                        "output.probe_interval", "got 'often'");
  expect_scenario_error(dir, "correction", kBase + "forest: {strong_wind_correction: yes}\n", 5,
                        "forest.strong_wind_correction", "true or false expected, got 'yes'");
}

TEST_CASE("load_scenario: each output's every-N is a whole number >= 1, else FILE:LINE: KEY", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string path =
      dir.write("every.yaml", kBase +
                                  "output:\n  vtk: {wind_every: 2, trees_every: 3}\n  vdb: {every: 4}\n"
                                  "  leaves: {every: 5}\n");
  const fw::io::OutputSettings output = fw::io::load_scenario(path).output;
  CHECK(output.vtk_wind_every == 2);
  CHECK(output.vtk_trees_every == 3);
  CHECK(output.vdb_every == 4);
  CHECK(output.leaves_every == 5);
  const fw::io::OutputSettings defaults = fw::io::load_scenario(dir.write("plain.yaml", kBase)).output;
  CHECK(defaults.vtk_wind_every == 1);
  CHECK(defaults.vtk_trees_every == 1);
  CHECK(defaults.vdb_every == 1);
  CHECK(defaults.leaves_every == 1);

  expect_scenario_error(dir, "trees_zero", kBase + "output:\n  vtk: {trees_every: 0}\n", 6,
                        "output.vtk.trees_every", "an integer 1..1000000000 expected, got '0'");
  expect_scenario_error(dir, "wind_fraction", kBase + "output:\n  vtk: {wind_every: 1.5}\n", 6,
                        "output.vtk.wind_every", "got '1.5'");
  expect_scenario_error(dir, "vdb_word", kBase + "output:\n  vdb: {every: often}\n", 6, "output.vdb.every",
                        "got 'often'");
  expect_scenario_error(dir, "leaves_negative", kBase + "output:\n  leaves: {every: -2}\n", 6,
                        "output.leaves.every", "got '-2'");
}

namespace {

// A species with foliage on lines 7-9 and its `leaves` on line 10 (leaves_line), on the first lines of kBase.
std::string leafy_species(const std::string& leaves_line,
                          const std::string& canopy_line = "      canopy: {leaf_area_index: 3.0}\n") {
  return kBase +
         "forest:\n"                                            // 5
         "  species:\n"                                         // 6
         "    - name: oak\n"                                    // 7
         "      skeleton: {generate: {preset: broadleaf}}\n" +  // 8
         canopy_line +                                          // 9
         leaves_line;                                           // 10
}

}  // namespace

TEST_CASE("load_scenario: species leaves are read, and leaves: {} gets LeafSettings' defaults",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("leaves.yaml", R"(scenario: leaves
seed: 7
time: {end: 10.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
wind: {speed: 4.0, direction: 270}
forest:
  species:
    - name: oak
      skeleton: {generate: {preset: broadleaf}}
      canopy: {leaf_area_index: 3.0}
      leaves:
        model: stochastic
        area: 0.0025
        fraction: 0.5
        mass_per_area: 0.08
        frequency: 4.5
        damping_ratio: 0.1
        petiole_strength: 0.7
        strength_spread: 0.3
        flight_drag_coefficient: 1.4
        amplitudes: [10, 25, 90]
        roll_coupling: -0.25
        reference_speed: 8
        seed: 123
    - name: birch
      skeleton: {generate: {preset: weeping}}
      canopy: {leaf_area_index: 2.0}
      leaves: {}
    - name: pine
      skeleton: {generate: {preset: conifer}}
      leaves: {model: none}
    - name: palm
      skeleton: {generate: {preset: palm}}
)"));
  REQUIRE(s.forest.species.size() == 4);
  const fw::trees::LeafSettings& oak = s.forest.species[0].leaves;
  CHECK(oak.model == fw::trees::FlutterModel::stochastic);
  CHECK(oak.area == 0.0025);
  CHECK(oak.fraction == 0.5);
  CHECK(oak.mass_per_area == 0.08);
  CHECK(oak.frequency == 4.5);
  CHECK(oak.damping_ratio == 0.1);
  CHECK(oak.petiole_strength == 0.7);
  CHECK(oak.strength_spread == 0.3);
  CHECK(oak.flight_drag_coefficient == 1.4);
  CHECK(oak.amplitudes_deg == std::array<double, 3>{10, 25, 90});
  CHECK(oak.roll_coupling == -0.25);
  CHECK(oak.reference_speed == 8.0);
  CHECK(oak.seed == 123);

  // leaves: {} is every default of trees::LeafSettings, the seed from the global seed and the species index.
  const fw::trees::LeafSettings defaults;
  const fw::trees::LeafSettings& birch = s.forest.species[1].leaves;
  CHECK(birch.model == fw::trees::FlutterModel::pseudo_branch);
  CHECK(birch.model == defaults.model);
  CHECK(birch.area == defaults.area);
  CHECK(birch.fraction == defaults.fraction);
  CHECK(birch.mass_per_area == defaults.mass_per_area);
  CHECK(birch.frequency == defaults.frequency);
  CHECK(birch.damping_ratio == defaults.damping_ratio);
  CHECK(birch.petiole_strength == defaults.petiole_strength);
  CHECK(birch.strength_spread == defaults.strength_spread);
  CHECK(birch.flight_drag_coefficient == defaults.flight_drag_coefficient);
  CHECK(birch.amplitudes_deg == defaults.amplitudes_deg);
  CHECK(birch.roll_coupling == defaults.roll_coupling);
  CHECK(birch.reference_speed == defaults.reference_speed);
  CHECK(birch.seed == 7 + fw::io::kLeafSeedOffset + 1);
  CHECK(birch.seed == 7 + (std::uint64_t(1) << 32) + 1);  // as docs/scenario.md says: seed + 2^32 + k

  // model none needs no foliage; no `leaves` at all is model none too.
  CHECK_FALSE(s.forest.species[2].leaves.has_leaves());
  CHECK_FALSE(s.forest.species[3].leaves.has_leaves());
  CHECK(s.forest.species[3].leaves.seed == 7 + fw::io::kLeafSeedOffset + 3);
}

TEST_CASE("load_scenario: bad leaf keys name the key and say what is expected", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string key = "forest.species[0].leaves.";
  expect_scenario_error(dir, "leaf_area_type", leafy_species("      leaves: {area: big}\n"), 10, key + "area",
                        "a number > 0 and <= 100 (m^2) expected, got 'big'");
  expect_scenario_error(dir, "leaf_area_zero", leafy_species("      leaves: {area: 0}\n"), 10, key + "area",
                        "a number > 0 and <= 100 (m^2) expected, got '0'");
  expect_scenario_error(dir, "leaf_fraction", leafy_species("      leaves: {fraction: 1.5}\n"), 10,
                        key + "fraction", "a number > 0 and <= 1 expected, got '1.5'");
  expect_scenario_error(dir, "leaf_fraction_zero", leafy_species("      leaves: {fraction: 0}\n"), 10,
                        key + "fraction", "a number > 0 and <= 1 expected, got '0'");
  expect_scenario_error(dir, "leaf_mass", leafy_species("      leaves: {mass_per_area: -0.1}\n"), 10,
                        key + "mass_per_area", "a number > 0 and <= 5 (kg/m^2) expected, got '-0.1'");
  expect_scenario_error(dir, "leaf_frequency", leafy_species("      leaves: {frequency: [3]}\n"), 10,
                        key + "frequency", "a number > 0 and <= 500 (Hz) expected, got '[3]'");
  expect_scenario_error(dir, "leaf_damping", leafy_species("      leaves: {damping_ratio: 1}\n"), 10,
                        key + "damping_ratio", "a number >= 0 and < 1 expected, got '1'");
  expect_scenario_error(dir, "leaf_strength", leafy_species("      leaves: {petiole_strength: 0}\n"), 10,
                        key + "petiole_strength", "a number > 0 and <= 10000 (N) expected, got '0'");
  expect_scenario_error(dir, "leaf_spread", leafy_species("      leaves: {strength_spread: -1}\n"), 10,
                        key + "strength_spread", "a number >= 0 and <= 10 expected, got '-1'");
  expect_scenario_error(dir, "leaf_drag", leafy_species("      leaves: {flight_drag_coefficient: 0}\n"), 10,
                        key + "flight_drag_coefficient", "a number > 0 and <= 10 expected, got '0'");
  expect_scenario_error(dir, "leaf_roll", leafy_species("      leaves: {roll_coupling: .inf}\n"), 10,
                        key + "roll_coupling", "a number >= -10 and <= 10 expected, got '.inf'");
  expect_scenario_error(dir, "leaf_reference_speed", leafy_species("      leaves: {reference_speed: 0}\n"),
                        10, key + "reference_speed", "a number > 0 and <= 150 (m/s) expected, got '0'");
  expect_scenario_error(dir, "leaf_seed", leafy_species("      leaves: {seed: -1}\n"), 10, key + "seed",
                        "an integer 0..18446744073709551615 expected, got '-1'");
  expect_scenario_error(dir, "leaf_model", leafy_species("      leaves: {model: flutter}\n"), 10,
                        key + "model", "one of none | pseudo_branch | stochastic expected, got 'flutter'");
  expect_scenario_error(
      dir, "leaf_amplitudes_pair", leafy_species("      leaves: {amplitudes: [20, 30]}\n"), 10,
      key + "amplitudes",
      "a list of 3 numbers [W_H, W_V, W_R], each >= 0 and <= 90 (degrees) expected, got '[20, 30]'");
  expect_scenario_error(
      dir, "leaf_amplitudes_four", leafy_species("      leaves: {amplitudes: [20, 30, 15, 5]}\n"), 10,
      key + "amplitudes", "a list of 3 numbers [W_H, W_V, W_R], each >= 0 and <= 90 (degrees) expected");
  expect_scenario_error(dir, "leaf_amplitude_high",
                        leafy_species("      leaves: {amplitudes: [20, 95, 15]}\n"), 10,
                        key + "amplitudes[1]", "a number >= 0 and <= 90 (degrees) expected, got '95'");
  expect_scenario_error(dir, "leaf_amplitude_negative",
                        leafy_species("      leaves: {amplitudes: [20, 30, -5]}\n"), 10,
                        key + "amplitudes[2]", "a number >= 0 and <= 90 (degrees) expected, got '-5'");
  expect_scenario_error(
      dir, "leaf_unknown_key", leafy_species("      leaves: {colour: green}\n"), 10, key + "colour",
      "one of the keys model, area, fraction, mass_per_area, frequency, damping_ratio, "
      "petiole_strength, strength_spread, flight_drag_coefficient, amplitudes, roll_coupling, "
      "reference_speed, seed expected, got 'colour'");
  expect_scenario_error(dir, "leaves_not_a_map", leafy_species("      leaves: true\n"), 10,
                        "forest.species[0].leaves", "a map with the keys model, area, fraction");

  // Leaves sit on the canopy's foliage: a leaf area index of 0 (given or the default) is blamed on the key.
  const std::string lai = "forest.species[0].canopy.leaf_area_index";
  expect_scenario_error(
      dir, "leaves_lai_zero", leafy_species("      leaves: {}\n", "      canopy: {leaf_area_index: 0}\n"), 9,
      lai,
      "a number > 0 (m^2/m^2) (leaves need a leaf area index > 0; forest.species[0].leaves is on line "
      "10) expected, got '0'");
  expect_scenario_error(
      dir, "leaves_lai_default",
      leafy_species("      leaves: {area: 0.01}\n", "      canopy: {drag_coefficient: 0.4}\n"), 9, lai,
      "a number > 0 (m^2/m^2) expected (required here: leaves need a leaf area index > 0; "
      "forest.species[0].leaves is on line 10, and the default is 0), got nothing");
  expect_scenario_error(
      dir, "leaves_no_canopy", leafy_species("      leaves: {}\n", ""), 7, lai,
      "(required here: leaves need a leaf area index > 0; forest.species[0].leaves is on line 9");
  // Without leaves (model none) a bare crown is fine.
  CHECK_NOTHROW(
      fw::io::load_scenario(dir.write("winter.yaml", leafy_species("      leaves: {model: none}\n", ""))));
}

namespace {

// A species oak on lines 7-8 and the lines `model_lines` from line 9 on, on the first lines of kBase.
std::string model_species(const std::string& model_lines) {
  return kBase +
         "forest:\n"                                            // 5
         "  species:\n"                                         // 6
         "    - name: oak\n"                                    // 7
         "      skeleton: {generate: {preset: broadleaf}}\n" +  // 8
         model_lines;                                           // 9 on
}

}  // namespace

TEST_CASE(
    "load_scenario: each species' dynamics and its model's keys are read over SpeciesDynamics' defaults",
    "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("models.yaml", R"(scenario: models
time: {end: 10.0}
domain: {size: [40, 20, 10], cell_size: 2.0}
wind: {speed: 4.0, direction: 270}
forest:
  species:
    - name: plain
      skeleton: {generate: {preset: broadleaf}}
      modes: {count: 8}
    - name: modal
      skeleton: {generate: {preset: broadleaf}}
      dynamics: modal
    - name: rigid
      skeleton: {generate: {preset: broadleaf}}
      dynamics: rigid_bodies
      rigid_bodies: {damping_ratio: 0.12}
    - name: springs
      skeleton: {generate: {preset: broadleaf}}
      dynamics: springs
      springs:
        max_angle_deg: 15
        sway_amplitude: 0.35
        sway_frequency: 0.8
    - name: rigid_default
      skeleton: {generate: {preset: broadleaf}}
      dynamics: rigid_bodies
    - name: springs_default
      skeleton: {generate: {preset: broadleaf}}
      dynamics: springs
      springs: {}
)"));
  using fw::trees::TreeDynamics;
  REQUIRE(s.forest.species.size() == 6);
  const fw::trees::SpeciesDynamics defaults;
  CHECK(s.forest.species[0].dynamics.model == TreeDynamics::modal);  // no `dynamics`: modal
  CHECK(s.forest.species[0].modes.count == 8);
  CHECK(s.forest.species[1].dynamics.model == TreeDynamics::modal);

  const fw::trees::SpeciesDynamics& rigid = s.forest.species[2].dynamics;
  CHECK(rigid.model == TreeDynamics::rigid_bodies);
  CHECK(rigid.rigid_bodies.damping_ratio == 0.12);

  const fw::trees::SpeciesDynamics& springs = s.forest.species[3].dynamics;
  CHECK(springs.model == TreeDynamics::springs);
  CHECK(springs.springs.max_angle_deg == 15.0);
  CHECK(springs.springs.sway_amplitude == 0.35);
  CHECK(springs.springs.sway_frequency_hz == 0.8);

  // Without its map, or with an empty one, a model takes every default of trees::SpeciesDynamics, and the
  // modes of every species not modal are the default ones.
  const fw::trees::SpeciesDynamics& rigid_default = s.forest.species[4].dynamics;
  CHECK(rigid_default.model == TreeDynamics::rigid_bodies);
  CHECK(rigid_default.rigid_bodies.damping_ratio == defaults.rigid_bodies.damping_ratio);
  const fw::trees::SpeciesDynamics& springs_default = s.forest.species[5].dynamics;
  CHECK(springs_default.model == TreeDynamics::springs);
  CHECK(springs_default.springs.max_angle_deg == defaults.springs.max_angle_deg);
  CHECK(springs_default.springs.sway_amplitude == defaults.springs.sway_amplitude);
  CHECK(springs_default.springs.sway_frequency_hz == defaults.springs.sway_frequency_hz);
  const fw::io::ModeSettings modes;
  for (std::size_t k = 2; k < s.forest.species.size(); ++k) {
    INFO("species " << k);
    CHECK(s.forest.species[k].modes.count == modes.count);
    CHECK(s.forest.species[k].modes.damping_ratio == modes.damping_ratio);
    CHECK(s.forest.species[k].modes.wind_samples == modes.wind_samples);
  }
  // The defaults the docs print are these (io/ScenarioSchema_test.cpp holds the schema to them).
  CHECK(defaults.model == TreeDynamics::modal);
  CHECK(defaults.rigid_bodies.damping_ratio == 0.05);
  CHECK(defaults.springs.max_angle_deg == 20.0);
  CHECK(defaults.springs.sway_amplitude == 0.2);
  CHECK(defaults.springs.sway_frequency_hz == 0.5);
}

TEST_CASE("load_scenario: a bad dynamics word, a bad model value and a key of another model name the key",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string species = "forest.species[0].";
  expect_scenario_error(dir, "dynamics_word", model_species("      dynamics: pendulum\n"), 9,
                        species + "dynamics",
                        "one of modal | rigid_bodies | springs expected, got 'pendulum'");
  expect_scenario_error(dir, "dynamics_list", model_species("      dynamics: [modal]\n"), 9,
                        species + "dynamics",
                        "one of modal | rigid_bodies | springs expected, got '[modal]'");

  // A key of one model on a species that another moves: the key's line, its model and the species' dynamics.
  expect_scenario_error(
      dir, "springs_on_default", model_species("      springs: {max_angle_deg: 10}\n"), 9,
      species + "springs",
      "a key of the springs model, but this species' dynamics is modal (the default); leave springs "
      "out or set dynamics: springs");
  expect_scenario_error(
      dir, "springs_on_rigid",
      model_species("      dynamics: rigid_bodies\n      springs: {max_angle_deg: 10}\n"), 10,
      species + "springs",
      "a key of the springs model, but this species' dynamics is rigid_bodies (on line 9); leave "
      "springs out or set dynamics: springs");
  expect_scenario_error(
      dir, "rigid_on_modal",
      model_species("      rigid_bodies: {damping_ratio: 0.1}\n      dynamics: modal\n"), 9,
      species + "rigid_bodies",
      "a key of the rigid_bodies model, but this species' dynamics is modal (on line 10); leave "
      "rigid_bodies out or set dynamics: rigid_bodies");
  expect_scenario_error(
      dir, "rigid_on_springs", model_species("      dynamics: springs\n      rigid_bodies: {}\n"), 10,
      species + "rigid_bodies",
      "a key of the rigid_bodies model, but this species' dynamics is springs (on line 9); leave "
      "rigid_bodies out or set dynamics: rigid_bodies");
  expect_scenario_error(
      dir, "modes_on_rigid", model_species("      dynamics: rigid_bodies\n      modes: {count: 8}\n"), 10,
      species + "modes",
      "a key of the modal model, but this species' dynamics is rigid_bodies (on line 9); leave modes "
      "out or set dynamics: modal");
  expect_scenario_error(
      dir, "modes_on_springs", model_species("      modes: {count: 8}\n      dynamics: springs\n"), 9,
      species + "modes",
      "a key of the modal model, but this species' dynamics is springs (on line 10); leave modes out "
      "or set dynamics: modal");
  // The second species is blamed by its index.
  expect_scenario_error(
      dir, "second_species",
      model_species("    - name: elm\n"                                  // 9
                    "      skeleton: {generate: {preset: broadleaf}}\n"  // 10
                    "      dynamics: rigid_bodies\n"                     // 11
                    "      springs: {sway_amplitude: 0.1}\n"),           // 12
      12, "forest.species[1].springs",
      "a key of the springs model, but this species' dynamics is rigid_bodies (on line 11)");

  // The model's own keys, out of range or unknown.
  const std::string springs = species + "springs.";
  const auto spring = [&](const std::string& map) {
    return model_species("      dynamics: springs\n" + map);
  };
  expect_scenario_error(dir, "angle_right", spring("      springs: {max_angle_deg: 90}\n"), 10,
                        springs + "max_angle_deg", "a number > 0 and < 90 (degrees) expected, got '90'");
  expect_scenario_error(dir, "angle_zero", spring("      springs: {max_angle_deg: 0}\n"), 10,
                        springs + "max_angle_deg", "a number > 0 and < 90 (degrees) expected, got '0'");
  expect_scenario_error(dir, "sway_amplitude", spring("      springs: {sway_amplitude: -0.1}\n"), 10,
                        springs + "sway_amplitude", "a number >= 0 and <= 10 expected, got '-0.1'");
  expect_scenario_error(dir, "sway_frequency", spring("      springs: {sway_frequency: 0}\n"), 10,
                        springs + "sway_frequency", "a number > 0 and <= 500 (Hz) expected, got '0'");
  expect_scenario_error(
      dir, "springs_unknown", spring("      springs: {stiffness: 3}\n"), 10, springs + "stiffness",
      "one of the keys max_angle_deg, sway_amplitude, sway_frequency expected, got 'stiffness'");
  expect_scenario_error(
      dir, "rigid_damping",
      model_species("      dynamics: rigid_bodies\n      rigid_bodies: {damping_ratio: -0.05}\n"), 10,
      species + "rigid_bodies.damping_ratio", "a number >= 0 and <= 10 expected, got '-0.05'");
  expect_scenario_error(dir, "rigid_not_a_map",
                        model_species("      dynamics: rigid_bodies\n      rigid_bodies: 0.1\n"), 10,
                        species + "rigid_bodies", "a map with the keys damping_ratio expected, got '0.1'");
}

TEST_CASE("load_scenario: output.leaves takes all, none or a stride, and vtk", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const auto stride = [&](const std::string& name, const std::string& attached) {
    return fw::io::load_scenario(
               dir.write(name + ".yaml", kBase + "output: {leaves: {attached: " + attached + "}}\n"))
        .output.leaves_attached_stride;
  };
  CHECK(stride("all", "all") == 1);
  CHECK(stride("none", "none") == 0);
  CHECK(stride("every_one", "1") == 1);
  CHECK(stride("every_tenth", "10") == 10);
  const Scenario off = fw::io::load_scenario(
      dir.write("off.yaml", kBase + "output: {leaves: {vtk: false}, vdb: {grids: [leaves]}}\n"));
  CHECK_FALSE(off.output.vtk_leaves);
  CHECK(off.output.leaves_attached_stride == 1);  // the default, all
  CHECK(off.output.vdb_grids == std::vector<std::string>{"leaves"});

  const std::string what = "one of all | none or an integer 1..2147483647 expected";
  expect_scenario_error(dir, "attached_zero", kBase + "output: {leaves: {attached: 0}}\n", 5,
                        "output.leaves.attached", what + ", got '0'");
  expect_scenario_error(dir, "attached_negative", kBase + "output: {leaves: {attached: -3}}\n", 5,
                        "output.leaves.attached", what + ", got '-3'");
  expect_scenario_error(dir, "attached_fraction", kBase + "output: {leaves: {attached: 2.5}}\n", 5,
                        "output.leaves.attached", what + ", got '2.5'");
  expect_scenario_error(dir, "attached_word", kBase + "output: {leaves: {attached: some}}\n", 5,
                        "output.leaves.attached", what + ", got 'some'");
  expect_scenario_error(dir, "attached_list", kBase + "output: {leaves: {attached: [1]}}\n", 5,
                        "output.leaves.attached", what + ", got '[1]'");
  expect_scenario_error(dir, "leaves_vtk", kBase + "output: {leaves: {vtk: yes}}\n", 5, "output.leaves.vtk",
                        "true or false expected, got 'yes'");
  expect_scenario_error(dir, "leaves_unknown", kBase + "output: {leaves: {flying: all}}\n", 5,
                        "output.leaves.flying",
                        "one of the keys attached, vtk, every expected, got 'flying'");
  expect_scenario_error(dir, "vdb_grid", kBase + "output: {vdb: {grids: [vel, leaf]}}\n", 5,
                        "output.vdb.grids[1]", "one of vel | speed | leaves expected, got 'leaf'");
}

TEST_CASE("load_scenario: domain.decomposition takes whole blocks along x and y, with its line",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("blocks.yaml", R"(scenario: blocks
time: {end: 10.0}
domain:
  size: [40, 20, 10]
  cell_size: 2.0
  decomposition: [2, 1]
wind: {speed: 4.0, direction: 270}
)"));
  REQUIRE(s.domain.decomposition.has_value());
  CHECK(*s.domain.decomposition == std::array<int, 2>{2, 1});
  CHECK(s.domain.decomposition_line == 6);
  expect_scenario_error(
      dir, "blocks_fraction",
      "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0, decomposition: "
      "[2.5, 1]}\nwind: {speed: 4.0, direction: 270}\n",
      3, "domain.decomposition[0]", "a whole number of blocks along x expected, got '2.5'");
  expect_scenario_error(
      dir, "blocks_zero",
      "scenario: errors\ntime: {end: 10.0}\ndomain: {size: [40, 20, 10], cell_size: 2.0, decomposition: "
      "[0, 1]}\nwind: {speed: 4.0, direction: 270}\n",
      3, "domain.decomposition[0]", "a number >= 1 and <= 2147483647 expected, got '0'");
}

namespace {

// kBase and two species: `oak`, whose strength is `oak_strength`, and `ash`, whose strength is
// `ash_strength`; `damage_line` (forest.damage, say) stands first in forest, on line 6, and moves the rest
// one line down.
std::string strong_species(const std::string& oak_strength, const std::string& damage_line = "",
                           const std::string& ash_strength = "      strength: {preset: birch}\n") {
  return kBase + "forest:\n" +                                  // 5
         damage_line +                                          // (6)
         "  species:\n"                                         // 6
         "    - name: oak\n"                                    // 7
         "      skeleton: {generate: {preset: broadleaf}}\n" +  // 8
         oak_strength +                                         // 9
         "    - name: ash\n"                                    // 10 (with oak's strength on one line)
         "      skeleton: {generate: {preset: broadleaf}}\n" +  // 11
         ash_strength;                                          // 12
}

}  // namespace

TEST_CASE("load_scenario: a species' strength is its preset's on its soil and rooting, numbers given over it",
          "[scenario]") {
  using fw::trees::RootingDepth, fw::trees::SoilGroup, fw::trees::StrengthPreset;
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("strength.yaml", kBase + R"(forest:
  damage: {enabled: true, consequences: false}
  species:
    - name: spruce
      skeleton: {generate: {preset: conifer}}
      strength: {preset: norway_spruce, knot_factor: 0.7}
    - name: gleyed
      skeleton: {generate: {preset: conifer}}
      strength:
        preset: norway_spruce
        soil: B
    - name: deep
      skeleton: {generate: {preset: conifer}}
      strength: {preset: sitka_spruce, rooting: deep}
    - name: measured
      skeleton: {generate: {preset: broadleaf}}
      strength: {modulus_of_rupture: 4.0e7, knot_factor: 0.95, green_density: 900, anchorage: 140}
)"));
  CHECK(s.forest.damage.enabled);
  CHECK_FALSE(s.forest.damage.consequences);
  CHECK(s.forest.damage.line == 6);
  REQUIRE(s.forest.species.size() == 4);

  // The explicit knot factor replaces norway_spruce's 0.9; the other three are the preset's (soil A, mean).
  const fw::io::Species& spruce = s.forest.species[0];
  const fw::trees::TreeStrength norway = fw::trees::strength_preset(StrengthPreset::norway_spruce);
  REQUIRE(spruce.strength.has_value());
  CHECK(norway.knot_factor == 0.9);
  CHECK(spruce.strength->knot_factor == 0.7);
  CHECK(spruce.strength->modulus_of_rupture == norway.modulus_of_rupture);
  CHECK(spruce.strength->green_density == norway.green_density);
  CHECK(spruce.strength->anchorage == norway.anchorage);
  CHECK(spruce.strength_line == 10);
  CHECK(spruce.strength_source == "knot_factor given over norway_spruce (soil A, mean rooting)");

  // Soil B: the table's anchorage on gleyed mineral soil, weaker than on soil A; the wood is the preset's.
  const fw::io::Species& gleyed = s.forest.species[1];
  REQUIRE(gleyed.strength.has_value());
  CHECK(
      gleyed.strength->anchorage ==
      fw::trees::strength_preset(StrengthPreset::norway_spruce, SoilGroup::B, RootingDepth::mean).anchorage);
  CHECK(gleyed.strength->anchorage < norway.anchorage);
  CHECK(gleyed.strength->modulus_of_rupture == norway.modulus_of_rupture);
  CHECK(gleyed.strength_line == 14);  // a block map: its first key's line, as the loader blames maps
  CHECK(gleyed.strength_source == "norway_spruce (soil B, mean rooting)");

  const fw::io::Species& deep = s.forest.species[2];
  REQUIRE(deep.strength.has_value());
  CHECK(deep.strength->anchorage ==
        fw::trees::strength_preset(StrengthPreset::sitka_spruce, SoilGroup::A, RootingDepth::deep).anchorage);
  CHECK(deep.strength_source == "sitka_spruce (soil A, deep rooting)");

  // Without a preset, the four numbers as given.
  const fw::io::Species& measured = s.forest.species[3];
  REQUIRE(measured.strength.has_value());
  CHECK(measured.strength->modulus_of_rupture == 4.0e7);
  CHECK(measured.strength->knot_factor == 0.95);
  CHECK(measured.strength->green_density == 900.0);
  CHECK(measured.strength->anchorage == 140.0);
  CHECK(measured.strength_source == "given");
}

TEST_CASE("load_scenario: without strength and damage, no strength, damage off and its consequences on",
          "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const Scenario s = fw::io::load_scenario(dir.write("no_damage.yaml", strong_species("", "", "")));
  REQUIRE(s.forest.species.size() == 2);
  for (const fw::io::Species& species : s.forest.species) {
    CHECK_FALSE(species.strength.has_value());
    CHECK(species.strength_source.empty());
    CHECK(species.strength_line == species.line);
  }
  CHECK_FALSE(s.forest.damage.enabled);
  CHECK(s.forest.damage.consequences);
  CHECK(s.forest.damage.line == 0);
  CHECK_FALSE(fw::io::DamageSettings{}.enabled);
  CHECK(fw::io::DamageSettings{}.consequences);
  // Damage off: a species may go without strength beside one with it; damage: {} is damage off.
  const Scenario mixed =
      fw::io::load_scenario(dir.write("mixed.yaml", strong_species("", "  damage: {consequences: false}\n")));
  CHECK_FALSE(mixed.forest.damage.enabled);
  CHECK_FALSE(mixed.forest.species[0].strength.has_value());
  CHECK(mixed.forest.species[1].strength.has_value());
}

TEST_CASE("load_scenario: bad strength and damage keys name the key and say what is expected", "[scenario]") {
  fw::test::TempDir dir("fw_scenario");
  const std::string key = "forest.species[0].strength.";
  expect_scenario_error(dir, "strength_preset", strong_species("      strength: {preset: oak}\n"), 9,
                        key + "preset",
                        "one of sitka_spruce | norway_spruce | scots_pine | birch expected, got 'oak'");
  expect_scenario_error(dir, "strength_soil_word",
                        strong_species("      strength: {preset: birch, soil: E}\n"), 9, key + "soil",
                        "one of A | B | C | D expected, got 'E'");
  expect_scenario_error(dir, "strength_knot_factor",
                        strong_species("      strength: {preset: scots_pine, knot_factor: 1.5}\n"), 9,
                        key + "knot_factor", "a number > 0 and <= 1 expected, got '1.5'");
  expect_scenario_error(dir, "strength_mor_bound",
                        strong_species("      strength: {preset: scots_pine, modulus_of_rupture: 1e30}\n"), 9,
                        key + "modulus_of_rupture", "a number >= 1e6 and <= 3e8 (Pa) expected, got '1e30'");
  expect_scenario_error(dir, "strength_density_bound",
                        strong_species("      strength: {preset: scots_pine, green_density: 50}\n"), 9,
                        key + "green_density", "a number >= 100 and <= 2000 (kg/m^3) expected, got '50'");
  expect_scenario_error(dir, "strength_anchorage_bound",
                        strong_species("      strength: {preset: scots_pine, anchorage: 5000}\n"), 9,
                        key + "anchorage", "a number >= 10 and <= 1000 (N m/kg) expected, got '5000'");
  // Shallow and deep rooting: soil A only.
  expect_scenario_error(
      dir, "strength_deep_on_c",
      strong_species("      strength:\n        preset: sitka_spruce\n        soil: C\n"
                     "        rooting: deep\n"),
      12, key + "rooting",
      "one of mean (the table has no anchorage for deep rooting on soil C, line 11) expected, got 'deep'");
  // Soil and rooting choose a preset's anchorage only.
  expect_scenario_error(dir, "strength_soil_without_preset",
                        strong_species("      strength: {soil: B, modulus_of_rupture: 4e7, knot_factor: 1, "
                                       "green_density: 850, anchorage: 140}\n"),
                        9, key + "soil",
                        "soil only beside a preset (soil and rooting choose a preset's anchorage)");
  expect_scenario_error(dir, "strength_rooting_beside_anchorage",
                        strong_species("      strength: {preset: birch, rooting: deep, anchorage: 140}\n"), 9,
                        key + "rooting", "rooting only without anchorage (anchorage on line 9 replaces");
  // Without a preset, the first number missing, in the table's order, at the map's line.
  expect_scenario_error(
      dir, "strength_no_anchorage",
      strong_species("      strength: {modulus_of_rupture: 4e7, knot_factor: 1, green_density: 850}\n"), 9,
      key + "anchorage",
      "a number >= 10 and <= 1000 (N m/kg), needed without a preset expected (required), got nothing");
  expect_scenario_error(dir, "strength_empty", strong_species("      strength: {}\n"), 9,
                        key + "modulus_of_rupture",
                        "needed without a preset expected (required), got nothing");
  // Damage needs every species' strength: the one without is named at its entry's line.
  expect_scenario_error(
      dir, "damage_without_strength",
      strong_species("      strength: {preset: birch}\n", "  damage: {enabled: true}\n", ""), 11,
      "forest.species[1].strength",
      "a map {preset, soil, rooting, modulus_of_rupture, knot_factor, green_density, anchorage} "
      "expected (required: forest.damage.enabled is true on line 6), got nothing");
  expect_scenario_error(dir, "damage_enabled_word", strong_species("", "  damage: {enabled: yes}\n"), 6,
                        "forest.damage.enabled", "true or false expected, got 'yes'");
  expect_scenario_error(dir, "damage_unknown_key", strong_species("", "  damage: {enable: true}\n"), 6,
                        "forest.damage.enable", "one of the keys enabled, consequences expected");
}
