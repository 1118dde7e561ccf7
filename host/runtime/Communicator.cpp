#include "host/runtime/Communicator.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>

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
