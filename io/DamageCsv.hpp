// damage.csv (docs/damage.md, "Outputs"): one row per tree of what the storm did to it, written whole.
//
//   std::vector<fw::io::DamageTree> trees = ...;           // what never changes: id, species, place, size
//   std::string text = fw::io::damage_csv(trees, records);  // records: trees::TreeDamageRecord, same order
//   fw::base::write_text_atomically("DamageCsv", dir / "damage.csv", text);
//
// Columns: tree_id, species, x, y (m, the root's position), height_m, dbh_m, state (standing, broken,
// overturned), time_s (when it failed; empty while standing), break_height_m (m above the root; 0 when
// overturned, empty while standing), top_wind_m_s (the wind speed at its top when it failed; empty while
// standing), max_base_moment_Nm (the largest root moment over the run), critical_breakage_Nm (M_b at the
// base), critical_overturning_Nm (M_o), max_utilisation (the largest applied-to-critical ratio of any stem
// section or the root over the run), inventory_id (the tree's id in the forest inventory, docs/gis.md; empty
// for a tree not from one). Comma-separated, a header line, '\n' line ends; numbers with 9 significant
// digits, time with 12; an id holding a comma, a quote or a line end is quoted as RFC 4180 quotes it.
#pragma once

#include <string>
#include <vector>

#include "trees/TreeDamage.hpp"

namespace fw::io {

/// What damage.csv says of a tree that never changes.
struct DamageTree {
  int id = 0;                         ///< the tree's id (trees::Forest::id)
  std::string species;                ///< its species' name (no comma, quote or line break)
  double x = 0.0, y = 0.0;            ///< m, its root
  double height = 0.0, dbh = 0.0;     ///< m
  double critical_breakage = 0.0;     ///< N m, M_b at the base
  double critical_overturning = 0.0;  ///< N m, M_o
  std::string inventory_id;           ///< its id in the inventory; empty for a tree not from one
};

/// The header line, without its line end.
std::string damage_csv_header();
/// The whole file: the header and one row per tree. Throws std::invalid_argument("DamageCsv: ...") when the
/// two lists differ in length.
std::string damage_csv(const std::vector<DamageTree>& trees,
                       const std::vector<trees::TreeDamageRecord>& records);

}  // namespace fw::io
