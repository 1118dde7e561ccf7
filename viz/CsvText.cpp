#include "viz/CsvText.hpp"

namespace fw::viz {

std::vector<std::string> csv_lines(const std::string& text, bool keep_unfinished_last) {
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) {
      if (keep_unfinished_last) lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> split_csv(const std::string& line) {
  // RFC 4180's quotes (damage.csv quotes an inventory id that holds a comma); an unclosed quote runs to the
  // end of the line.
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"' && (quoted || fields.back().empty())) {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  if (line.empty()) fields.clear();
  return fields;
}

}  // namespace fw::viz
