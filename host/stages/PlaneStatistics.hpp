// The wind's profiles against height (fluid/PlaneProfiles: the definitions and the CPU reference), taken on
// the device from the fields in place, the same on every rank and, to the bit, whatever the split.
//
//   fw::host::PlaneStatistics statistics(cc, wind.spec(), wind.local_spec(), wind.block(), world);
//   fw::fluid::PlaneProfiles p = statistics.sample(wind.statistics_fields(), max_speed_component);
//   double uw = p.at(fw::fluid::Profile::u_w, k);                  // m^2/s^2, plane k's resolved flux
//
// One kernel pass (kernels/plane_statistics.cl) sums, for every row of the block's own cells, the raw
// moments of each cell's centred velocity (u, u^2, u^3, u w, ...), the subgrid terms -2 nu_t S_xz and
// -2 nu_t S_yz, the subgrid energy and the drag density, each cell's term cut toward 0 to a 32-bit multiple
// of 2^-s (a fixed point, s per term) and summed as 64-bit integers. Integers add exactly in any order, so
// the plane sums, added over the rows on the host and over the ranks by an exchange, are the same for every
// split. The host then forms the central moments in double: u_2 = <u^2> - <u>^2, u_3 = <u^3> - 3 <u> <u^2> +
// 2 <u>^3, u_w = <u w> - <u> <w>. Their error is the float rounding of each cell's product (a relative 2^-24
// of u^3, not of the moment), and the fixed point's cut, less than 2^-22 of the term's largest value
// (docs/statistics.md).
//
// The scales: s is the largest exponent for which a bound on |term| times 2^s stays within 2^27
// (FW_PLANE_CELL_BITS: 15 cells add in a 32-bit lane, and a plane of up to 2^35 cells sums below 2^62): the
// region's last sample's maxima, doubled (PlaneScales), or at first bounds from the speed. The pass also
// returns each term's largest |value| over every rank; a term that passed its scale's range, or used less
// than 2^-4 of it, is summed again at its own. So no sum overflows, every term is resolved to 2^-22 of its
// largest value, and the bits depend only on the fields and the scales (which a checkpoint keeps).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/PlaneProfiles.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/WindGrid.hpp"
#include "kernels/shared_types.h"

namespace fw::host {

/// The scales a region's last sample found (2^exponent per term, room for its maxima to double), for its
/// next: a caller that keeps them takes one pass a sample where the fields change slowly. What a checkpoint
/// keeps with the run's statistics, so that a resumed run sums at the same scales.
struct PlaneScales {
  std::array<int, FW_PLANE_TERMS> exponents{};
  bool known = false;
};

/// A horizontal part of the domain the planes are averaged over: cells first .. end - 1 along x and y,
/// global indices. The default, or an end of 0, is the whole plane.
struct PlaneRegion {
  std::array<int, 2> first{0, 0};
  std::array<int, 2> end{0, 0};
};

class PlaneStatistics {
 public:
  /// spec: the whole grid; local: this rank's block with its halo (spec in one process); block: its cells.
  PlaneStatistics(ComputeContext& cc, const fluid::GridSpec& spec, const fluid::GridSpec& local,
                  const BlockArray& block, const Communicator& world);

  /// Bytes the statistics allocate on a block of `local` (a row's partials and maxima, the scales).
  static std::size_t estimate_device_bytes(const fluid::GridSpec& local);

  /// The profiles of `fields` over `region` now: the same on every rank (collective over ranks). scales: the
  /// region's from its last sample, updated for the next (null or not known: from speed_bound, the largest
  /// |u|, |v| or |w| of the field in m/s or any estimate of it). A wrong scale costs a second pass, never a
  /// wrong sum. Blocks until the device is done.
  fluid::PlaneProfiles sample(const WindStatisticsFields& fields, double speed_bound,
                              const PlaneRegion& region = {}, PlaneScales* scales = nullptr);

  /// The largest speed |(u, v, w)| at a cell centre of the last sample's region, m/s (over every rank).
  double largest_speed() const { return largest_[FW_TERM_SPEED]; }
  /// How many passes the samples so far took beyond one each (a bound passed): for tests and benchmarks.
  long extra_passes() const { return extra_passes_; }

  /// Bytes a pass over the whole of `local` reads at least once: the face velocity, the mask and each
  /// optional field `fields` holds (what a benchmark divides by the time for the bandwidth).
  static std::size_t bytes_read(const fluid::GridSpec& local, const WindStatisticsFields& fields);

  /// The largest s with bound * 2^s <= 2^FW_PLANE_CELL_BITS (kept within the float's exponents): a term's
  /// scale.
  static int scale_exponent(double bound);

 private:
  /// Runs the pass at `exponents` over this rank's part of `region`; fills sums_ (added over rows and ranks,
  /// per term and height) and largest_ (per term, over every rank).
  void run_pass(const WindStatisticsFields& fields, const std::array<int, FW_PLANE_TERMS>& exponents,
                const PlaneRegion& region);
  /// largest_ of the products of u, v and w from their factors' (the kernel takes no maximum of them).
  void bound_products();
  /// The profiles from sums_ at `exponents`.
  fluid::PlaneProfiles profiles(const std::array<int, FW_PLANE_TERMS>& exponents, double plane_cells) const;

  ComputeContext& cc_;
  fluid::GridSpec spec_, local_;
  BlockArray block_;
  const Communicator& world_;
  Kernel kernel_;
  cl::Buffer sums_device_, largest_device_, scales_device_;
  std::vector<std::int64_t> sums_;               // [k][term], over the region's planes
  std::array<float, FW_PLANE_TERMS> largest_{};  // |term|, over every rank
  long extra_passes_ = 0;
};

}  // namespace fw::host
