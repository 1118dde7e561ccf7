#include "base/Fnv1a.hpp"

#include <fmt/format.h>

namespace fw::base {

std::string fnv1a_hex(std::string_view text) {
  Fnv1a hash;
  hash.bytes(text.data(), text.size());
  return fmt::format("{:016x}", hash.digest());
}

}  // namespace fw::base
