// A binary record sealed by a checksum: plain values appended to a byte buffer, then the 64-bit FNV-1a of
// every byte before it (base/Fnv1a). Opening a record checks the seal first, and every read checks the length
// left, so a truncated or damaged file is refused before a value of it is used. The bytes are the host's
// (little-endian here): records are per machine (the basis cache) or per run (checkpoints).
//
//   fw::base::RecordWriter out;
//   out.value(std::uint32_t{3});
//   out.values(field.data(), field.size());           // any trivially copyable T
//   std::string bytes = out.sealed();                  // the values and the checksum
//
//   fw::base::RecordReader in(fw::base::open_sealed(bytes));   // throws RecordError unless the seal holds
//   auto version = in.value<std::uint32_t>();
//   in.values(field.data(), field.size());             // throws RecordError("... is truncated") when short
//   in.expect_end();                                   // throws when bytes are left over
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace fw::base {

/// What is wrong with a record: truncated, its checksum fails, or its content is not what the reader expects.
class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Appends plain values to a byte buffer.
class RecordWriter {
 public:
  template <typename T>
  void value(const T& v) {
    values(&v, 1);
  }
  template <typename T>
  void values(const T* data, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(data), count * sizeof(T));
  }
  /// A u32 length, then the characters.
  void text(std::string_view s) {
    value(std::uint32_t(s.size()));
    bytes_.append(s);
  }
  /// The bytes of another record, as they are.
  void record(const RecordWriter& other) { bytes_.append(other.bytes_); }
  std::size_t size() const { return bytes_.size(); }
  /// The bytes so far followed by their u64 FNV-1a checksum.
  std::string sealed() const;

 private:
  std::string bytes_;
};

/// The bytes of a sealed record without its checksum. Throws RecordError("the record is truncated") when
/// shorter than a checksum, RecordError("the checksum does not match") when the seal fails.
std::span<const char> open_sealed(std::string_view sealed);

/// Reads plain values from a byte span, each read checking the length left.
class RecordReader {
 public:
  explicit RecordReader(std::span<const char> bytes) : bytes_(bytes) {}
  template <typename T>
  T value() {
    T v;
    values(&v, 1);
    return v;
  }
  template <typename T>
  void values(T* data, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (count > (bytes_.size() - offset_) / sizeof(T)) throw RecordError("the record is truncated");
    if (count == 0) return;  // an empty vector's data() may be null, which memcpy must not be given
    std::memcpy(data, bytes_.data() + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
  }
  std::string text();
  std::size_t offset() const { return offset_; }
  std::size_t left() const { return bytes_.size() - offset_; }
  /// Throws RecordError("the record has trailing bytes") unless every byte was read.
  void expect_end() const;

 private:
  std::span<const char> bytes_;
  std::size_t offset_ = 0;
};

}  // namespace fw::base
