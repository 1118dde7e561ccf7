#include <fmt/format.h>

#include <iostream>
#include <stdexcept>

#include "host/bench/CoupledBench.hpp"
#include "host/bench/RanksBench.hpp"
#include "host/bench/TreeBench.hpp"
#include "host/bench/TreeModelsBench.hpp"
#include "host/bench/WindBench.hpp"
#include "host/cli/Commands.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/runtime/Device.hpp"

namespace fw::cli {

namespace {

// The command line's choices over each benchmark's defaults.
bench::WindBenchOptions wind_options(const BenchOptions& options) {
  bench::WindBenchOptions opt;
  if (!options.grids.empty()) opt.grids = options.grids;
  if (options.steps > 0) opt.steps = options.steps;
  return opt;
}

bench::CoupledBenchOptions coupled_options(const BenchOptions& options) {
  bench::CoupledBenchOptions opt;
  if (!options.grids.empty()) opt.grids = options.grids;
  if (options.steps > 0) opt.steps = options.steps;
  if (options.trees > 0) opt.trees = options.trees;
  return opt;
}

}  // namespace

std::array<int, 3> parse_grid(const std::string& text) {
  std::array<int, 3> g{};
  char x1 = 0, x2 = 0;
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c%d%n", &g[0], &x1, &g[1], &x2, &g[2], &consumed) != 5 ||
      consumed != static_cast<int>(text.size()) || (x1 != 'x' && x1 != 'X') || (x2 != 'x' && x2 != 'X') ||
      g[0] <= 0 || g[1] <= 0 || g[2] <= 0)
    throw std::invalid_argument(
        fmt::format("--grid: expected NXxNYxNZ with positive integers, got '{}'", text));
  return g;
}

int run_bench(const BenchOptions& options, const GlobalOptions& global, const host::Communicator& world) {
  const bool ranks = world.size() > 1;
  if (options.what == "trees") {
    if (ranks)
      throw std::invalid_argument(
          "bench trees: the modal analysis runs on the host in one process; run it without mpirun");
    // Precomputation on the host: no OpenCL device involved.
    if (!options.json) std::cerr << "running the tree modal-analysis benchmark ...\n";
    const auto result = bench::run_tree_bench(bench::TreeBenchOptions{});
    if (options.json)
      std::cout << bench::tree_bench_json(result) << "\n";
    else
      bench::print_tree_bench_table(result, std::cout);
    return 0;
  }
  if (options.what != "wind" && options.what != "coupled" && options.what != "models")
    throw std::invalid_argument(
        fmt::format("bench {}: not available in this build (wind, trees, coupled or models)", options.what));
  if (options.what == "models" && ranks)
    throw std::invalid_argument(
        "bench models: the trees' kernels alone, in one process; run it without mpirun");
  // Over ranks, as in a run: a machine's r-th rank takes its r-th device, and rank 0 speaks for all.
  host::ComputeContext cc(
      host::select_device(host::device_filter_from_env(global.device_filter), world.node_rank()),
      global.profile);
  const bool speaks = world.rank() == 0;
  if (speaks && !options.json)
    std::cerr << fmt::format(
        "running the {} benchmark on {}{} ...\n",
        options.what == "wind" ? "wind-tunnel"
                               : (options.what == "models" ? "tree models" : "coupled forest"),
        cc.device().device_name, ranks ? fmt::format(" over {} ranks, a device each", world.size()) : "");
  if (ranks) {
    bench::RanksBenchResult result;
    if (options.what == "coupled")
      result = bench::run_coupled_bench_ranks(cc, coupled_options(options), world);
    else
      result = bench::run_wind_bench_ranks(cc, wind_options(options), world);
    if (speaks) {
      if (options.json)
        std::cout << bench::ranks_bench_json(result) << "\n";
      else
        bench::print_ranks_bench_table(result, std::cout);
    }
  } else if (options.what == "models") {
    bench::TreeModelsBenchOptions models;
    if (options.trees > 0) models.trees = options.trees;
    const auto result = bench::run_tree_models_bench(cc, models);
    if (options.json)
      std::cout << bench::tree_models_bench_json(result) << "\n";
    else
      bench::print_tree_models_bench_table(result, std::cout);
  } else if (options.what == "coupled") {
    const auto result = bench::run_coupled_bench(cc, coupled_options(options));
    if (options.json)
      std::cout << bench::coupled_bench_json(result) << "\n";
    else
      bench::print_coupled_bench_table(result, std::cout);
  } else {
    const auto result = bench::run_wind_bench(cc, wind_options(options));
    if (options.json)
      std::cout << bench::wind_bench_json(result) << "\n";
    else
      bench::print_wind_bench_table(result, std::cout);
  }
  if (speaks && cc.profiling()) cc.profiler()->print(options.json ? std::cerr : std::cout);
  return 0;
}

}  // namespace fw::cli
