#include "viz/DamageTable.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "base/SourceError.hpp"
#include "base/TextNumber.hpp"
#include "viz/CsvText.hpp"

namespace fw::viz {

namespace {

// The relative tolerance of state_at: the frames' and damage.csv's times are written to 9 or more digits.
constexpr double kTimeTolerance = 1e-6;

enum Column {
  kTreeId,
  kSpecies,
  kX,
  kY,
  kHeight,
  kDbh,
  kState,
  kTime,
  kBreakHeight,
  kTopWind,
  kMaxBaseMoment,
  kCriticalBreakage,
  kCriticalOverturning,
  kMaxUtilisation
};

std::string quoted(const std::string& text) {
  return "'" + text + "'";
}

// One row's values, read column by column with the row's line for errors.
struct Row {
  const std::string& file;
  int line;
  const std::vector<std::string>& values;

  [[noreturn]] void fail(int column, const std::string& expected) const {
    throw base::SourceError(file, line, kDamageColumns[std::size_t(column)], expected,
                            quoted(values[std::size_t(column)]));
  }
  const std::string& text(int column) const { return values[std::size_t(column)]; }
  // A finite number >= lo (or > lo when `open`).
  double number(int column, double lo, bool open) const {
    const std::optional<double> value = base::parse_finite(text(column));
    if (!value || (open ? !(*value > lo) : !(*value >= lo)))
      fail(column, fmt::format("expected a number {} {:g}", open ? ">" : ">=", lo));
    return *value;
  }
  double finite(int column) const {
    const std::optional<double> value = base::parse_finite(text(column));
    if (!value) fail(column, "expected a number");
    return *value;
  }
};

trees::TreeState state_of(const Row& row) {
  for (trees::TreeState state :
       {trees::TreeState::standing, trees::TreeState::broken, trees::TreeState::overturned})
    if (row.text(kState) == trees::tree_state_name(state)) return state;
  row.fail(kState, "expected standing, broken or overturned");
}

DamagedTree tree_of(const Row& row) {
  DamagedTree t;
  t.line = row.line;
  const std::optional<int> id = base::parse_number<int>(row.text(kTreeId));
  if (!id || *id < 0) row.fail(kTreeId, "expected a whole number >= 0");
  t.id = *id;
  t.species = row.text(kSpecies);
  if (t.species.empty()) row.fail(kSpecies, "expected the species' name");
  t.x = row.finite(kX);
  t.y = row.finite(kY);
  t.height = row.number(kHeight, 0.0, true);
  t.dbh = row.number(kDbh, 0.0, true);
  t.state = state_of(row);
  if (t.state == trees::TreeState::standing) {
    for (int column : {kTime, kBreakHeight, kTopWind})
      if (!row.text(column).empty()) row.fail(column, "expected no value for a standing tree");
  } else {
    t.time = row.number(kTime, 0.0, false);
    if (t.state == trees::TreeState::broken) {
      t.break_height = row.number(kBreakHeight, 0.0, false);
      if (*t.break_height > t.height)
        row.fail(kBreakHeight, fmt::format("expected a height up to the tree's, {:g} m", t.height));
    } else {
      const std::optional<double> zero = base::parse_finite(row.text(kBreakHeight));
      if (!zero || *zero != 0.0) row.fail(kBreakHeight, "expected 0 for an overturned tree");
      t.break_height = 0.0;
    }
    t.top_wind = row.number(kTopWind, 0.0, false);
  }
  t.max_base_moment = row.number(kMaxBaseMoment, 0.0, false);
  t.critical_breakage = row.number(kCriticalBreakage, 0.0, true);
  t.critical_overturning = row.number(kCriticalOverturning, 0.0, true);
  t.max_utilisation = row.number(kMaxUtilisation, 0.0, false);
  if (t.state != trees::TreeState::standing && t.max_utilisation < 1.0)
    row.fail(kMaxUtilisation, fmt::format("expected a number >= 1 for a {} tree", row.text(kState)));
  return t;
}

}  // namespace

trees::TreeState DamagedTree::state_at(double t) const {
  if (!time || *time > t + kTimeTolerance * std::max(1.0, std::abs(t))) return trees::TreeState::standing;
  return state;
}

std::array<int, 3> DamageTable::counts_at(double t) const {
  std::array<int, 3> counts{0, 0, 0};
  for (const DamagedTree& tree : trees) ++counts[std::size_t(tree.state_at(t))];
  return counts;
}

DamageCounts DamageTable::counts_over(double start, double end) const {
  end = std::max(start, end);
  std::vector<double> times{start};
  for (const DamagedTree& tree : trees)
    if (tree.state_at(start) == trees::TreeState::standing &&
        tree.state_at(end) != trees::TreeState::standing)
      times.push_back(*tree.time);
  std::sort(times.begin() + 1, times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  if (times.back() < end) times.push_back(end);
  DamageCounts series;
  for (double t : times) {
    const std::array<int, 3> counts = counts_at(t);
    series.time.push_back(t);
    series.standing.push_back(counts[0]);
    series.broken.push_back(counts[1]);
    series.overturned.push_back(counts[2]);
  }
  return series;
}

DamageTable read_damage_table(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw base::SourceError::unreadable(file, fmt::format("cannot open: {}", std::strerror(errno)));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::vector<std::string> lines = csv_lines(buffer.str(), /*keep_unfinished_last=*/true);
  const std::vector<std::string> header =
      lines.empty() ? std::vector<std::string>{} : split_csv(lines[0], file, 1);
  for (std::size_t c = 0; c < kDamageColumns.size(); ++c)
    if (c >= header.size() || header[c] != kDamageColumns[c])
      throw base::SourceError(file, 1, "header",
                              fmt::format("expected column {} '{}' (a forestwind damage.csv starts with {})",
                                          c + 1, kDamageColumns[c], fmt::join(kDamageColumns, ",")),
                              c < header.size() ? quoted(header[c]) : "the end of the line");

  DamageTable table;
  table.file = path;
  std::map<int, int> line_of_tree;
  for (std::size_t n = 1; n < lines.size(); ++n) {
    if (lines[n].empty()) continue;
    const int line = int(n) + 1;
    const std::vector<std::string> values = split_csv(lines[n], file, line);
    if (values.size() != header.size())
      throw base::SourceError(file, line, "row", fmt::format("expected {} values", header.size()),
                              std::to_string(values.size()));
    const Row row{file, line, values};
    DamagedTree tree = tree_of(row);
    if (const auto [at, fresh] = line_of_tree.emplace(tree.id, line); !fresh)
      row.fail(kTreeId,
               fmt::format("expected each tree once: tree {} is on line {} already", tree.id, at->second));
    table.trees.push_back(std::move(tree));
  }
  return table;
}

}  // namespace fw::viz
