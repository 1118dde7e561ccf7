// The output section of a scenario (docs/scenario.md, "output"): the folder, the frame and probe intervals,
// the VTK, VDB and leaf outputs, the probes and the checkpoints. Defaults are the schema's
// (io/schema/OutputKeys.hpp).
//
//   fw::io::OutputSettings output;   // a frame a second, every VTK field
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/schema/OutputKeys.hpp"

namespace fw::io {

struct Probe {
  std::string name;                  ///< [A-Za-z0-9_]+, unique
  std::array<double, 3> position{};  ///< m, inside the domain (faces included)
};

/// The group name of the statistics' region of stand N (from 1): stand_N.
inline constexpr std::string_view kStandRegionPrefix = "stand_";

/// The cells along one axis whose centres lie in [min, max] (m) on a grid from `origin` of `cells` cells of
/// `h`: [first, end), empty when none does.
inline std::array<int, 2> statistics_cells(double min, double max, double origin, double h, int cells) {
  const auto first = static_cast<int>(std::ceil((min - origin) / h - 0.5));
  const auto last = static_cast<int>(std::floor((max - origin) / h - 0.5));
  return {std::max(first, 0), std::min(last + 1, cells)};
}

/// A horizontal box the statistics average over on their own (output.statistics.regions[]).
struct StatisticsRegion {
  std::string name;             ///< [A-Za-z0-9_]+, unique
  std::array<double, 2> min{};  ///< m, south-west corner
  std::array<double, 2> max{};  ///< m, north-east corner
};

/// output.statistics: stats.nc's records (docs/statistics.md).
struct StatisticsSettings {
  double interval = 0.0;   ///< s between profile records, > 0
  double averaging = 0.0;  ///< s each record averages over, in [0, interval]
  int sample_every = int(schema::key(schema::kOutputKeys, "output.statistics.sample_every").number);
  int series_every = int(schema::key(schema::kOutputKeys, "output.statistics.series_every").number);
  bool stands = schema::key(schema::kOutputKeys, "output.statistics.stands").flag;
  std::vector<StatisticsRegion> regions;
};

struct OutputSettings {
  std::filesystem::path directory;  ///< absolute: the file's value (default out/<scenario>) against the cwd
  /// s of simulated time between frames, > 0
  double interval = schema::key(schema::kOutputKeys, "output.interval").number;
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
  /// leaves.pvd, in runs with leaves
  bool vtk_leaves = schema::key(schema::kOutputKeys, "output.leaves.vtk").flag;
  /// output.leaves.attached: the frames hold the attached leaves whose index on their tree is a multiple of
  /// N; 1 all, 0 none. Flying and landed leaves are always written.
  int leaves_attached_stride =
      schema::value_of(schema::kLeafStrideWords, schema::kLeafStrides,
                       schema::key(schema::kOutputKeys, "output.leaves.attached").word);
  std::vector<Probe> probes;
  /// output.statistics; nullopt without the key (no stats.nc).
  std::optional<StatisticsSettings> statistics;
  /// output.checkpoint.interval, s; 0 without the key (checkpoints only when a signal stops the run).
  double checkpoint_interval = 0.0;
  /// the newest ones kept
  int checkpoints_kept = int(schema::key(schema::kOutputKeys, "output.checkpoint.keep").number);
};

}  // namespace fw::io
