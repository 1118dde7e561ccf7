#include "host/stages/PointSampler.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::host {

std::size_t PointSampler::estimate_device_bytes(std::size_t point_count) {
  if (point_count == 0) return 0;
  return 2 * ComputeContext::allocation_bytes(3 * point_count * sizeof(float));
}

PointSampler::PointSampler(ComputeContext& cc, const fluid::GridSpec& spec,
                           const std::vector<std::array<double, 3>>& points)
    : cc_(cc), count_(static_cast<int>(points.size())) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("PointSampler: ") + e.what());
  }
  grid_ = spec.to_device();
  std::vector<float> flat;
  for (const auto& p : points)
    for (double x : p) {
      if (!std::isfinite(x))
        throw std::invalid_argument(fmt::format("PointSampler: position {} is not finite", x));
      flat.push_back(static_cast<float>(x));
    }
  if (count_ == 0) return;
  positions_ = cc_.buffer(flat.size() * sizeof(float), CL_MEM_READ_ONLY);
  cc_.queue().enqueueWriteBuffer(positions_, CL_TRUE, 0, flat.size() * sizeof(float), flat.data());
  wind_ = cc_.buffer(flat.size() * sizeof(float));
  kernel_ = Kernel(cc_.build("probe_sample.cl"), "probe_sample");
}

std::vector<std::array<float, 3>> PointSampler::sample(DeviceVelocity& velocity) {
  std::vector<std::array<float, 3>> wind(static_cast<std::size_t>(count_));
  if (count_ == 0) return wind;
  kernel_.set_args(grid_, count_, positions_, velocity.u, velocity.v, velocity.w, wind_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(count_))));
  cc_.queue().enqueueReadBuffer(wind_, CL_TRUE, 0, wind.size() * 3 * sizeof(float), wind.data());
  return wind;
}

}  // namespace fw::host
