// base/AtomicFile: a file appears under its name only complete (temporary name + rename), a failure leaves
// neither it nor its temporary behind, and a file it replaces stays intact until the rename.
#include "base/AtomicFile.hpp"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/TempDir.hpp"

namespace fs = std::filesystem;
using fw::base::AtomicFile;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out.write(content.data(), std::streamsize(content.size()));
}

// The names in a folder, sorted.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

ino_t inode_of(const fs::path& path) {
  struct stat s {};
  REQUIRE(::stat(path.c_str(), &s) == 0);
  return s.st_ino;
}

// While alive, files this process writes stop growing at `bytes` (writes past it fail with EFBIG instead of
// raising SIGXFSZ): a disk that fills up in the middle of a write.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &saved_) == 0);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limited = saved_;
    limited.rlim_cur = bytes;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = SIG_DFL;
};

}  // namespace

TEST_CASE("AtomicFile: the file appears under its name only at commit, complete, and no temporary is left",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path target = fs::path(dir.path()) / "modes.vtp";
  {
    AtomicFile file(target);
    // Beside the target (the same file system, so the rename is atomic), named after it and this process.
    CHECK(file.temporary_path().parent_path() == target.parent_path());
    CHECK(file.temporary_path().filename() == "modes.vtp.tmp-" + std::to_string(::getpid()));
    CHECK_FALSE(fs::exists(file.temporary_path()));  // nothing is created before the writer writes

    std::ofstream out(file.temporary_path(), std::ios::binary);
    out << "first half, ";
    out.flush();
    CHECK_FALSE(fs::exists(target));  // a reader sees nothing while the file is being written
    out << "second half";
    out.close();
    CHECK_FALSE(fs::exists(target));
    file.commit();
    CHECK(read_text(target) == "first half, second half");
    CHECK_FALSE(fs::exists(file.temporary_path()));
  }
  // The destructor after a commit removes nothing.
  CHECK(read_text(target) == "first half, second half");
  CHECK(names_in(dir.path()) == std::vector<std::string>{"modes.vtp"});
}

TEST_CASE("AtomicFile: a write that fails before commit leaves no file and no temporary, an old file intact",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path fresh = fs::path(dir.path()) / "fresh.vti";
  const fs::path old = fs::path(dir.path()) / "old.vti";
  write_file(old, "the previous run's complete frame");
  for (const fs::path& target : {fresh, old}) {
    INFO(target);
    fs::path temporary;
    try {
      AtomicFile file(target);
      temporary = file.temporary_path();
      std::ofstream out(temporary, std::ios::binary);
      out << "half a fra";
      out.close();
      REQUIRE(fs::exists(temporary));
      throw std::runtime_error("the writer failed");  // before commit(), as an exception unwinds a writer
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()) == "the writer failed");
    }
    CHECK_FALSE(fs::exists(temporary));
  }
  CHECK_FALSE(fs::exists(fresh));
  CHECK(read_text(old) == "the previous run's complete frame");
  CHECK(names_in(dir.path()) == std::vector<std::string>{"old.vti"});
}

TEST_CASE(
    "AtomicFile: an existing file is replaced by the rename: intact until commit, readers keep it whole",
    "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path target = fs::path(dir.path()) / "wind.pvd";
  const std::string old_content(10000, 'o');
  write_file(target, old_content);
  const ino_t old_inode = inode_of(target);
  std::ifstream reader(target, std::ios::binary);  // a reader (ParaView) that opened the old file
  char first[100];
  reader.read(first, sizeof first);
  {
    AtomicFile file(target);
    write_file(file.temporary_path(), "new");
    CHECK(read_text(target) == old_content);  // untouched while the new one is written
    file.commit();
  }
  CHECK(read_text(target) == "new");
  CHECK(inode_of(target) != old_inode);  // a new file took the name; the old one was never written over
  // The reader goes on reading the old file to its end, the bytes it had not read yet included.
  const std::string rest((std::istreambuf_iterator<char>(reader)), std::istreambuf_iterator<char>());
  CHECK(std::string(first, sizeof first) + rest == old_content);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"wind.pvd"});
}

TEST_CASE("AtomicFile: commit without a written temporary, or a failed rename, throws naming both paths",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  {
    const fs::path target = fs::path(dir.path()) / "never.vtp";
    AtomicFile file(target);
    try {
      file.commit();
      FAIL("commit() without a temporary did not throw");
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      INFO(message);
      CHECK(message.rfind("AtomicFile: ", 0) == 0);
      CHECK(message.find(target.string()) != std::string::npos);
      CHECK(message.find(file.temporary_path().string()) != std::string::npos);
      CHECK(message.find("was not written") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(target));
  }
  {
    // A folder (not empty) holds the target's name: rename(2) cannot replace it.
    const fs::path target = fs::path(dir.path()) / "frames";
    fs::create_directories(target / "inside");
    fs::path temporary;
    {
      AtomicFile file(target);
      temporary = file.temporary_path();
      write_file(temporary, "a frame");
      try {
        file.commit();
        FAIL("renaming onto a folder did not throw");
      } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.rfind("AtomicFile: cannot rename ", 0) == 0);
        CHECK(message.find(temporary.string()) != std::string::npos);
        CHECK(message.find(target.string()) != std::string::npos);
      }
    }
    // The failed commit's temporary goes with the object; the folder stays as it was.
    CHECK_FALSE(fs::exists(temporary));
    CHECK(fs::is_directory(target / "inside"));
    CHECK(names_in(dir.path()) == std::vector<std::string>{"frames"});
  }
}

TEST_CASE("write_text_atomically: writes the bytes exactly, replaces a file, and leaves only the file",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path path = fs::path(dir.path()) / "run.json";
  // No text-mode translation. The length comes from the array: a count written by hand (25) read past the
  // literal's 24 bytes, which ASan reported (make sanitize).
  static constexpr char kBytes[] = "line\r\nnul \0 high \xff\xfe end";
  const std::string bytes(kBytes, sizeof kBytes - 1);
  fw::base::write_text_atomically("Test", path, bytes);
  CHECK(read_text(path) == bytes);
  fw::base::write_text_atomically("Test", path, "");  // replaced by an empty file, which still exists
  CHECK(fs::exists(path));
  CHECK(fs::file_size(path) == 0);
  CHECK(names_in(dir.path()) == std::vector<std::string>{"run.json"});
}

TEST_CASE("write_text_atomically: a missing folder or a file in its place is refused, naming the path",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path missing = fs::path(dir.path()) / "no" / "such" / "run.json";
  CHECK_THROWS_WITH(fw::base::write_text_atomically("ManifestWriter", missing, "{}"),
                    "ManifestWriter: cannot write " + missing.string() + ": the folder " +
                        missing.parent_path().string() + " does not exist");
  write_file(fs::path(dir.path()) / "blocked", "a file");
  const fs::path blocked = fs::path(dir.path()) / "blocked" / "run.json";
  CHECK_THROWS_WITH(fw::base::write_text_atomically("ManifestWriter", blocked, "{}"),
                    "ManifestWriter: cannot write " + blocked.string() + ": " +
                        blocked.parent_path().string() + " is not a folder");
  CHECK(names_in(dir.path()) == std::vector<std::string>{"blocked"});
  // A bare name is a file in the working folder, which exists.
  CHECK_NOTHROW(fw::base::require_output_folder("Test", "bare.json"));
}

TEST_CASE("write_text_atomically: a disk that fills up mid-write leaves no file, no temporary, the old file",
          "[base]") {
  fw::test::TempDir dir("fw_atomic");
  const fs::path fresh = fs::path(dir.path()) / "fresh.pvd";
  const fs::path old = fs::path(dir.path()) / "old.pvd";
  write_file(old, "the complete old collection");
  const std::string content(1 << 20, 'x');  // 1 MiB: far past the 4 KiB the "disk" takes
  for (const fs::path& path : {fresh, old}) {
    INFO(path);
    std::string message;
    {
      const FileSizeLimit full_disk(4096);
      try {
        fw::base::write_text_atomically("PvdCollection", path, content);
      } catch (const std::runtime_error& e) {
        message = e.what();
      }
    }
    INFO(message);
    CHECK(message == "PvdCollection: cannot write " + path.string() + ": " + std::strerror(EFBIG));
  }
  CHECK_FALSE(fs::exists(fresh));
  CHECK(read_text(old) == "the complete old collection");
  CHECK(names_in(dir.path()) == std::vector<std::string>{"old.pvd"});
}

TEST_CASE("append_text: appends, and a disk that fills up mid-append cuts the file back to its old end",
          "[base]") {
  fw::test::TempDir dir("fw_append");
  const fs::path csv = fs::path(dir.path()) / "probes.csv";
  fw::base::append_text("ProbesCsv", csv, "time_s,u\n");
  fw::base::append_text("ProbesCsv", csv, "0,1\n");
  CHECK(read_text(csv) == "time_s,u\n0,1\n");
  const std::string rows(1 << 20, 'x');  // 1 MiB: far past the 4 KiB the "disk" takes
  std::string message;
  {
    const FileSizeLimit full_disk(4096);
    try {
      fw::base::append_text("ProbesCsv", csv, rows);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
  }
  CHECK(message == "ProbesCsv: cannot write " + csv.string() + ": " + std::strerror(EFBIG));
  CHECK(read_text(csv) == "time_s,u\n0,1\n");  // no partial row
}
