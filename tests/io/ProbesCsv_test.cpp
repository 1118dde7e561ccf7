#include "io/ProbesCsv.hpp"

#include "io/WindFrame.hpp"
#include "io/writers/ProbesWriter.hpp"
#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using fw::test::has_temporary;

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE_FALSE(text.empty());
  CHECK(text.back() == '\n');  // the last row is complete
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream stream(line);
  for (std::string cell; std::getline(stream, cell, ',');) cells.push_back(cell);
  return cells;
}

const std::string kHeader =
    "time_s,mast_u,mast_v,mast_w,gap_u,gap_v,gap_w,tree0_tip_dx,tree0_tip_dy,tree0_tip_dz,"
    "tree17_tip_dx,tree17_tip_dy,tree17_tip_dz";

// Row n of a synthetic series, with values that need all 9 digits of a float.
std::vector<std::array<float, 3>> velocities(int n) {
  return {{1.0f / 3.0f + float(n), -2.718281828f, 1e-7f * float(n + 1)},
          {12.345678f, 0.0f, -0.1f * float(n)}};
}
std::vector<std::array<double, 3>> tips(int n) {
  return {{0.001 * n, -0.25, 1.0 / 7.0}, {3.0e-5, double(n), -0.5}};
}

void check_rows(const fs::path& path, int rows) {
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == std::size_t(rows) + 1);
  CHECK(lines[0] == kHeader);
  for (int n = 0; n < rows; ++n) {
    INFO("row " << n << ": " << lines[std::size_t(n) + 1]);
    const auto cells = split(lines[std::size_t(n) + 1]);
    REQUIRE(cells.size() == 13);
    // Tolerance: the time is printed with 12 significant digits (0.1 * 3 = 0.30000000000000004 -> "0.3").
    CHECK(std::stod(cells[0]) == Approx(0.1 * n).epsilon(1e-11).margin(1e-300));
    const auto v = velocities(n);
    const auto d = tips(n);
    for (int p = 0; p < 2; ++p) {
      for (int c = 0; c < 3; ++c) {
        // Exact: 9 significant digits read a float32 back bit for bit.
        CHECK(std::strtof(cells[std::size_t(1 + 3 * p + c)].c_str(), nullptr) ==
              v[std::size_t(p)][std::size_t(c)]);
        // Tolerance: doubles are printed with 9 significant digits (relative 5e-9).
        CHECK(std::stod(cells[std::size_t(7 + 3 * p + c)]) ==
              Approx(d[std::size_t(p)][std::size_t(c)]).epsilon(1e-8).margin(1e-15));
      }
    }
  }
}

}  // namespace

TEST_CASE("ProbesCsv: header, then one complete row per append, rewritten atomically", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "probes.csv";
  dir.write("probes.csv", "an old file from an earlier run\n");
  fw::io::ProbesCsv probes(path, {"mast", "gap"}, {0, 17});
  CHECK(probes.header() == kHeader);
  check_rows(path, 0);  // the header alone replaces the old file
  for (int n = 0; n < 4; ++n) {
    probes.append(0.1 * n, velocities(n), tips(n));
    check_rows(path, n + 1);
    CHECK_FALSE(has_temporary(dir.path()));
  }
  CHECK(probes.rows() == 4);

  // The wrong counts write nothing.
  CHECK_THROWS_AS(probes.append(1.0, {velocities(0)[0]}, tips(0)), std::invalid_argument);
  CHECK_THROWS_AS(probes.append(1.0, velocities(0), {}), std::invalid_argument);
  check_rows(path, 4);
}

TEST_CASE("ProbesCsv: past the rewrite limit rows are appended, with the same content", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "probes.csv";
  // A limit of the header plus about two rows: the first rows are rewritten, the later ones appended.
  fw::io::ProbesCsv probes(path, {"mast", "gap"}, {0, 17}, kHeader.size() + 200);
  for (int n = 0; n < 6; ++n) {
    probes.append(0.1 * n, velocities(n), tips(n));
    check_rows(path, n + 1);
  }
  CHECK(probes.rows() == 6);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("ProbesCsv: leaf count columns follow the existing columns only when asked", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "probes.csv";
  const std::string leaf_columns = ",leaves_shed,leaves_flying,leaves_landed,leaves_exited";
  // A limit of the header plus about two rows: rewritten rows and appended rows both carry the counts.
  fw::io::ProbesCsv probes(path, {"mast", "gap"}, {0, 17}, kHeader.size() + leaf_columns.size() + 220,
                           {.leaves = true});
  CHECK(probes.header() == kHeader + leaf_columns);
  for (int n = 0; n < 5; ++n) {
    const fw::trees::LeafCounts counts{
        .shed = 10L * n + 3, .flying = 7L * n, .landed = 2L * n + 3, .exited = n, .attached = 1000 - n};
    if (n % 2 == 0) {
      probes.append(0.1 * n, velocities(n), tips(n), counts);
    } else {
      const auto v = velocities(n);
      const auto d = tips(n);
      probes.append_rows({{0.1 * n, &v, &d, &counts}});
    }
  }
  CHECK(probes.rows() == 5);
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 6);
  CHECK(lines[0] == kHeader + leaf_columns);
  for (int n = 0; n < 5; ++n) {
    INFO("row " << n << ": " << lines[std::size_t(n) + 1]);
    const auto cells = split(lines[std::size_t(n) + 1]);
    REQUIRE(cells.size() == 17);
    CHECK(std::strtof(cells[1].c_str(), nullptr) == velocities(n)[0][0]);
    // The counts as integers, after the tip columns; attached is not a column.
    CHECK(cells[13] == std::to_string(10 * n + 3));
    CHECK(cells[14] == std::to_string(7 * n));
    CHECK(cells[15] == std::to_string(2 * n + 3));
    CHECK(cells[16] == std::to_string(n));
  }

  // A row without counts in a file with count columns writes nothing.
  CHECK_THROWS_AS(probes.append(1.0, velocities(0), tips(0)), std::invalid_argument);
  CHECK(lines_of(path).size() == 6);

  // Without the flag the counts are ignored and the file is exactly as before.
  const fs::path plain_path = fs::path(dir.path()) / "plain.csv";
  fw::io::ProbesCsv plain(plain_path, {"mast", "gap"}, {0, 17});
  CHECK(plain.header() == kHeader);
  for (int n = 0; n < 3; ++n) plain.append(0.1 * n, velocities(n), tips(n), fw::trees::LeafCounts{.shed = 9});
  check_rows(plain_path, 3);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("probes writer: with leaf counts on, each sample's counts end its row", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path out(dir.path());
  fw::io::ProbesWriter writer(out, {"mast"}, {}, {.leaves = true});
  CHECK(writer.needs().probe_samples);
  writer.begin();
  fw::io::OutputFrame frame;
  for (int n = 0; n < 2; ++n) {
    fw::io::ProbeSample sample;
    sample.time = 0.5 * n;
    sample.wind = {{1.0f, 2.0f, 3.0f}};
    sample.leaf_counts = {.shed = 4L + n, .flying = 2L + n, .landed = 1, .exited = 1, .attached = 96L - n};
    frame.probe_samples.push_back(sample);
  }
  writer.write(frame);
  const auto lines = lines_of(out / "probes.csv");
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == "time_s,mast_u,mast_v,mast_w,leaves_shed,leaves_flying,leaves_landed,leaves_exited");
  CHECK(lines[1] == "0,1,2,3,4,2,1,1");
  CHECK(lines[2] == "0.5,1,2,3,5,3,1,1");
}

TEST_CASE("ProbesCsv: probes sampled on the MAC grid go in as m/s", "[output]") {
  fw::test::TempDir dir("fw_out");
  fw::fluid::GridSpec spec;
  spec.nx = spec.ny = spec.nz = 2;
  spec.h = 1.0;
  fw::fluid::MacVelocity vel(spec);
  std::fill(vel.u.begin(), vel.u.end(), 3.0f);
  std::fill(vel.w.begin(), vel.w.end(), -0.5f);
  fw::io::ProbesCsv probes(fs::path(dir.path()) / "probes.csv", {"centre"}, {});
  probes.append(2.5, {fw::io::sample_velocity(spec, vel, {1.0, 1.0, 1.0})}, {});
  const auto lines = lines_of(fs::path(dir.path()) / "probes.csv");
  REQUIRE(lines.size() == 2);
  CHECK(lines[0] == "time_s,centre_u,centre_v,centre_w");
  CHECK(lines[1] == "2.5,3,0,-0.5");
}

TEST_CASE("ProbesCsv: bad names throw invalid_argument, a missing or unwritable folder runtime_error",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "probes.csv";
  CHECK_THROWS_AS(fw::io::ProbesCsv(path, {""}, {}), std::invalid_argument);
  CHECK_THROWS_WITH(fw::io::ProbesCsv(path, {"a,b"}, {}),
                    "ProbesCsv: probe \"a,b\": a name may not contain a comma, a quote or a line break");
  CHECK_THROWS_AS(fw::io::ProbesCsv(path, {"m", "m"}, {}), std::invalid_argument);
  CHECK_THROWS_AS(fw::io::ProbesCsv(path, {"m"}, {3, 3}), std::invalid_argument);
  CHECK_FALSE(fs::exists(path));

  const fs::path missing = fs::path(dir.path()) / "none" / "probes.csv";
  CHECK_THROWS_MATCHES(
      fw::io::ProbesCsv(missing, {"m"}, {}), std::runtime_error,
      Catch::Matchers::Message("ProbesCsv: cannot write " + missing.string() + ": the folder " +
                               missing.parent_path().string() + " does not exist"));

  // A folder nobody may create files in, root included.
  if (fs::is_directory("/proc")) {
    const fs::path target = "/proc/fw_probes_test.csv";
    CHECK_THROWS_WITH(fw::io::ProbesCsv(target, {"m"}, {}),
                      Catch::Matchers::StartsWith("ProbesCsv: cannot write " + target.string() + ": "));
  }

  // A read-only folder. Root ignores permissions, so the check only runs where they apply.
  const fs::path locked = fs::path(dir.path()) / "locked";
  fs::create_directory(locked);
  ::chmod(locked.c_str(), 0555);
  if (::access(locked.c_str(), W_OK) == 0) {
    WARN("running with permission overrides (root): the read-only folder case is skipped");
  } else {
    const fs::path target = locked / "probes.csv";
    CHECK_THROWS_WITH(fw::io::ProbesCsv(target, {"m"}, {}),
                      Catch::Matchers::StartsWith("ProbesCsv: cannot write " + target.string() + ": "));
    CHECK(fs::is_empty(locked));
  }
  ::chmod(locked.c_str(), 0755);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE(
    "ProbesCsv: a resumed run keeps the header and the rows up to its checkpoint, and appends after them",
    "[output]") {
  fw::test::TempDir dir("fw_probes_resume");
  const fs::path path = fs::path(dir.path()) / "probes.csv";
  // Rows past the rewrite limit (64 bytes): the file is appended, as in a long run.
  constexpr std::size_t kSmallLimit = 64;
  {
    fw::io::ProbesCsv csv(path, {"mast"}, {}, kSmallLimit);
    for (int row = 0; row < 6; ++row) csv.append(0.5 * row, {{float(row), 0.0f, 0.0f}}, {});
  }
  auto resumed = fw::io::ProbesCsv::continued(path, {"mast"}, {}, 3, kSmallLimit);
  CHECK(resumed.rows() == 3);
  resumed.append(9.0, {{9.0f, 0.0f, 0.0f}}, {});
  const std::vector<std::string> lines = lines_of(path);
  REQUIRE(lines.size() == 5);  // the header, rows 0-2, the new row
  CHECK(lines[0] == "time_s,mast_u,mast_v,mast_w");
  CHECK(split(lines[3])[1] == "2");
  CHECK(split(lines[4])[0] == "9");
  CHECK_FALSE(has_temporary(dir.path()));

  // Other columns, or fewer rows than the checkpoint counted: not this run's file, which stays as it was.
  CHECK_THROWS_AS(fw::io::ProbesCsv::continued(path, {"gap"}, {}, 3), std::invalid_argument);
  CHECK_THROWS_AS(fw::io::ProbesCsv::continued(path, {"mast"}, {}, 10), std::invalid_argument);
  CHECK(lines_of(path) == lines);
  // No file (a resume into a new folder): a new one with the header only.
  fs::remove(path);
  CHECK(fw::io::ProbesCsv::continued(path, {"mast"}, {}, 3).rows() == 0);
  CHECK(lines_of(path) == std::vector<std::string>{"time_s,mast_u,mast_v,mast_w"});
}
