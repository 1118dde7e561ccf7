// A checkpoint file: named arrays of a run's state at one simulated time, sealed by a checksum (the container
// of output.checkpoint, docs/design.md "Long runs"). What goes in it, and under which names, is the run's
// business; this file only keeps arrays intact and refuses a file it cannot trust.
//
//   fw::io::Checkpoint c;
//   c.time = 12.5;                                     // s
//   c.step = 250;
//   c.put("wind.u", std::vector<float>{...});          // float, double, int32, int64 or uint8 arrays
//   c.write("out/storm/checkpoints/t000012.500.fwcheck");   // under a temporary name, then renamed
//
//   const fw::io::Checkpoint back = fw::io::Checkpoint::read(path);   // throws CheckpointError with the
//   reason const std::vector<float>& u = back.get<float>("wind.u");
//
// Layout (binary, the host's byte order: a checkpoint resumes on the machine type that wrote it):
//   "FWCHECK\0", u32 format version (kFormatVersion), u64 size of the whole file, f64 time, i64 step, u32
//   section count, then per
//   section: u32 name length and the name, u8 element kind (1 float32, 2 float64, 3 int32, 4 int64,
//   5 uint8), u64 element count, the elements; then the u64 FNV-1a checksum of every byte before it
//   (base/SealedRecord). Sections are written in name order, so the same state gives the same bytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace fw::io {

/// A checkpoint that cannot be used: unreadable, truncated, another format version, a failed checksum, or a
/// section missing or of another kind. The message names the file (when read from one) and the reason. It
/// is bad input to a resume, a std::invalid_argument, so the command line exits 2 with it.
class CheckpointError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class Checkpoint {
 public:
  /// The format this build writes and reads; a file of another version is refused.
  static constexpr std::uint32_t kFormatVersion = 1;

  double time = 0.0;      ///< simulated time, s
  std::int64_t step = 0;  ///< solver steps taken

  /// Stores `values` under `name`, replacing a section of that name.
  template <typename T>
  void put(const std::string& name, std::vector<T> values) {
    sections_[name] = std::move(values);
  }
  bool has(const std::string& name) const { return sections_.count(name) > 0; }
  /// The section `name` as T. Throws CheckpointError when it is missing or holds another kind.
  template <typename T>
  const std::vector<T>& get(const std::string& name) const {
    const auto at = sections_.find(name);
    if (at == sections_.end()) throw CheckpointError("the checkpoint has no section \"" + name + "\"");
    const auto* values = std::get_if<std::vector<T>>(&at->second);
    if (values == nullptr) throw CheckpointError("the section \"" + name + "\" holds another kind of value");
    return *values;
  }
  /// The sections' names, in order.
  std::vector<std::string> names() const;

  /// The file's bytes (the layout above).
  std::string bytes() const;
  /// Parses bytes(); throws CheckpointError with the reason.
  static Checkpoint from_bytes(const std::string& bytes);

  /// Writes the file under a temporary name in its folder (which must exist) and renames it into place.
  /// Throws std::runtime_error naming the path when it cannot be written; an earlier file there is kept.
  void write(const std::filesystem::path& path) const;
  /// Throws CheckpointError("PATH: reason") for a file that cannot be read or used.
  static Checkpoint read(const std::filesystem::path& path);

 private:
  using Section = std::variant<std::vector<float>, std::vector<double>, std::vector<std::int32_t>,
                               std::vector<std::int64_t>, std::vector<std::uint8_t>>;
  std::map<std::string, Section> sections_;
};

}  // namespace fw::io
