// A scenario file (docs/design.md, "File formats"), read and validated in full before anything is computed.
// Each section of the file is a struct of its own in io/settings/ (TimeSettings, WindSource, ForestSettings,
// ...), and io::WindScenario (io/WindScenario.hpp) is the scenario without its forest and outputs; a file
// that reads only some sections includes only theirs. Every key's type, unit, default and allowed values are
// defined once, in the schema (io/schema/, one table per section; io/ScenarioSchema.hpp over all of them):
// the structs' defaults are read from there, and docs/scenario.md's key tables are generated from there.
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
// and the loader converts them once: every struct of io/settings/ holds radians (yaw_rad, as
// fluid::SolidBox, trees::PlacedTree and trees::TreeInstance do). Relative paths in the file (skeletons,
// heightmap) resolve against the scenario file's folder; the output directory resolves against the current
// working directory at load time.
//
// Validation is strict: unknown keys at any level, duplicate keys, wrong types, missing required keys,
// out-of-range numbers, unknown enum words, positions outside the domain, missing or unreadable files and
// bad expressions are all errors. Every error is a ScenarioError whose what() reads exactly
//   FILE:LINE: KEY: what was expected[, got 'VALUE']
// with LINE 1-based (0 when the file itself cannot be read) and KEY the dotted path of the offending key,
// e.g. "forest.species[0].modes.count".
#pragma once

#include <filesystem>
#include <optional>

#include "io/ScenarioError.hpp"
#include "io/WindScenario.hpp"
#include "io/settings/ForestSettings.hpp"
#include "io/settings/OutputSettings.hpp"

namespace fw::io {

/// The whole scenario: its wind's part (WindScenario: where it came from, time, domain, boundaries, wind,
/// events, obstacles, terrain, solver), the forest and the outputs.
struct Scenario : WindScenario {
  ForestSettings forest;
  OutputSettings output;

  /// Simulated time between probe samples, s: output.probe_interval when given; for auto, nullopt (every
  /// solver step) with wind.turbulence, else output.interval.
  std::optional<double> resolved_probe_interval() const;
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
