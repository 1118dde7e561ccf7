#include "host/bench/StreamTriad.hpp"

#include "host/bench/BestTime.hpp"

namespace fw::bench {

double measure_stream_triad(host::ComputeContext& cc, std::size_t elements, int repetitions) {
  const std::size_t bytes = elements * sizeof(float);
  cl::Buffer a = cc.buffer(bytes), b = cc.buffer(bytes), c = cc.buffer(bytes);
  cc.queue().enqueueFillBuffer(a, 0.0f, 0, bytes);
  cc.queue().enqueueFillBuffer(b, 1.0f, 0, bytes);
  cc.queue().enqueueFillBuffer(c, 2.0f, 0, bytes);
  host::Kernel triad(cc.build("bench_stream.cl"), "stream_triad");
  triad.set_args(cl_ulong(elements), a, b, c, 3.0f);
  const cl::NDRange range(cc.flat_items(elements));
  const double best = best_seconds(cc, repetitions, [&] { triad.enqueue(cc, range); });
  return 3.0 * double(bytes) / best * 1e-9;
}

}  // namespace fw::bench
