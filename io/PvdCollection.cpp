#include "io/PvdCollection.hpp"

#include "io/AtomicFile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
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

}  // namespace detail

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
  write_text_atomically("PvdCollection", path_, text);
}

}  // namespace fw::io
