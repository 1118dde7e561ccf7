#include "base/AtomicFile.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <stdexcept>
#include <system_error>
#include <utility>

namespace fw::base {

namespace {
constexpr std::string_view kTemporaryTag = ".tmp-";
}  // namespace

int remove_stale_temporaries(const std::filesystem::path& folder) {
  int removed = 0;
  std::error_code error;
  for (auto it = std::filesystem::recursive_directory_iterator(folder, error);
       it != std::filesystem::recursive_directory_iterator(); it.increment(error)) {
    const std::string name = it->path().filename().string();
    const std::size_t at = name.rfind(kTemporaryTag);
    const bool temporary =
        at != std::string::npos && at > 0 && at + kTemporaryTag.size() < name.size() &&
        name.find_first_not_of("0123456789", at + kTemporaryTag.size()) == std::string::npos;
    if (temporary && it->is_regular_file()) removed += std::filesystem::remove(it->path(), error) ? 1 : 0;
  }
  return removed;
}

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  temporary_ = target_;
  temporary_ += fmt::format("{}{}", kTemporaryTag, static_cast<long>(::getpid()));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() {
  std::error_code error;
  if (!std::filesystem::is_regular_file(temporary_, error)) {
    throw std::runtime_error(fmt::format("AtomicFile: {} was not written (expected the temporary {})",
                                         target_.string(), temporary_.string()));
  }
  std::filesystem::rename(temporary_, target_, error);
  if (error) {
    throw std::runtime_error(fmt::format("AtomicFile: cannot rename {} to {}: {}", temporary_.string(),
                                         target_.string(), error.message()));
  }
  committed_ = true;
}

void require_output_folder(const char* function, const std::filesystem::path& path) {
  std::filesystem::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return;
  const bool exists = std::filesystem::exists(folder, error);
  throw std::runtime_error(exists ? fmt::format("{}: cannot write {}: {} is not a folder", function,
                                                path.string(), folder.string())
                                  : fmt::format("{}: cannot write {}: the folder {} does not exist", function,
                                                path.string(), folder.string()));
}

void write_text_atomically(const char* function, const std::filesystem::path& path,
                           std::string_view content) {
  require_output_folder(function, path);
  AtomicFile file(path);
  {
    // stdio rather than iostreams, for errno in the message.
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(file.temporary_path().c_str(), "wb"),
                                                        &std::fclose);
    if (!out) {
      throw std::runtime_error(
          fmt::format("{}: cannot write {}: {}", function, path.string(), std::strerror(errno)));
    }
    const bool written = std::fwrite(content.data(), 1, content.size(), out.get()) == content.size();
    const int saved = errno;
    if (!written || std::fclose(out.release()) != 0) {
      throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(),
                                           std::strerror(written ? errno : saved)));
    }
  }
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), error.what()));
  }
}

}  // namespace fw::base
