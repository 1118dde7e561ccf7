#include "host/bench/GatherThroughput.hpp"

#include "host/bench/BestTime.hpp"
#include "kernels/shared_types.h"

namespace fw::bench {

namespace {
constexpr int kMargin = 4;               // cells around the array, as FW_GATHER_MARGIN in the kernel
constexpr double kLoadsPerPosition = 8;  // the corners of one trilinear interpolation
}  // namespace

CornerLoadRates measure_corner_load_rates(host::ComputeContext& cc, const std::array<int, 3>& grid,
                                          int repetitions) {
  const auto [nx, ny, nz] = grid;
  const std::size_t padded = std::size_t(nx + 2 * kMargin) * (ny + 2 * kMargin) * (nz + 2 * kMargin);
  const std::size_t cells = std::size_t(nx) * ny * nz;
  // Windowed loads read FW_WINDOW_SLACK values past the last corner they need.
  cl::Buffer q = cc.buffer((padded + FW_WINDOW_SLACK) * sizeof(float)),
             out = cc.buffer(cells * sizeof(float));
  cc.queue().enqueueFillBuffer(q, 1.0f, 0, (padded + FW_WINDOW_SLACK) * sizeof(float));
  // Advection's own work-group, so that the limit is taken as advection loads.
  host::Kernel corners(cc.build("bench_gather.cl"), "corner_loads", host::RowItems::lanes);
  const cl::NDRange range(std::size_t((nx + FW_LANES - 1) / FW_LANES), std::size_t(ny), std::size_t(nz));
  auto rate = [&](int windowed) {
    corners.set_args(nx, ny, nz, windowed, q, out);
    return kLoadsPerPosition * double(cells) /
           best_seconds(cc, repetitions, [&] { corners.enqueue(cc, range); });
  };
  CornerLoadRates rates;
  rates.scattered = rate(0);
  rates.windowed = rate(1);
  return rates;
}

}  // namespace fw::bench
