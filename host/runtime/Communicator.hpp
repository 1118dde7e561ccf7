// The run's processes: one MPI rank per OpenCL device under mpirun or srun, or one process alone.
//
//   fw::host::MpiSession session(argc, argv);         // in main(): MPI_Init when a launcher started us
//   const fw::host::Communicator& world = session.world();
//   world.rank(); world.size();                       // 0 and 1 without a launcher
//   world.node_rank(); world.node_size();             // among the ranks of this machine: which device
//   fw::base::ExactSum local = ...;
//   double total = world.sum(local);                  // the same bits on every rank, whatever the split
//   double largest = world.max(x);                    // NaN on any rank wins
//   world.barrier();                                  // every rank here before any goes on
//   world.abort(1);                                   // stops every rank (never returns)
//
// Without a launcher (no OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK in the environment) MPI is never
// initialised, and the program runs as it always has: one rank, the collectives local. Communicator::alone()
// is that rank for code that runs without a session (tests, tools).
//
// Sums are exact (base/ExactSum): each rank's bins are added as 64-bit integers (MPI_SUM is then
// associative), and every rank rounds the same bins to the same double. A sum over ranks therefore equals the
// sum of the same terms in one process, bit for bit (docs/parallel.md).
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <type_traits>
#include <vector>

#include "base/ExactSum.hpp"

namespace fw::host {

/// True when an MPI launcher (mpirun, mpiexec, srun) started this process.
bool launched_by_mpi();

class Communicator {
 public:
  /// The one rank of a process that runs alone (no MPI).
  static const Communicator& alone();

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// This rank's index among the ranks on its machine, and their count: a node's r-th rank takes its r-th
  /// device, and on a CPU its share of the cores.
  int node_rank() const { return node_rank_; }
  int node_size() const { return node_size_; }
  bool uses_mpi() const { return comm_ != MPI_COMM_NULL; }
  MPI_Comm comm() const { return comm_; }

  /// The exact sum of every rank's terms, rounded to double: the same on every rank. Collective.
  double sum(const base::ExactSum& local) const;
  /// The largest of every rank's value; NaN when any rank's is NaN. Collective.
  double max(double local) const;
  /// The sum of every rank's count. Collective.
  long long sum(long long local) const;
  /// The smallest of every rank's count. Collective.
  long long min(long long local) const;
  /// Returns once every rank has called it (benchmarks start their clocks together). Collective.
  void barrier() const;
  /// An empty list for each rank, by rank: what exchange() sends, to fill.
  template <typename T>
  std::vector<std::vector<T>> lists() const {
    return std::vector<std::vector<T>>(static_cast<std::size_t>(size_));
  }
  /// Sends to_each[r] to rank r (to_each has size() lists; this rank's own list comes back to it) and
  /// returns what each rank sent this one, by rank. Collective.
  template <typename T>
  std::vector<std::vector<T>> exchange(const std::vector<std::vector<T>>& to_each) const;
  /// Every rank's `mine` on rank 0, by rank; on the other ranks empty lists. Collective (an exchange).
  template <typename T>
  std::vector<std::vector<T>> gather(const std::vector<T>& mine) const {
    std::vector<std::vector<T>> to_each = lists<T>();
    to_each[0] = mine;
    return exchange(to_each);
  }
  /// Every rank's `mine` on every rank, by rank. Collective (an exchange).
  template <typename T>
  std::vector<std::vector<T>> gather_to_all(const std::vector<T>& mine) const {
    return exchange(std::vector<std::vector<T>>(static_cast<std::size_t>(size_), mine));
  }
  /// Stops every rank with `code` (MPI_Abort), or exits this process when alone. Never returns.
  [[noreturn]] void abort(int code) const;

 private:
  friend class MpiSession;
  Communicator() = default;
  /// exchange() on bytes: MPI_Alltoall of the counts, then MPI_Alltoallv. Throws std::invalid_argument
  /// unless to_each has size() lists.
  std::vector<std::vector<std::byte>> exchange_bytes(
      const std::vector<std::vector<std::byte>>& to_each) const;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1, node_rank_ = 0, node_size_ = 1;
};

/// The lists one after another (what an exchange or a gather brought, from every rank in rank order).
template <typename T>
std::vector<T> joined(const std::vector<std::vector<T>>& lists) {
  std::vector<T> all;
  for (const auto& list : lists) all.insert(all.end(), list.begin(), list.end());
  return all;
}

template <typename T>
std::vector<std::vector<T>> Communicator::exchange(const std::vector<std::vector<T>>& to_each) const {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<std::vector<std::byte>> bytes(to_each.size());
  for (std::size_t r = 0; r < to_each.size(); ++r) {
    bytes[r].resize(to_each[r].size() * sizeof(T));
    if (!bytes[r].empty()) std::memcpy(bytes[r].data(), to_each[r].data(), bytes[r].size());
  }
  const std::vector<std::vector<std::byte>> received = exchange_bytes(bytes);
  std::vector<std::vector<T>> from_each(received.size());
  for (std::size_t r = 0; r < received.size(); ++r) {
    from_each[r].resize(received[r].size() / sizeof(T));
    if (!received[r].empty()) std::memcpy(from_each[r].data(), received[r].data(), received[r].size());
  }
  return from_each;
}

/// MPI for the life of main(): initialised when launched_by_mpi(), finalised at the end.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  const Communicator& world() const { return world_; }

 private:
  Communicator world_;
  MPI_Comm node_ = MPI_COMM_NULL;
  bool initialised_ = false;
};

}  // namespace fw::host
