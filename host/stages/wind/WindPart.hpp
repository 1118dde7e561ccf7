// A part of the wind grid's step (host/stages/WindGrid): one job, the device buffers it owns, what it needs
// of the neighbouring ranks, and what it carries from one step to the next.
//
//   fw::host::WallStress wall(context, mask);                     // allocates its buffers
//   wall.device_bytes() == fw::host::WallStress::estimate_device_bytes(...);   // exactly what it allocated
//   for (const fw::host::HaloNeed& need : wall.halo_needs()) seam.declare(need);
//   context.clock.time(wall.stage(), [&] { wall.apply(fields); });
//
// Every part
// - owns its buffers, and its class's static estimate_device_bytes() gives their bytes exactly before any is
//   allocated (the planner and the device-fit check add the parts up);
// - declares the fields it exchanges with the neighbouring ranks, and how wide (RankSeam refuses an exchange
//   nobody declared);
// - saves what it carries from step to step into the grid's StageState under its own names, restores it, and
//   names the arrays over the grid among them, which a resume over another split redistributes;
// - names the stage its work is timed under.
// A part never asks which kind another part is: what it needs of another comes in as a buffer or a setting.
#pragma once

#include <cstddef>
#include <vector>

#include "host/runtime/ComputeContext.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/RankSeam.hpp"
#include "host/stages/SavedShare.hpp"
#include "host/stages/StageState.hpp"
#include "host/stages/wind/StageClock.hpp"
#include "host/stages/wind/WindGridSetup.hpp"

namespace fw::host {

/// What every part works with: the device, the grid's kernels (over this rank's block), the seam, the
/// clock, and the whole grid's setup.
struct WindPartContext {
  ComputeContext& cc;
  FluidStages& stages;
  RankSeam& seam;
  StageClock& clock;
  const WindGridSetup& setup;
};

/// The velocity the parts step, and one scratch velocity of the same shape that a part may overwrite (what
/// it holds between parts means nothing). Owned by the grid.
struct WindFields {
  DeviceVelocity vel, tmp;
};

/// The name the wind grid's saved state and its errors go under.
inline constexpr const char* kWindGridState = "wind grid";

class WindPart {
 public:
  virtual ~WindPart() = default;
  /// The stage its work is timed under (WindGrid::stage_ms).
  virtual const char* stage() const = 0;
  /// Bytes of device memory it allocated: its class's estimate_device_bytes for the same grid.
  virtual std::size_t device_bytes() const = 0;
  /// The fields it exchanges with the neighbouring ranks, and how far past the block's edge it reads them.
  virtual std::vector<HaloNeed> halo_needs() const = 0;
  /// Adds what the next step reads of this part to `state` (blocking reads); nothing by default.
  virtual void save_state(StageState& state) { (void)state; }
  /// Sets what save_state saved; throws std::invalid_argument naming what does not fit.
  virtual void restore_state(const StageState& state) { (void)state; }
  /// The arrays over the grid that save_state writes: a checkpoint saved over other blocks puts each
  /// together from every block's own values and cuts it to this rank's (WindGrid::share_of). None by
  /// default; numbers (a time, an offset, an integral) are the same on every rank and carry over as saved.
  virtual std::vector<GridArray> saved_arrays() const { return {}; }
};

}  // namespace fw::host
