// The 64-bit FNV-1a hash: simple, stable across platforms and compilers, and plenty for a per-machine cache
// key, a file checksum or a run's scenario fingerprint (not for anything adversarial).
//
//   fw::base::Fnv1a hash;
//   hash.bytes(text.data(), text.size());
//   hash.value(std::int32_t{7});            // the value's bytes as they lie in memory
//   std::uint64_t h = hash.digest();
//   std::string hex = fw::base::fnv1a_hex("some text");   // 16 lower-case hex digits
//
// hash = offset; for each byte b: hash = (hash xor b) * prime, modulo 2^64 (offset 0xcbf29ce484222325,
// prime 0x100000001b3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace fw::base {

class Fnv1a {
 public:
  static constexpr std::uint64_t kOffset = 0xcbf29ce484222325ULL;
  static constexpr std::uint64_t kPrime = 0x100000001b3ULL;

  constexpr void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ ^= p[i];
      hash_ *= kPrime;
    }
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  constexpr std::uint64_t digest() const { return hash_; }

 private:
  std::uint64_t hash_ = kOffset;
};

/// FNV-1a of `text`, as 16 lower-case hex digits.
std::string fnv1a_hex(std::string_view text);

}  // namespace fw::base
