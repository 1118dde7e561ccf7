// enospc_shim.so: an LD_PRELOAD library that makes writes fail with ENOSPC ("No space left on device"), so
// that the tests fill a disk without mount(2), which a CI container may not allow (tests/cli/disk_full.sh).
//
//   ENOSPC_SHIM_PATTERN=wind_000003.vti ENOSPC_SHIM_AFTER=4096 LD_PRELOAD=enospc_shim.so forestwind run ...
//
// write, writev, pwrite and pwrite64 on a file whose path (/proc/self/fd/N) contains ENOSPC_SHIM_PATTERN
// succeed for the first ENOSPC_SHIM_AFTER bytes (0 when unset) written to such files by the process, then
// fail with ENOSPC; a write that crosses the limit is cut short at it, as on a disk that fills. Other files
// are written normally. It intercepts the calls made through the PLT: libstdc++'s filebuf (VTK's and
// OpenVDB's writers) and our own POSIX writes (base/AtomicFile). glibc's stdio calls its internal write and
// escapes it, which is one reason the writers do not use stdio.
#include <dlfcn.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

constexpr std::size_t kPathBytes = 4096;  // PATH_MAX on Linux
std::atomic<long long> g_written{0};      // bytes written to matching files so far (by any thread)

// Whether fd is a file whose path contains the pattern.
bool matches(int fd) {
  const char* pattern = std::getenv("ENOSPC_SHIM_PATTERN");
  if (pattern == nullptr || pattern[0] == '\0') return false;
  std::array<char, kPathBytes> link{}, path{};
  std::snprintf(link.data(), link.size(), "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link.data(), path.data(), path.size() - 1);
  if (n <= 0) return false;
  path[std::size_t(n)] = '\0';
  return std::strstr(path.data(), pattern) != nullptr;
}

// How many of `count` bytes fd may still take: count, fewer, or 0 (then errno is ENOSPC).
std::size_t allowed(int fd, std::size_t count) {
  if (count == 0 || !matches(fd)) return count;
  const char* after = std::getenv("ENOSPC_SHIM_AFTER");
  const long long limit = after != nullptr ? std::atoll(after) : 0;
  // Claimed atomically: the output thread and the run loop's thread both write.
  long long written = g_written.load();
  std::size_t granted = 0;
  do {
    const long long left = limit > written ? limit - written : 0;
    granted = (long long)count < left ? count : std::size_t(left);
  } while (!g_written.compare_exchange_weak(written, written + (long long)granted));
  if (granted == 0) errno = ENOSPC;
  return granted;
}

template <typename F>
F next(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" {

ssize_t write(int fd, const void* buffer, std::size_t count) {
  static const auto real = next<ssize_t (*)(int, const void*, std::size_t)>("write");
  const std::size_t granted = allowed(fd, count);
  if (count > 0 && granted == 0) return -1;
  return real(fd, buffer, granted);
}

ssize_t pwrite(int fd, const void* buffer, std::size_t count, off_t offset) {
  static const auto real = next<ssize_t (*)(int, const void*, std::size_t, off_t)>("pwrite");
  const std::size_t granted = allowed(fd, count);
  if (count > 0 && granted == 0) return -1;
  return real(fd, buffer, granted, offset);
}

ssize_t pwrite64(int fd, const void* buffer, std::size_t count, off64_t offset) {
  static const auto real = next<ssize_t (*)(int, const void*, std::size_t, off64_t)>("pwrite64");
  const std::size_t granted = allowed(fd, count);
  if (count > 0 && granted == 0) return -1;
  return real(fd, buffer, granted, offset);
}

// writev: the buffers up to the allowed bytes, one write each (a short write, as the kernel may make).
ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
  static const auto real = next<ssize_t (*)(int, const struct iovec*, int)>("writev");
  if (!matches(fd)) return real(fd, iov, iovcnt);
  ssize_t total = 0;
  for (int i = 0; i < iovcnt; ++i) {
    const ssize_t n = write(fd, iov[i].iov_base, iov[i].iov_len);
    if (n < 0) return total > 0 ? total : -1;
    total += n;
    if (std::size_t(n) < iov[i].iov_len) break;
  }
  return total;
}

}  // extern "C"
