#include "trees/QsmImport.hpp"

#include "base/SourceError.hpp"
#include "base/TextNumber.hpp"
#include "trees/TreeFile.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace fw::trees {

namespace {

using detail::printable;
using detail::quoted;

constexpr std::size_t kRequired = 9;
constexpr std::array<const char*, kRequired> kColumns = {"radius", "length", "start x", "start y", "start z",
                                                         "axis x", "axis y", "axis z",  "parent"};
constexpr const char* kLayout =
    "at least 9 columns: radius length start_x start_y start_z axis_x axis_y axis_z parent";
constexpr double kGapFraction = 0.1;    // of the cylinder's length
constexpr double kGapAllowance = 1e-3;  // m

struct Cylinder {
  int line = 0;
  std::array<std::string_view, kRequired> tokens;
  double radius = 0.0, length = 0.0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // unit length
  int parent = 0;                                  // 1-based, 0 for none
  Eigen::Vector3d end() const { return start + length * axis; }
};

std::string_view trim(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

// Fields of one line: comma-separated (trimmed) when it holds a comma, else whitespace-separated.
std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> fields;
  if (text.find(',') != std::string_view::npos) {
    for (std::size_t pos = 0;;) {
      const std::size_t comma = text.find(',', pos);
      fields.push_back(
          trim(text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos)));
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    return fields;
  }
  for (std::size_t k = 0; k < text.size();) {
    if (trim(text.substr(k, 1)).empty()) {
      ++k;
      continue;
    }
    std::size_t stop = k;
    while (stop < text.size() && !trim(text.substr(stop, 1)).empty()) ++stop;
    fields.push_back(text.substr(k, stop - k));
    k = stop;
  }
  return fields;
}

}  // namespace

Skeleton read_qsm_cylinders(const std::string& path, QsmImportInfo* info) {
  const std::string data = detail::read_text_file(path);

  std::vector<Cylinder> cylinders;
  int line_number = 0;
  bool header_allowed = true;
  for (std::size_t pos = 0; pos < data.size();) {
    ++line_number;
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::string_view text(data.data() + pos, end - pos);
    pos = end + 1;
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    if (trim(text).empty()) continue;

    const auto fields = split(text);
    if (header_allowed) {
      header_allowed = false;
      if (!base::parse_finite(fields.front())) continue;  // a header line of column names
    }
    Cylinder cylinder;
    cylinder.line = line_number;
    for (std::size_t c = 0; c < kRequired; ++c) {
      if (c >= fields.size())
        throw base::SourceError(path, line_number, kColumns[c],
                                fmt::format("expected a number ({})", kLayout), "end of line");
      cylinder.tokens[c] = fields[c];
    }
    double values[kRequired];
    for (std::size_t c = 0; c < kRequired; ++c) {
      const auto value = base::parse_finite(cylinder.tokens[c]);
      if (!value)
        throw base::SourceError(path, line_number, kColumns[c], "expected a finite number",
                                quoted(cylinder.tokens[c]));
      values[c] = *value;
    }
    if (values[0] <= 0.0)
      throw base::SourceError(path, line_number, "radius", "expected a positive radius in metres",
                              quoted(cylinder.tokens[0]));
    if (values[1] <= 0.0)
      throw base::SourceError(path, line_number, "length", "expected a positive length in metres",
                              quoted(cylinder.tokens[1]));
    const Eigen::Vector3d axis(values[5], values[6], values[7]);
    const double norm = axis.norm();
    if (!(norm > 0.0) || !std::isfinite(norm))
      throw base::SourceError(path, line_number, "axis x y z", "expected a non-zero axis direction",
                              fmt::format("'{} {} {}'", printable(cylinder.tokens[5]),
                                          printable(cylinder.tokens[6]), printable(cylinder.tokens[7])));
    if (values[8] != std::floor(values[8]) || values[8] < 0.0)
      throw base::SourceError(path, line_number, "parent",
                              "expected the row number of the parent cylinder (1..m), or 0 for none",
                              quoted(cylinder.tokens[8]));
    cylinder.radius = values[0];
    cylinder.length = values[1];
    cylinder.start = Eigen::Vector3d(values[2], values[3], values[4]);
    cylinder.axis = axis / norm;
    cylinder.parent = values[8] > 2e9 ? -1 : int(values[8]);  // -1: out of range, reported below
    cylinders.push_back(cylinder);
  }
  if (cylinders.empty())
    throw base::SourceError(path, std::max(line_number, 1), "radius",
                            fmt::format("expected at least one cylinder row ({})", kLayout), "end of file");

  // Parents in range and exactly one base cylinder.
  const int m = int(cylinders.size());
  int base = -1;  // 0-based row of the cylinder with parent 0
  for (int k = 0; k < m; ++k) {
    const Cylinder& cylinder = cylinders[std::size_t(k)];
    if (cylinder.parent < 0 || cylinder.parent > m)
      throw base::SourceError(
          path, cylinder.line, "parent",
          fmt::format("expected the row number of the parent cylinder in 1..{}, or 0 for none", m),
          quoted(cylinder.tokens[8]));
    if (cylinder.parent == 0) {
      if (base >= 0)
        throw base::SourceError(
            path, cylinder.line, "parent",
            fmt::format(
                "expected exactly one cylinder with parent 0, but cylinder {} on line {} already has it",
                base + 1, cylinders[std::size_t(base)].line),
            quoted(cylinder.tokens[8]));
      base = k;
    }
  }
  if (base < 0)
    throw base::SourceError(path, cylinders.front().line, "parent",
                            "expected exactly one cylinder with parent 0 (the base of the stem), found none",
                            quoted(cylinders.front().tokens[8]));

  // Nodes: 0 is the root, k is the end of cylinder k (1-based).
  std::vector<SkeletonNode> nodes(std::size_t(m) + 1);
  nodes[0] = SkeletonNode{-1, cylinders[std::size_t(base)].start, cylinders.front().radius};
  QsmImportInfo counts;
  counts.cylinders = m;
  for (int k = 0; k < m; ++k) {
    const Cylinder& cylinder = cylinders[std::size_t(k)];
    nodes[std::size_t(k) + 1] = SkeletonNode{cylinder.parent, cylinder.end(), cylinder.radius};
    if (cylinder.parent == 0) continue;
    const double gap = (cylinder.start - cylinders[std::size_t(cylinder.parent) - 1].end()).norm();
    if (gap > kGapFraction * cylinder.length + kGapAllowance) ++counts.gaps;
    if (gap > counts.largest_gap) {
      counts.largest_gap = gap;
      counts.largest_gap_line = cylinder.line;
    }
  }

  Skeleton skeleton;
  try {
    skeleton = Skeleton::from_nodes(std::move(nodes));
  } catch (const SkeletonError& error) {
    // Node k > 0 is cylinder k; node 0 comes from the base cylinder.
    const int row = error.node() > 0 ? error.node() - 1 : base;
    const Cylinder& cylinder = cylinders[std::size_t(row)];
    detail::throw_if_parent_or_radius(error, path, cylinder.line, cylinder.tokens[8], cylinder.tokens[0]);
    throw base::SourceError(
        path, cylinder.line, "length",
        fmt::format(
            "expected the cylinder's end point (start + length * axis) to differ from its parent's: {}",
            error.expected()),
        quoted(cylinder.tokens[1]));
  }
  if (info) *info = counts;
  return skeleton;
}

}  // namespace fw::trees
