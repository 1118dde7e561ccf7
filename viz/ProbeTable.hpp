// probes.csv read back (its layout: io/ProbesCsv.hpp): the sample times and, per probe, its wind; per
// tracked tree, its tip displacement; in a run with storm damage, how many trees stand, are broken and are
// overturned.
//
//   fw::viz::ProbeTable table = fw::viz::read_probe_table("out/storm/probes.csv");
//   for (const auto& probe : table.probes) plot(table.time, probe.speed());
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fw::viz {

struct ProbeSeries {
  std::string name;                        ///< the probe's name, or "tree<id>" for a tree's tip
  std::vector<std::array<double, 3>> xyz;  ///< per sample: wind (m/s) or tip displacement (m)
  /// |xyz| per sample.
  std::vector<double> magnitude() const;
};

/// How many trees stand, are broken and are overturned at each of `time` (storm damage, docs/damage.md).
struct DamageCounts {
  std::vector<double> time;  ///< s
  std::vector<int> standing, broken, overturned;
};

struct ProbeTable {
  std::vector<double> time;         ///< s, one per row
  std::vector<ProbeSeries> probes;  ///< wind probes, in column order
  std::vector<ProbeSeries> tips;    ///< tracked trees' tips, in column order
  /// The columns trees_standing,trees_broken,trees_overturned of a run with forest.damage.enabled, at
  /// every row (its time is `time`); none without them. Initialised so that an aggregate initializer may
  /// leave it out without -Wmissing-field-initializers.
  std::optional<DamageCounts> damage = std::nullopt;
};

/// Reads a probes.csv. Throws std::invalid_argument("FILE:LINE: ...") for a header that is not time_s
/// followed by <name>_u,_v,_w / tree<id>_tip_dx,_dy,_dz triples, then optionally the leaf counts leaves_*
/// (skipped) and the tree counts trees_standing,trees_broken,trees_overturned, or a row with another number
/// of values, a value that is not a number or a tree count that is not a whole number; std::runtime_error
/// when the file cannot be opened. A last line without its line end (a run killed mid-write) is ignored.
ProbeTable read_probe_table(const std::filesystem::path& path);

}  // namespace fw::viz
