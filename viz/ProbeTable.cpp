#include "viz/ProbeTable.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/TextNumber.hpp"
#include "viz/CsvText.hpp"

namespace fw::viz {

namespace {

const std::array<const char*, 3> kTreeCounts{"trees_standing", "trees_broken", "trees_overturned"};

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The name of a column triple <name><s0>, <name><s1>, <name><s2> starting at `column`, or empty.
std::string triple_name(const std::vector<std::string>& header, std::size_t column,
                        const std::array<const char*, 3>& suffixes) {
  if (column + 2 >= header.size() || !ends_with(header[column], suffixes[0])) return {};
  const std::string name = header[column].substr(0, header[column].size() - std::string(suffixes[0]).size());
  for (int c = 1; c < 3; ++c)
    if (header[column + c] != name + suffixes[c]) return {};
  return name;
}

}  // namespace

std::vector<double> ProbeSeries::magnitude() const {
  std::vector<double> out;
  for (const auto& v : xyz) out.push_back(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  return out;
}

ProbeTable read_probe_table(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("plot: {}: cannot open the file", path.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string file = path.string();

  const std::vector<std::string> lines = csv_lines(text, /*keep_unfinished_last=*/false);
  if (lines.empty() || split_csv(lines[0], file, 1).empty() || split_csv(lines[0], file, 1)[0] != "time_s")
    throw std::invalid_argument(
        fmt::format("{}:1: header: expected 'time_s,...' (a forestwind probes.csv)", file));
  const std::vector<std::string> header = split_csv(lines[0], file, 1);

  ProbeTable table;
  struct Columns {
    std::size_t first;
    bool tip;
  };
  std::vector<Columns> columns;
  std::optional<std::size_t> tree_counts;  // the first of the three columns
  std::size_t column = 1;
  while (column < header.size()) {
    if (std::string name = triple_name(header, column, {"_tip_dx", "_tip_dy", "_tip_dz"}); !name.empty()) {
      table.tips.push_back({name, {}});
      columns.push_back({column, true});
    } else if (std::string probe = triple_name(header, column, {"_u", "_v", "_w"}); !probe.empty()) {
      table.probes.push_back({probe, {}});
      columns.push_back({column, false});
    } else if (header[column].rfind("leaves_", 0) == 0) {
      ++column;  // a leaf count: not plotted
      continue;
    } else if (column + 2 < header.size() && header[column] == kTreeCounts[0] &&
               header[column + 1] == kTreeCounts[1] && header[column + 2] == kTreeCounts[2]) {
      tree_counts = column;
    } else {
      throw std::invalid_argument(
          fmt::format("{}:1: {}: expected a column triple NAME_u,NAME_v,NAME_w or treeID_tip_dx,_dy,_dz, the "
                      "leaf counts leaves_* or the tree counts trees_standing,trees_broken,trees_overturned",
                      file, header[column]));
    }
    column += 3;
  }
  if (tree_counts) table.damage = DamageCounts{};

  for (std::size_t n = 1; n < lines.size(); ++n) {
    if (lines[n].empty()) continue;
    const std::vector<std::string> fields = split_csv(lines[n], file, int(n) + 1);
    if (fields.size() != header.size())
      throw std::invalid_argument(
          fmt::format("{}:{}: row: expected {} values, got {}", file, n + 1, header.size(), fields.size()));
    auto number = [&](std::size_t c) {
      const std::optional<double> value = base::parse_number<double>(fields[c]);
      if (!value)
        throw std::invalid_argument(
            fmt::format("{}:{}: {}: expected a number, got '{}'", file, n + 1, header[c], fields[c]));
      return *value;
    };
    table.time.push_back(number(0));
    std::size_t probe = 0, tip = 0;
    for (const Columns& c : columns) {
      const std::array<double, 3> v{number(c.first), number(c.first + 1), number(c.first + 2)};
      (c.tip ? table.tips[tip++] : table.probes[probe++]).xyz.push_back(v);
    }
    if (!tree_counts) continue;
    std::array<int, 3> count{};
    for (std::size_t c = 0; c < 3; ++c) {
      const std::optional<int> value = base::parse_number<int>(fields[*tree_counts + c]);
      if (!value || *value < 0)
        throw std::invalid_argument(fmt::format("{}:{}: {}: expected a whole number >= 0, got '{}'", file,
                                                n + 1, header[*tree_counts + c], fields[*tree_counts + c]));
      count[c] = *value;
    }
    table.damage->time.push_back(table.time.back());
    table.damage->standing.push_back(count[0]);
    table.damage->broken.push_back(count[1]);
    table.damage->overturned.push_back(count[2]);
  }
  return table;
}

}  // namespace fw::viz
