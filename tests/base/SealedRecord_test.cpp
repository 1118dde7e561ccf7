// base/SealedRecord: values come back as written, and a record that was cut short or changed in any byte is
// refused before a value of it is read.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "base/SealedRecord.hpp"

using namespace fw;

namespace {

std::string sample_record() {
  base::RecordWriter out;
  out.value(std::uint32_t{7});
  const std::vector<double> values = {1.5, -2.25, 1e300};
  out.values(values.data(), values.size());
  out.text("wind.u");
  return out.sealed();
}

}  // namespace

TEST_CASE("SealedRecord: values, arrays and text come back as written, to the last byte", "[base]") {
  const std::string sealed = sample_record();
  base::RecordReader in(base::open_sealed(sealed));
  CHECK(in.value<std::uint32_t>() == 7);
  std::vector<double> values(3);
  in.values(values.data(), values.size());
  CHECK(values == std::vector<double>{1.5, -2.25, 1e300});
  CHECK(in.text() == "wind.u");
  CHECK_NOTHROW(in.expect_end());
}

TEST_CASE("SealedRecord: a changed byte anywhere, a cut record and a short read are refused", "[base]") {
  const std::string sealed = sample_record();
  for (std::size_t at = 0; at < sealed.size(); ++at) {
    std::string changed = sealed;
    changed[at] = char(changed[at] ^ 0x10);
    INFO("byte " << at);
    CHECK_THROWS_WITH(base::open_sealed(changed), "the checksum does not match");
  }
  for (const std::size_t keep : {std::size_t(0), std::size_t(5), sealed.size() - 1})
    CHECK_THROWS_AS(base::open_sealed(sealed.substr(0, keep)), base::RecordError);
  base::RecordReader in(base::open_sealed(sealed));
  std::vector<double> too_many(100);
  CHECK_THROWS_WITH(in.values(too_many.data(), too_many.size()), "the record is truncated");
  base::RecordReader partly(base::open_sealed(sealed));
  partly.value<std::uint32_t>();
  CHECK_THROWS_WITH(partly.expect_end(), "the record has trailing bytes");
}
