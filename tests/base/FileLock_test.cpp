// base/FileLock: one holder at a time, the holder's note in the file, the file gone when the holder lets go,
// and a file left by a holder that died taken over.
#include "base/FileLock.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/support/TempDir.hpp"

namespace fs = std::filesystem;
using fw::base::FileLock;

TEST_CASE("FileLock: a second taker is refused and reads the holder's note") {
  fw::test::TempDir dir("file_lock");
  const fs::path path = fs::path(dir.path()) / "run.lock";
  auto first = FileLock::try_take(path, "process 1 on here");
  REQUIRE(first);
  // flock(2) locks conflict between open files, even in one process: the second open is another taker.
  CHECK_FALSE(FileLock::try_take(path, "process 2"));
  CHECK(FileLock::holder(path) == "process 1 on here");
  first.reset();
  CHECK_FALSE(fs::exists(path));  // removed when the holder lets go
  auto second = FileLock::try_take(path, "process 2");
  REQUIRE(second);
  CHECK(FileLock::holder(path) == "process 2");
}

TEST_CASE("FileLock: a file left unlocked (a killed holder's) is taken over and its note replaced") {
  fw::test::TempDir dir("file_lock_stale");
  const fs::path path = fs::path(dir.path()) / "run.lock";
  std::ofstream(path) << "process 99999 on a machine long gone, with a longer note";
  auto lock = FileLock::try_take(path, "process 3");
  REQUIRE(lock);
  CHECK(FileLock::holder(path) == "process 3");
}

TEST_CASE("FileLock: a folder that does not exist is an error naming the file") {
  fw::test::TempDir dir("file_lock_missing");
  const fs::path path = fs::path(dir.path()) / "missing" / "run.lock";
  CHECK_THROWS_WITH(FileLock::try_take(path, "x"),
                    Catch::Contains(path.string()) && Catch::Contains("No such file"));
}
