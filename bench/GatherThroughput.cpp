#include "bench/GatherThroughput.hpp"

#include "bench/BestTime.hpp"
#include "kernels/shared_types.h"

namespace fw::bench {

namespace {
constexpr int kMargin = 4;               // cells around the array, as FW_GATHER_MARGIN in the kernel
constexpr double kLoadsPerPosition = 8;  // the corners of one trilinear interpolation
}  // namespace

double measure_gather_rate(host::ComputeContext& cc, const std::array<int, 3>& grid, int repetitions) {
  const auto [nx, ny, nz] = grid;
  const std::size_t padded = std::size_t(nx + 2 * kMargin) * (ny + 2 * kMargin) * (nz + 2 * kMargin);
  const std::size_t cells = std::size_t(nx) * ny * nz;
  cl::Buffer q = cc.buffer(padded * sizeof(float)), out = cc.buffer(cells * sizeof(float));
  cc.queue().enqueueFillBuffer(q, 1.0f, 0, padded * sizeof(float));
  host::Kernel gather(cc.build("bench_gather.cl"), "gather_corners");
  gather.set_args(nx, ny, nz, q, out);
  const cl::NDRange range(std::size_t((nx + FW_LANES - 1) / FW_LANES), std::size_t(ny), std::size_t(nz));
  const double best = best_seconds(cc, repetitions, [&] { gather.enqueue(cc, range); });
  return kLoadsPerPosition * double(cells) / best;
}

}  // namespace fw::bench
