#include "host/app/OutputSpace.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "host/app/OutputSize.hpp"

namespace fw::host {

namespace {
constexpr double kPercent = 100.0;
constexpr int kMebiShift = 20;  // bytes >> 20: MiB
}  // namespace

std::filesystem::path nearest_existing(const std::filesystem::path& path) {
  std::filesystem::path at = std::filesystem::absolute(path);
  std::error_code error;
  while (!std::filesystem::exists(at, error) && at.has_relative_path()) at = at.parent_path();
  return at;
}

void require_output_space(const SimulationPlan& plan, const std::filesystem::path& directory, double end_time,
                          const Communicator& world, std::optional<std::uint64_t> free_bytes,
                          double resumed_at) {
  double measured = 0.0;  // bytes; rank 0's, shared (a double holds them exactly below 2^53)
  const std::filesystem::path existing = nearest_existing(directory);
  if (world.rank() == 0) {
    if (free_bytes) {
      measured = double(*free_bytes);
    } else {
      std::error_code error;
      const std::filesystem::space_info space = std::filesystem::space(existing, error);
      // A filesystem that does not say how much room it has is not refused.
      measured = error ? std::numeric_limits<double>::infinity() : double(space.available);
    }
  }
  const double available = world.max(measured);
  const OutputSize size = predict_output_size(plan, end_time);
  // With every leaf shed: the bound, not the estimate; after a checkpoint, what the run adds to the folder.
  const std::uint64_t before = resumed_at > 0.0 ? predict_output_size(plan, resumed_at).most() : 0;
  const std::uint64_t needed = size.most() - std::min(before, size.most());
  const std::uint64_t margin =
      std::uint64_t(std::llround(kSpaceMarginFraction * double(needed))) + kSpaceMarginBytes;
  if (double(needed + margin) <= available) return;
  throw std::invalid_argument(fmt::format(
      "{}: not enough disk space for the output: the run would write {} ({} bytes; `forestwind check` lists "
      "it by output), with a margin of {} ({} bytes: {:g}% + {} MiB) it needs {} bytes, and {} has {} ({} "
      "bytes) "
      "free. Shrink the output with output.interval, output.vtk.wind_every, output.vtk.trees_every, "
      "output.leaves.every, output.vdb.every, output.vtk.fields, output.leaves.attached, output.vdb.enabled "
      "or output.vdb.grids, or time.end (--end); or run with --force",
      plan.scenario.file_name, human_bytes(needed), needed, human_bytes(margin), margin,
      kSpaceMarginFraction * kPercent, kSpaceMarginBytes >> kMebiShift, needed + margin, existing.string(),
      human_bytes(std::uint64_t(available)), std::uint64_t(available)));
}

}  // namespace fw::host
