// Whether the output folder's filesystem has room for a run (docs/design.md, "Long runs"): the predicted
// output (host/app/OutputSize.hpp, its bound) plus a margin, against the free space of the folder's nearest
// existing ancestor, checked before the device or the folder is touched.
//
//   fw::host::require_output_space(plan, "out/storm", plan.end_time, world);   // throws when it lacks room
//   fw::host::require_output_space(plan, dir, end, world, /*free_bytes=*/1000);  // a test's free space
//
// The margin is 5% of the prediction plus 64 MiB: the prediction's own tolerance (within 15% on the
// examples, mostly under; see docs/design.md) and room for the temporaries of the frames being written
// and for other writers on the same disk.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "host/app/SimulationPlan.hpp"
#include "host/runtime/Communicator.hpp"

namespace fw::host {

inline constexpr double kSpaceMarginFraction = 0.05;
inline constexpr std::uint64_t kSpaceMarginBytes = std::uint64_t(64) << 20;

/// `path` itself when it exists, else its nearest existing ancestor (the working directory for a relative
/// path without one).
std::filesystem::path nearest_existing(const std::filesystem::path& path);

/// Throws std::invalid_argument (exit 2) when the free space for `directory` (its nearest existing
/// ancestor's filesystem; `free_bytes` instead when given, a test hook) is less than the predicted output of
/// a run to `end_time` (s) plus the margin. The message gives the prediction, the free space and the margin
/// and names the keys that shrink the output. Over ranks rank 0 measures and every rank decides alike
/// (collective). resumed_at: a run resumed from a checkpoint at that time (s) writes only what comes after
/// it (what came before is in the folder already, or is not written in a new one).
void require_output_space(const SimulationPlan& plan, const std::filesystem::path& directory, double end_time,
                          const Communicator& world, std::optional<std::uint64_t> free_bytes = std::nullopt,
                          double resumed_at = 0.0);

}  // namespace fw::host
