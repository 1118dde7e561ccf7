#include "base/SealedRecord.hpp"

#include "base/Fnv1a.hpp"

namespace fw::base {

std::string RecordWriter::sealed() const {
  Fnv1a checksum;
  checksum.bytes(bytes_.data(), bytes_.size());
  const std::uint64_t digest = checksum.digest();
  std::string out = bytes_;
  out.append(reinterpret_cast<const char*>(&digest), sizeof digest);
  return out;
}

std::span<const char> open_sealed(std::string_view sealed) {
  if (sealed.size() < sizeof(std::uint64_t)) throw RecordError("the record is truncated");
  const std::size_t body = sealed.size() - sizeof(std::uint64_t);
  Fnv1a checksum;
  checksum.bytes(sealed.data(), body);
  std::uint64_t stored = 0;
  std::memcpy(&stored, sealed.data() + body, sizeof stored);
  if (stored != checksum.digest()) throw RecordError("the checksum does not match");
  return {sealed.data(), body};
}

std::string RecordReader::text() {
  const auto size = value<std::uint32_t>();
  if (size > left()) throw RecordError("the record is truncated");
  std::string s(bytes_.data() + offset_, size);
  offset_ += size;
  return s;
}

void RecordReader::expect_end() const {
  if (left() != 0) throw RecordError("the record has trailing bytes");
}

}  // namespace fw::base
