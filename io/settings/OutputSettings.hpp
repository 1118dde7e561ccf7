// The output section of a scenario (docs/scenario.md, "output"): the folder, the frame and probe intervals,
// the VTK, VDB and leaf outputs, the probes and the checkpoints. Defaults are the schema's
// (io/schema/OutputKeys.hpp).
//
//   fw::io::OutputSettings output;   // a frame a second, every VTK field
#pragma once

#include <array>
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
  /// output.checkpoint.interval, s; 0 without the key (checkpoints only when a signal stops the run).
  double checkpoint_interval = 0.0;
  /// the newest ones kept
  int checkpoints_kept = int(schema::key(schema::kOutputKeys, "output.checkpoint.keep").number);
};

}  // namespace fw::io
