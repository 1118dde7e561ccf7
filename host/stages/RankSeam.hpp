// The wind grid's one seam with the other MPI ranks (docs/parallel.md): which block of the grid this rank
// holds, the halo exchanges its parts declared, and its collectives. In one process the block is the whole
// grid, and every exchange does nothing; the parts call the same functions either way, so that no part asks
// how many ranks there are.
//
//   fw::host::RankSeam seam(cc, spec, blocks);             // blocks: null in one process
//   seam.declare({fw::host::HaloField::faces, FW_PAD});     // what a part reads of its neighbours' cells
//   seam.exchange(velocity);                                // fills the declared halos (nothing alone)
//   double total = seam.world().sum(local_sum);             // exact over ranks (Communicator)
//   std::vector<float> mine = seam.cut(whole_field);         // this rank's block of a whole-grid array
//
// A field exchanged without a declaration is refused (std::logic_error, in one process too), so a part's
// halo_needs() stay what it exchanges. A declared width wider than the decomposition's halo is refused when
// declared (std::invalid_argument): the ranks would read cells nobody sent.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/HaloExchange.hpp"
#include "host/stages/PressureSolver.hpp"

namespace fw::host {

/// The layouts a part can exchange: the velocity's three face arrays, a float a cell, four floats a cell
/// (interleaved, as the vorticity and its magnitude).
enum class HaloField { faces, cells, cell_quads };
/// A part's need: a layout, and how many cells of it beyond the block's edge it reads.
struct HaloNeed {
  HaloField field = HaloField::faces;
  int width = 1;
};

class RankSeam {
 public:
  /// The block this rank holds of `whole`: its decomposition's block with the halo under mpirun (blocks
  /// non-null over several ranks), else the whole grid.
  RankSeam(ComputeContext& cc, const fluid::GridSpec& whole, const WindBlocks* blocks);
  RankSeam(const RankSeam&) = delete;  // share_ points into it
  RankSeam& operator=(const RankSeam&) = delete;

  /// This rank's share of the grid.
  const BlockShare& share() const { return share_; }
  /// The pressure solver's view of the ranks: null in one process.
  const PressureBlocks* pressure_blocks() const { return share_.splits() ? &pressure_blocks_ : nullptr; }

  const fluid::GridSpec& local() const { return local_; }
  /// This rank's cells with the halo (the whole grid in one process).
  const BlockArray& block() const { return block_; }
  const Communicator& world() const { return *world_; }
  /// The cells of halo the exchanges fill: the decomposition's; unbounded in one process, where no value
  /// lies beyond a block's edge.
  int halo_width() const { return share_.splits() ? decomposition_.halo() : std::numeric_limits<int>::max(); }

  /// This rank's block of a whole-grid array of cells (or of component c's faces), x fastest; `whole`
  /// itself in one process.
  template <typename T>
  std::vector<T> cut(std::vector<T> whole, int component = -1) const {
    return share_.cut(std::move(whole), whole_, component);
  }

  /// Makes the exchange of `need.field` available. Throws std::invalid_argument when need.width exceeds
  /// halo_width().
  void declare(const HaloNeed& need);
  /// Fills the halo of each velocity component from the neighbours (HaloField::faces).
  void exchange(DeviceVelocity& vel);
  /// Fills the halo of a field of a float a cell (HaloField::cells).
  void exchange_cells(cl::Buffer& field);
  /// Fills the halo of a field of four floats a cell (HaloField::cell_quads).
  void exchange_quads(cl::Buffer& field);
  /// Across a cut periodic axis, the domain's last face of u (along x) and v (along y) becomes a copy of its
  /// first, as a whole grid's boundary pass makes it (HaloExchange::copy_seam; HaloField::faces).
  void copy_seam(DeviceVelocity& vel);
  /// What every exchange of this seam has sent, and its time.
  HaloTraffic traffic() const;

 private:
  void require(HaloField field, const char* what) const;

  ComputeContext& cc_;
  fluid::GridSpec whole_;
  const Communicator* world_;
  fluid::Decomposition decomposition_;
  BlockShare share_;  // points at decomposition_
  BlockArray block_;
  fluid::GridSpec local_;
  PressureBlocks pressure_blocks_;
  std::set<HaloField> declared_;
  std::array<std::optional<HaloExchange>, 3> faces_;  // per velocity component, over several ranks
  std::optional<HaloExchange> cells_, quads_;
};

}  // namespace fw::host
