// probes.csv read back (its layout: io/ProbesCsv.hpp): the sample times and, per probe, its wind; per
// tracked tree, its tip displacement.
//
//   fw::viz::ProbeTable table = fw::viz::read_probe_table("out/storm/probes.csv");
//   for (const auto& probe : table.probes) plot(table.time, probe.speed());
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace fw::viz {

struct ProbeSeries {
  std::string name;                        ///< the probe's name, or "tree<id>" for a tree's tip
  std::vector<std::array<double, 3>> xyz;  ///< per sample: wind (m/s) or tip displacement (m)
  /// |xyz| per sample.
  std::vector<double> magnitude() const;
};

struct ProbeTable {
  std::vector<double> time;         ///< s, one per row
  std::vector<ProbeSeries> probes;  ///< wind probes, in column order
  std::vector<ProbeSeries> tips;    ///< tracked trees' tips, in column order
};

/// Reads a probes.csv. Throws std::invalid_argument("FILE:LINE: ...") for a header that is not
/// time_s followed by <name>_u,_v,_w / tree<id>_tip_dx,_dy,_dz triples (leaf counts after them are skipped),
/// or a row with another number of values or a value that is not a number; std::runtime_error when the
/// file cannot be opened. A last line without its line end (a run killed mid-write) is ignored.
ProbeTable read_probe_table(const std::filesystem::path& path);

}  // namespace fw::viz
