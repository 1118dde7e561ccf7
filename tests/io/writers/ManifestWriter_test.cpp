// run.json (io/writers/ManifestWriter): the leaves' counts of runs with leaves, and nothing of them without.
#include "io/writers/ManifestWriter.hpp"

#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
  REQUIRE(fs::is_regular_file(path));
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

fw::io::RunManifest manifest(bool leaves) {
  fw::io::RunManifest m;
  m.version = "0.test";
  m.scenario_name = "grove";
  m.scenario_file_name = "run.yaml";
  m.scenario_text = "name: grove\n";
  m.grid = {8, 8, 4};
  m.cell_size = 1.0;
  m.leaves = leaves;
  return m;
}

fw::io::OutputFrame frame_with_counts(int index, double time, const fw::trees::LeafCounts& counts) {
  fw::io::OutputFrame frame;
  frame.index = index;
  frame.time = time;
  frame.leaves.counts = counts;
  return frame;
}

}  // namespace

TEST_CASE("run.json: with leaves on, a leaves object holds the counts of the last frame at its time",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path out = fs::path(dir.path()) / "run";
  fw::io::ManifestWriter writer(out, manifest(true));
  CHECK(writer.needs().leaf_counts);  // the counts only: no frame's leaves are copied back for run.json
  CHECK_FALSE(writer.needs().leaves);
  CHECK_FALSE(writer.needs().velocity);
  writer.begin();
  writer.write(frame_with_counts(0, 0.0, {.shed = 0, .flying = 0, .landed = 0, .exited = 0, .attached = 40}));
  writer.write(
      frame_with_counts(1, 1.25, {.shed = 12, .flying = 5, .landed = 4, .exited = 3, .attached = 28}));
  writer.finish(fw::io::RunOutcome{});
  const std::string json = read_text(out / "run.json");
  INFO(json);
  CHECK(json.find(R"("leaves":{"shed":12,"flying":5,"landed":4,"exited":3,"attached":28,"time_s":1.25})") !=
        std::string::npos);
  CHECK(json.find(R"("status":"completed")") != std::string::npos);
  CHECK(json.back() == '\n');
}

TEST_CASE("run.json: leaves are null when no frame was written and absent in runs without leaves",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path none = fs::path(dir.path()) / "none";
  fw::io::ManifestWriter failed_early(none, manifest(true));
  failed_early.begin();
  fw::io::RunOutcome failed;
  failed.status = "failed";
  failed.message = "no device";
  failed_early.finish(failed);
  CHECK(read_text(none / "run.json").find(R"("leaves":null)") != std::string::npos);

  const fs::path plain = fs::path(dir.path()) / "plain";
  fw::io::ManifestWriter writer(plain, manifest(false));
  CHECK_FALSE(writer.needs().leaves);
  writer.begin();
  writer.write(frame_with_counts(0, 0.5, {.shed = 1, .flying = 1}));
  writer.finish(fw::io::RunOutcome{});
  const std::string json = read_text(plain / "run.json");
  CHECK(json.find("\"leaves\"") == std::string::npos);
  CHECK(json.find(R"("stages_ms":{}})") != std::string::npos);  // still the last key
}
