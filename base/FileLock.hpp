// An exclusive lock on a file, flock(2), held while the object lives: one process at a time, as one run at a
// time in an output folder (host/app/OutputFolder.hpp). The kernel drops the lock when its process ends,
// however it ends (kill -9 too), so a lock is never stale.
//
//   std::unique_ptr<fw::base::FileLock> lock = fw::base::FileLock::try_take("out/.forestwind.lock", note);
//   if (!lock) std::cerr << "held by " << fw::base::FileLock::holder("out/.forestwind.lock");
//
// The file holds the holder's note (who and since when) while the lock is held, and is removed when the
// holder lets go normally; a killed holder leaves it, unlocked, for the next one to take over.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace fw::base {

class FileLock {
 public:
  /// Takes the lock of `path` (creating the file) without waiting and writes `note` into it; nullptr when
  /// another process holds it. Throws std::runtime_error("FileLock: cannot lock PATH: reason") when the file
  /// cannot be created or locked for another reason.
  static std::unique_ptr<FileLock> try_take(const std::filesystem::path& path, std::string_view note);
  /// The note of the process that holds `path`'s lock ("" when the file does not read).
  static std::string holder(const std::filesystem::path& path);

  /// Removes the file, then lets go of the lock.
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  FileLock(std::filesystem::path path, int fd);
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace fw::base
