// The wind at points whose positions live on the device, sampled into a device buffer every step: the trees'
// wind samples and the leaves' sites. Over MPI ranks each point is sampled by the rank whose block holds it
// (host/stages/PointWindAcrossRanks), and only those points travel through the host.
//
//   fw::host::PointWindOnDevice samples(cc, spec, blocks, positions, count);   // positions: 3 floats a point
//   samples.enqueue_sample(wind.velocity());    // collective over ranks
//   kernel.set_args(..., samples.wind());       // 3 floats a point, m/s
//
// Each point is sampled as a probe is (kernels/probe_sample.cl: trilinear on each component's staggered
// lattice, clamped to it, in the domain's indices), so the wind is the bits one process samples whichever
// rank holds the point.
#pragma once

#include <memory>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/PointWindAcrossRanks.hpp"
#include "kernels/shared_types.h"

namespace fw::host {

class PointWindOnDevice {
 public:
  /// positions: `count` points, 3 floats each (world frame, m), already on the device and fixed from here on.
  /// spec: this rank's grid (block_spec over ranks); blocks: null alone. Over ranks it reads the positions
  /// back once and is collective.
  PointWindOnDevice(ComputeContext& cc, const fluid::GridSpec& spec, const WindBlocks* blocks,
                    cl::Buffer positions, int count);

  /// Bytes of device memory the wind of `count` points takes (what the constructor allocates alone).
  static std::size_t estimate_device_bytes(std::size_t count);

  int count() const { return count_; }
  /// The points another rank samples for this one.
  int remote_count() const { return exchange_ ? exchange_->point_count() : 0; }
  /// The wind at every point into wind(). Over ranks collective (every rank calls it at the same steps, with
  /// or without points), and it blocks while the remote points' wind travels.
  void enqueue_sample(DeviceVelocity& velocity);
  /// 3 floats a point, m/s.
  cl::Buffer& wind() { return wind_; }

 private:
  /// Over ranks: the points whose cells another rank holds, and the exchange that brings their wind.
  void share(const fluid::GridSpec& spec, const WindBlocks& blocks);

  ComputeContext& cc_;
  FwGrid grid_;
  int count_ = 0;
  cl::Buffer positions_, wind_;
  Kernel sample_, place_;
  std::unique_ptr<PointWindAcrossRanks> exchange_;
  cl::Buffer remote_slots_, remote_wind_;  // the remote points' indices, and the wind they bring
};

}  // namespace fw::host
