// damage.csv read back: what storm damage did to each tree of a run (forest.damage.enabled; the run writes
// the file into its output folder whole, through a rename, at every frame and at the end, so it holds the
// state at the last frame written). One row per tree: where it stands, its size, what happened to it and
// when, and the largest load it took against its strength.
//
//   fw::viz::DamageTable damage = fw::viz::read_damage_table("out/storm/damage.csv");
//   for (const fw::viz::DamagedTree& tree : damage.trees)
//     if (tree.state_at(frame_time) == fw::trees::TreeState::broken) mark(tree.x, tree.y);
//
// Reading rules; a file that breaks one throws base::SourceError "FILE:LINE: COLUMN: what was expected, got
// 'what was there'" (exit 2 on the command line):
// - Line 1, the header, starts with these 14 columns in this order: tree_id, species, x, y, height_m, dbh_m,
//   state, time_s, break_height_m, top_wind_m_s, max_base_moment_Nm, critical_breakage_Nm,
//   critical_overturning_Nm, max_utilisation. Columns after them are allowed and ignored (a later writer may
//   add some).
// - Every later line is one tree: as many comma-separated values as the header has columns (no quoting).
//   Empty lines are skipped; the last line may lack its line end (the file is written whole, so it is a
//   whole row). A header alone is a stand of no trees.
// - tree_id: a whole number >= 0, each tree once; species: any text but empty; x, y: finite numbers (m, the
//   root in the run's world frame); height_m, dbh_m: finite numbers > 0.
// - state: standing, broken or overturned.
// - A standing tree has time_s, break_height_m and top_wind_m_s empty. A value there is an error, not
//   tolerated: the writer leaves them empty, and a standing tree with a failure time is a row that
//   contradicts itself (it could be drawn either way).
// - A failed tree has all three: time_s a finite number >= 0 (s); break_height_m, for a broken tree, a
//   number from 0 to height_m, for an overturned one 0; top_wind_m_s a finite number >= 0 (m/s).
// - max_base_moment_Nm a finite number >= 0; critical_breakage_Nm and critical_overturning_Nm finite numbers
//   > 0 (N m); max_utilisation a finite number >= 0, and >= 1 for a failed tree.
// Numbers are base::parse_number's: locale independent, a leading '+' allowed, no space, nan and inf
// refused.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "trees/TreeDamage.hpp"
#include "viz/ProbeTable.hpp"

namespace fw::viz {

/// The columns damage.csv starts with, in order.
inline constexpr std::array<const char*, 14> kDamageColumns{"tree_id",
                                                            "species",
                                                            "x",
                                                            "y",
                                                            "height_m",
                                                            "dbh_m",
                                                            "state",
                                                            "time_s",
                                                            "break_height_m",
                                                            "top_wind_m_s",
                                                            "max_base_moment_Nm",
                                                            "critical_breakage_Nm",
                                                            "critical_overturning_Nm",
                                                            "max_utilisation"};

/// One row of damage.csv.
struct DamagedTree {
  int id = 0;
  std::string species;
  double x = 0.0, y = 0.0;                              ///< m, the root
  double height = 0.0, dbh = 0.0;                       ///< m
  trees::TreeState state = trees::TreeState::standing;  ///< at the last frame written
  std::optional<double> time;                           ///< s, when it failed; none while standing
  std::optional<double> break_height;  ///< m above the root (broken), 0 (overturned); none while standing
  std::optional<double> top_wind;      ///< m/s at its top when it failed; none while standing
  double max_base_moment = 0.0;        ///< N m
  double critical_breakage = 0.0;      ///< N m, the least breaking moment of its stem
  double critical_overturning = 0.0;   ///< N m
  double max_utilisation = 0.0;        ///< the largest applied-to-critical ratio up to the last frame
  int line = 0;                        ///< its line in the file, for messages

  /// Its state at `time` (s): standing before its failure time, `state` from then on. A time within a
  /// millionth (relative, at least 1e-6 s) of the failure counts as after it: the frames' times and
  /// damage.csv's are written with different numbers of digits.
  trees::TreeState state_at(double time) const;
};

struct DamageTable {
  std::filesystem::path file;
  std::vector<DamagedTree> trees;  ///< in the file's order

  /// How many trees stand, are broken and are overturned at `time` (state_at).
  std::array<int, 3> counts_at(double time) const;
  /// The counts as a series over [start, end] (s): at `start`, at every failure time inside, one point each
  /// (the count from then on), and at `end`; what probes.csv's tree count columns hold, but at the exact
  /// failure times. Failures before `start` are in every point; end < start is taken as start.
  DamageCounts counts_over(double start, double end) const;
};

/// Reads a damage.csv by the rules above. Throws base::SourceError: "FILE: cannot open: ..." when it cannot
/// be read, "FILE:LINE: COLUMN: ..." for a bad header or row.
DamageTable read_damage_table(const std::filesystem::path& path);

}  // namespace fw::viz
