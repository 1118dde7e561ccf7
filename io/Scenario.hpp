// A scenario file (docs/design.md, "File formats"), read and validated in full before anything is computed.
// Every key's type, unit, default and allowed values are defined once, in the schema (io/schema/, one table
// per section; io/ScenarioSchema.hpp over all of them): the defaults below are read from the tables, and
// docs/scenario.md's key tables are generated from the schema.
//
//   fw::io::Scenario scenario = fw::io::load_scenario("scenarios/storm.yaml");   // throws ScenarioError
//   scenario.domain.cells;                       // {160, 80, 24}: 480 x 240 x 72 m in cells of 3 m
//   scenario.wind_vector(60.0);                  // m/s at the reference height, x east, y north
//   fw::fluid::GridSpec grid = scenario.grid_spec(0.0);   // "auto" faces resolved for the wind at t = 0
//   for (const auto& obstacle : scenario.obstacles)
//     std::visit([&](const auto& shape) { solids.add(shape); }, obstacle);
//
// Conventions: SI units (m, s, kg, m/s, Pa); axes x east, y north, z up; the domain's minimum corner is
// domain.origin. Wind directions are meteorological (degrees the wind blows FROM, clockwise from north).
// Yaws of trees and boxes turn counter-clockwise about +z seen from above; the file gives them in degrees,
// and the loader converts them once: every struct here holds radians (yaw_rad, as fluid::SolidBox,
// trees::PlacedTree and trees::TreeInstance do). Relative
// paths in the file (skeletons, heightmap) resolve against the scenario file's folder; the output directory
// resolves against the current working directory at load time.
//
// Validation is strict: unknown keys at any level, duplicate keys, wrong types, missing required keys,
// out-of-range numbers, unknown enum words, positions outside the domain, missing or unreadable files and
// bad expressions are all errors. Every error is a ScenarioError whose what() reads exactly
//   FILE:LINE: KEY: what was expected[, got 'VALUE']
// with LINE 1-based (0 when the file itself cannot be read) and KEY the dotted path of the offending key,
// e.g. "forest.species[0].modes.count".
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/Heightmap.hpp"
#include "fluid/InflowProfile.hpp"
#include "fluid/SolidMap.hpp"
#include "fluid/WindSettings.hpp"
#include "io/Expression.hpp"
#include "io/ScenarioSchema.hpp"
#include "io/schema/BoundaryKeys.hpp"
#include "io/schema/DomainKeys.hpp"
#include "io/schema/EventKeys.hpp"
#include "io/schema/ForestKeys.hpp"
#include "io/schema/ObstacleKeys.hpp"
#include "io/schema/OutputKeys.hpp"
#include "io/schema/SolverKeys.hpp"
#include "io/schema/SpeciesKeys.hpp"
#include "io/schema/TerrainKeys.hpp"
#include "io/schema/TimeKeys.hpp"
#include "io/schema/TopLevelKeys.hpp"
#include "io/schema/WindKeys.hpp"
#include "trees/ForestLayout.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/Material.hpp"
#include "trees/ModalIntegrator.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/TreeGenerator.hpp"

namespace fw::io {

/// An angle the file gives in degrees (yaws), in the radians of every struct past the loader.
constexpr double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

/// A scenario that cannot be used: what() is "FILE:LINE: KEY: what was expected[, got 'VALUE']".
class ScenarioError : public std::invalid_argument {
 public:
  /// message is the part after "KEY: ".
  ScenarioError(std::string file, int line, std::string key, const std::string& message);

  const std::string& file() const { return file_; }
  /// 1-based line of the offending node; 0 when the file could not be read at all.
  int line() const { return line_; }
  /// Dotted path such as "wind.speed" or "forest.species[0].modes.count"; "(file)" when the file could
  /// not be read, "(yaml)" for a YAML syntax error.
  const std::string& key() const { return key_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string key_;
};

/// A face's boundary condition as written in the file. automatic ("auto", the four sides only): inflow where
/// the ambient wind enters the domain, outflow where it leaves; see Scenario::grid_spec. rough (the ground
/// only): a slip wall whose lowest fluid cells feel the log-law wall stress of
/// Scenario::ground_roughness_length.
enum class BoundaryChoice { automatic, inflow, outflow, slip, no_slip, periodic, rough };
std::string to_string(BoundaryChoice choice);  // the word used in the file

/// In the order of schema::kBoundaryWords.
inline constexpr BoundaryChoice kBoundaryChoices[] = {
    BoundaryChoice::automatic, BoundaryChoice::inflow,   BoundaryChoice::outflow, BoundaryChoice::slip,
    BoundaryChoice::no_slip,   BoundaryChoice::periodic, BoundaryChoice::rough};

/// The schema's default per face, indexed by FW_FACE_* (west, east, south, north, ground, top).
constexpr std::array<BoundaryChoice, 6> default_boundaries() {
  const auto choice = [](std::string_view word) {
    return schema::value_of(schema::kBoundaryWords, kBoundaryChoices, word);
  };
  return {choice(schema::key(schema::kBoundaryKeys, "boundaries.west").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.east").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.south").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.north").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.ground").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.top").word)};
}

struct TimeSettings {
  double end = 0.0;          ///< s, > 0: the run covers [0, end]
  std::optional<double> dt;  ///< s, > 0: fixed step; nullopt for "auto"
  double cfl =
      schema::key(schema::kTimeKeys, "time.cfl").number;  ///< > 0, used with auto: dt = cfl * h / max|u|
  /// s, >= 0: the wind steps from -spin_up to 0 before the run (trees held in equilibrium); 0: none
  double spin_up = schema::key(schema::kTimeKeys, "time.spin_up").number;
};

struct DomainSettings {
  /// minimum corner, m
  std::array<double, 3> origin{schema::key(schema::kDomainKeys, "domain.origin").number,
                               schema::key(schema::kDomainKeys, "domain.origin").number,
                               schema::key(schema::kDomainKeys, "domain.origin").number};
  std::array<double, 3> size{0, 0, 0};  ///< extent along x, y, z, m (> 0)
  double cell_size = 0.0;               ///< h, m (> 0); cells are cubic
  std::array<int, 3> cells{0, 0, 0};    ///< round(size / h); size is a whole multiple of h
  /// Blocks along x and y over MPI ranks (fluid/Decomposition), as given; else chosen from the ranks.
  std::optional<std::array<int, 2>> decomposition;
  int decomposition_line = 0;  ///< the line of decomposition in the file (of domain when not given)

  /// origin + size, m.
  std::array<double, 3> max_corner() const {
    return {origin[0] + size[0], origin[1] + size[1], origin[2] + size[2]};
  }
};

/// The spectral model of wind.turbulence.
enum class TurbulenceModel { von_karman };

/// In the order of schema::kTurbulenceModelWords.
inline constexpr TurbulenceModel kTurbulenceModels[] = {TurbulenceModel::von_karman};

/// wind.turbulence: a periodic box of synthetic turbulence, swept through the inflow faces at the ambient
/// wind (Taylor) and added to the initial field; plus, optionally, Stam's unresolved modal forcing per tree.
struct TurbulenceSettings {
  TurbulenceModel model = schema::value_of(schema::kTurbulenceModelWords, kTurbulenceModels,
                                           schema::key(schema::kWindKeys, "wind.turbulence.model").word);
  /// sigma_u / wind.speed at reference_height, dimensionless, >= 0; sigma_v = sigma_w = sigma_u. Exactly one
  /// of intensity and sigma is set.
  std::optional<double> intensity;
  /// [sigma_u, sigma_v, sigma_w], m/s, each > 0, fixed over time (along-wind, across-wind, vertical).
  std::optional<std::array<double, 3>> sigma;
  double length_scale = 0.0;  ///< L_u, the longitudinal integral length scale, m, > 0
  /// The box's cells along x, y, z, each even and >= schema::kMinTurbulenceBoxCells, resolved at load (from
  /// box_size, else computed). The fluid::TurbulenceBox a run builds has fluid::kTurbulencePointsPerCell
  /// points per cell along each axis (h / 2 apart), at most TurbulenceBoxSpec::kMaxPoints in all.
  std::array<int, 3> box_cells{0, 0, 0};
  /// box_cells * domain.cell_size, m: the box's period along x, y, z (a given box_size, rounded).
  std::array<double, 3> box_size{0, 0, 0};
  bool box_size_given = false;  ///< whether the file gave box_size
  std::uint64_t seed = 0;       ///< the file's, else the scenario's top-level seed
  bool unresolved =
      schema::key(schema::kWindKeys, "wind.turbulence.unresolved").flag;  ///< Stam's modal forcing per tree
  /// The smallest resolved eddy in cells (> 0): wavenumbers above 2 pi / (cutoff_cells h) are unresolved.
  double cutoff_cells = schema::key(schema::kWindKeys, "wind.turbulence.cutoff_cells").number;

  /// [sigma_u, sigma_v, sigma_w], m/s, for the wind speed `speed` (m/s) at the reference height: intensity
  /// times speed on all three, or sigma as given.
  std::array<double, 3> standard_deviations(double speed) const;
};

/// wind.forcing: the mean body force of a domain whose four sides are all periodic (no inflow), a PI
/// controller that holds the horizontal mean wind at reference_height at the ambient wind.
struct ForcingSettings {
  double relaxation_time =
      schema::key(schema::kWindKeys, "wind.forcing.relaxation_time").number;  ///< tau, s, > 0
};

struct WindSource {
  Expression speed;      ///< m/s at reference_height, a function of t (s)
  Expression direction;  ///< degrees the wind blows FROM, clockwise from north, a function of t
  double reference_height =
      schema::key(schema::kWindKeys, "wind.reference_height").number;  ///< m above the domain floor
  /// Vertical shape; profile.reference_height == reference_height. Defaults: the schema's wind.profile.*
  /// (roughness_length has none).
  fluid::InflowProfile profile;
  /// Synthetic turbulence; nullopt (no wind.turbulence) for a laminar wind.
  std::optional<TurbulenceSettings> turbulence;
  /// Set exactly when west, east, south and north are all periodic (wind.forcing given or not); nullopt
  /// otherwise (the file may give wind.forcing only then).
  std::optional<ForcingSettings> forcing;
};

/// A gust: a Gaussian ball of extra wind with a 1-cos envelope over [start, start + duration].
struct GustEvent {
  double start = 0.0;              ///< s, >= 0
  double duration = 0.0;           ///< s, > 0
  double peak_speed = 0.0;         ///< m/s, >= 0, at the envelope's peak and the ball's centre
  std::array<double, 3> center{};  ///< m, at `start`
  double radius = 0.0;             ///< m, > 0
  bool travel_with_wind = true;    ///< `travel: with_wind` in the file
  std::array<double, 3> travel{};  ///< m/s; with_wind: wind_vector(start), resolved at load
};

/// Shapes the wind grid voxelises (fluid/SolidMap.hpp), with the same parameters.
using Obstacle = std::variant<fluid::SolidBox, fluid::SolidCylinder, fluid::SolidSphere>;

struct TerrainSettings {
  std::filesystem::path heightmap;  ///< resolved against the scenario folder
  double cell_size = 0.0;           ///< m between samples (PGM; ignored for ESRI grids, 0 when not given)
  double max_height = 0.0;          ///< m for the PGM's maxval (PGM; ignored for ESRI grids)
  /// The heightmap, read and checked at load (always set). A PGM's south-west corner is placed at the
  /// domain's (origin x, origin y); an ESRI grid keeps the placement of its header.
  std::optional<fluid::Heightmap> map;
};

/// Where a species' skeleton comes from: exactly one of the three.
struct SkeletonSource {
  enum class Kind { generate, file, qsm };
  Kind kind = Kind::generate;
  trees::GeneratorSettings generate;  ///< Kind::generate: preset, height (m, 0 = preset default), seed
  std::filesystem::path path;         ///< Kind::file (.tree) or Kind::qsm (TreeQSM text); resolved, exists
};

struct ModeSettings {
  int count = int(
      schema::key(schema::kSpeciesKeys, "forest.species[].modes.count").number);  ///< lowest modes kept, >= 1
  double damping_ratio = schema::key(schema::kSpeciesKeys, "forest.species[].modes.damping_ratio")
                             .number;  ///< zeta per mode, >= 0
  /// Height bands with their own projection, 1..FW_MAX_TREE_SAMPLES.
  int wind_samples = int(schema::key(schema::kSpeciesKeys, "forest.species[].modes.wind_samples").number);
  int count_line = 0;  ///< line of `count` in the file (of the species entry when not given)
};

struct CanopySettings {
  /// One-sided m^2 leaf per m^2 ground, >= 0 (0: no leaves).
  double leaf_area_index =
      schema::key(schema::kSpeciesKeys, "forest.species[].canopy.leaf_area_index").number;
  /// C_D of the leaves per one-sided leaf area (the branches' convention), >= 0.
  double drag_coefficient =
      schema::key(schema::kSpeciesKeys, "forest.species[].canopy.drag_coefficient").number;
  int leaf_area_index_line = 0;  ///< the line of leaf_area_index (of canopy, or the species, when not given)
};

/// A species' leaves seed when the file gives none: the global seed + kLeafSeedOffset + the species' index
/// (apart from the stands' seed + k and the skeletons' seed + 1 + k).
inline constexpr std::uint64_t kLeafSeedOffset = std::uint64_t(1) << 32;

struct Species {
  std::string name;  ///< unique among the species
  SkeletonSource skeleton;
  trees::Material material{
      schema::key(schema::kSpeciesKeys, "forest.species[].material.youngs_modulus").number,
      schema::key(schema::kSpeciesKeys, "forest.species[].material.shear_modulus").number,
      schema::key(schema::kSpeciesKeys, "forest.species[].material.density")
          .number};  ///< E, G (Pa), rho (kg/m^3)
  /// forest.species[].dynamics and the keys of its model (rigid_bodies, springs) over trees::SpeciesDynamics'
  /// defaults (the schema's); validated. The keys of another model are errors, `modes` included: every
  /// species' modes are still computed from `modes` (its defaults, for the other models).
  trees::SpeciesDynamics dynamics;
  ModeSettings modes;
  /// C_D of the branches (cylinders in cross flow) per frontal area, >= 0.
  double drag_coefficient = schema::key(schema::kSpeciesKeys, "forest.species[].drag_coefficient").number;
  CanopySettings canopy;
  /// forest.species[].leaves: the file's keys over trees::LeafSettings' defaults (the schema's), seed
  /// resolved (kLeafSeedOffset). Model none (no leaves) when the file has no `leaves`; with leaves,
  /// canopy.leaf_area_index > 0.
  trees::LeafSettings leaves{.model = trees::FlutterModel::none};
};

/// A stand: trees placed by trees::place_stand (yaws uniform at random, scales uniform in [min, max]).
struct Stand {
  std::string species;      ///< a Species::name
  trees::StandSpec layout;  ///< layout.species is the index into ForestSettings::species; region in m
  /// The stand's own leaf area index, m^2/m^2, in (0, trees::StandDensity::kMaxLeafAreaIndex]; nullopt:
  /// the species' canopy.leaf_area_index on every crown.
  std::optional<double> leaf_area_index;
  int line = 0;                  ///< the stand entry's line in the file
  int leaf_area_index_line = 0;  ///< the line of leaf_area_index (the entry's when not given)
};

/// One tree placed by hand.
struct PlacedTreeSettings {
  std::string species;               ///< a Species::name
  int species_index = 0;             ///< into ForestSettings::species
  std::array<double, 3> position{};  ///< m; z from the file, else the ground (terrain) under (x, y)
  bool height_given = false;         ///< whether the file gave z
  /// Counter-clockwise about +z seen from above (the file's degrees, converted).
  double yaw_rad = radians(schema::key(schema::kForestKeys, "forest.trees[].yaw").number);
  double scale = schema::key(schema::kForestKeys, "forest.trees[].scale").number;  ///< > 0
};

struct ForestSettings {
  bool two_way_coupling =
      schema::key(schema::kForestKeys, "forest.two_way_coupling").flag;  ///< trees' drag returned to the wind
  /// The modal time step: exact for the force held over a step, or Diener's semi-implicit Euler.
  trees::ModalIntegrator integrator =
      schema::value_of(schema::kIntegratorWords, schema::kIntegrators,
                       schema::key(schema::kForestKeys, "forest.integrator").word);
  /// Diener's (2008, section 5.2) quadratic correction of the linear modal displacement on output frames.
  bool strong_wind_correction = schema::key(schema::kForestKeys, "forest.strong_wind_correction").flag;
  fluid::DragLaw drag_law;  ///< forest.drag_law (validated by the reader's bounds)
  std::vector<Species> species;
  std::vector<Stand> stands;
  std::vector<PlacedTreeSettings> trees;
};

struct SolverSettings {
  fluid::PressureSolverType pressure =
      schema::value_of(schema::kPressureWords, schema::kPressureSolvers,
                       schema::key(schema::kSolverKeys, "solver.pressure").word);
  double tolerance = schema::key(schema::kSolverKeys, "solver.tolerance")
                         .number;  ///< relative residual (multigrid, cg), > 0
  int max_iterations =
      int(schema::key(schema::kSolverKeys, "solver.max_iterations").number);  ///< >= 1 (multigrid, cg)
  int jacobi_iterations =
      int(schema::key(schema::kSolverKeys, "solver.jacobi_iterations").number);  ///< >= 1 (jacobi)
  fluid::AdvectionScheme advection =
      schema::value_of(schema::kAdvectionWords, schema::kAdvectionSchemes,
                       schema::key(schema::kSolverKeys, "solver.advection").word);
  fluid::StageProjection stage_projection =
      schema::value_of(schema::kStageProjectionWords, schema::kStageProjections,
                       schema::key(schema::kSolverKeys, "solver.stage_projection").word);
  /// epsilon, dimensionless, >= 0 (0: off)
  double vorticity_confinement = schema::key(schema::kSolverKeys, "solver.vorticity_confinement").number;
  /// The subgrid stress's model (smagorinsky: on while smagorinsky_constant > 0)
  fluid::SubgridModel subgrid = schema::value_of(schema::kSubgridWords, schema::kSubgridModels,
                                                 schema::key(schema::kSolverKeys, "solver.subgrid").word);
  /// C_s of the eddy viscosity (C_s h)^2 |S|, dimensionless, in [0, 1) (0: off); not given with tke
  double smagorinsky_constant = schema::key(schema::kSolverKeys, "solver.smagorinsky_constant").number;
};

struct Probe {
  std::string name;                  ///< [A-Za-z0-9_]+, unique
  std::array<double, 3> position{};  ///< m, inside the domain (faces included)
};

struct OutputSettings {
  std::filesystem::path directory;  ///< absolute: the file's value (default out/<scenario>) against the cwd
  double interval = schema::key(schema::kOutputKeys, "output.interval")
                        .number;  ///< s of simulated time between frames, > 0
  /// s of simulated time between probe samples, > 0, as the file gives it; nullopt for "auto" (see
  /// Scenario::resolved_probe_interval).
  std::optional<double> probe_interval;
  bool vtk_wind = schema::key(schema::kOutputKeys, "output.vtk.wind").flag;
  bool vtk_trees = schema::key(schema::kOutputKeys, "output.vtk.trees").flag;
  /// Each output's every-N: it writes the frames K with K % N == 0, keeping K as the file's number, so that
  /// the outputs' collections line up in time (>= 1; 1 every frame).
  int vtk_wind_every = int(schema::key(schema::kOutputKeys, "output.vtk.wind_every").number);
  int vtk_trees_every = int(schema::key(schema::kOutputKeys, "output.vtk.trees_every").number);
  int vdb_every = int(schema::key(schema::kOutputKeys, "output.vdb.every").number);
  int leaves_every = int(schema::key(schema::kOutputKeys, "output.leaves.every").number);
  /// Subset of schema::kVtkFieldWords, in the file's order.
  std::vector<std::string> vtk_fields =
      schema::strings(schema::key(schema::kOutputKeys, "output.vtk.fields").chosen);
  bool vdb_enabled = schema::key(schema::kOutputKeys, "output.vdb.enabled").flag;
  /// Subset of schema::kVdbGridWords, in the file's order ("leaves": a points grid, in runs with leaves).
  std::vector<std::string> vdb_grids =
      schema::strings(schema::key(schema::kOutputKeys, "output.vdb.grids").chosen);
  bool vtk_leaves =
      schema::key(schema::kOutputKeys, "output.leaves.vtk").flag;  ///< leaves.pvd, in runs with leaves
  /// output.leaves.attached: the frames hold the attached leaves whose index on their tree is a multiple of
  /// N; 1 all, 0 none. Flying and landed leaves are always written.
  int leaves_attached_stride =
      schema::value_of(schema::kLeafStrideWords, schema::kLeafStrides,
                       schema::key(schema::kOutputKeys, "output.leaves.attached").word);
  std::vector<Probe> probes;
  /// output.checkpoint.interval, s; 0 without the key (checkpoints only when a signal stops the run).
  double checkpoint_interval = 0.0;
  int checkpoints_kept =
      int(schema::key(schema::kOutputKeys, "output.checkpoint.keep").number);  ///< the newest ones kept
};

/// The ambient wind of `wind` at the reference height at time t (s), m/s: Scenario::wind_vector without the
/// rest of the scenario, for whoever keeps only the wind.
std::array<double, 3> wind_vector(const WindSource& wind, double t);

struct Scenario {
  std::filesystem::path file;    ///< as given to load_scenario
  std::filesystem::path folder;  ///< absolute folder of the file: relative paths resolve here
  std::string text;              ///< the file's bytes, to copy into the output folder

  std::string name;        ///< `scenario`: no path separators, not "." or ".."
  std::uint64_t seed = 0;  ///< global seed
  TimeSettings time;
  DomainSettings domain;
  /// Indexed by FW_FACE_* (west, east, south, north, ground, top).
  std::array<BoundaryChoice, 6> boundaries = default_boundaries();
  /// z0 of a rough ground, m, in (0, domain.cell_size / 2): boundaries.roughness_length, else the log
  /// profile's roughness_length, else 0.1 m. 0 when the ground is not rough.
  double ground_roughness_length = 0.0;
  WindSource wind;
  std::vector<GustEvent> events;
  std::vector<Obstacle> obstacles;
  std::optional<TerrainSettings> terrain;
  ForestSettings forest;
  SolverSettings solver;
  OutputSettings output;

  /// The ambient wind at the reference height at time t (s), m/s, x east, y north: the wind blows TOWARD
  /// direction + 180 degrees, so v = -speed * (sin theta, cos theta, 0). Direction 270 blows toward +x.
  std::array<double, 3> wind_vector(double t) const;
  /// The grid with "auto" faces resolved for the wind at time t: inflow where wind_vector(t) points into
  /// the domain, outflow elsewhere (also where the wind runs parallel to the face). A rough ground is slip
  /// (its wall stress is a separate stage).
  fluid::GridSpec grid_spec(double t) const;
  /// Simulated time between probe samples, s: output.probe_interval when given; for auto, nullopt (every
  /// solver step) with wind.turbulence, else output.interval.
  std::optional<double> resolved_probe_interval() const;
  /// Advection, pressure solver and time step as fluid::WindSettings (auto dt: cfl > 0; fixed: cfl = 0).
  fluid::WindSettings wind_settings() const;
};

/// Reads and validates a scenario file. Throws ScenarioError (see the header comment) for every problem.
Scenario load_scenario(const std::filesystem::path& file);

/// The checks that need a species' skeleton, once it is built or read (`check` and `run` both call this):
/// a modal species' modes.count must stay below the skeleton's 6 (nodes - 1) DOFs. Throws ScenarioError at
/// modes.count.
void check_species_skeleton(const Scenario& scenario, int species_index, int skeleton_nodes);

/// The modes a species' basis keeps on a skeleton of `skeleton_nodes` nodes: modes.count for a modal species
/// (check_species_skeleton has checked it); for the other models, which cannot set `modes` and read only the
/// basis' first frequency, the default count, or as many modes as the skeleton has DOFs less one when that
/// is fewer (a small skeleton file).
int species_mode_count(const Scenario& scenario, int species_index, int skeleton_nodes);

}  // namespace fw::io
