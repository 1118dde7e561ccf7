#include "host/stages/PointWindReadback.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::host {

std::size_t PointWindReadback::estimate_device_bytes(std::size_t point_count) {
  if (point_count == 0) return 0;
  return 2 * ComputeContext::allocation_bytes(3 * point_count * sizeof(float));
}

std::vector<float> PointWindReadback::flat_positions(const std::vector<std::array<double, 3>>& points) {
  std::vector<float> flat;
  for (const auto& p : points)
    for (double x : p) flat.push_back(static_cast<float>(x));
  return flat;
}

PointWindReadback::PointWindReadback(ComputeContext& cc, const fluid::GridSpec& spec,
                                     const std::vector<std::array<double, 3>>& points)
    : PointWindReadback(cc, spec, flat_positions(points)) {}

PointWindReadback::PointWindReadback(ComputeContext& cc, const fluid::GridSpec& spec, std::vector<float> flat)
    : cc_(cc), count_(static_cast<int>(flat.size() / 3)) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("PointWindReadback: ") + e.what());
  }
  grid_ = spec.to_device();
  if (flat.size() % 3 != 0)
    throw std::invalid_argument(
        fmt::format("PointWindReadback: {} coordinates are not whole points", flat.size()));
  for (float x : flat)
    if (!std::isfinite(x))
      throw std::invalid_argument(fmt::format("PointWindReadback: position {} is not finite", x));
  if (count_ == 0) return;
  positions_ = cc_.buffer(flat.size() * sizeof(float), CL_MEM_READ_ONLY);
  cc_.queue().enqueueWriteBuffer(positions_, CL_TRUE, 0, flat.size() * sizeof(float), flat.data());
  wind_ = cc_.buffer(flat.size() * sizeof(float));
  kernel_ = Kernel(cc_.build("probe_sample.cl"), "probe_sample");
}

std::vector<float> PointWindReadback::sample_flat(DeviceVelocity& velocity) {
  std::vector<float> wind(3 * static_cast<std::size_t>(count_));
  if (count_ == 0) return wind;
  kernel_.set_args(grid_, count_, positions_, velocity.u, velocity.v, velocity.w, wind_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(count_))));
  cc_.queue().enqueueReadBuffer(wind_, CL_TRUE, 0, wind.size() * sizeof(float), wind.data());
  return wind;
}

std::vector<std::array<float, 3>> PointWindReadback::sample(DeviceVelocity& velocity) {
  const std::vector<float> flat = sample_flat(velocity);
  std::vector<std::array<float, 3>> wind(static_cast<std::size_t>(count_));
  for (std::size_t n = 0; n < wind.size(); ++n) wind[n] = {flat[3 * n], flat[3 * n + 1], flat[3 * n + 2]};
  return wind;
}

}  // namespace fw::host
