// A fresh folder under the system temp directory, removed with everything in it at scope exit.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>

namespace fw::test {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "fw_test") {
    std::random_device random;
    const std::uint64_t tag = (std::uint64_t(random()) << 32) ^ random();
    path_ = std::filesystem::temp_directory_path() / fmt::format("{}_{:016x}", prefix, tag);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path() const { return path_.string(); }

  /// Writes content byte for byte and returns the file's path.
  std::string write(const std::string& name, std::string_view content) const {
    const auto file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out.write(content.data(), std::streamsize(content.size()));
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace fw::test
