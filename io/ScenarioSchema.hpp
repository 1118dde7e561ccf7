// The scenario schema: every key a scenario file may hold, with its type, unit, default, allowed values and
// meaning, defined once (issue 9, "The schema in one place"). The loader (io/scenario/) takes from here its
// unknown-key checks, its required keys, its vocabularies and the "... expected" part of its messages; the
// defaults of the io::Scenario structs are read from here; and the key tables of docs/scenario.md are
// generated from here (render_scenario_docs; tests/io/ScenarioSchema_test.cpp fails when the committed page
// differs).
//
//   constexpr double cfl = fw::io::schema::key("time.cfl").number;       // 0.8, looked up at compile time
//   const fw::io::schema::Key* found = fw::io::schema::find("forest.species[].modes.count");   // at run time
//   fw::io::schema::expected(*found);                                   // "an integer >= 1"
//   fw::io::schema::child_names("wind.profile");                        // type, alpha, roughness_length, ...
//
// Paths are dotted, with "[]" for the items of a list: "forest.species[].canopy.leaf_area_index". A file's
// key "forest.species[2].modes" is generic_path'd to "forest.species[].modes" before a lookup. Defaults that
// belong to another part of the program (the pressure tolerance of fluid::PressureSettings, the wood of
// trees::kDefaultWood, the drag coefficients of trees::WindBasisSettings, the modal defaults of
// trees::ModalSettings, the leaves of trees::LeafSettings) are taken from there, so that each value is
// written once. So are the limits: a number's upper limit (at_most, below) and the numbers a constraint
// names (limits) come from the type that checks them again at run time (trees::LeafSettings::kMaxFraction,
// fluid::GridSpec::kMaxFaces, ...), and the loader, its messages and the docs all read them from here.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/InflowProfile.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "fluid/WindSettings.hpp"
#include "kernels/shared_types.h"
#include "trees/ForestLayout.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/Material.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/ModalIntegrator.hpp"
#include "trees/StandDensity.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/WindBasis.hpp"

namespace fw::io::schema {

/// What a key holds. The loader reads each type with one function, and the docs' type column names it.
enum class Type {
  map,                    ///< a map of the keys below it
  choice,                 ///< a map with exactly one of the keys below it
  list,                   ///< a list of maps of the keys below PATH[]
  choice_list,            ///< a list of maps, each with exactly one of the keys below PATH[]
  text,                   ///< a non-empty string
  file,                   ///< a readable file, relative to the scenario's folder
  directory,              ///< a folder, relative to the working directory
  number,                 ///< a finite decimal number
  number_or_auto,         ///< a number, or the word auto (no number)
  integer,                ///< a whole number within [lowest, highest]
  integer_or_word,        ///< a whole number within [lowest, highest], or one of words
  seed,                   ///< an unsigned 64-bit integer
  boolean,                ///< true or false
  word,                   ///< one of words
  word_set,               ///< a list of distinct words of words
  point2,                 ///< [x, y]
  point3,                 ///< [x, y, z]
  point2_or_3,            ///< [x, y] or [x, y, z]
  expression,             ///< a number or a muparser expression of t
  velocity_or_with_wind,  ///< [vx, vy, vz], or the word with_wind
};

/// The sign a number (or each number of a point, or each value of an expression) must have.
enum class Bound { any, positive, non_negative };

using Words = std::span<const std::string_view>;

inline constexpr double kNoNumberLimit = std::numeric_limits<double>::infinity();

struct Key {
  std::string_view path{};
  Type type = Type::map;
  std::string_view unit{};  ///< SI unit; empty when dimensionless or not a quantity
  bool required = false;
  Bound bound = Bound::any;
  double at_least = -kNoNumberLimit;  ///< number, point: each value must be >= this
  double at_most = kNoNumberLimit;    ///< number, point: each value must be <= this
  double below = kNoNumberLimit;      ///< number, point: each value must be < this
  long long lowest = 0;               ///< integer: the smallest value allowed
  long long highest = 0;  ///< integer: the largest value allowed (numeric_limits<int>::max(): no limit)
  Words words{};          ///< word, word_set: the vocabulary
  /// word: a vocabulary known only at run time (replaces words).
  std::vector<std::string> (*run_time_words)() = nullptr;
  double number = 0.0;                   ///< default of number, integer (and of every component of point3)
  std::span<const double> components{};  ///< default of point3 per component, where they differ (not number)
  bool flag = false;                     ///< default of boolean
  /// default of word, number_or_auto, integer_or_word, velocity_or_with_wind, directory
  std::string_view word{};
  Words chosen{};  ///< default of word_set
  /// text, file, directory, list: what the value is, in messages; point2, point3: its components' names
  /// ("[x, y, z]" when empty)
  std::string_view noun{};
  std::string_view only_with{};     ///< the key applies only where its sibling `type` is this word
  std::string_view default_note{};  ///< docs: the default in words, where it is not a plain value
  std::string_view allowed{};       ///< docs: replaces the allowed values derived from the type
  /// docs: what is allowed beyond the type's own rule; {0}, {1}, {2} stand for the numbers in `limits`
  std::string_view constraint{};
  std::array<double, 3> limits{};  ///< the numbers `constraint` names, taken from the type that checks them
  std::string_view description{};  ///< docs: the meaning, one table row
};

inline constexpr int kNoUpperLimit = std::numeric_limits<int>::max();

// --- vocabularies ----------------------------------------------------------------------------------------

/// In the order of io::BoundaryChoice. The four sides take all but the last ("rough"), the ground all but the
/// first ("auto"), the top neither.
inline constexpr std::string_view kBoundaryWords[] = {"auto",    "inflow",   "outflow", "slip",
                                                      "no_slip", "periodic", "rough"};
inline constexpr Words kSideBoundaryWords = Words(kBoundaryWords).first(6);
inline constexpr Words kGroundBoundaryWords = Words(kBoundaryWords).subspan(1);
inline constexpr Words kTopBoundaryWords = Words(kBoundaryWords).subspan(1, 5);

/// In the order of io::TurbulenceModel.
inline constexpr std::string_view kTurbulenceModelWords[] = {"von_karman"};

inline constexpr std::string_view kProfileWords[] = {"uniform", "power", "log"};
inline constexpr fluid::InflowProfile::Type kProfileTypes[] = {
    fluid::InflowProfile::Type::uniform, fluid::InflowProfile::Type::power, fluid::InflowProfile::Type::log};

inline constexpr std::string_view kIntegratorWords[] = {"exact", "semi_implicit"};
inline constexpr trees::ModalIntegrator kIntegrators[] = {trees::ModalIntegrator::exact,
                                                          trees::ModalIntegrator::semi_implicit};

inline constexpr std::string_view kLayoutWords[] = {"poisson", "grid"};
inline constexpr trees::StandLayout kLayouts[] = {trees::StandLayout::poisson, trees::StandLayout::grid};

inline constexpr std::string_view kPressureWords[] = {"multigrid", "cg", "jacobi"};
inline constexpr fluid::PressureSolverType kPressureSolvers[] = {
    fluid::PressureSolverType::multigrid, fluid::PressureSolverType::cg, fluid::PressureSolverType::jacobi};

inline constexpr std::string_view kAdvectionWords[] = {"semi_lagrangian", "maccormack", "upwind5"};
inline constexpr fluid::AdvectionScheme kAdvectionSchemes[] = {fluid::AdvectionScheme::semi_lagrangian,
                                                               fluid::AdvectionScheme::maccormack,
                                                               fluid::AdvectionScheme::upwind5};
inline constexpr std::string_view kStageProjectionWords[] = {"final_stage", "every_stage"};
inline constexpr fluid::StageProjection kStageProjections[] = {fluid::StageProjection::final_stage,
                                                               fluid::StageProjection::every_stage};

inline constexpr std::string_view kSubgridWords[] = {"smagorinsky", "tke"};
inline constexpr fluid::SubgridModel kSubgridModels[] = {fluid::SubgridModel::smagorinsky,
                                                         fluid::SubgridModel::tke};

inline constexpr std::string_view kVtkFieldWords[] = {"velocity",  "pressure", "speed",
                                                      "vorticity", "solid",    "canopy_density"};
inline constexpr std::string_view kVdbGridWords[] = {"vel", "speed", "leaves"};

/// In the order of trees::FlutterModel (trees::to_string gives the same words).
inline constexpr std::string_view kLeafModelWords[] = {"none", "pseudo_branch", "stochastic"};
inline constexpr trees::FlutterModel kLeafModels[] = {
    trees::FlutterModel::none, trees::FlutterModel::pseudo_branch, trees::FlutterModel::stochastic};

/// In the order of trees::TreeDynamics (trees::dynamics_name gives the same words).
inline constexpr std::string_view kDynamicsWords[] = {"modal", "rigid_bodies", "springs"};
inline constexpr trees::TreeDynamics kDynamicsModels[] = {
    trees::TreeDynamics::modal, trees::TreeDynamics::rigid_bodies, trees::TreeDynamics::springs};

/// The words of output.leaves.attached and the stride each stands for (io::OutputSettings).
inline constexpr std::string_view kLeafStrideWords[] = {"all", "none"};
inline constexpr int kLeafStrides[] = {1, 0};

/// The word of `value` in a vocabulary and its values, aligned by position (a default owned elsewhere).
template <typename Enum, std::size_t N>
constexpr std::string_view word_of(const std::string_view (&words)[N], const Enum (&values)[N], Enum value) {
  for (std::size_t i = 0; i < N; ++i)
    if (values[i] == value) return words[i];
  throw "not a value of the vocabulary";
}

/// The generator's presets (trees::preset_names), known at run time.
std::vector<std::string> preset_words();

// --- the table ---------------------------------------------------------------------------------------------

// Each map's keys in the order the loader's messages and the docs list them. Defaults owned elsewhere:
inline constexpr fluid::PressureSettings kPressureDefaults{};
inline constexpr trees::WindBasisSettings kDragDefaults{};
inline constexpr trees::LeafSettings kLeafDefaults{};
inline constexpr trees::SpeciesDynamics kDynamicsDefaults{};
/// springs.max_angle_deg stays below a right angle, as trees::SpeciesDynamics::validate checks (a bend past
/// it has no meaning for one element turning about its base). TreeDynamics.cpp keeps its limit to itself, so
/// it is written here too; tests/io/ScenarioSchema_test.cpp holds the two equal.
inline constexpr double kSpringMaxAngleBelowDeg = 90.0;
/// How far domain.size may lie from a whole multiple of cell_size, relative to the size.
inline constexpr double kCellMultipleTolerance = 1e-6;
/// The fewest cells of wind.turbulence.box_size along an axis (a box given smaller is rounded up to it).
inline constexpr int kMinTurbulenceBoxCells = 4;

inline constexpr Key kKeys[] = {
    // top level
    {.path = "scenario",
     .type = Type::text,
     .required = true,
     .noun = "a scenario name",
     .constraint = "no `/` or `\\`, no control characters, not `.` or `..`",
     .description = "Name of the scenario. Used as the folder name in the default output directory "
                    "`out/<scenario>`."},
    {.path = "seed",
     .type = Type::seed,
     .description = "Global seed, recorded in `run.json`. Seeds the file does not give derive from it: stand "
                    "k is laid out with `seed + k`, species k generates its skeleton with `seed + 1 + k` and "
                    "its leaves with `seed + 2^32 + k`."},
    // time
    {.path = "time", .required = true, .description = "Simulated time span, time step and wind spin-up."},
    {.path = "time.end",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .description =
         "The run covers t = 0 to `end`. `forestwind run --end SECONDS` overrides it for one run."},
    {.path = "time.dt",
     .type = Type::number_or_auto,
     .unit = "s",
     .bound = Bound::positive,
     .word = "auto",
     .description =
         "Time step. With a number, the step is fixed; a run stops with exit code 1 when that "
         "step's CFL number exceeds 5 (checked before every step), or with `upwind5` when the sum of "
         "its Courant numbers `(max\\|u\\| + max\\|v\\| + max\\|w\\|) dt / h` exceeds the scheme's "
         "stability limit 1.2; `check` refuses (exit 2) an `upwind5` step past that limit at the peak "
         "wind. With `auto`, each step uses `dt = cfl * h / max\\|u\\|` (h = `domain.cell_size`, max "
         "over the velocity components), capped at 1 s and, with `upwind5`, at `1.2 h / (max\\|u\\| + "
         "max\\|v\\| + max\\|w\\|)`."},
    {.path = "time.cfl",
     .type = Type::number,
     .bound = Bound::positive,
     .number = 0.8,
     .description = "CFL number for `dt: auto`. With a fixed `dt` it is still validated, but not used."},
    {.path = "time.spin_up",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::non_negative,
     .number = 0.0,
     .description =
         "Wind spin-up before t = 0, so that the stand's shelter forms before the trees move: for `spin_up` "
         "seconds the wind grid steps (`dt` as in the run) from t = -`spin_up` to 0 with the inputs held at "
         "their t = 0 values (no event fires), trees and leaves still and nothing written; the trees then "
         "take their equilibrium with the wind it ends on. The run then starts at t = 0, step 0, "
         "with the trees at rest in equilibrium with the sheltered wind. A resumed run does not spin up "
         "again. 0: no spin-up, the trees start in equilibrium with the unsheltered inflow profile."},
    // domain
    {.path = "domain", .required = true, .description = "The wind grid."},
    {.path = "domain.origin",
     .type = Type::point3,
     .unit = "m",
     .number = 0.0,
     .description = "The minimum (south-west, bottom) corner. Its z is the domain floor."},
    {.path = "domain.size",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .constraint = "each a whole multiple of `cell_size` (to {0} relative), at least one cell",
     .limits = {kCellMultipleTolerance},
     .description = "Extent along x, y and z."},
    {.path = "domain.cell_size",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .constraint = "(nx + 1)(ny + 1)(nz + 1) <= {0}",
     .limits = {double(fluid::GridSpec::kMaxFaces)},
     .description = "Cell edge h. The grid has `size / cell_size` cells along each axis."},
    {.path = "domain.decomposition",
     .type = Type::point2,
     .at_least = 1,
     .noun = "[px, py]",
     .default_note = "chosen: the split of the ranks that exchanges the fewest halo cells",
     .constraint = "whole numbers whose product is the number of ranks (`mpirun -np`)",
     .description = "Blocks along x and y of a run over MPI ranks, one block a rank (docs/parallel.md). "
                    "Ignored by a run in one process."},
    // boundaries, in the order of FW_FACE_*
    {.path = "boundaries", .description = "Boundary condition per face."},
    {.path = "boundaries.west",
     .type = Type::word,
     .words = kSideBoundaryWords,
     .word = "auto",
     .description = "West face (x minimum)."},
    {.path = "boundaries.east",
     .type = Type::word,
     .words = kSideBoundaryWords,
     .word = "auto",
     .description = "East face (x maximum)."},
    {.path = "boundaries.south",
     .type = Type::word,
     .words = kSideBoundaryWords,
     .word = "auto",
     .description = "South face (y minimum)."},
    {.path = "boundaries.north",
     .type = Type::word,
     .words = kSideBoundaryWords,
     .word = "auto",
     .description = "North face (y maximum)."},
    {.path = "boundaries.ground",
     .type = Type::word,
     .words = kGroundBoundaryWords,
     .word = "no_slip",
     .constraint = "no `auto`",
     .description =
         "Bottom face (z minimum). `rough` (the ground only): a rough wall, whose drag on the air is "
         "the log-law wall shear stress of `roughness_length` (see below the table)."},
    {.path = "boundaries.top",
     .type = Type::word,
     .words = kTopBoundaryWords,
     .word = "slip",
     .constraint = "no `auto`, no `rough`",
     .description = "Top face (z maximum)."},
    {.path = "boundaries.roughness_length",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .number = 0.1,
     .default_note = "`wind.profile.roughness_length` with a `log` profile, else `0.1`",
     .constraint = "below `domain.cell_size` / 2; only with `ground: rough`",
     .description =
         "Aerodynamic roughness length z0 of a `rough` ground. The first fluid cell above the ground, and "
         "above terrain and other solid cells, feels the log law's wall shear stress `tau / rho = u*^2`, "
         "`u* = kappa \\|U\\| / ln((h / 2) / z0)`, with \\|U\\| that cell's horizontal speed at its centre, "
         "h / 2 above the surface (h = `domain.cell_size`, kappa = 0.41); so z0 must lie below h / 2. "
         "Davenport-Wieringa classes: 0.03 m open flat land, 0.1 m low crops, 0.25 m high crops, 0.5 m "
         "parkland, 1 m forest or suburbs. Under trees that the scenario resolves, give the floor's own "
         "roughness (grass, litter), not the forest's: the trees' drag is already modelled."},
    // wind
    {.path = "wind", .required = true, .description = "The ambient wind."},
    {.path = "wind.speed",
     .type = Type::expression,
     .unit = "m/s",
     .required = true,
     .bound = Bound::non_negative,
     .description = "Wind speed at `reference_height`."},
    {.path = "wind.direction",
     .type = Type::expression,
     .unit = "degrees",
     .required = true,
     .constraint = "any value (370 is the same as 10)",
     .description = "Direction the wind blows FROM, clockwise from north."},
    {.path = "wind.reference_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .number = 10.0,
     .description = "Height above the domain floor where the wind has speed `wind.speed`."},
    {.path = "wind.profile",
     .default_note = "`{type: uniform}`",
     .allowed = "keys `type` plus that type's keys",
     .description = "Vertical shape of the wind on inflow faces. A key that belongs to another type is an "
                    "error."},
    {.path = "wind.profile.type",
     .type = Type::word,
     .required = true,
     .words = kProfileWords,
     .word = "uniform",
     .default_note = "required when `profile` is given",
     .description = "`uniform`: shape 1 at every height. `power`: `(z / reference_height)^alpha`. `log`: "
                    "`ln((z - d) / z0) / ln((reference_height - d) / z0)`, and 0 where `z - d <= z0`."},
    {.path = "wind.profile.alpha",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = 0.2,
     .only_with = "power",
     .description = "Power-law exponent."},
    {.path = "wind.profile.roughness_length",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .only_with = "log",
     .description = "Roughness length z0. `reference_height` must exceed `displacement_height + "
                    "roughness_length` (the log law gives no wind below it); the error names "
                    "`displacement_height` when given, else `roughness_length`."},
    {.path = "wind.profile.displacement_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .number = 0.0,
     .only_with = "log",
     .description = "Displacement height d (of a canopy, for example)."},
    {.path = "wind.turbulence",
     .default_note = "none (a laminar wind)",
     .allowed = "keys `model`, `intensity` or `sigma`, `length_scale`, `box_size`, `seed`, `unresolved`, "
                "`cutoff_cells`",
     .description = "Synthetic turbulence in the wind. Without it the inflow is the laminar profile alone."},
    {.path = "wind.turbulence.model",
     .type = Type::word,
     .words = kTurbulenceModelWords,
     .word = "von_karman",
     .description =
         "`von_karman`: homogeneous isotropic turbulence with the von Kármán energy spectrum E(k) of "
         "integral scale `length_scale`. Before the run, a periodic, divergence-free box of velocity "
         "fluctuations is synthesised from random Fourier modes by FFT (FFTW), deterministic from `seed`. "
         "The box is added to the initial wind field, and it is swept through the inflow faces at the "
         "ambient wind (Taylor's frozen turbulence): at time t an inflow face point x carries the mean "
         "profile plus the box's fluctuation at x - U t, U the ambient wind vector at `reference_height`. "
         "The fluctuations' statistics are the same at every height."},
    {.path = "wind.turbulence.intensity",
     .type = Type::number,
     .bound = Bound::non_negative,
     .default_note = "required unless `sigma` is given",
     .constraint = "exactly one of `intensity` and `sigma`",
     .description = "Turbulence intensity I = sigma_u / U, with U the wind speed `wind.speed` at "
                    "`reference_height`. sigma_u = I U follows `wind.speed` over time, and sigma_v = sigma_w "
                    "= sigma_u (isotropic). For neutral wind over uniform ground, EN 1991-1-4 gives I = 1 / "
                    "ln(z / z0) at height z: 0.17 at 10 m over grass (z0 = 0.03 m), 0.43 over forest (z0 "
                    "= 1 m)."},
    {.path = "wind.turbulence.sigma",
     .type = Type::point3,
     .unit = "m/s",
     .bound = Bound::positive,
     .noun = "[sigma_u, sigma_v, sigma_w]",
     .default_note = "required unless `intensity` is given",
     .allowed = "each > 0; exactly one of `intensity` and `sigma`",
     .description =
         "Standard deviations [sigma_u, sigma_v, sigma_w] of the along-wind, across-wind and "
         "vertical fluctuations, fixed over time whatever `wind.speed` does. Unequal values scale "
         "the components of the isotropic box, which leaves a small divergence that the pressure "
         "projection removes; in the atmospheric surface layer sigma_v / sigma_u is about 0.75 and "
         "sigma_w / sigma_u about 0.5."},
    {.path = "wind.turbulence.length_scale",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "L_u, the longitudinal integral length scale: the integral of the along-wind "
                    "fluctuation's autocorrelation along the wind. The premultiplied spectrum f S_u(f) peaks "
                    "at f = 0.146 U / L_u. EN 1991-1-4 gives L_u = 300 m (z / 200 m)^(0.67 + 0.05 ln z0): "
                    "about 40 m at 10 m over forest, 70 m over grass. The grid resolves eddies of "
                    "`cutoff_cells` cells and more, so L_u should span many cells."},
    {.path = "wind.turbulence.box_size",
     .type = Type::point3,
     .unit = "m",
     .bound = Bound::positive,
     .default_note = "computed: along x and y the smallest power-of-two cell count >= the domain's cells "
                     "and >= 8 `length_scale` / `cell_size`; along z the smallest power of two >= the "
                     "domain's cells; each at least the fewest allowed",
     .constraint =
         "rounded to a whole, even number of cells, at least {0}, per axis; the box has {1} points "
         "per cell along each axis (h / {1} apart, h = `domain.cell_size`), at most {2} points in all",
     .limits = {kMinTurbulenceBoxCells, fluid::kTurbulencePointsPerCell,
                double(fluid::TurbulenceBoxSpec::kMaxPoints)},
     .description =
         "Extent of the periodic turbulence box along x, y and z, in cells of the grid. Its points are "
         "finer than the cells (see the allowed values), so that every face of an inflow plane sits on a "
         "box point and takes the box's value without interpolation. Turbulence repeats with the box's "
         "period: a point fixed in the inflow sees the same gusts again once the wind has carried the box "
         "one period past it, and the box holds no wavelength longer than itself, so along the wind it "
         "should be several L_u long."},
    {.path = "wind.turbulence.seed",
     .type = Type::seed,
     .default_note = "global `seed`",
     .description = "Seed of the box's random Fourier amplitudes and of the unresolved forcing. The same "
                    "seed gives the same turbulence."},
    {.path = "wind.turbulence.unresolved",
     .type = Type::boolean,
     .flag = true,
     .description =
         "With `true`, each tree also feels the turbulence the grid cannot resolve (wavelengths "
         "below `cutoff_cells` cells): Stam's (1997) stochastic modal forcing, random modal forces "
         "with the spectrum's unresolved part, synthesised in the frequency domain, deterministic "
         "per tree from `seed`. With `false`, trees feel only the resolved wind."},
    {.path = "wind.turbulence.cutoff_cells",
     .type = Type::number,
     .bound = Bound::positive,
     .number = 2.0,
     .description =
         "The smallest eddy the grid resolves, in cells: wavelengths below `cutoff_cells` × "
         "`cell_size` (wavenumbers above 2 pi / (`cutoff_cells` h)) belong to the unresolved "
         "forcing. 2 is the grid's Nyquist limit; numerical diffusion damps eddies of a few cells, "
         "so 4 to 8 can be closer to what the grid really carries."},
    {.path = "wind.forcing",
     .default_note = "none; on, with the defaults below, when the four sides are all `periodic`",
     .allowed = "keys `relaxation_time`; only when `west`, `east`, `south` and `north` are all `periodic`",
     .description =
         "A mean body force for a domain whose four sides are all periodic, which has no inflow: "
         "it holds the horizontal mean wind at `reference_height` at `wind.speed` from "
         "`wind.direction`, as a pressure gradient drives the atmosphere, so that the flow neither "
         "decays under the trees' and the ground's drag nor runs away."},
    {.path = "wind.forcing.relaxation_time",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::positive,
     .number = 10.0,
     .description = "Time constant tau of the PI controller that sets the force from the difference between "
                    "the target wind and the horizontal mean at `reference_height`. Shorter follows a "
                    "changing `wind.speed` more closely; longer disturbs the turbulence less."},
    // events
    {.path = "events",
     .type = Type::choice_list,
     .noun = "a list of events (- gust: {...})",
     .description = "Gust events."},
    {.path = "events[].gust",
     .required = true,
     .default_note = "required in each item",
     .description = "One gust."},
    {.path = "events[].gust.start",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::non_negative,
     .description = "Time at which the gust begins."},
    {.path = "events[].gust.duration",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .description = "Length of the envelope."},
    {.path = "events[].gust.peak_speed",
     .type = Type::number,
     .unit = "m/s",
     .required = true,
     .bound = Bound::non_negative,
     .description = "Extra speed at the envelope's peak and the ball's centre. A plain number, not an "
                    "expression."},
    {.path = "events[].gust.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .constraint = "may lie outside the domain",
     .description = "Position of the ball's centre at `start`."},
    {.path = "events[].gust.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "Radius R of the Gaussian."},
    {.path = "events[].gust.travel",
     .type = Type::velocity_or_with_wind,
     .unit = "m/s",
     .word = "with_wind",
     .description = "Velocity of the ball. `with_wind` takes the ambient wind vector at the reference height "
                    "at time `start` and keeps it constant."},
    // obstacles
    {.path = "obstacles",
     .type = Type::choice_list,
     .noun = "a list of obstacles (- box|cylinder|sphere: {...})",
     .description = "Solid obstacles."},
    {.path = "obstacles[].box",
     .description = "A box, possibly turned about the vertical axis through its centre."},
    {.path = "obstacles[].box.name",
     .type = Type::text,
     .required = true,
     .noun = "a name",
     .description = "Name, used in messages. Names need not be unique."},
    {.path = "obstacles[].box.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .description = "Centre of the box."},
    {.path = "obstacles[].box.size",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "Full edge lengths along the box's own axes (before yaw)."},
    {.path = "obstacles[].box.yaw",
     .type = Type::number,
     .unit = "degrees",
     .number = 0.0,
     .description = "Rotation about +z, counter-clockwise seen from above."},
    {.path = "obstacles[].cylinder", .description = "A vertical cylinder standing on its base."},
    {.path = "obstacles[].cylinder.name",
     .type = Type::text,
     .required = true,
     .noun = "a name",
     .description = "Name, used in messages."},
    {.path = "obstacles[].cylinder.base",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .description = "Centre of the bottom disc."},
    {.path = "obstacles[].cylinder.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "Radius."},
    {.path = "obstacles[].cylinder.height",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "Extent upward from the base."},
    {.path = "obstacles[].sphere", .description = "A sphere."},
    {.path = "obstacles[].sphere.name",
     .type = Type::text,
     .required = true,
     .noun = "a name",
     .description = "Name, used in messages."},
    {.path = "obstacles[].sphere.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .description = "Centre."},
    {.path = "obstacles[].sphere.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .description = "Radius."},
    // terrain
    {.path = "terrain", .default_note = "none (flat floor)", .description = "Terrain."},
    {.path = "terrain.heightmap",
     .type = Type::file,
     .required = true,
     .noun = "a file path (PGM or ESRI ASCII grid)",
     .allowed = "a readable PGM or ESRI ASCII grid; relative to the scenario's folder",
     .description = "The height field."},
    {.path = "terrain.cell_size",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .default_note = "required for a PGM; ignored for an ESRI grid",
     .constraint = "checked for an ESRI grid too",
     .description = "Distance between PGM pixels."},
    {.path = "terrain.max_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .default_note = "required for a PGM; ignored for an ESRI grid",
     .constraint = "checked for an ESRI grid too",
     .description = "Height that the PGM's maxval stands for."},
    // forest
    {.path = "forest", .default_note = "no trees", .description = "The forest."},
    {.path = "forest.two_way_coupling",
     .type = Type::boolean,
     .flag = true,
     .description =
         "With `true`, the drag of the trees' branches and leaves slows the wind on the grid. With "
         "`false`, the trees feel the wind but do not affect it."},
    {.path = "forest.integrator",
     .type = Type::word,
     .words = kIntegratorWords,
     .word = "exact",
     .description = "The modal time step. `exact` solves each mode's damped oscillator exactly for the force "
                    "held over the step, stable at any dt. `semi_implicit` is Diener's semi-implicit Euler, "
                    "stable only while dt² ω² + 2 γ dt < 4 for every mode; a run whose dt breaks that stops "
                    "with exit code 1 at that step. Modal species only (`forest.species[].dynamics`)."},
    {.path = "forest.strong_wind_correction",
     .type = Type::boolean,
     .flag = true,
     .description = "With `true`, output frames show each tree with Diener's (2008, §5.2) quadratic "
                    "correction of its linear modal displacement, fitted per species and mode: a linear mode "
                    "moves every node along a straight line, which stretches the branches as the tree bends "
                    "far, and the correction keeps branch lengths nearly constant under strong wind. It "
                    "changes the written geometry only; the modal dynamics stay linear. With `false`, frames "
                    "show the linear displacement. Modal species only (`forest.species[].dynamics`)."},
    {.path = "forest.drag_law",
     .default_note = "a constant drag coefficient",
     .description = "How the drag coefficients of every species (branches and foliage) vary with the local "
                    "wind speed: C_D(\\|u\\|) = C_D (max(\\|u\\|, 0.1 U_ref) / U_ref)^exponent, the species' "
                    "coefficients holding at U_ref. Leaves and twigs streamline in strong wind (Vogel 1984); "
                    "the air's canopy drag and the trees' modal forces follow the same law."},
    {.path = "forest.drag_law.exponent",
     .type = Type::number,
     .at_least = fluid::DragLaw::kLowestExponent,
     .at_most = 0.0,
     .number = fluid::DragLaw{}.exponent,
     .description = "The Vogel exponent: 0 keeps the coefficient constant; plants measure 0 to -4/3 "
                    "(strongly reconfiguring ones)."},
    {.path = "forest.drag_law.reference_speed",
     .type = Type::number,
     .unit = "m/s",
     .bound = Bound::positive,
     .number = fluid::DragLaw{}.reference_speed,
     .description = "U_ref, where the species' drag coefficients hold."},
    {.path = "forest.species",
     .type = Type::list,
     .noun = "a list of species",
     .description = "Tree species."},
    {.path = "forest.stands",
     .type = Type::list,
     .noun = "a list of stands",
     .description = "Stands: trees scattered over a region."},
    {.path = "forest.trees",
     .type = Type::list,
     .noun = "a list of trees",
     .description = "Single trees placed by hand."},
    // forest.species
    {.path = "forest.species[].name",
     .type = Type::text,
     .required = true,
     .noun = "a species name",
     .constraint = "unique among the species",
     .description = "Name that stands and trees refer to."},
    {.path = "forest.species[].skeleton",
     .type = Type::choice,
     .required = true,
     .description = "Where the species' skeleton comes from."},
    {.path = "forest.species[].skeleton.generate",
     .description = "Grow a skeleton with the built-in L-system generator, as `forestwind tree generate` "
                    "does."},
    {.path = "forest.species[].skeleton.generate.preset",
     .type = Type::word,
     .required = true,
     .run_time_words = preset_words,
     .description = "Tree shape."},
    {.path = "forest.species[].skeleton.generate.height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .number = 0.0,
     .default_note = "`0` (the preset's height: broadleaf 15, conifer 20, palm 12, weeping 10)",
     .description = "Height of the generated tree."},
    {.path = "forest.species[].skeleton.generate.seed",
     .type = Type::seed,
     .default_note = "global `seed` + 1 + species index",
     .description = "Generator seed. The same seed gives the same tree."},
    {.path = "forest.species[].skeleton.file",
     .type = Type::file,
     .noun = "a file path",
     .allowed = "a readable `.tree` file; relative to the scenario's folder",
     .description = "A skeleton in the `.tree` format (`id parent x y z radius` per line, metres)."},
    {.path = "forest.species[].skeleton.qsm",
     .type = Type::file,
     .noun = "a file path",
     .allowed = "a readable TreeQSM cylinder table; relative to the scenario's folder",
     .description = "A scanned tree, as a TreeQSM text export."},
    {.path = "forest.species[].material", .description = "Wood, isotropic."},
    {.path = "forest.species[].material.youngs_modulus",
     .type = Type::number,
     .unit = "Pa",
     .bound = Bound::positive,
     .number = trees::kDefaultWood.youngs_modulus,
     .description = "Young's modulus E (stretching and bending)."},
    {.path = "forest.species[].material.shear_modulus",
     .type = Type::number,
     .unit = "Pa",
     .bound = Bound::positive,
     .number = trees::kDefaultWood.shear_modulus,
     .description = "Shear modulus G (torsion)."},
    {.path = "forest.species[].material.density",
     .type = Type::number,
     .unit = "kg/m^3",
     .bound = Bound::positive,
     .number = trees::kDefaultWood.density,
     .description = "Wood density rho."},
    {.path = "forest.species[].dynamics",
     .type = Type::word,
     .words = kDynamicsWords,
     .word = word_of(kDynamicsWords, kDynamicsModels, kDynamicsDefaults.model),
     .description =
         "The model that moves the species' trees; all three read the same wind samples, give the air the "
         "same drag and write the same outputs. `modal`: the FEM's lowest vibration modes, driven through "
         "the "
         "wind basis (Diener 2008). `rigid_bodies`: Oliapuram & Kumar (2010, §3.1): each element a rigid "
         "body "
         "rotating about its parent's end against a joint spring of stiffness of the form E I / L, "
         "integrated "
         "implicitly. `springs`: Ota et al. (2004) as Yildiz implements it: each element a quasi-static "
         "cantilever flat spring, k = E b t³ / (4 l³), bent by its own wind load to the angle "
         "atan(deflection / l), capped at `springs.max_angle_deg`, with a stochastic sine on top; no "
         "inertia. "
         "Every species' modes are computed (with the default `modes` for the other two models), because "
         "those models build on the same skeleton, beam model and first frequency."},
    {.path = "forest.species[].modes",
     .constraint = "only for a species whose `dynamics` is `modal`",
     .description = "Modal model."},
    {.path = "forest.species[].modes.count",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = double(trees::ModalSettings{}.mode_count),  // clang refuses the narrowing unspelt
     .constraint = "fewer than the skeleton's 6 × (nodes − 1) DOFs",
     .description = "Number of lowest vibration modes kept."},
    {.path = "forest.species[].modes.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = trees::Damping{}.ratios.front(),
     .description = "Damping ratio zeta, the same for every mode."},
    {.path = "forest.species[].modes.wind_samples",
     .type = Type::integer,
     .lowest = 1,
     .highest = FW_MAX_TREE_SAMPLES,
     .number = 3,
     .description = "Number of height bands per tree. Each band samples the wind separately, which captures "
                    "shear and gust fronts within one crown."},
    {.path = "forest.species[].rigid_bodies",
     .constraint = "only for a species whose `dynamics` is `rigid_bodies`",
     .description = "Articulated rigid branches (`dynamics: rigid_bodies`)."},
    {.path = "forest.species[].rigid_bodies.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = kDynamicsDefaults.rigid_bodies.damping_ratio,
     .description =
         "Damping ratio zeta of the tree's first mode. The joints' damping is proportional to their "
         "stiffness, C = 2 zeta / omega_1 K with omega_1 the species' first FEM frequency, so that "
         "the slowest sway decays as a modal tree's with the same ratio."},
    {.path = "forest.species[].springs",
     .constraint = "only for a species whose `dynamics` is `springs`",
     .description = "Quasi-static cantilever springs (`dynamics: springs`)."},
    {.path = "forest.species[].springs.max_angle_deg",
     .type = Type::number,
     .unit = "degrees",
     .bound = Bound::positive,
     .below = kSpringMaxAngleBelowDeg,
     .number = kDynamicsDefaults.springs.max_angle_deg,
     .description = "The largest bend of one element from its parent, theta_max (Yildiz's cap)."},
    {.path = "forest.species[].springs.sway_amplitude",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = kDynamicsDefaults.springs.sway_amplitude,
     .description = "The stochastic sine's amplitude at the largest bend: an element's load is F (1 + a "
                    "sin(2 pi f t + b)), with a = `sway_amplitude` theta / theta_max (a bent element sways "
                    "more) and a random phase b per element."},
    {.path = "forest.species[].springs.sway_frequency",
     .type = Type::number,
     .unit = "Hz",
     .bound = Bound::positive,
     .number = kDynamicsDefaults.springs.sway_frequency_hz,
     .description = "f, the stochastic sine's frequency."},
    {.path = "forest.species[].drag_coefficient",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = kDragDefaults.branch_drag_coefficient,
     .description =
         "Drag coefficient C_D of the branches, as cylinders in cross flow: the drag is 1/2 rho_air "
         "C_D D L \\|u\\| u per element of diameter D and length L, with air density 1.225 kg/m^3. "
         "Used for the wind load on the tree and for its drag on the wind."},
    {.path = "forest.species[].canopy",
     .description = "Foliage: its leaf area and drag. The single leaves of `leaves` sit on it."},
    {.path = "forest.species[].canopy.leaf_area_index",
     .type = Type::number,
     .unit = "m^2/m^2",
     .bound = Bound::non_negative,
     .number = 0.0,
     .default_note = "`0` (no leaves)",
     .description = "One-sided leaf area per ground area under the crown. The crown's ground area is the "
                    "horizontal convex hull of the tree's branches (the trunk excluded)."},
    {.path = "forest.species[].canopy.drag_coefficient",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = kDragDefaults.leaf_drag_coefficient,
     .description = "Drag coefficient C_D of the leaves, in the convention of the branches' "
                    "`drag_coefficient`: the drag is 1/2 rho_air C_D A \\|u\\| u per one-sided leaf area A. "
                    "The default 0.4 makes 1/2 C_D = 0.2, the canopy drag coefficient C_d of canopy LES in "
                    "the form C_d a \\|u\\| u (Shaw & Schumann 1992)."},
    {.path = "forest.species[].leaves",
     .default_note = "none (no leaves)",
     .description =
         "Single leaves that flutter in the wind, shed when it pulls harder than their petioles hold, "
         "and fly until they land or leave the domain (docs/leaves.md has the model). They sit on the "
         "canopy's foliage, so the species needs `canopy.leaf_area_index` > 0. Without `leaves` the "
         "species has no single leaves; the canopy's drag is the same either way."},
    {.path = "forest.species[].leaves.model",
     .type = Type::word,
     .words = kLeafModelWords,
     .word = word_of(kLeafModelWords, kLeafModels, kLeafDefaults.model),
     .description =
         "How attached leaves flutter. `pseudo_branch`: each leaf turns about its branch, a damped "
         "oscillator driven by the wind normal to the blade (Oliapuram 2010). `stochastic`: three "
         "sine angles per leaf whose amplitudes grow with the wind speed (Ota et al. 2004). `none`: "
         "no leaves (a winter tree)."},
    {.path = "forest.species[].leaves.area",
     .type = Type::number,
     .unit = "m^2",
     .bound = Bound::positive,
     .number = kLeafDefaults.area,
     .description =
         "One-sided area a of one leaf (a square blade of side sqrt(a) on a petiole half as long). "
         "The species holds N = round(`fraction` × A_leaf / a) leaves, where A_leaf = "
         "`canopy.leaf_area_index` × the crown's ground area is its one-sided leaf area; every tree "
         "of the species carries the same leaves, scaled and turned with it."},
    {.path = "forest.species[].leaves.fraction",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = trees::LeafSettings::kMaxFraction,
     .number = kLeafDefaults.fraction,
     .description = "Share of the foliage's leaves that are simulated. Below 1, a thinned sample of the same "
                    "leaves, each of the real size, for big forests."},
    {.path = "forest.species[].leaves.mass_per_area",
     .type = Type::number,
     .unit = "kg/m^2",
     .bound = Bound::positive,
     .number = kLeafDefaults.mass_per_area,
     .description = "Leaf mass per area sigma: a leaf's mass is sigma a."},
    {.path = "forest.species[].leaves.frequency",
     .type = Type::number,
     .unit = "Hz",
     .bound = Bound::positive,
     .number = kLeafDefaults.frequency,
     .description = "Flutter frequency f_leaf: the natural frequency of the `pseudo_branch` oscillator; for "
                    "`stochastic`, the angles' frequency, with a jitter of ±20% per leaf and angle."},
    {.path = "forest.species[].leaves.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .below = trees::LeafSettings::kDampingRatioBelow,
     .number = kLeafDefaults.damping_ratio,
     .description = "Damping ratio zeta of the `pseudo_branch` oscillator. Low, so that leaves flutter; the "
                    "air damps their motion too."},
    {.path = "forest.species[].leaves.petiole_strength",
     .type = Type::number,
     .unit = "N",
     .bound = Bound::positive,
     .number = kLeafDefaults.petiole_strength,
     .description =
         "Median petiole strength S. Each leaf draws its own S from a log-normal distribution and "
         "sheds when the wind's normal force on its blade, 1/2 rho C_n a \\|u . n\\| \\|u\\| (C_n = "
         "1.2), exceeds it."},
    {.path = "forest.species[].leaves.strength_spread",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = kLeafDefaults.strength_spread,
     .description =
         "Log-standard deviation of the petiole strengths: the wider, the more gradually the leaves "
         "shed as the wind rises (0: all at once)."},
    {.path = "forest.species[].leaves.flight_drag_coefficient",
     .type = Type::number,
     .bound = Bound::positive,
     .number = kLeafDefaults.flight_drag_coefficient,
     .description =
         "Drag coefficient C_D of a tumbling leaf in flight, per one-sided area. In still air a leaf "
         "falls at sqrt(2 sigma g / (rho C_D)), 1.28 m/s at the defaults."},
    {.path = "forest.species[].leaves.amplitudes",
     .type = Type::point3,
     .unit = "degrees",
     .bound = Bound::non_negative,
     .at_most = trees::LeafSettings::kMaxAmplitudeDeg,
     .components = kLeafDefaults.amplitudes_deg,
     .noun = "[W_H, W_V, W_R]",
     .description = "`stochastic` only: the amplitudes of the three angles at and above `reference_speed`, "
                    "about the vertical (W_H), about the branch (W_V) and about the petiole (W_R)."},
    {.path = "forest.species[].leaves.roll_coupling",
     .type = Type::number,
     .number = kLeafDefaults.roll_coupling,
     .description = "`stochastic` only: a, the roll angle's share of the horizontal angle (theta_R gains a "
                    "theta_H)."},
    {.path = "forest.species[].leaves.reference_speed",
     .type = Type::number,
     .unit = "m/s",
     .bound = Bound::positive,
     .number = kLeafDefaults.reference_speed,
     .description =
         "`stochastic` only: U_ref. The angles' amplitudes scale with min(1, \\|u\\| / U_ref), u the "
         "wind at the leaf."},
    {.path = "forest.species[].leaves.seed",
     .type = Type::seed,
     .default_note = "global `seed` + 2^32 + species index",
     .description =
         "Seed of the leaves' positions, angles and petiole strengths. The same seed gives the same "
         "leaves on every machine."},
    // forest.stands
    {.path = "forest.stands[].species",
     .type = Type::text,
     .required = true,
     .noun = "a species name",
     .allowed = "the name of a species in `forest.species`",
     .description = "Species of every tree in the stand."},
    {.path = "forest.stands[].region",
     .required = true,
     .description = "Horizontal rectangle the trees stand in."},
    {.path = "forest.stands[].region.min",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .allowed = "inside the domain's horizontal extent, edges included",
     .description = "South-west corner."},
    {.path = "forest.stands[].region.max",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .allowed = "inside the domain's horizontal extent; x and y both larger than `min`",
     .description = "North-east corner."},
    {.path = "forest.stands[].layout",
     .type = Type::word,
     .words = kLayoutWords,
     .word = "poisson",
     .description = "`poisson`: a natural stand, with no two trees closer than `spacing` and no gaps much "
                    "wider than twice `spacing`. `grid`: rows and columns `spacing` apart, centred in the "
                    "region."},
    {.path = "forest.stands[].spacing",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .constraint = "`2 (width / spacing + 1) (depth / spacing + 1)`, a bound on the trees the region holds, "
                   "at most {0}, where width and depth are the region's extents",
     .limits = {double(trees::kMaxTreesPerStand)},
     .description = "Minimum distance between trees (`poisson`) or exact distance (`grid`)."},
    {.path = "forest.stands[].scale",
     .default_note = "`{min: 1, max: 1}`",
     .description =
         "Range of uniform tree scales. A tree scaled by s is s times as tall, and its frequencies "
         "are divided by s."},
    {.path = "forest.stands[].scale.min",
     .type = Type::number,
     .bound = Bound::positive,
     .number = 1.0,
     .constraint = "<= `scale.max`",
     .description = "Smallest scale."},
    {.path = "forest.stands[].scale.max",
     .type = Type::number,
     .bound = Bound::positive,
     .number = 1.0,
     .constraint = ">= `scale.min`",
     .description = "Largest scale."},
    {.path = "forest.stands[].seed",
     .type = Type::seed,
     .default_note = "global `seed` + stand index",
     .description = "Seed for positions, yaws and scales. The same seed gives the same stand."},
    {.path = "forest.stands[].leaf_area_index",
     .type = Type::number,
     .unit = "m^2/m^2",
     .bound = Bound::positive,
     .at_most = trees::StandDensity::kMaxLeafAreaIndex,
     .default_note = "none: the species' `canopy.leaf_area_index` on every crown",
     .description =
         "The stand's leaf area index as measured in the field: one-sided leaf area of the stand's trees "
         "per m^2 of its region. The stand's trees then carry the species' foliage scaled so that their "
         "leaf area (whole crowns) over the region's area is this figure, in place of the species' "
         "`canopy.leaf_area_index`, which stays for the species' other stands and single trees. Their "
         "leaves are scaled with the foliage. The upper limit is the largest leaf area index of the "
         "field measurements Asner, Scurlock & Hicke (2003) kept after their outlier analysis."},
    // forest.trees
    {.path = "forest.trees[].species",
     .type = Type::text,
     .required = true,
     .noun = "a species name",
     .allowed = "the name of a species in `forest.species`",
     .description = "Species of the tree."},
    {.path = "forest.trees[].position",
     .type = Type::point2_or_3,
     .unit = "m",
     .required = true,
     .allowed = "inside the domain, edges included",
     .description = "Position of the root. Without z, the tree stands on the ground: the terrain surface, "
                    "else the domain floor."},
    {.path = "forest.trees[].yaw",
     .type = Type::number,
     .unit = "degrees",
     .number = 0.0,
     .description = "Rotation about +z, counter-clockwise seen from above."},
    {.path = "forest.trees[].scale",
     .type = Type::number,
     .bound = Bound::positive,
     .number = 1.0,
     .description = "Uniform scale of the species' skeleton."},
    // solver
    {.path = "solver", .description = "Wind solver settings."},
    {.path = "solver.pressure",
     .type = Type::word,
     .words = kPressureWords,
     .word = "cg",
     .description = "Pressure solver. `cg`: conjugate gradients preconditioned by a multigrid V-cycle. "
                    "`multigrid`: V-cycles alone. `jacobi`: a fixed number of Jacobi sweeps (the baseline)."},
    {.path = "solver.tolerance",
     .type = Type::number,
     .bound = Bound::positive,
     .number = fluid::kDefaultPressureTolerance,
     .description = "Relative residual `\\|\\|b - A p\\|\\| / \\|\\|b\\|\\|` at which `cg` and `multigrid` "
                    "stop. In float32, values below about 1e-5 cannot be reached."},
    {.path = "solver.max_iterations",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = kPressureDefaults.max_iterations,
     .description = "Most CG iterations or V-cycles per solve (`cg`, `multigrid`)."},
    {.path = "solver.jacobi_iterations",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = kPressureDefaults.jacobi_iterations,
     .description = "Sweeps per solve (`jacobi`)."},
    {.path = "solver.advection",
     .type = Type::word,
     .words = kAdvectionWords,
     .word = "semi_lagrangian",
     .description = "Advection scheme of the momentum. `semi_lagrangian`: back-traced, stable at any "
                    "Courant number, damps eddies under about 15 cells. `maccormack` (clamped) keeps "
                    "gusts sharper. `upwind5`: flux-form fifth-order upwind with three Runge-Kutta stages "
                    "(Wicker & Skamarock 2002, as PALM and WRF), conservative, resolves eddies down to "
                    "about 6 to 7 cells, stable up to a summed Courant number of 1.2; third and then "
                    "first order over the last cells before walls, inflow and outflow faces and solids."},
    {.path = "solver.stage_projection",
     .type = Type::word,
     .words = kStageProjectionWords,
     .word = "final_stage",
     .description = "With `upwind5`: `final_stage` projects once a step, after the last Runge-Kutta stage; "
                    "`every_stage` also projects the first two stages (three pressure solves a step)."},
    {.path = "solver.vorticity_confinement",
     .type = Type::number,
     .bound = Bound::non_negative,
     .number = fluid::WindSettings{}.vorticity_confinement,
     .default_note = "`0` (off)",
     .description = "Vorticity confinement strength epsilon."},
    {.path = "solver.subgrid",
     .type = Type::word,
     .words = kSubgridWords,
     .word = "smagorinsky",
     .description =
         "Model of the subgrid stress. `smagorinsky`: the eddy viscosity `(C_s h)^2 \\|S\\|` of "
         "`smagorinsky_constant`, on while that is above 0. `tke`: Deardorff's 1.5-order closure "
         "(as PALM): each cell carries a subgrid kinetic energy e, advected, diffused, produced by "
         "the strain and by the canopy's wakes, dissipated and drained by the canopy's drag; the "
         "eddy viscosity is `C_m l sqrt(e)`, C_m = 0.1, l = h (0.9 h on a wall). With `tke`, leave "
         "`smagorinsky_constant` out. docs/numerics.md, \"Subgrid energy\"."},
    {.path = "solver.smagorinsky_constant",
     .type = Type::number,
     .bound = Bound::non_negative,
     .below = fluid::WindSettings::kSmagorinskyConstantBelow,
     .number = fluid::WindSettings{}.smagorinsky_constant,
     .default_note = "`0` (off); `0.16` with `advection: upwind5`",
     .description =
         "With `subgrid: smagorinsky`: the constant C_s of the subgrid eddy viscosity `nu_t = (C_s h)^2 "
         "\\|S\\|`, h = `domain.cell_size` and `\\|S\\| = sqrt(2 S_ij S_ij)` the resolved strain rate: "
         "the stress of the eddies smaller than a cell, which drains energy at the grid scale. Typical "
         "0.1 to 0.2 (0.17 for isotropic turbulence, Lilly 1967; smaller in shear near walls). "
         "`upwind5` dissipates too little on its own, so it gets 0.16 unless this names another (`0` "
         "turns it off): the smallest constant that keeps decaying turbulence on the -5/3 line, without "
         "a pile-up, down to 6 cells (docs/numerics.md). `semi_lagrangian` and `maccormack` drain the "
         "cascade themselves."},
    // output
    {.path = "output", .description = "What to write, and where."},
    {.path = "output.directory",
     .type = Type::directory,
     .word = "out/<scenario>",
     .noun = "a directory path",
     .allowed = "non-empty; relative to the **current working directory**",
     .description = "Output folder, created when the run starts. `forestwind run -o DIR` overrides it."},
    {.path = "output.interval",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::positive,
     .number = 1.0,
     .description = "Simulated time between output frames."},
    {.path = "output.probe_interval",
     .type = Type::number_or_auto,
     .unit = "s",
     .bound = Bound::positive,
     .word = "auto",
     .default_note = "`auto`: every solver step with `wind.turbulence`, else `output.interval`",
     .description = "Simulated time between the rows of `probes.csv`, independent of the frames, so that a "
                    "probe's record is fine enough for spectra (its Nyquist frequency is 1 / (2 "
                    "`probe_interval`))."},
    {.path = "output.vtk", .description = "ParaView output."},
    {.path = "output.vtk.wind",
     .type = Type::boolean,
     .flag = true,
     .description = "Write `wind.pvd` with `wind/wind_NNNNNN.vti`."},
    {.path = "output.vtk.trees",
     .type = Type::boolean,
     .flag = true,
     .description = "Write `trees.pvd` with `trees/trees_NNNNNN.vtp` (when there are trees)."},
    {.path = "output.vtk.wind_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = 1,
     .description =
         "Write `wind.pvd` on every N-th frame only: the frames K (0, 1, 2, ... every `output.interval`) "
         "with K mod N = 0. A file keeps its frame's number, so that the collections of different "
         "outputs line up in time. To keep the folder small (`forestwind check` predicts its size)."},
    {.path = "output.vtk.trees_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = 1,
     .description = "As `output.vtk.wind_every`, for `trees.pvd`."},
    {.path = "output.vtk.fields",
     .type = Type::word_set,
     .words = kVtkFieldWords,
     .chosen = kVtkFieldWords,
     .description = "Arrays in the wind `.vti` files. `pressure` is the kinematic pressure p/rho (m^2/s^2). "
                    "`canopy_density` is the trees' frontal area density (1/m)."},
    {.path = "output.vdb", .description = "OpenVDB output (Houdini, Blender)."},
    {.path = "output.vdb.enabled",
     .type = Type::boolean,
     .flag = false,
     .description = "Write `vdb/wind.NNNN.vdb` per frame."},
    {.path = "output.vdb.grids",
     .type = Type::word_set,
     .words = kVdbGridWords,
     .chosen = kVdbGridWords,
     .description =
         "Grids in each VDB file: `vel` (Vec3s, m/s), `speed` (float, m/s), `leaves` (a points grid "
         "of the written leaves with `P`, `N`, `state`, `tree_id` and `pscale`; in runs with "
         "leaves, ignored in runs without)."},
    {.path = "output.vdb.every",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = 1,
     .description = "As `output.vtk.wind_every`, for the VDB files."},
    {.path = "output.leaves", .description = "Leaves in the frames (runs whose species have `leaves`)."},
    {.path = "output.leaves.attached",
     .type = Type::integer_or_word,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .words = kLeafStrideWords,
     .word = "all",
     .description =
         "Which attached leaves the frames hold (`leaves.pvd` and the VDB `leaves` grid): `all`, "
         "`none`, or the attached leaves whose index among their tree's leaves is a multiple of N "
         "(the same leaves in every frame, however many have been shed and however the run is "
         "split over MPI ranks), to keep the files of a big forest small. Flying and landed leaves "
         "are always written, leaves that left the domain never."},
    {.path = "output.leaves.vtk",
     .type = Type::boolean,
     .flag = true,
     .description = "Write `leaves.pvd` with `leaves/leaves_NNNNNN.vtp` (when the run has leaves)."},
    {.path = "output.leaves.every",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = 1,
     .description =
         "As `output.vtk.wind_every`, for `leaves.pvd` (the VDB `leaves` grid comes with the VDB files)."},
    {.path = "output.probes",
     .type = Type::list,
     .noun = "a list of probes",
     .description = "Points where `probes.csv` records the wind velocity every `probe_interval`."},
    {.path = "output.probes[].name",
     .type = Type::text,
     .required = true,
     .noun = "a probe name",
     .allowed = "letters, digits and `_`; unique",
     .description = "Probe name, used in the column names `<name>_u`, `<name>_v`, `<name>_w`."},
    {.path = "output.probes[].position",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .allowed = "inside the domain, faces included",
     .description = "Probe location. The velocity there is interpolated trilinearly."},
    {.path = "output.checkpoint",
     .description = "Checkpoints of the whole state in `checkpoints/`, from which `forestwind run --resume` "
                    "continues bit for bit. Without this key a run still writes one when a signal stops it "
                    "(SIGTERM, SIGUSR1, SIGINT)."},
    {.path = "output.checkpoint.interval",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .description = "Simulated time between checkpoints; the run also writes one when it reaches its end, "
                    "so that it can be extended."},
    {.path = "output.checkpoint.keep",
     .type = Type::integer,
     .lowest = 1,
     .highest = kNoUpperLimit,
     .number = 2,
     .description = "How many of the newest checkpoints are kept; older ones are removed."},
};

// --- look-ups ----------------------------------------------------------------------------------------------

/// The key at a generic path, at compile time: a path not in the table does not compile.
consteval const Key& key(std::string_view path) {
  for (const Key& entry : kKeys)
    if (entry.path == path) return entry;
  throw "not a key of the scenario schema";
}

/// Whether a generic path names a map of keys: the top level (""), a map or choice key, or the items of a
/// list ("forest.species[]").
consteval bool holds_keys(std::string_view path) {
  if (path.empty()) return true;
  const bool items = path.ends_with("[]");
  if (items) path.remove_suffix(2);
  for (const Key& entry : kKeys) {
    if (entry.path != path) continue;
    return items ? entry.type == Type::list || entry.type == Type::choice_list
                 : entry.type == Type::map || entry.type == Type::choice;
  }
  return false;
}

/// The key `name` below the map at generic path `parent` ("" for the top level), or nullptr; `name` may reach
/// further down ("canopy.leaf_area_index"). Usable at compile time.
constexpr const Key* find(std::string_view parent, std::string_view name) {
  for (const Key& entry : kKeys) {
    const std::string_view path = entry.path;
    if (parent.empty() ? path == name
                       : path.size() == parent.size() + 1 + name.size() && path.starts_with(parent) &&
                             path[parent.size()] == '.' && path.ends_with(name))
      return &entry;
  }
  return nullptr;
}

/// The key `name` below the map at `parent`, at compile time: a name the map lacks does not compile. The
/// loader's readers name their keys so (io/scenario/Reader.hpp).
///   schema::key("forest.species[]", "modes")   // the key forest.species[].modes
consteval const Key& key(std::string_view parent, std::string_view name) {
  if (const Key* found = find(parent, name)) return *found;
  throw "not a key of this map in the scenario schema";
}

/// The value of `word` (a key's default word, say) in a vocabulary and its values, aligned by position.
template <typename Enum, std::size_t N>
constexpr Enum value_of(const std::string_view (&words)[N], const Enum (&values)[N], std::string_view word) {
  for (std::size_t i = 0; i < N; ++i)
    if (words[i] == word) return values[i];
  throw "not a word of the vocabulary";
}

/// A vocabulary as strings (the defaults of the io::Scenario structs).
inline std::vector<std::string> strings(Words words) {
  return {words.begin(), words.end()};
}

/// The key at a generic path, or nullptr.
const Key* find(std::string_view path);

/// A file's dotted key with its list indices dropped: "forest.species[2].modes" -> "forest.species[].modes".
std::string generic_path(std::string_view key);
/// A generic path's key in item `index` of its (first) list: ("forest.stands[].spacing", 2) ->
/// "forest.stands[2].spacing". Where messages past the loader name a key of the file.
std::string item_path(std::string_view path, std::size_t index);

/// The keys directly below a map's generic path ("" for the top level, "events[]" for an event), in table
/// order.
std::vector<const Key*> children(std::string_view parent);
std::vector<std::string> child_names(std::string_view parent);

/// The vocabulary of a word or word_set key.
std::vector<std::string> words(const Key& key);

/// The "... expected" part of the loader's messages for a value of this key, e.g. "a number > 0 (s)".
std::string expected(const Key& key);

/// docs/scenario.md with each block between a line "<!-- schema: SECTION -->" and the next line
/// "<!-- end schema -->" replaced by the key table of SECTION: a generic path ("time", "forest.species[]") or
/// "(top level)". A key goes to the longest SECTION it equals or lies below ("forest.species[].name" to
/// "forest.species[]", "forest.species" to "forest"); "(top level)" takes the top-level keys no other SECTION
/// takes. Throws std::invalid_argument for a marker left open, a SECTION without keys, or a key of the table
/// that no SECTION takes (so every key is documented).
std::string render_scenario_docs(std::string_view page);

}  // namespace fw::io::schema
