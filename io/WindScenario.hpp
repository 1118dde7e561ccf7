// A scenario without its forest and its outputs: where it came from, and the sections the wind grid is made
// from (time, domain, boundaries, wind, events, obstacles, terrain, solver), with what they give at a time.
// io::Scenario (io/Scenario.hpp) adds the forest and the outputs. Whoever reads only this part of a scenario
// takes it (the wind's part of a run's plan, host/app/plan/WindPlan.cpp), and compiles none of the forest's
// or the outputs' keys; a Scenario binds to it.
//
//   void plan_wind(const fw::io::WindScenario& scenario, ...);
//   scenario.wind_vector(60.0);                           // m/s at the reference height, x east, y north
//   fw::fluid::GridSpec grid = scenario.grid_spec(0.0);   // "auto" faces resolved for the wind at t = 0
//   for (const auto& obstacle : scenario.obstacles)
//     std::visit([&](const auto& shape) { solids.add(shape); }, obstacle);
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/WindSettings.hpp"
#include "io/settings/BoundaryChoice.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/GustEvent.hpp"
#include "io/settings/Obstacle.hpp"
#include "io/settings/SolverSettings.hpp"
#include "io/settings/TerrainSettings.hpp"
#include "io/settings/TimeSettings.hpp"
#include "io/settings/WindSource.hpp"

namespace fw::io {

struct WindScenario {
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
  SolverSettings solver;

  /// The site a terrain.raster places the run on, or nullptr (io/settings/SiteSettings.hpp).
  const SiteSettings* site() const { return terrain && terrain->site ? &*terrain->site : nullptr; }

  /// The ambient wind at the reference height at time t (s), m/s, x east, y north: the wind blows TOWARD
  /// direction + 180 degrees, so v = -speed * (sin theta, cos theta, 0). Direction 270 blows toward +x.
  std::array<double, 3> wind_vector(double t) const;
  /// The grid with "auto" faces resolved for the wind at time t: inflow where wind_vector(t) points into
  /// the domain, outflow elsewhere (also where the wind runs parallel to the face). A rough ground is slip
  /// (its wall stress is a separate stage).
  fluid::GridSpec grid_spec(double t) const;
  /// Advection, pressure solver and time step as fluid::WindSettings (auto dt: cfl > 0; fixed: cfl = 0).
  fluid::WindSettings wind_settings() const;
};

}  // namespace fw::io
