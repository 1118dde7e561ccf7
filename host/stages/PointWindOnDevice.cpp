#include "host/stages/PointWindOnDevice.hpp"

#include <vector>

#include "host/runtime/Communicator.hpp"

namespace fw::host {

std::size_t PointWindOnDevice::estimate_device_bytes(std::size_t count) {
  return ComputeContext::allocation_bytes(3 * count * sizeof(float));
}

PointWindOnDevice::PointWindOnDevice(ComputeContext& cc, const fluid::GridSpec& spec,
                                     const WindBlocks* blocks, cl::Buffer positions, int count)
    : cc_(cc), grid_(spec.to_device()), count_(count), positions_(std::move(positions)) {
  wind_ = cc_.zero_floats(3 * std::size_t(count_));
  const cl::Program program = cc_.build("probe_sample.cl");
  sample_ = Kernel(program, "probe_sample");
  place_ = Kernel(program, "probe_place");
  if (const WindBlocks* split = splitting(blocks)) share(spec, *split);
}

void PointWindOnDevice::share(const fluid::GridSpec& spec, const WindBlocks& blocks) {
  std::vector<float> points(3 * std::size_t(count_));
  if (count_ > 0)
    cc_.queue().enqueueReadBuffer(positions_, CL_TRUE, 0, points.size() * sizeof(float), points.data());
  std::vector<int> slots;
  std::vector<float> needed;
  for (int n = 0; n < count_; ++n) {
    const float* point = &points[3 * std::size_t(n)];
    if (PointWindAcrossRanks::holder(spec, blocks.decomposition, point) == blocks.world->rank()) continue;
    slots.push_back(n);
    needed.insert(needed.end(), point, point + 3);
  }
  exchange_ = std::make_unique<PointWindAcrossRanks>(cc_, spec, &blocks, needed);
  if (slots.empty()) return;
  remote_slots_ = cc_.upload(slots, CL_MEM_READ_ONLY);
  remote_wind_ = cc_.zero_floats(needed.size());
}

void PointWindOnDevice::enqueue_sample(DeviceVelocity& velocity) {
  if (count_ > 0)
    sample_.set_args(grid_, count_, positions_, velocity.u, velocity.v, velocity.w, wind_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(count_))));
  if (!exchange_) return;
  // Every rank takes part, with or without points of its own.
  const std::vector<float> wind = exchange_->exchange(velocity);
  const int remote = exchange_->point_count();
  if (remote == 0) return;
  cc_.queue().enqueueWriteBuffer(remote_wind_, CL_TRUE, 0, wind.size() * sizeof(float), wind.data());
  place_.set_args(remote, remote_slots_, remote_wind_, wind_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(remote))));
}

}  // namespace fw::host
