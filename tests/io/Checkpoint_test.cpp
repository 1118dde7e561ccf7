// io/Checkpoint: a checkpoint file gives back every array bit for bit, and a damaged, cut, foreign or
// other-version file is refused with its path and reason (what `--resume` turns into exit 2).
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "base/SealedRecord.hpp"
#include "io/Checkpoint.hpp"
#include "tests/support/TempDir.hpp"

using namespace fw;

namespace {

io::Checkpoint sample() {
  io::Checkpoint c;
  c.time = 12.5;
  c.step = 250;
  // Values whose bits matter: a negative zero, a denormal, the largest float, a NaN payload.
  c.put("wind.u", std::vector<float>{-0.0f, std::numeric_limits<float>::denorm_min(),
                                     std::numeric_limits<float>::max(), std::nanf("7")});
  c.put("forcing.integral", std::vector<double>{1.0 / 3.0});
  c.put("leaves.tree", std::vector<std::int32_t>{0, 5, -1});
  c.put("random.state", std::vector<std::int64_t>{std::numeric_limits<std::int64_t>::min()});
  c.put("leaves.state", std::vector<std::uint8_t>{0, 1, 2, 3});
  c.put("empty", std::vector<float>{});
  return c;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

TEST_CASE("Checkpoint: every section comes back bit for bit, and the same state gives the same bytes",
          "[io]") {
  const test::TempDir dir("fw_checkpoint");
  const std::filesystem::path folder = dir.path();
  const io::Checkpoint c = sample();
  const auto path = folder / "t.fwcheck";
  c.write(path);
  const io::Checkpoint back = io::Checkpoint::read(path);
  CHECK(back.time == 12.5);
  CHECK(back.step == 250);
  CHECK(back.names() == c.names());
  CHECK(same_bits(back.get<float>("wind.u"), c.get<float>("wind.u")));
  CHECK(same_bits(back.get<double>("forcing.integral"), c.get<double>("forcing.integral")));
  CHECK(back.get<std::int32_t>("leaves.tree") == c.get<std::int32_t>("leaves.tree"));
  CHECK(back.get<std::int64_t>("random.state") == c.get<std::int64_t>("random.state"));
  CHECK(back.get<std::uint8_t>("leaves.state") == c.get<std::uint8_t>("leaves.state"));
  CHECK(back.get<float>("empty").empty());
  CHECK(back.bytes() == c.bytes());
  // No temporary is left beside it.
  CHECK(std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator{}) ==
        1);
}

TEST_CASE("Checkpoint: a missing section or one of another kind is named", "[io]") {
  const io::Checkpoint c = sample();
  CHECK_THROWS_WITH(c.get<float>("wind.v"), "the checkpoint has no section \"wind.v\"");
  CHECK_THROWS_WITH(c.get<double>("wind.u"), "the section \"wind.u\" holds another kind of value");
}

TEST_CASE("Checkpoint: a damaged, cut, foreign or other-version file is refused with its path and reason",
          "[io]") {
  const test::TempDir dir("fw_checkpoint");
  const std::filesystem::path folder = dir.path();
  const std::string bytes = sample().bytes();
  const auto path = folder / "bad.fwcheck";
  const auto refused = [&](const std::string& content) {
    std::ofstream(path, std::ios::binary) << content;
    try {
      io::Checkpoint::read(path);
    } catch (const io::CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  const std::string prefix = path.string() + ": ";
  std::string flipped = bytes;
  flipped[bytes.size() / 2] = char(flipped[bytes.size() / 2] ^ 1);
  CHECK(refused(flipped) == prefix + "the checksum does not match");
  // A file cut short is named as such (its header gives its size), however short.
  CHECK(refused(bytes.substr(0, bytes.size() / 2)) ==
        prefix + fmt::format("the file is truncated: {} of its {} bytes", bytes.size() / 2, bytes.size()));
  CHECK(refused(bytes.substr(0, 3)) == prefix + "the file is truncated");
  CHECK(refused(bytes + "x") == prefix + fmt::format("the file goes on past its end: {} bytes, {} expected",
                                                     bytes.size() + 1, bytes.size()));
  // A well-sealed file of another version, and one that is not a checkpoint at all.
  base::RecordWriter other;
  other.values("FWCHECK", 8);
  other.value(io::Checkpoint::kFormatVersion + 1);
  other.value(std::uint64_t{0});
  CHECK(refused(other.sealed()) == prefix + "checkpoint format version 2, and this build reads version 1");
  base::RecordWriter foreign;
  foreign.values("FWBASIS", 8);
  CHECK(refused(foreign.sealed()) == prefix + "not a forestwind checkpoint");
  CHECK_THROWS_WITH(io::Checkpoint::read(folder / "none.fwcheck"),
                    (folder / "none.fwcheck").string() + ": cannot be read");
}
