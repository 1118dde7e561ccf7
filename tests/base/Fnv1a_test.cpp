// base/Fnv1a: the published FNV-1a 64-bit test values, and the streaming form equal to the one-shot form.
#include "base/Fnv1a.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

TEST_CASE("Fnv1a: the published 64-bit test vectors", "[base]") {
  // From the FNV reference's test suite: the empty string is the offset basis itself.
  CHECK(fw::base::fnv1a_hex("") == "cbf29ce484222325");
  CHECK(fw::base::fnv1a_hex("a") == "af63dc4c8601ec8c");
  CHECK(fw::base::fnv1a_hex("foobar") == "85944171f73967e8");
}

TEST_CASE("Fnv1a: bytes fed in pieces hash as the whole, and values hash as their bytes", "[base]") {
  const std::string text = "forestwind basis cache";
  fw::base::Fnv1a pieces;
  pieces.bytes(text.data(), 10);
  pieces.bytes(text.data() + 10, text.size() - 10);
  fw::base::Fnv1a whole;
  whole.bytes(text.data(), text.size());
  CHECK(pieces.digest() == whole.digest());

  const std::uint32_t value = 0x01020304u;
  fw::base::Fnv1a as_value, as_bytes;
  as_value.value(value);
  as_bytes.bytes(&value, sizeof value);
  CHECK(as_value.digest() == as_bytes.digest());
  CHECK(as_value.digest() != fw::base::Fnv1a().digest());
}
