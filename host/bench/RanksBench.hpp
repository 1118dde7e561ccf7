// `forestwind bench wind|coupled` over MPI ranks (mpirun -np N): what each rank measured on a grid,
// gathered on rank 0, and the figures made of them: the step's wall time (the slowest rank's), the halo
// bytes and the time of the halo exchanges, the parallel efficiency against one rank running the whole grid
// in the same process, and a weak-scaling estimate to 64 ranks (host/bench/WeakScaling.hpp).
// docs/parallel.md, "Benchmarks over ranks", says what each figure means and how it is measured.
//
//   RankRun mine{ms_per_step, alone_ms, halo_traffic, steps, pressure_iterations};   // on every rank
//   RanksCase c = gather_case(world, grid, decomposition, mine);   // c.ranks: on rank 0 every rank's
//   if (world.rank() == 0) print_ranks_bench_table(result, std::cout);   // or ranks_bench_json(result)
#pragma once

#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "host/bench/WeakScaling.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/Device.hpp"
#include "host/stages/HaloExchange.hpp"

namespace fw::bench {

/// One rank's figures on one grid, per timed step.
struct RankStep {
  double ms = 0.0;             // the rank's wall time of a step
  double halo_ms = 0.0;        // of which in halo exchanges (device-host copies and MPI waits)
  double halo_copy_ms = 0.0;   // of which the device-host copies
  double halo_bytes = 0.0;     // bytes the rank sent
  double halo_messages = 0.0;  // messages the rank sent
  double alone_ms = 0.0;       // a step of the whole grid on this rank alone, every rank at once; 0: not run
  int sides = 0;               // sides of the rank's block with a neighbour (0 to 4)
};

/// A rank's RankStep: `timed` is its halo traffic over `steps` timed steps, `block` its block.
RankStep rank_step(double ms_per_step, double alone_ms, const host::HaloTraffic& timed, int steps,
                   const fluid::Block& block);

/// Every rank's `mine`, on rank 0 in rank order; an empty list on the others. Collective.
std::vector<RankStep> gather_rank_steps(const host::Communicator& world, const RankStep& mine);

/// Whether every rank can hold the whole grid for its one-rank run (`bytes` of device memory), with the
/// ranks of a machine sharing a CPU device's memory. Collective: every rank gets the same answer.
bool alone_run_fits(const host::Communicator& world, const host::DeviceInfo& device, std::size_t bytes);

/// One grid over the ranks.
struct RanksCase {
  std::array<int, 3> grid{};
  std::string decomposition;         // fluid::Decomposition::describe()
  std::array<int, 2> blocks{1, 1};   // along x and y
  int halo = 0;                      // cells
  double pressure_iterations = 0.0;  // mean per step (every rank's is the same)
  std::vector<RankStep> ranks;       // every rank's, by rank

  /// The step's wall time: the slowest rank's ms per step (the ranks wait for each other every step).
  double ms_per_step() const;
  /// The mean of the ranks' one-rank runs; 0 when they did not run.
  double alone_ms_per_step() const;
  /// alone_ms_per_step() / ms_per_step(), and that over the ranks; 0 without the one-rank runs.
  double speedup() const;
  double efficiency() const;
  double halo_bytes() const;   // every rank's, per step
  double halo_ms_max() const;  // the largest rank's halo time per step
  /// The figures of the weak-scaling estimate: the slowest rank's compute, and the largest cost of a side.
  MeasuredBlock measured_block() const;
};

/// What a rank timed on one grid: its run over the ranks and its one-rank run.
struct RankRun {
  double ms_per_step = 0.0;
  double alone_ms = 0.0;             // 0: not run
  host::HaloTraffic halo;            // over the timed steps
  int steps = 1;                     // timed
  double pressure_iterations = 0.0;  // mean per step
};

/// The case of `grid` split by `decomposition` over the ranks of `world`, every rank's figures gathered on
/// rank 0 from its `mine`. Collective.
RanksCase gather_case(const host::Communicator& world, const std::array<int, 3>& grid,
                      const fluid::Decomposition& decomposition, const RankRun& mine);

struct RanksBenchResult {
  std::string bench;     // "wind" or "coupled"
  std::string device;    // rank 0's
  std::string workload;  // what a timed step does, one line
  std::string skipped;   // what the benchmark times in one process and not over ranks
  int ranks = 0;
  int steps = 0;
  Interconnect interconnect;
  std::vector<RanksCase> cases;
};

void print_ranks_bench_table(const RanksBenchResult& result, std::ostream& out);
std::string ranks_bench_json(const RanksBenchResult& result);

}  // namespace fw::bench
