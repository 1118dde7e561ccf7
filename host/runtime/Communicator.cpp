#include "host/runtime/Communicator.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace fw::host {

bool launched_by_mpi() {
  // OpenMPI's mpirun, a PMIx launcher (srun --mpi=pmix, prterun) and PMI-1/2 launchers (srun --mpi=pmi2,
  // MPICH's Hydra) each set one of these in every process they start.
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(variable) != nullptr) return true;
  return false;
}

const Communicator& Communicator::alone() {
  static const Communicator one;
  return one;
}

double Communicator::sum(const base::ExactSum& local) const {
  if (!uses_mpi()) return local.value();
  base::ExactSum total;
  MPI_Allreduce(local.slots().data(), total.slots().data(), base::ExactSum::kSlots, MPI_INT64_T, MPI_SUM,
                comm_);
  return total.value();
}

double Communicator::max(double local) const {
  if (!uses_mpi()) return local;
  // MPI_MAX has no rule for NaN, so NaN travels as a count beside the maximum of the numbers.
  const double values[2] = {std::isnan(local) ? -std::numeric_limits<double>::infinity() : local,
                            std::isnan(local) ? 1.0 : 0.0};
  double result[2] = {0, 0};
  MPI_Allreduce(values, result, 2, MPI_DOUBLE, MPI_MAX, comm_);
  return result[1] > 0.0 ? std::numeric_limits<double>::quiet_NaN() : result[0];
}

long long Communicator::sum(long long local) const {
  if (!uses_mpi()) return local;
  long long total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, comm_);
  return total;
}

long long Communicator::min(long long local) const {
  if (!uses_mpi()) return local;
  long long least = 0;
  MPI_Allreduce(&local, &least, 1, MPI_LONG_LONG, MPI_MIN, comm_);
  return least;
}

void Communicator::barrier() const {
  if (uses_mpi()) MPI_Barrier(comm_);
}

std::vector<std::vector<std::byte>> Communicator::exchange_bytes(
    const std::vector<std::vector<std::byte>>& to_each) const {
  if (to_each.size() != std::size_t(size_))
    throw std::invalid_argument(
        fmt::format("Communicator::exchange: {} lists for {} ranks", to_each.size(), size_));
  if (!uses_mpi()) return to_each;
  const auto ranks = static_cast<std::size_t>(size_);
  std::vector<int> send_counts(ranks), send_offsets(ranks);
  std::vector<std::byte> sent;
  for (std::size_t r = 0; r < to_each.size(); ++r) {
    send_offsets[r] = int(sent.size());
    send_counts[r] = int(to_each[r].size());
    sent.insert(sent.end(), to_each[r].begin(), to_each[r].end());
  }
  std::vector<int> receive_counts(ranks), receive_offsets(ranks);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm_);
  int total = 0;
  for (std::size_t r = 0; r < receive_counts.size(); ++r) {
    receive_offsets[r] = total;
    total += receive_counts[r];
  }
  std::vector<std::byte> received(static_cast<std::size_t>(total));
  MPI_Alltoallv(sent.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, received.data(),
                receive_counts.data(), receive_offsets.data(), MPI_BYTE, comm_);
  std::vector<std::vector<std::byte>> from_each(ranks);
  for (std::size_t r = 0; r < from_each.size(); ++r)
    from_each[r].assign(received.begin() + receive_offsets[r],
                        received.begin() + receive_offsets[r] + receive_counts[r]);
  return from_each;
}

void Communicator::abort(int code) const {
  if (uses_mpi()) MPI_Abort(comm_, code);
  std::exit(code);
}

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  MPI_Init(&argc, &argv);
  initialised_ = true;
  world_.comm_ = MPI_COMM_WORLD;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &world_.size_);
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, world_.rank_, MPI_INFO_NULL, &node_);
  MPI_Comm_rank(node_, &world_.node_rank_);
  MPI_Comm_size(node_, &world_.node_size_);
}

MpiSession::~MpiSession() {
  if (!initialised_) return;
  MPI_Comm_free(&node_);
  MPI_Finalize();
}

}  // namespace fw::host
