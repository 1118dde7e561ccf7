#include "base/AtomicFile.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <stdexcept>
#include <system_error>
#include <utility>

namespace fw::base {

namespace {
constexpr std::string_view kTemporaryTag = ".tmp-";
constexpr mode_t kFileMode = 0666;  // rw for everyone, less the umask: what fopen(3) creates

// POSIX rather than stdio or iostreams: each failing call's errno reaches the message, and a close(2) that
// reports a late write error (NFS, a full disk) is not lost.
// Writes every byte of `content` to fd; false with errno set when a write fails.
bool write_all(int fd, std::string_view content) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;  // no progress and no error: give up rather than spin
      return false;
    }
    content.remove_prefix(std::size_t(n));
  }
  return true;
}

[[noreturn]] void throw_write_error(const char* function, const std::filesystem::path& path, int error) {
  throw std::runtime_error(
      fmt::format("{}: cannot write {}: {}", function, path.string(), std::strerror(error)));
}
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
  const int fd = ::open(file.temporary_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, kFileMode);
  if (fd < 0) throw_write_error(function, path, errno);
  const bool written = write_all(fd, content);
  const int saved = errno;
  if (::close(fd) != 0 && written) throw_write_error(function, path, errno);
  if (!written) throw_write_error(function, path, saved);
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), error.what()));
  }
}

void append_text(const char* function, const std::filesystem::path& path, std::string_view content) {
  require_output_folder(function, path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, kFileMode);
  if (fd < 0) throw_write_error(function, path, errno);
  struct stat before {};
  if (::fstat(fd, &before) != 0) {
    const int saved = errno;
    ::close(fd);
    throw_write_error(function, path, saved);
  }
  const bool written = write_all(fd, content);
  const int saved = errno;
  if (!written && ::ftruncate(fd, before.st_size) != 0) {
    // The file keeps a partial line: say so with the write's error, which is the cause.
    ::close(fd);
    throw std::runtime_error(
        fmt::format("{}: cannot write {}: {}; the file could not be cut back to its {} "
                    "bytes and ends with a partial line",
                    function, path.string(), std::strerror(saved), before.st_size));
  }
  if (::close(fd) != 0 && written) throw_write_error(function, path, errno);
  if (!written) throw_write_error(function, path, saved);
}

}  // namespace fw::base
