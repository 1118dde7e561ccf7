// What the fuzz targets of tests/fuzz share: a scratch folder of their own for readers that take a path, and
// the check that a refusal is a clean one (docs/fuzzing.md).
//
//   const auto path = fw::fuzz::write_input("oak.tree", data, size);   // the bytes, as a file
//   try { read_tree_file(path.string()); }
//   catch (const fw::base::SourceError& e) { fw::fuzz::expect_names_file(e, path); }   // else a bug
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

namespace fw::fuzz {

/// This process's own folder under the system's temporary folder, created on the first call and emptied
/// of nothing: targets overwrite their files, and a crash leaves them for a look.
const std::filesystem::path& scratch_folder();

/// Writes the bytes to scratch_folder() / name (replacing it) and returns that path.
std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size);

/// A clean refusal names the file it refuses: its what() starts with "PATH:" for `path` or, when `path` is a
/// folder, for a file in it. Anything else aborts with the message, which libFuzzer reports as a crash.
void expect_names_file(const std::exception& error, const std::filesystem::path& path);

/// Aborts with "fuzz: WHAT" on stderr: a property the target checks does not hold.
[[noreturn]] void fail(std::string_view what);

}  // namespace fw::fuzz
