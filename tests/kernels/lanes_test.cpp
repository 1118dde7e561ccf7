// The lanes' own sine and cosine (kernels/lanes.cl: sincos_lanes, sincos_quarter_lanes) against the C
// library in double, over the arguments the leaves give them.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "host/runtime/KernelSources.hpp"
#include "kernels/shared_types.h"
#include "tests/support/TestDevice.hpp"

using namespace fw;

namespace {

// A test kernel: sine and cosine of FW_LANES arguments per work-item, by either function, over n arguments
// (the range is rounded up to whole work-groups).
const char* kLaneSincos = R"(
__kernel void lane_sincos(const int n, const int quarter, __global const float* x, __global float* s,
                          __global float* c) {
  const int first = get_global_id(0) * FW_LANES;
  if (first >= n) return;
  lanef cosine;
  const lanef sine = quarter ? sincos_quarter_lanes(lane_load(0, x + first), &cosine)
                             : sincos_lanes(lane_load(0, x + first), &cosine);
  lane_store(sine, 0, s + first);
  lane_store(cosine, 0, c + first);
}
)";

// A test kernel: the arctangent of FW_LANES arguments per work-item, over n arguments.
const char* kLaneAtan = R"(
__kernel void lane_atan(const int n, __global const float* x, __global float* out) {
  const int first = get_global_id(0) * FW_LANES;
  if (first >= n) return;
  lane_store(atan_lanes(lane_load(0, x + first)), 0, out + first);
}
)";

// The largest error of atan_lanes on the device over the float arguments `x` (a multiple of FW_LANES).
double largest_atan_error(host::ComputeContext& cc, const std::vector<float>& x) {
  host::Kernel kernel(cc.build_source("lane_atan.cl", host::kernel_source("lanes.cl") + kLaneAtan),
                      "lane_atan");
  cl::Buffer in = cc.upload(x, CL_MEM_READ_ONLY);
  cl::Buffer out = cc.zero_floats(x.size());
  kernel.set_args(cl_int(x.size()), in, out).enqueue(cc, cl::NDRange(x.size() / FW_LANES));
  std::vector<float> angle(x.size());
  cc.queue().enqueueReadBuffer(out, CL_TRUE, 0, x.size() * sizeof(float), angle.data());
  double error = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n)
    error = std::max(error, std::abs(angle[n] - std::atan(double(x[n]))));
  return error;
}

// The largest error of sine and cosine on the device over the float arguments `x` (a multiple of FW_LANES).
double largest_error(host::ComputeContext& cc, const std::vector<float>& x, bool quarter) {
  host::Kernel kernel(cc.build_source("lane_sincos.cl", host::kernel_source("lanes.cl") + kLaneSincos),
                      "lane_sincos");
  cl::Buffer in = cc.upload(x, CL_MEM_READ_ONLY);
  cl::Buffer s = cc.zero_floats(x.size()), c = cc.zero_floats(x.size());
  kernel.set_args(cl_int(x.size()), cl_int(quarter), in, s, c).enqueue(cc, cl::NDRange(x.size() / FW_LANES));
  std::vector<float> sine(x.size()), cosine(x.size());
  cc.queue().enqueueReadBuffer(s, CL_FALSE, 0, x.size() * sizeof(float), sine.data());
  cc.queue().enqueueReadBuffer(c, CL_TRUE, 0, x.size() * sizeof(float), cosine.data());
  double error = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    error = std::max(error, std::abs(sine[n] - std::sin(double(x[n]))));
    error = std::max(error, std::abs(cosine[n] - std::cos(double(x[n]))));
  }
  return error;
}

std::vector<float> evenly(double lo, double hi, int count) {
  std::vector<float> x;
  for (int n = 0; n < count; ++n) x.push_back(float(lo + (hi - lo) * n / (count - 1)));
  return x;
}

}  // namespace

TEST_CASE("lanes: sine and cosine match the C library over the leaves' arguments", "[lanes]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // The blade's angle, |theta| <= pi/2: the series to r^11 and r^12 leave below 6e-8, and the float rounding
  // of the Horner sums a few ulps of values near 1 (6e-8 each; measured 1.8e-7 in all): 3e-7 bounds both.
  const double quarter = largest_error(*cc, evenly(-1.5707963, 1.5707963, 4096 * FW_LANES), true);
  INFO("quarter turn: " << quarter);
  CHECK(quarter < 3e-7);
  // The stochastic angles' phases, 2 pi f t + phi, up to 1e4 rad (an hour of a 0.3 Hz leaf): the reduction by
  // whole turns loses about 1e-7 a thousand turns (the split 2 pi's rounding), plus the series (measured
  // 2.4e-7 in all): 1e-6 bounds.
  const double any = largest_error(*cc, evenly(-1e4, 1e4, 65536 * FW_LANES), false);
  INFO("any argument: " << any);
  CHECK(any < 1e-6);
}

TEST_CASE("lanes: the arctangent matches the C library across its reductions", "[lanes]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // The springs' bends, 0 to a few, and the tails out to 1e6 and back through zero: every branch of the two
  // reductions. The series leaves 3e-9; the reductions' float divisions and the Horner sum round a few ulps
  // of values up to pi/2 (1.2e-7 each): 4e-7 bounds them.
  std::vector<float> x = evenly(-4.0, 4.0, 4096 * FW_LANES);
  const std::vector<float> far = evenly(-1e6, 1e6, 1024 * FW_LANES);
  x.insert(x.end(), far.begin(), far.end());
  const double error = largest_atan_error(*cc, x);
  INFO("arctangent: " << error);
  CHECK(error < 4e-7);
}
