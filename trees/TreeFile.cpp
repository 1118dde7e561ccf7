#include "trees/TreeFile.hpp"

#include "base/AtomicFile.hpp"
#include "base/SourceError.hpp"
#include "base/TextNumber.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace fw::trees {

namespace detail {

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw base::SourceError::unreadable(path, fmt::format("cannot open: {}", std::strerror(errno)));
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw base::SourceError::unreadable(path, "read error");
  return data;
}

std::string printable(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t k = 0; k < text.size() && k < kMax; ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\')
      out += char(c);
    else
      out += fmt::format("\\x{:02x}", c);
  }
  if (text.size() > kMax) out += "...";
  return out;
}

std::string quoted(std::string_view token) {
  return fmt::format("'{}'", printable(token));
}

void throw_if_parent_or_radius(const SkeletonError& error, const std::string& path, int line,
                               std::string_view parent, std::string_view radius) {
  switch (error.field()) {
    case SkeletonError::Field::parent:
      throw base::SourceError(path, line, "parent", error.expected(), quoted(parent));
    case SkeletonError::Field::radius:
      throw base::SourceError(path, line, "radius", error.expected(), quoted(radius));
    case SkeletonError::Field::position:
    case SkeletonError::Field::nodes:
      return;
  }
}

}  // namespace detail

namespace {

using detail::printable;
using detail::quoted;

constexpr std::array<const char*, 6> kColumns = {"id", "parent", "x", "y", "z", "radius"};
constexpr const char* kLayout = "6 fields: id parent x y z radius";

// One node line as read: its line number and its six tokens.
struct NodeLine {
  int line = 0;
  std::array<std::string_view, 6> tokens;
};

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

}  // namespace

Skeleton read_tree_file(const std::string& path) {
  const std::string data = detail::read_text_file(path);

  // Split into node lines of exactly six tokens.
  std::vector<NodeLine> lines;
  int line_number = 0;
  for (std::size_t pos = 0; pos < data.size();) {
    ++line_number;
    std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) end = data.size();
    std::string_view text(data.data() + pos, end - pos);
    pos = end + 1;
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);

    NodeLine node{line_number, {}};
    std::size_t count = 0;
    for (std::size_t k = 0; k < text.size();) {
      if (is_blank(text[k])) {
        ++k;
        continue;
      }
      std::size_t stop = k;
      while (stop < text.size() && !is_blank(text[stop])) ++stop;
      const std::string_view token = text.substr(k, stop - k);
      if (count == kColumns.size())
        throw base::SourceError(path, line_number, kColumns.back(),
                                fmt::format("expected end of line after the radius ({})", kLayout),
                                quoted(token));
      node.tokens[count++] = token;
      k = stop;
    }
    if (count == 0) continue;
    if (count < kColumns.size())
      throw base::SourceError(path, line_number, kColumns[count],
                              fmt::format("expected a value ({})", kLayout), "end of line");
    lines.push_back(node);
  }
  if (lines.empty())
    throw base::SourceError(path, std::max(line_number, 1), "id",
                            fmt::format("expected at least one node line ({})", kLayout), "end of file");

  // Numbers, and ids that are unique and cover 0..n-1.
  const long long n = static_cast<long long>(lines.size());
  std::vector<SkeletonNode> nodes(lines.size());
  std::vector<const NodeLine*> source(lines.size(), nullptr);  // node id -> its line
  std::unordered_map<long long, int> seen;                     // id -> line number
  std::vector<long long> ids(lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const NodeLine& node = lines[k];
    const auto id = base::parse_number<long long>(node.tokens[0]);
    if (!id)
      throw base::SourceError(path, node.line, "id", "expected an integer node id", quoted(node.tokens[0]));
    if (const auto [it, inserted] = seen.emplace(*id, node.line); !inserted)
      throw base::SourceError(
          path, node.line, "id",
          fmt::format("expected a unique id (id {} is already on line {})", *id, it->second),
          quoted(node.tokens[0]));
    const auto parent = base::parse_number<long long>(node.tokens[1]);
    if (!parent)
      throw base::SourceError(path, node.line, "parent", "expected an integer: -1 (root) or a node id",
                              quoted(node.tokens[1]));
    double values[4];
    for (int c = 0; c < 4; ++c) {
      const auto value = base::parse_finite(node.tokens[std::size_t(c) + 2]);
      if (!value)
        throw base::SourceError(
            path, node.line, kColumns[std::size_t(c) + 2],
            c < 3 ? "expected a finite number in metres" : "expected a positive number in metres",
            quoted(node.tokens[std::size_t(c) + 2]));
      values[c] = *value;
    }
    ids[k] = *id;
    SkeletonNode& out = nodes[k];
    // A parent outside -1..n-1 is left for Skeleton to report; clamp it so that it fits in an int.
    out.parent = *parent < -1 ? -2 : *parent >= n ? int(n) : int(*parent);
    out.position = Eigen::Vector3d(values[0], values[1], values[2]);
    out.radius = values[3];
  }
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (ids[k] < 0 || ids[k] >= n)
      throw base::SourceError(
          path, lines[k].line, "id",
          fmt::format("expected an id in 0..{} (ids number the file's {} nodes from 0)", n - 1, n),
          quoted(lines[k].tokens[0]));
    source[std::size_t(ids[k])] = &lines[k];
  }
  // Reorder by id: unique ids in 0..n-1 are a permutation.
  std::vector<SkeletonNode> by_id(lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k) by_id[std::size_t(ids[k])] = nodes[k];

  try {
    return Skeleton::from_nodes(std::move(by_id));
  } catch (const SkeletonError& error) {
    if (error.node() < 0 || error.node() >= int(n))
      throw base::SourceError::unreadable(path, fmt::format("{}, got {}", error.expected(), error.got()));
    const NodeLine& node = *source[std::size_t(error.node())];
    detail::throw_if_parent_or_radius(error, path, node.line, node.tokens[1], node.tokens[5]);
    throw base::SourceError(path, node.line, "x y z", error.expected(),
                            fmt::format("'{} {} {}'", printable(node.tokens[2]), printable(node.tokens[3]),
                                        printable(node.tokens[4])));
  }
}

void write_tree_file(const Skeleton& skeleton, const std::string& path) {
  std::string text = fmt::format(
      "# forestwind skeleton: {} nodes\n# id parent x y z radius (metres; parent -1 is the root)\n",
      skeleton.size());
  for (int i = 0; i < skeleton.size(); ++i) {
    const SkeletonNode& node = skeleton.node(i);
    text += fmt::format("{} {} {:.17g} {:.17g} {:.17g} {:.17g}\n", i, node.parent, node.position.x(),
                        node.position.y(), node.position.z(), node.radius);
  }
  base::write_text_atomically("write_tree_file", path, text);
}

}  // namespace fw::trees
