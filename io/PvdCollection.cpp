#include "io/PvdCollection.hpp"

#include "base/AtomicFile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <system_error>
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

std::vector<PvdCollection::Entry> read_pvd(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("read_pvd: {}: cannot open the file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  const std::string content = text.str();
  // One DataSet element per frame, attributes in any order (PvdCollection writes timestep, group, part,
  // file).
  const std::regex element(R"re(<DataSet\s([^>]*)/>)re");
  const std::regex timestep(R"re(\btimestep="([^"]*)")re"), file(R"re(\bfile="([^"]*)")re");
  std::vector<PvdCollection::Entry> entries;
  for (auto it = std::sregex_iterator(content.begin(), content.end(), element); it != std::sregex_iterator();
       ++it) {
    const std::string attributes = (*it)[1].str();
    std::smatch t, f;
    if (!std::regex_search(attributes, t, timestep) || !std::regex_search(attributes, f, file) ||
        f[1].str().empty())
      throw std::runtime_error(fmt::format("read_pvd: {}: DataSet {}: expected timestep and file attributes",
                                           path.string(), entries.size()));
    char* end = nullptr;
    const std::string time_text = t[1].str();
    const double time = std::strtod(time_text.c_str(), &end);
    if (end == time_text.c_str() || *end != '\0' || !std::isfinite(time))
      throw std::runtime_error(
          fmt::format("read_pvd: {}: DataSet {}: timestep: expected a finite number, got '{}'", path.string(),
                      entries.size(), time_text));
    entries.push_back({time, detail::xml_unescape(f[1].str())});
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
