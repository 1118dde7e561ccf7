#include "host/app/OutputFolder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include "host/app/OutputSpace.hpp"

namespace fw::host {

namespace {
constexpr std::size_t kHostNameBytes = 256;  // HOST_NAME_MAX (64) with room

// Why `directory` cannot take a run's output, or "" when it can.
std::string unwritable_reason(const std::filesystem::path& directory) {
  std::error_code error;
  if (std::filesystem::exists(directory, error) && !std::filesystem::is_directory(directory, error))
    return fmt::format("{}: the output folder is not a folder", directory.string());
  const std::filesystem::path existing = nearest_existing(directory);
  if (!std::filesystem::is_directory(existing, error))
    return fmt::format("{}: the output folder cannot be made: {} is not a folder", directory.string(),
                       existing.string());
  if (::faccessat(AT_FDCWD, existing.c_str(), W_OK | X_OK, AT_EACCESS) == 0) return "";
  const std::string why = std::strerror(errno);
  return existing == std::filesystem::absolute(directory)
             ? fmt::format("{}: the output folder cannot be written ({}); choose another with -o DIR",
                           directory.string(), why)
             : fmt::format(
                   "{}: the output folder cannot be made: {} cannot be written ({}); choose another "
                   "with -o DIR",
                   directory.string(), existing.string(), why);
}

// Who takes the lock, for the message of a run refused by it.
std::string holder_note() {
  std::array<char, kHostNameBytes> host{};
  if (::gethostname(host.data(), host.size() - 1) != 0) host[0] = '\0';
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::array<char, kHostNameBytes> since{};
  std::strftime(since.data(), since.size(), "%Y-%m-%dT%H:%M:%S%z", std::localtime(&now));
  return fmt::format("process {} on {} since {}", long(::getpid()), host.data(), since.data());
}
}  // namespace

void require_writable_output(const std::filesystem::path& directory, const Communicator& world) {
  std::string reason = world.rank() == 0 ? unwritable_reason(directory) : "";
  // Rank 0 decides; the others learn that it refused and say why in rank 0's words when they are rank 0's.
  const bool refused = world.max(reason.empty() ? 0.0 : 1.0) > 0.0;
  if (!refused) return;
  if (reason.empty())
    reason = fmt::format("{}: the output folder cannot be written (rank 0 says why)", directory.string());
  throw std::invalid_argument(reason);
}

std::unique_ptr<base::FileLock> lock_output_folder(const std::filesystem::path& directory,
                                                   const Communicator& world) {
  std::unique_ptr<base::FileLock> lock;
  std::string holder;
  bool held_elsewhere = false;
  if (world.rank() == 0) {
    std::filesystem::create_directories(directory);
    const std::filesystem::path file = directory / kOutputLockName;
    lock = base::FileLock::try_take(file, holder_note());
    if (!lock) {
      held_elsewhere = true;
      holder = base::FileLock::holder(file);
    }
  }
  held_elsewhere = world.max(held_elsewhere ? 1.0 : 0.0) > 0.0;
  if (!held_elsewhere) return lock;
  throw std::invalid_argument(fmt::format(
      "{}: another run is writing into this output folder ({}; its lock is {}); wait for it to end, or "
      "choose another folder with -o DIR",
      directory.string(), holder.empty() ? "rank 0 names it" : holder,
      (directory / kOutputLockName).string()));
}

}  // namespace fw::host
