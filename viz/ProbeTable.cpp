#include "viz/ProbeTable.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/TextNumber.hpp"

namespace fw::viz {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

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

  std::vector<std::string> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // an unfinished last row
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (lines.empty() || split(lines[0]).empty() || split(lines[0])[0] != "time_s")
    throw std::invalid_argument(
        fmt::format("{}:1: header: expected 'time_s,...' (a forestwind probes.csv)", file));
  const std::vector<std::string> header = split(lines[0]);

  ProbeTable table;
  struct Columns {
    std::size_t first;
    bool tip;
  };
  std::vector<Columns> columns;
  std::size_t column = 1;
  while (column < header.size()) {
    if (std::string name = triple_name(header, column, {"_tip_dx", "_tip_dy", "_tip_dz"}); !name.empty()) {
      table.tips.push_back({name, {}});
      columns.push_back({column, true});
    } else if (std::string probe = triple_name(header, column, {"_u", "_v", "_w"}); !probe.empty()) {
      table.probes.push_back({probe, {}});
      columns.push_back({column, false});
    } else if (header[column].rfind("leaves_", 0) == 0) {
      break;  // the leaf counts close the row
    } else {
      throw std::invalid_argument(
          fmt::format("{}:1: {}: expected a column triple NAME_u,NAME_v,NAME_w or treeID_tip_dx,_dy,_dz",
                      file, header[column]));
    }
    column += 3;
  }

  for (std::size_t n = 1; n < lines.size(); ++n) {
    if (lines[n].empty()) continue;
    const std::vector<std::string> fields = split(lines[n]);
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
  }
  return table;
}

}  // namespace fw::viz
