// A ParaView collection file (.pvd): the list of a time series' frames, each a dataset file and its time.
//
//   fw::io::PvdCollection wind("out/wind.pvd");
//   fw::io::write_wind_vti("out/wind/wind_000000.vti", frame, fields);
//   wind.add(frame.time, "wind/wind_000000.vti");   // rewrites out/wind.pvd atomically
//
// ParaView: File > Open wind.pvd, Apply; the time slider steps through the frames (times in seconds).
// The file is rewritten in full through AtomicFile on every add(), so a run interrupted at any point leaves a
// valid .pvd that lists every frame finished so far. Datasets are listed in increasing time.
//
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace fw::io {

class PvdCollection {
 public:
  struct Entry {
    double time = 0.0;  ///< s
    std::string file;   ///< relative to the folder of the .pvd (forward slashes), as written
  };

  /// path: the .pvd file. Nothing is written until add() or write().
  explicit PvdCollection(std::filesystem::path path);

  /// Adds a frame and rewrites the .pvd. file: the dataset's path relative to the .pvd's folder. A time
  /// equal to an existing entry's goes after it (stable order); a file already listed is replaced (its time
  /// updated) rather than listed twice. Throws std::invalid_argument for a non-finite time or an empty file
  /// name, and std::runtime_error naming the path if the .pvd cannot be written (the entry is kept).
  void add(double time, const std::string& file);

  /// A resumed run's collection: takes over the .pvd at path(), when there is one, keeping its entries up
  /// to `last_time` (s) and dropping later ones, and rewrites it. Throws std::runtime_error naming the path
  /// when the file cannot be read or written.
  void continue_existing(double last_time);
  /// Writes the .pvd (also with no entries: an empty, valid collection). Throws std::runtime_error naming
  /// the path on failure; no temporary is left behind.
  void write() const;

  const std::filesystem::path& path() const { return path_; }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::filesystem::path path_;
  std::vector<Entry> entries_;
};

/// The entries of a .pvd written by PvdCollection (its DataSet elements' timestep and file, in file order),
/// for the readers of a run folder (viz/). Throws std::runtime_error("read_pvd: PATH: ...") when the file
/// cannot be read or a DataSet lacks a finite timestep or a file.
std::vector<PvdCollection::Entry> read_pvd(const std::filesystem::path& path);

namespace detail {

/// The inverse of xml_escape for the five entities it writes.
std::string xml_unescape(std::string_view text);

/// `text` with &, <, >, " and ' replaced by XML entities, for attribute values.
std::string xml_escape(std::string_view text);

}  // namespace detail
}  // namespace fw::io
