#include "host/bench/FmaPeak.hpp"

#include "host/bench/BestTime.hpp"

namespace fw::bench {

double measure_fma_peak(host::ComputeContext& cc, int repetitions) {
  // Enough work-items for every compute unit and SIMD lane, enough iterations to dwarf the launch.
  const std::size_t items = cc.is_cpu() ? 4096 : 1 << 20;
  const int iterations = cc.is_cpu() ? 20000 : 4000;
  cl::Buffer out = cc.buffer(items * sizeof(float));
  host::Kernel kernel(cc.build("bench_fma.cl"), "fma_peak");
  kernel.set_args(out, iterations);
  const double best = best_seconds(cc, repetitions, [&] { kernel.enqueue(cc, cl::NDRange(items)); });
  const double fmas = double(items) * double(iterations) * 8.0 * 8.0;  // 8 chains of float8
  return fmas / best * 1e-9;
}

}  // namespace fw::bench
