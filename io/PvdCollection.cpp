#include "io/PvdCollection.hpp"

#include "base/AtomicFile.hpp"
#include "base/TextNumber.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fw::io {
namespace detail {

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string xml_unescape(std::string_view text) {
  static const std::pair<std::string_view, char> entities[] = {
      {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::string out;
  for (std::size_t n = 0; n < text.size();) {
    bool replaced = false;
    for (const auto& [entity, c] : entities)
      if (text.substr(n, entity.size()) == entity) {
        out += c, n += entity.size(), replaced = true;
        break;
      }
    if (!replaced) out += text[n++];
  }
  return out;
}

}  // namespace detail

namespace {

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}
bool is_word(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// The attribute texts of each <DataSet ... /> element of `content`, in order. Scanned by hand, not with
// std::regex: libstdc++'s regex recurses once a character, and a .pvd with a long attribute text (21 KB
// under ASan, 2 MB in a release build) overflowed the stack (tests/fuzz/run_folder_fuzz).
std::vector<std::string_view> data_set_attributes(std::string_view content) {
  constexpr std::string_view kOpen = "<DataSet";
  std::vector<std::string_view> elements;
  for (std::size_t at = content.find(kOpen); at != std::string_view::npos; at = content.find(kOpen, at + 1)) {
    const std::size_t first = at + kOpen.size();
    if (first >= content.size() || !is_space(content[first])) continue;
    const std::size_t close = content.find('>', first + 1);
    if (close == std::string_view::npos) break;
    if (content[close - 1] != '/' || close - 1 < first + 1) continue;
    elements.push_back(content.substr(first + 1, close - 1 - (first + 1)));
  }
  return elements;
}

// The value of attribute `name` (name="value", the name not part of a longer word), or nullopt.
std::optional<std::string_view> attribute(std::string_view attributes, std::string_view name) {
  const std::string key = fmt::format("{}=\"", name);
  for (std::size_t at = attributes.find(key); at != std::string_view::npos;
       at = attributes.find(key, at + 1)) {
    if (at > 0 && is_word(attributes[at - 1])) continue;
    const std::size_t first = at + key.size();
    const std::size_t end = attributes.find('"', first);
    if (end != std::string_view::npos) return attributes.substr(first, end - first);
  }
  return std::nullopt;
}

}  // namespace

std::vector<PvdCollection::Entry> read_pvd(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("read_pvd: {}: cannot open the file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  // One DataSet element per frame, attributes in any order (PvdCollection writes timestep, group, part,
  // file).
  std::vector<PvdCollection::Entry> entries;
  for (const std::string_view attributes : data_set_attributes(content)) {
    const auto timestep = attribute(attributes, "timestep");
    const auto file = attribute(attributes, "file");
    if (!timestep || !file || file->empty())
      throw std::runtime_error(fmt::format("read_pvd: {}: DataSet {}: expected timestep and file attributes",
                                           path.string(), entries.size()));
    const std::optional<double> time = base::parse_finite(*timestep);
    if (!time)
      throw std::runtime_error(
          fmt::format("read_pvd: {}: DataSet {}: timestep: expected a finite number, got '{}'", path.string(),
                      entries.size(), *timestep));
    entries.push_back({*time, detail::xml_unescape(*file)});
  }
  return entries;
}

PvdCollection::PvdCollection(std::filesystem::path path) : path_(std::move(path)) {}

void PvdCollection::add(double time, const std::string& file) {
  if (!std::isfinite(time)) {
    throw std::invalid_argument(fmt::format("PvdCollection: {}: expected a finite time, got {}", file, time));
  }
  if (file.empty()) throw std::invalid_argument("PvdCollection: expected a file name, got an empty one");
  std::erase_if(entries_, [&](const Entry& entry) { return entry.file == file; });
  const auto after = std::upper_bound(entries_.begin(), entries_.end(), time,
                                      [](double t, const Entry& entry) { return t < entry.time; });
  entries_.insert(after, Entry{time, file});
  write();
}

void PvdCollection::continue_existing(double last_time) {
  entries_.clear();
  if (std::filesystem::exists(path_))
    for (const Entry& entry : read_pvd(path_))
      if (entry.time <= last_time) entries_.push_back(entry);
  write();
}

void PvdCollection::write() const {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const Entry& entry : entries_) {
    // {} prints the shortest text that reads back to the same double.
    text += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", entry.time,
                        detail::xml_escape(entry.file));
  }
  text +=
      "  </Collection>\n"
      "</VTKFile>\n";
  base::write_text_atomically("PvdCollection", path_, text);
}

}  // namespace fw::io
