#include "base/FileLock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace fw::base {

namespace {
constexpr mode_t kLockFileMode = 0644;
// A holder may remove the file between our open and our lock: then we lock a file no one else will open,
// and take the new one instead. Two tries suffice unless holders come and go that fast; a few more are free.
constexpr int kLockTries = 8;

[[noreturn]] void throw_lock_error(const std::filesystem::path& path, int error) {
  throw std::runtime_error(fmt::format("FileLock: cannot lock {}: {}", path.string(), std::strerror(error)));
}
}  // namespace

FileLock::FileLock(std::filesystem::path path, int fd) : path_(std::move(path)), fd_(fd) {}

std::unique_ptr<FileLock> FileLock::try_take(const std::filesystem::path& path, std::string_view note) {
  for (int attempt = 0; attempt < kLockTries; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, kLockFileMode);
    if (fd < 0) throw_lock_error(path, errno);
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK) return nullptr;
      throw_lock_error(path, error);
    }
    // The file we locked must still be the one under `path` (its holder removes it when it lets go).
    struct stat locked {
    }, named{};
    if (::fstat(fd, &locked) != 0 || ::stat(path.c_str(), &named) != 0 || locked.st_ino != named.st_ino ||
        locked.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    std::unique_ptr<FileLock> lock(new FileLock(path, fd));
    // The note is for people; a lock whose note does not fit is still a lock.
    if (::ftruncate(fd, 0) == 0) {
      const ssize_t ignored = ::write(fd, note.data(), note.size());
      static_cast<void>(ignored);
    }
    return lock;
  }
  throw_lock_error(path, EAGAIN);
}

std::string FileLock::holder(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

FileLock::~FileLock() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
  ::close(fd_);
}

}  // namespace fw::base
