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

void require_output_folder(const char* function, const std::filesystem::path& path) {
  std::filesystem::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return;
  const bool exists = std::filesystem::exists(folder, error);
  throw std::runtime_error(exists ? fmt::format("{}: cannot write {}: {} is not a folder", function,
                                                path.string(), folder.string())
                                  : fmt::format("{}: cannot write {}: the folder {} does not exist", function,
                                                path.string(), folder.string()));
}

void write_text_atomically(const char* function, const std::filesystem::path& path,
                           std::string_view content) {
  require_output_folder(function, path);
  AtomicFile file(path);
  {
    // stdio rather than iostreams, for errno in the message.
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(file.temporary_path().c_str(), "wb"),
                                                        &std::fclose);
    if (!out) {
      throw std::runtime_error(
          fmt::format("{}: cannot write {}: {}", function, path.string(), std::strerror(errno)));
    }
    const bool written = std::fwrite(content.data(), 1, content.size(), out.get()) == content.size();
    const int saved = errno;
    if (!written || std::fclose(out.release()) != 0) {
      throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(),
                                           std::strerror(written ? errno : saved)));
    }
  }
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), error.what()));
  }
}

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
  detail::write_text_atomically("PvdCollection", path_, text);
}

}  // namespace fw::io
