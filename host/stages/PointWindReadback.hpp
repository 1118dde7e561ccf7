// The wind at fixed world points on the device, read back as a few floats: what probes sample every probe
// interval without copying the grid back (kernels/probe_sample.cl).
//
//   fw::host::PointWindReadback probes(cc, spec, {{40, 120, 10}, {160, 120, 10}});   // m, world frame
//   std::vector<std::array<float, 3>> wind = probes.sample(grid.velocity());      // m/s, blocks
//
// Each point is sampled like a tree's wind sample (trilinear on each component's staggered lattice, clamped
// to it), so that a probe and a tree at the same place see the same wind. On a rank's block, only points
// whose cell lies in the block's cells (or a cell or two into its halo) sample correctly; over ranks,
// host/stages/PointWindAcrossRanks sends each point to the rank that holds it.
#pragma once

#include <array>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/FluidStages.hpp"

namespace fw::host {

class PointWindReadback {
 public:
  /// points: world positions, m. Throws std::invalid_argument("PointWindReadback: ...") for an invalid spec
  /// or a non-finite position.
  PointWindReadback(ComputeContext& cc, const fluid::GridSpec& spec,
                    const std::vector<std::array<double, 3>>& points);
  /// positions: 3 floats a point, world frame, m, as the device rounds them.
  PointWindReadback(ComputeContext& cc, const fluid::GridSpec& spec, std::vector<float> positions);

  /// points as 3 floats a point, as the device rounds them (what the second constructor takes).
  static std::vector<float> flat_positions(const std::vector<std::array<double, 3>>& points);

  /// Bytes the constructor allocates for `point_count` points: their positions and their sampled wind.
  static std::size_t estimate_device_bytes(std::size_t point_count);

  int point_count() const { return count_; }
  /// The velocity at every point, m/s, in the constructor's order. Blocks until read back.
  std::vector<std::array<float, 3>> sample(DeviceVelocity& velocity);
  /// The same as 3 floats a point.
  std::vector<float> sample_flat(DeviceVelocity& velocity);

 private:
  ComputeContext& cc_;
  FwGrid grid_;
  int count_ = 0;
  cl::Buffer positions_, wind_;
  Kernel kernel_;
};

}  // namespace fw::host
