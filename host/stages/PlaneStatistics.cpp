#include "host/stages/PlaneStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace fw::host {

namespace {

// A cell's scaled term stays within 2^FW_PLANE_CELL_BITS (kernels/shared_types.h): the kernel adds a few in
// 32-bit lanes before widening them, and a plane of up to 2^35 cells sums below 2^62.
constexpr int kCellBits = FW_PLANE_CELL_BITS;
// A term whose largest value uses less than 2^-kLooseBits of its scale's range is summed again at its own
// scale: a coarse scale cuts a field of values all much smaller than its step to 0, a bias. So each
// term is resolved to at least 2^-(FW_PLANE_CELL_BITS - kLooseBits) of its largest value.
constexpr int kLooseBits = 4;
// A float scales by 2^s exactly while s stays well inside its exponent range.
constexpr int kLowestExponent = -120, kHighestExponent = 120;
// Bounds below this are taken as it: a term that small everywhere sums to 0 at any scale that matters.
constexpr double kSmallestBound = 0x1p-40;
// The default bounds, as factors of the velocity's bound U (a power of two at least twice the speed): the
// subgrid flux -2 nu_t S_xz reaches about (C_s h)^2 |S| |S| ~ 0.03 U^2 under Smagorinsky's model and more
// near the eddy-diffusion cap, so 16 U^2 leaves room; the subgrid energy stays below U^2; a drag density
// above 256 1/m would be a solid. A bound that is passed costs a second pass, never a wrong sum.
constexpr double kSubgridFluxFactor = 16.0, kDragDensityBound = 256.0;

// The terms' default bounds for a velocity bound u (m/s).
std::array<double, FW_PLANE_TERMS> default_bounds(double u) {
  std::array<double, FW_PLANE_TERMS> b{};
  b[FW_TERM_CELLS] = 1.0;
  b[FW_TERM_U] = b[FW_TERM_V] = b[FW_TERM_W] = u;
  b[FW_TERM_UU] = b[FW_TERM_VV] = b[FW_TERM_WW] = b[FW_TERM_UW] = b[FW_TERM_VW] = u * u;
  b[FW_TERM_UUU] = b[FW_TERM_WWW] = u * u * u;
  b[FW_TERM_U_DIFF] = b[FW_TERM_V_DIFF] = kSubgridFluxFactor * u * u;
  b[FW_TERM_E] = u * u;
  b[FW_TERM_LAD] = kDragDensityBound;
  b[FW_TERM_SPEED] = 0.0;  // no sum
  return b;
}

// The smallest power of two at least twice `speed` (m/s): the velocity's bound, with room for the field to
// have grown since the speed was taken.
double velocity_bound(double speed) {
  if (!(speed > 0.0) || !std::isfinite(speed)) return kSmallestBound;
  return std::exp2(std::ceil(std::log2(2.0 * speed)));
}

// This rank's own cells of `region` along axis a, as local indices [first, end).
std::array<int, 2> own_span(const BlockArray& block, const fluid::GridSpec& spec, const PlaneRegion& region,
                            int a) {
  const int own_first = block.halo_low[std::size_t(a)];
  const int own_end = block.extent[std::size_t(a)] - block.halo_high[std::size_t(a)];
  const int origin = block.origin[std::size_t(a)];
  const int region_end = region.end[std::size_t(a)] > 0 ? region.end[std::size_t(a)] : spec.cells_along(a);
  const int first = std::max(own_first, region.first[std::size_t(a)] - origin);
  const int end = std::min(own_end, region_end - origin);
  return {first, std::max(first, end)};
}

double region_cells(const fluid::GridSpec& spec, const PlaneRegion& region) {
  double cells = 1.0;
  for (int a = 0; a < 2; ++a) {
    const int end = region.end[std::size_t(a)] > 0 ? region.end[std::size_t(a)] : spec.cells_along(a);
    cells *= double(std::max(0, end - region.first[std::size_t(a)]));
  }
  return cells;
}

}  // namespace

PlaneStatistics::PlaneStatistics(ComputeContext& cc, const fluid::GridSpec& spec,
                                 const fluid::GridSpec& local, const BlockArray& block,
                                 const Communicator& world)
    : cc_(cc),
      spec_(spec),
      local_(local),
      block_(block),
      world_(world),
      kernel_(cc.build("plane_statistics.cl"), "plane_statistics") {
  const std::size_t rows = std::size_t(local.ny) * std::size_t(local.nz);
  sums_device_ = cc.buffer(rows * FW_PLANE_TERMS * sizeof(cl_long));
  largest_device_ = cc.buffer(rows * FW_PLANE_TERMS * sizeof(float));
  scales_device_ = cc.buffer(FW_PLANE_TERMS * sizeof(float));
}

std::size_t PlaneStatistics::estimate_device_bytes(const fluid::GridSpec& local) {
  const std::size_t rows = std::size_t(local.ny) * std::size_t(local.nz);
  return ComputeContext::allocation_bytes(rows * FW_PLANE_TERMS * sizeof(cl_long)) +
         ComputeContext::allocation_bytes(rows * FW_PLANE_TERMS * sizeof(float)) +
         ComputeContext::allocation_bytes(FW_PLANE_TERMS * sizeof(float));
}

std::size_t PlaneStatistics::bytes_read(const fluid::GridSpec& local, const WindStatisticsFields& fields) {
  std::size_t per_cell = sizeof(cl_uchar);  // the mask
  for (const cl::Buffer* field : {fields.eddy_viscosity, fields.subgrid_energy, fields.drag_density})
    if (field) per_cell += sizeof(float);
  return (local.u_count() + local.v_count() + local.w_count()) * sizeof(float) +
         local.cell_count() * per_cell;
}

int PlaneStatistics::scale_exponent(double bound) {
  const int s = kCellBits - int(std::ceil(std::log2(std::max(bound, kSmallestBound))));
  return std::clamp(s, kLowestExponent, kHighestExponent);
}

void PlaneStatistics::run_pass(const WindStatisticsFields& fields,
                               const std::array<int, FW_PLANE_TERMS>& exponents, const PlaneRegion& region) {
  const std::array<int, 2> x = own_span(block_, spec_, region, 0), y = own_span(block_, spec_, region, 1);
  // No own cell of the region: no rows (the rank still takes part in the sums over ranks).
  const int rows = x[1] > x[0] ? y[1] - y[0] : 0, nz = local_.nz;
  std::vector<cl_long> row_sums;
  std::vector<float> row_largest;
  if (rows > 0) {
    std::array<float, FW_PLANE_TERMS> scales{};
    for (int t = 0; t < FW_PLANE_TERMS; ++t)
      scales[std::size_t(t)] = std::ldexp(1.0f, exponents[std::size_t(t)]);
    cc_.queue().enqueueWriteBuffer(scales_device_, CL_FALSE, 0, sizeof(scales), scales.data());
    // Absent arrays: the kernel does not read them, but every argument needs a buffer.
    cl::Buffer& mask = *fields.mask;
    kernel_
        .set_args(local_.to_device(), x[0], x[1], y[0], rows, int(fields.eddy_viscosity != nullptr),
                  int(fields.subgrid_energy != nullptr), int(fields.drag_density != nullptr), scales_device_,
                  mask, fields.velocity->u, fields.velocity->v, fields.velocity->w,
                  fields.eddy_viscosity ? *fields.eddy_viscosity : scales_device_,
                  fields.subgrid_energy ? *fields.subgrid_energy : scales_device_,
                  fields.drag_density ? *fields.drag_density : scales_device_, sums_device_, largest_device_)
        .enqueue_from(cc_, cl::NDRange(0, std::size_t(y[0]), 0),
                      cl::NDRange(1, std::size_t(rows), std::size_t(nz)));
    const std::size_t values = std::size_t(rows) * std::size_t(nz) * FW_PLANE_TERMS;
    row_sums.resize(values);
    row_largest.resize(values);
    cc_.queue().enqueueReadBuffer(sums_device_, CL_FALSE, 0, values * sizeof(cl_long), row_sums.data());
    cc_.queue().enqueueReadBuffer(largest_device_, CL_TRUE, 0, values * sizeof(float), row_largest.data());
  }
  // This rank's plane sums and maxima, then every rank's added: integers, so in any order.
  std::vector<std::int64_t> plane(std::size_t(nz) * FW_PLANE_TERMS, 0);
  std::vector<float> largest(FW_PLANE_TERMS, 0.0f);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < rows; ++j)
      for (int t = 0; t < FW_PLANE_TERMS; ++t) {
        const std::size_t at = FW_PLANE_TERMS * (std::size_t(j) + std::size_t(rows) * k) + t;
        plane[FW_PLANE_TERMS * std::size_t(k) + t] += row_sums[at];
        // NaN wins, so that a blown-up field is never read as a small one.
        if (!(row_largest[at] <= largest[std::size_t(t)])) largest[std::size_t(t)] = row_largest[at];
      }
  sums_.assign(plane.size(), 0);
  largest_.fill(0.0f);
  for (const auto& theirs : world_.gather_to_all(plane))
    for (std::size_t n = 0; n < theirs.size(); ++n) sums_[n] += theirs[n];
  for (const auto& theirs : world_.gather_to_all(largest))
    for (int t = 0; t < FW_PLANE_TERMS; ++t)
      if (!(theirs[std::size_t(t)] <= largest_[std::size_t(t)]))
        largest_[std::size_t(t)] = theirs[std::size_t(t)];
  bound_products();
}

void PlaneStatistics::bound_products() {
  // A float product's magnitude grows with its factors', so the largest factors' product, rounded up by an
  // ulp for the float's own rounding, bounds it (NaN stays NaN).
  constexpr double kRoundedUp = 1.0 + 0x1p-22;
  const auto product = [&](std::initializer_list<int> factors) {
    double p = kRoundedUp;
    for (const int f : factors) p *= largest_[std::size_t(f)];
    return float(p * kRoundedUp);
  };
  largest_[FW_TERM_UU] = product({FW_TERM_U, FW_TERM_U});
  largest_[FW_TERM_VV] = product({FW_TERM_V, FW_TERM_V});
  largest_[FW_TERM_WW] = product({FW_TERM_W, FW_TERM_W});
  largest_[FW_TERM_UUU] = product({FW_TERM_U, FW_TERM_U, FW_TERM_U});
  largest_[FW_TERM_WWW] = product({FW_TERM_W, FW_TERM_W, FW_TERM_W});
  largest_[FW_TERM_UW] = product({FW_TERM_U, FW_TERM_W});
  largest_[FW_TERM_VW] = product({FW_TERM_V, FW_TERM_W});
}

fluid::PlaneProfiles PlaneStatistics::sample(const WindStatisticsFields& fields, double speed_bound,
                                             const PlaneRegion& region, PlaneScales* scales) {
  const double cells = region_cells(spec_, region);
  std::array<int, FW_PLANE_TERMS> exponents{};
  if (scales && scales->known) {
    exponents = scales->exponents;
    // The count and the speed are not scaled, whatever a scale says.
    exponents[FW_TERM_CELLS] = exponents[FW_TERM_SPEED] = 0;
  } else {
    const std::array<double, FW_PLANE_TERMS> bounds = default_bounds(velocity_bound(speed_bound));
    for (int t = 0; t < FW_PLANE_TERMS; ++t)
      if (t != FW_TERM_CELLS && t != FW_TERM_SPEED)
        exponents[std::size_t(t)] = scale_exponent(bounds[std::size_t(t)]);
  }
  run_pass(fields, exponents, region);
  // A term whose largest value passed its scale's range, or used less than 2^-kLooseBits of it, is summed
  // again at that value's own scale (every rank sees the same maxima, so all take the second pass or none).
  // A term of zeros is exact at any scale; a non-finite one stays: its profile reads NaN.
  bool again = false;
  for (int t = 0; t < FW_PLANE_TERMS; ++t) {
    const double most = largest_[std::size_t(t)];
    if (t == FW_TERM_CELLS || t == FW_TERM_SPEED || !std::isfinite(most) || most == 0.0) continue;
    const int fits = scale_exponent(most);
    if (fits < exponents[std::size_t(t)] || fits - exponents[std::size_t(t)] > kLooseBits) {
      exponents[std::size_t(t)] = fits;
      again = true;
    }
  }
  if (again) {
    run_pass(fields, exponents, region);
    ++extra_passes_;
  }
  if (scales) {
    // The next sample's scales: these maxima with room to double.
    for (int t = 0; t < FW_PLANE_TERMS; ++t) {
      const double most = largest_[std::size_t(t)];
      if (t == FW_TERM_CELLS || t == FW_TERM_SPEED || !std::isfinite(most)) continue;
      if (most > 0.0 || !scales->known) scales->exponents[std::size_t(t)] = scale_exponent(2.0 * most);
    }
    scales->known = true;
  }
  return profiles(exponents, cells);
}

fluid::PlaneProfiles PlaneStatistics::profiles(const std::array<int, FW_PLANE_TERMS>& exponents,
                                               double plane_cells) const {
  using fluid::Profile;
  fluid::PlaneProfiles out;
  const int nz = local_.nz;
  out.nz = nz;
  for (auto& values : out.values) values.assign(std::size_t(nz), 0.0);
  for (int k = 0; k < nz; ++k) {
    const auto sum = [&](int t) {
      const double value =
          std::ldexp(double(sums_[FW_PLANE_TERMS * std::size_t(k) + t]), -exponents[std::size_t(t)]);
      return std::isfinite(largest_[std::size_t(t)]) ? value : std::numeric_limits<double>::quiet_NaN();
    };
    const auto set = [&](Profile p, double value) { out.values[std::size_t(p)][std::size_t(k)] = value; };
    const double n = sum(FW_TERM_CELLS);
    set(Profile::area, plane_cells > 0 ? n / plane_cells : 0.0);
    if (!(n > 0)) continue;
    const double u = sum(FW_TERM_U) / n, v = sum(FW_TERM_V) / n, w = sum(FW_TERM_W) / n;
    const double uu = sum(FW_TERM_UU) / n, vv = sum(FW_TERM_VV) / n, ww = sum(FW_TERM_WW) / n;
    // Central moments from the raw ones; a variance below 0 is rounding and reads 0.
    const double u_2 = std::max(0.0, uu - u * u), v_2 = std::max(0.0, vv - v * v),
                 w_2 = std::max(0.0, ww - w * w);
    const double u_3 = sum(FW_TERM_UUU) / n - 3.0 * u * uu + 2.0 * u * u * u;
    const double w_3 = sum(FW_TERM_WWW) / n - 3.0 * w * ww + 2.0 * w * w * w;
    const double u_w = sum(FW_TERM_UW) / n - u * w, v_w = sum(FW_TERM_VW) / n - v * w;
    const double u_diff = sum(FW_TERM_U_DIFF) / n, v_diff = sum(FW_TERM_V_DIFF) / n;
    set(Profile::u, u);
    set(Profile::v, v);
    set(Profile::w, w);
    set(Profile::u_2, u_2);
    set(Profile::v_2, v_2);
    set(Profile::w_2, w_2);
    set(Profile::u_3, u_3);
    set(Profile::w_3, w_3);
    set(Profile::u_w, u_w);
    set(Profile::v_w, v_w);
    set(Profile::u_diff, u_diff);
    set(Profile::v_diff, v_diff);
    set(Profile::u_flux, u_w + u_diff);
    set(Profile::v_flux, v_w + v_diff);
    set(Profile::tke, 0.5 * (u_2 + v_2 + w_2));
    set(Profile::sgs_tke, sum(FW_TERM_E) / n);
    set(Profile::lad, sum(FW_TERM_LAD) / n);
  }
  return out;
}

}  // namespace fw::host
