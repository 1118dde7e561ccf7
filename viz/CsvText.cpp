#include "viz/CsvText.hpp"

#include "io/gis/TreeInventory.hpp"

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

std::vector<std::string> split_csv(const std::string& line, const std::string& file, int line_number) {
  if (line.empty()) return {};
  return io::split_csv_fields(line, file, line_number);
}

}  // namespace fw::viz
