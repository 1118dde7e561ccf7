#include "io/Checkpoint.hpp"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <fstream>
#include <iterator>

#include "base/AtomicFile.hpp"
#include "base/SealedRecord.hpp"

namespace fw::io {
namespace {

constexpr std::array<char, 8> kMagic = {'F', 'W', 'C', 'H', 'E', 'C', 'K', '\0'};
// The magic, the u32 version and the u64 size of the whole file, read before the seal is checked: a file of
// another version, or one cut short, is named as such rather than as a failed checksum.
constexpr std::size_t kVersionOffset = kMagic.size();
constexpr std::size_t kSizeOffset = kVersionOffset + sizeof(std::uint32_t);
constexpr std::size_t kHeaderBytes = kSizeOffset + sizeof(std::uint64_t);
constexpr std::size_t kSealBytes = sizeof(std::uint64_t);

template <typename T>
T header_value(const std::string& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

// The element kinds of the layout, in the order of Checkpoint::Section's alternatives (kind = index + 1).
constexpr std::uint8_t kind_of(std::size_t alternative) {
  return static_cast<std::uint8_t>(alternative + 1);
}

template <typename T>
std::vector<T> read_values(base::RecordReader& in) {
  const auto count = in.value<std::uint64_t>();
  if (count > in.left() / sizeof(T)) throw base::RecordError("the record is truncated");
  std::vector<T> values(static_cast<std::size_t>(count));
  in.values(values.data(), values.size());
  return values;
}

}  // namespace

std::vector<std::string> Checkpoint::names() const {
  std::vector<std::string> out;
  for (const auto& [name, section] : sections_) out.push_back(name);
  return out;
}

std::string Checkpoint::bytes() const {
  base::RecordWriter body;
  body.value(time);
  body.value(step);
  body.value(static_cast<std::uint32_t>(sections_.size()));
  for (const auto& [name, section] : sections_) {
    body.text(name);
    body.value(kind_of(section.index()));
    std::visit(
        [&](const auto& values) {
          body.value(static_cast<std::uint64_t>(values.size()));
          body.values(values.data(), values.size());
        },
        section);
  }
  base::RecordWriter out;
  out.values(kMagic.data(), kMagic.size());
  out.value(kFormatVersion);
  out.value(static_cast<std::uint64_t>(kHeaderBytes + body.size() + kSealBytes));
  out.record(body);
  return out.sealed();
}

Checkpoint Checkpoint::from_bytes(const std::string& bytes) {
  if (bytes.size() < kHeaderBytes) {
    const std::size_t compared = std::min(bytes.size(), kMagic.size());
    throw CheckpointError(std::equal(bytes.begin(), bytes.begin() + long(compared), kMagic.begin())
                              ? "the file is truncated"
                              : "not a forestwind checkpoint");
  }
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin()))
    throw CheckpointError("not a forestwind checkpoint");
  const auto version = header_value<std::uint32_t>(bytes, kVersionOffset);
  if (version != kFormatVersion)
    throw CheckpointError(fmt::format("checkpoint format version {}, and this build reads version {}",
                                      version, kFormatVersion));
  const auto size = header_value<std::uint64_t>(bytes, kSizeOffset);
  if (bytes.size() < size)
    throw CheckpointError(fmt::format("the file is truncated: {} of its {} bytes", bytes.size(), size));
  if (bytes.size() > size)
    throw CheckpointError(
        fmt::format("the file goes on past its end: {} bytes, {} expected", bytes.size(), size));
  try {
    base::RecordReader in(base::open_sealed(bytes));
    std::array<char, kHeaderBytes> header{};
    in.values(header.data(), header.size());
    Checkpoint c;
    c.time = in.value<double>();
    c.step = in.value<std::int64_t>();
    const auto count = in.value<std::uint32_t>();
    for (std::uint32_t n = 0; n < count; ++n) {
      const std::string name = in.text();
      switch (in.value<std::uint8_t>()) {
        case kind_of(0):
          c.sections_[name] = read_values<float>(in);
          break;
        case kind_of(1):
          c.sections_[name] = read_values<double>(in);
          break;
        case kind_of(2):
          c.sections_[name] = read_values<std::int32_t>(in);
          break;
        case kind_of(3):
          c.sections_[name] = read_values<std::int64_t>(in);
          break;
        case kind_of(4):
          c.sections_[name] = read_values<std::uint8_t>(in);
          break;
        default:
          throw CheckpointError(fmt::format("the section \"{}\" has an unknown element kind", name));
      }
    }
    in.expect_end();
    return c;
  } catch (const base::RecordError& e) {
    throw CheckpointError(e.what());
  }
}

void Checkpoint::write(const std::filesystem::path& path) const {
  base::write_text_atomically("Checkpoint", path, bytes());
}

Checkpoint Checkpoint::read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(fmt::format("{}: cannot be read", path.string()));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return from_bytes(bytes);
  } catch (const CheckpointError& e) {
    throw CheckpointError(fmt::format("{}: {}", path.string(), e.what()));
  }
}

}  // namespace fw::io
