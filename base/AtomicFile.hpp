// A file that appears under its final name only once it is complete: it is written under a temporary name in
// the same folder and renamed into place by commit(). Readers (ParaView watching a folder, a crash midway)
// therefore never see a half-written file.
//
//   fw::base::AtomicFile file("out/modes.vtp");
//   writer->SetFileName(file.temporary_path().c_str());   // any writer that takes a path
//   writer->Write();
//   file.commit();                                        // rename(temporary, final); throws on failure
//
// If commit() is never called (an exception on the way), the destructor removes the temporary file.
#pragma once

#include <string_view>

#include <filesystem>

namespace fw::base {

class AtomicFile {
 public:
  /// target: the final path. The temporary is "<target>.tmp-<pid>" next to it. The parent folder must exist.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temporary_path() const { return temporary_; }

  /// Renames the temporary onto the target (replacing it). Throws std::runtime_error("AtomicFile: ...")
  /// naming both paths if the temporary is missing or the rename fails.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

/// Removes, in `folder` and below, the temporaries of atomic writes whose process was killed before its
/// commit (kill -9 leaves "<target>.tmp-<pid>"); a resumed run calls it on its output folder, which no other
/// process writes. Returns how many it removed.
int remove_stale_temporaries(const std::filesystem::path& folder);

// The two helpers every writer shares: the same folder check and the same atomic text write, with the
// same error messages.

/// Throws std::runtime_error("FUNCTION: cannot write PATH: the folder F does not exist" / "F is not a
/// folder") unless the parent folder of `path` (or "." for a bare name) is an existing folder.
void require_output_folder(const char* function, const std::filesystem::path& path);

/// Writes `content` byte for byte to `path` through AtomicFile (temporary + rename). Throws
/// std::runtime_error("FUNCTION: cannot write PATH: reason") on failure (a full disk: "No space left on
/// device", from the failing write(2) or close(2)); no temporary is left behind.
void write_text_atomically(const char* function, const std::filesystem::path& path, std::string_view content);

/// Appends `content` to `path` (created if missing) with POSIX writes. Throws std::runtime_error("FUNCTION:
/// cannot write PATH: reason") on failure, after cutting the file back to its size before the call, so that
/// a full disk never leaves half a line at its end.
void append_text(const char* function, const std::filesystem::path& path, std::string_view content);

}  // namespace fw::base
