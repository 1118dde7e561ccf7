// The output folder's two conditions for a run (docs/runs.md, "Faults"): it can be written, checked before
// the device is touched; and no other run writes into it, a lock held for the whole run.
//
//   fw::host::require_writable_output("out/storm", world);               // exit 2 for a read-only folder
//   auto lock = fw::host::lock_output_folder("out/storm", world);        // creates it; exit 2 when held
//
// The lock is an flock(2) on DIR/.forestwind.lock (base/FileLock), taken by rank 0 alone over MPI ranks;
// every rank stops when it fails. The file names the holder (process id, machine, start) and is removed when
// the run ends; a killed run's is taken over. `check` writes nothing and takes no lock.
#pragma once

#include <filesystem>
#include <memory>

#include "base/FileLock.hpp"
#include "host/runtime/Communicator.hpp"

namespace fw::host {

/// The lock file's name in the output folder.
inline constexpr const char* kOutputLockName = ".forestwind.lock";

/// Throws std::invalid_argument (exit 2) naming `directory` when it cannot be written: it is not a folder, or
/// it (when it exists; else its nearest existing ancestor, where it would be created) denies writing
/// (access(2) with the effective ids: a read-only mount or missing permission). Rank 0 checks, every rank
/// throws alike (collective).
void require_writable_output(const std::filesystem::path& directory, const Communicator& world);

/// Creates `directory` and takes its lock on rank 0 (nullptr elsewhere). Throws std::invalid_argument (exit
/// 2), on every rank, when another run holds it, naming the folder and that run; std::runtime_error when the
/// folder cannot be made or locked. Collective.
std::unique_ptr<base::FileLock> lock_output_folder(const std::filesystem::path& directory,
                                                   const Communicator& world);

}  // namespace fw::host
