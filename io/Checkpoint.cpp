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
  base::RecordWriter out;
  out.values(kMagic.data(), kMagic.size());
  out.value(kFormatVersion);
  out.value(time);
  out.value(step);
  out.value(static_cast<std::uint32_t>(sections_.size()));
  for (const auto& [name, section] : sections_) {
    out.text(name);
    out.value(kind_of(section.index()));
    std::visit(
        [&](const auto& values) {
          out.value(static_cast<std::uint64_t>(values.size()));
          out.values(values.data(), values.size());
        },
        section);
  }
  return out.sealed();
}

Checkpoint Checkpoint::from_bytes(const std::string& bytes) {
  try {
    base::RecordReader in(base::open_sealed(bytes));
    std::array<char, 8> magic{};
    in.values(magic.data(), magic.size());
    if (magic != kMagic) throw CheckpointError("not a forestwind checkpoint");
    const auto version = in.value<std::uint32_t>();
    if (version != kFormatVersion)
      throw CheckpointError(fmt::format("checkpoint format version {}, and this build reads version {}",
                                        version, kFormatVersion));
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
