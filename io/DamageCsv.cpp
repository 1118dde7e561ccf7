#include "io/DamageCsv.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::io {

std::string damage_csv_header() {
  return "tree_id,species,x,y,height_m,dbh_m,state,time_s,break_height_m,top_wind_m_s,max_base_moment_Nm,"
         "critical_breakage_Nm,critical_overturning_Nm,max_utilisation,inventory_id";
}

namespace {

// RFC 4180: a field holding a comma, a quote or a line end is quoted, its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

std::string damage_csv(const std::vector<DamageTree>& trees,
                       const std::vector<trees::TreeDamageRecord>& records) {
  if (trees.size() != records.size())
    throw std::invalid_argument(
        fmt::format("DamageCsv: {} trees and {} damage records", trees.size(), records.size()));
  std::string text = damage_csv_header() + "\n";
  for (std::size_t k = 0; k < trees.size(); ++k) {
    const DamageTree& t = trees[k];
    const trees::TreeDamageRecord& r = records[k];
    const bool failed = r.state != trees::TreeState::standing;
    text += fmt::format("{},{},{:.9g},{:.9g},{:.9g},{:.9g},{},", t.id, t.species, t.x, t.y, t.height, t.dbh,
                        trees::tree_state_name(r.state));
    text += failed ? fmt::format("{:.12g},{:.9g},{:.9g},", r.time, r.break_height, r.top_wind.norm()) : ",,,";
    text += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{}\n", r.max_base_moment, t.critical_breakage,
                        t.critical_overturning, r.max_utilisation, csv_field(t.inventory_id));
  }
  return text;
}

}  // namespace fw::io
