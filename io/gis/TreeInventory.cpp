#include "io/gis/TreeInventory.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>

#include "base/SourceError.hpp"
#include "base/TextNumber.hpp"

namespace fw::io {

namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

std::string quoted(const std::string& text) {
  return fmt::format("\"{}\"", text);
}

// Where each field the mapping names sits in the header (-1: absent; the required ones are checked).
struct ColumnIndex {
  int x = -1, y = -1, species = -1, height = -1, dbh = -1, crown_width = -1, id = -1;
};

ColumnIndex index_header(const std::vector<std::string>& header, const InventoryColumns& names,
                         const std::string& file) {
  std::map<std::string, int> at;
  for (int c = 0; c < int(header.size()); ++c) {
    if (!at.emplace(header[std::size_t(c)], c).second && !header[std::size_t(c)].empty())
      throw base::SourceError(file, 1, header[std::size_t(c)], "each column named once", "it twice");
  }
  const auto find = [&](const std::string& name, bool required) {
    const auto it = at.find(name);
    if (it != at.end()) return it->second;
    if (required)
      throw base::SourceError(file, 1, name, fmt::format("a column named {}", name),
                              fmt::format("the header {}", fmt::join(header, ", ")));
    return -1;
  };
  ColumnIndex index;
  index.x = find(names.x, true);
  index.y = find(names.y, true);
  index.species = find(names.species, true);
  index.height = find(names.height, true);
  index.dbh = find(names.dbh, true);
  index.crown_width = find(names.crown_width, false);
  index.id = find(names.id, false);
  return index;
}

}  // namespace

std::vector<std::string> split_csv_fields(const std::string& line, const std::string& file, int line_number) {
  std::vector<std::string> fields(1);
  bool quoted_field = false, in_quotes = false, closed = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c != '"') {
        fields.back() += c;
      } else if (i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';  // "" inside quotes: one quote
        ++i;
      } else {
        in_quotes = false;
        closed = true;
      }
      continue;
    }
    if (c == ',') {
      fields.emplace_back();
      quoted_field = closed = false;
    } else if (closed) {
      throw base::SourceError(file, line_number, fmt::format("field {}", fields.size()),
                              "a comma after a closing quote", std::string(1, c));
    } else if (c == '"' && fields.back().empty() && !quoted_field) {
      in_quotes = quoted_field = true;
    } else {
      fields.back() += c;
    }
  }
  if (in_quotes)
    throw base::SourceError(file, line_number, fmt::format("field {}", fields.size()),
                            "a closing quote before the line ends (a field does not span lines)", "");
  return fields;
}

TreeInventory read_tree_inventory(const std::string& path, const InventoryColumns& columns,
                                  const std::vector<std::string>& species) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw base::SourceError::unreadable(path, "cannot open it");
  TreeInventory inventory;
  inventory.file = path;
  std::string line;
  std::vector<std::string> header;
  ColumnIndex at;
  std::map<std::string, int> id_lines;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1 && line.starts_with(kByteOrderMark)) line.erase(0, kByteOrderMark.size());
    if (header.empty()) {
      if (line.empty()) throw base::SourceError(path, number, "header", "the column names on line 1", "");
      header = split_csv_fields(line, path, number);
      at = index_header(header, columns, path);
      continue;
    }
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::vector<std::string> fields = split_csv_fields(line, path, number);
    if (fields.size() != header.size())
      throw base::SourceError(path, number, "row", fmt::format("{} fields, as the header has", header.size()),
                              std::to_string(fields.size()));
    const auto field = [&](int c) -> const std::string& { return fields[std::size_t(c)]; };
    const auto name = [&](int c) -> const std::string& { return header[std::size_t(c)]; };
    const auto number_at = [&](int c, const char* expected) {
      const std::optional<double> value = base::parse_finite(field(c));
      if (!value) throw base::SourceError(path, number, name(c), expected, quoted(field(c)));
      return *value;
    };
    const auto positive_at = [&](int c) {
      const double value = number_at(c, "a number > 0 (m)");
      if (!(value > 0.0)) throw base::SourceError(path, number, name(c), "a number > 0 (m)", field(c));
      return value;
    };
    InventoryTree tree;
    tree.line = number;
    tree.x = number_at(at.x, "a number (m, the site's CRS)");
    tree.y = number_at(at.y, "a number (m, the site's CRS)");
    const auto known = std::find(species.begin(), species.end(), field(at.species));
    if (known == species.end())
      throw base::SourceError(path, number, name(at.species),
                              fmt::format("one of the scenario's species ({})", fmt::join(species, ", ")),
                              quoted(field(at.species)));
    tree.species = int(known - species.begin());
    tree.height = positive_at(at.height);
    tree.dbh = positive_at(at.dbh);
    if (at.crown_width >= 0 && !field(at.crown_width).empty()) tree.crown_width = positive_at(at.crown_width);
    tree.id = at.id >= 0 ? field(at.id) : std::to_string(number);
    if (at.id >= 0 && tree.id.empty())
      throw base::SourceError(path, number, name(at.id), "an id (any text, unique)", "an empty field");
    if (const auto [it, fresh] = id_lines.emplace(tree.id, number); !fresh)
      throw base::SourceError(path, number, at.id >= 0 ? name(at.id) : "id",
                              fmt::format("an id no other row has (line {} has it)", it->second),
                              quoted(tree.id));
    inventory.trees.push_back(std::move(tree));
  }
  if (header.empty())
    throw base::SourceError::unreadable(path, "empty: a header and a row per tree expected");
  if (inventory.trees.empty())
    throw base::SourceError::unreadable(path, "a row per tree expected, found none");
  return inventory;
}

}  // namespace fw::io
