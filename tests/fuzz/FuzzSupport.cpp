#include "tests/fuzz/FuzzSupport.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iostream>

namespace fw::fuzz {

const std::filesystem::path& scratch_folder() {
  static const std::filesystem::path folder = [] {
    auto path = std::filesystem::temp_directory_path() / ("forestwind-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return folder;
}

std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const auto path = scratch_folder() / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) fail("cannot write " + path.string());
  return path;
}

void expect_names_file(const std::exception& error, const std::filesystem::path& path) {
  const std::string_view what = error.what();
  const std::string file = path.string();
  if (what.starts_with(file + ":")) return;
  if (std::filesystem::is_directory(path) && what.starts_with(file + "/")) return;
  fail("a refusal that does not name the file " + file + ": " + std::string(what));
}

void fail(std::string_view what) {
  std::cerr << "fuzz: " << what << std::endl;
  std::abort();
}

}  // namespace fw::fuzz
