// `forestwind bench models`: the three tree models (docs/tree-models.md) on the same forest and the same
// wind, per step (the wind at the samples, and the model's step) and per output frame (the deformation of
// every node), each per element, with the modal model as the baseline run in the same process and the
// device's FMA peak as the limit; and the storm damage's loads and failure check (docs/damage.md,
// ForestStages::enqueue_damage_check) per step, beside the step it follows.
//
//   fw::bench::TreeModelsBenchOptions options;                  // 1000 trees of about 3,500 nodes
//   auto result = fw::bench::run_tree_models_bench(cc, options);
//   fw::bench::print_tree_models_bench_table(result, std::cout);
//
// The forest stands on a uniform 10 m/s wind uploaded once (the grid is not stepped: only the trees' kernels
// are timed). Each figure is the best of `repetitions` launches (BestTime.hpp).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

struct TreeModelsBenchOptions {
  int trees = 1000;
  int nodes_per_tree = 3500;  // the coupled bench's tree (CoupledBench.hpp)
  int modes = 25;
  int samples = 3;
  int repetitions = 5;
};

struct TreeModelCase {
  std::string model;
  double step_ms = 0.0;   // wind sampling + the model's step, every tree
  double frame_ms = 0.0;  // the deformation of every node
  double loads_ms = 0.0;  // the damage check: every tree's stem loads against its strength
  double step_ns_per_element = 0.0, frame_ns_per_element = 0.0, loads_ns_per_element = 0.0;
  double loads_vs_step = 0.0;                        // the damage check's time over the step's
  double step_vs_modal = 0.0, frame_vs_modal = 0.0;  // ratios to the modal case's times
  double flops_per_element_step = 0.0;  // counted from the kernel's arithmetic, per element and step
  double step_fraction_of_peak = 0.0;   // flops_per_element_step x elements / step time, over the FMA peak
};

struct TreeModelsBenchResult {
  std::string device;
  int trees = 0, nodes_per_tree = 0, modes = 0;
  double fma_peak_gfma_s = 0.0;
  std::vector<TreeModelCase> cases;  // modal, rigid_bodies, springs
};

TreeModelsBenchResult run_tree_models_bench(host::ComputeContext& cc, const TreeModelsBenchOptions& options);
void print_tree_models_bench_table(const TreeModelsBenchResult& result, std::ostream& out);
std::string tree_models_bench_json(const TreeModelsBenchResult& result);

}  // namespace fw::bench
