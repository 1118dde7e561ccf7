// `forestwind bench trees`: the precomputation of one species, timed on the host CPU.
//
// Each case generates a broadleaf tree (trees/TreeGenerator.hpp) whose element length is chosen so that it
// has about the target node count (300, 1,000, 3,437 = Diener's digitised walnut, 10,000, 30,000), then times
// BeamModel assembly plus ModalBasis::compute for 25 modes (Spectra shift-invert Lanczos on the sparse
// matrices). Where the dense matrices are small enough to solve in reasonable time (dofs <= dense_max_dofs),
// Eigen's dense generalized eigensolver runs on the same model in the same process as the baseline, and the
// largest relative difference between the two sets of frequencies is reported.
//
//   TreeBenchOptions opt;                       // defaults as above
//   TreeBenchResult r = run_tree_bench(opt);
//   print_tree_bench_table(r, std::cout);       // or tree_bench_json(r)
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace fw::bench {

struct TreeBenchOptions {
  std::vector<int> target_nodes{300, 1000, 3437, 10000, 30000};
  int modes = 25;
  int dense_max_dofs = 2500;  // dense baseline only up to this many DOFs: O(n^3) time (88 s at 6,000)
  std::string preset = "broadleaf";
  double height = 15.0;  // m
  unsigned seed = 1;
};

struct TreeBenchCase {
  int target_nodes = 0;
  int nodes = 0;
  int dofs = 0;
  int modes = 0;
  double max_element_length = 0.0;  // m, chosen to approach target_nodes
  double seconds = 0.0;             // assembly + modal solve
  double assembly_seconds = 0.0;
  double factorise_seconds = 0.0;
  double lanczos_seconds = 0.0;
  int iterations = 0;
  int operations = 0;
  double max_residual = 0.0;
  double first_hz = 0.0;
  double last_hz = 0.0;
  double dense_seconds = 0.0;            // 0 when the dense baseline did not run
  double dense_max_relative_diff = 0.0;  // max_i |f_sparse - f_dense| / f_dense over the m modes
};

struct TreeBenchResult {
  std::string cpu;
  int threads = 1;
  std::vector<TreeBenchCase> cases;
};

TreeBenchResult run_tree_bench(const TreeBenchOptions& options);
void print_tree_bench_table(const TreeBenchResult& result, std::ostream& out);
std::string tree_bench_json(const TreeBenchResult& result);

}  // namespace fw::bench
