#include "host/stages/wind/BodyForces.hpp"

#include <algorithm>

#include "base/ExactSum.hpp"

namespace fw::host {
namespace {

constexpr int kVorticityFloats = 4;  // the vorticity and its magnitude, a cell

// The gusts' buffer: a kernel argument needs a buffer even without gusts.
std::size_t gust_buffer_bytes(const WindGridSetup& setup) {
  return std::max<std::size_t>(setup.gusts.size(), 1) * sizeof(FwGust);
}

}  // namespace

BodyForces::BodyForces(const WindPartContext& context) : context_(context) {
  const std::vector<FwGust>& gusts = context.setup.gusts;
  gusts_ = context.cc.buffer(gust_buffer_bytes(context.setup));
  if (!gusts.empty())
    context.cc.queue().enqueueWriteBuffer(gusts_, CL_TRUE, 0, gusts.size() * sizeof(FwGust), gusts.data());
  if (confines())
    vorticity_ = context.cc.buffer(context.seam.local().cell_count() * kVorticityFloats * sizeof(float));
}

std::size_t BodyForces::estimate_device_bytes(const fluid::GridSpec& grid, const WindGridSetup& setup) {
  std::size_t bytes = ComputeContext::allocation_bytes(gust_buffer_bytes(setup));
  if (setup.settings.vorticity_confinement > 0.0)
    bytes += ComputeContext::allocation_bytes(grid.cell_count() * kVorticityFloats * sizeof(float));
  return bytes;
}

std::vector<HaloNeed> BodyForces::halo_needs() const {
  std::vector<HaloNeed> needs{{HaloField::faces, 1}};
  // The confinement reads the vorticity's gradient: across a periodic seam too, as for nu_t.
  if (confines()) needs.push_back({HaloField::cell_quads, 1});
  return needs;
}

std::array<double, 2> BodyForces::reference_layer_mean(WindFields& fields) {
  const fluid::GridSpec& spec = context_.setup.spec;
  const BlockArray& block = context_.seam.block();
  // Cell-centre layers k0 and k0 + 1 around the reference height, weight t on the upper one.
  const double level = std::clamp(context_.setup.profile.reference_height / spec.h - 0.5, 0.0, spec.nz - 1.0);
  const int k0 = std::min(static_cast<int>(level), spec.nz - 1), k1 = std::min(k0 + 1, spec.nz - 1);
  const double t = level - k0;
  std::array<double, 2> mean{0, 0};
  for (int c = 0; c < 2; ++c) {
    const BlockArray faces = face_array(block, c);
    const std::size_t ex = std::size_t(faces.values(0)), ey = std::size_t(faces.values(1)), layer = ex * ey;
    // The faces that are distinct (a periodic axis' last face repeats its first) and this rank's own: its
    // cells' low faces, and the domain's high face where the block ends at it (the face between two blocks
    // is the upper block's).
    std::array<std::size_t, 2> from{}, to{};
    for (int a = 0; a < 2; ++a) {
      const bool across = a == c, ends_domain = faces.halo_high[a] == 0;
      from[a] = std::size_t(faces.halo_low[a]);
      to[a] = std::size_t(faces.values(a) - faces.halo_high[a]) -
              (across && (!ends_domain || spec.periodic(a)) ? 1 : 0);
    }
    std::vector<float> rows(2 * layer);
    cl::CommandQueue& queue = context_.cc.queue();
    queue.enqueueReadBuffer(fields.vel.component(c), CL_FALSE, layer * k0 * sizeof(float),
                            layer * sizeof(float), rows.data());
    queue.enqueueReadBuffer(fields.vel.component(c), CL_TRUE, layer * k1 * sizeof(float),
                            layer * sizeof(float), rows.data() + layer);
    // Exact sums: the same on any number of ranks (base/ExactSum).
    base::ExactSum lower, upper;
    for (std::size_t j = from[1]; j < to[1]; ++j)
      for (std::size_t i = from[0]; i < to[0]; ++i) {
        lower.add(rows[i + ex * j]);
        upper.add(rows[layer + i + ex * j]);
      }
    const std::size_t distinct = (spec.nx + (c == 0 && !spec.periodic(0) ? 1 : 0)) *
                                 std::size_t(spec.ny + (c == 1 && !spec.periodic(1) ? 1 : 0));
    const Communicator& world = context_.seam.world();
    mean[c] = ((1.0 - t) * world.sum(lower) + t * world.sum(upper)) / double(distinct);
  }
  return mean;
}

void BodyForces::update_mean_forcing(WindFields& fields, double dt) {
  const double tau = context_.setup.forcing.relaxation_time;
  if (!(tau > 0.0)) return;
  const auto mean = reference_layer_mean(fields);
  for (int c = 0; c < 2; ++c) {
    const double error = context_.setup.ambient[c] - mean[c];
    forcing_integral_[c] += error * dt;
    forcing_acceleration_[c] = error / tau + forcing_integral_[c] / (tau * tau);
  }
}

void BodyForces::apply(WindFields& fields) {
  const fluid::WindSettings& st = context_.setup.settings;
  FluidStages& stages = context_.stages;
  const int gust_count = static_cast<int>(context_.setup.gusts.size());
  std::array<double, 3> body = st.body_force;
  for (int c = 0; c < 2; ++c) body[c] += forcing_acceleration_[c];
  const bool any_body = body[0] != 0.0 || body[1] != 0.0 || body[2] != 0.0;
  if (any_body || gust_count > 0)
    for (int c = 0; c < 3; ++c)
      stages.enqueue_apply_forces(c, static_cast<float>(body[c]), gusts_, gust_count,
                                  fields.vel.component(c));
  if (confines()) {
    stages.enqueue_vorticity(fields.vel, vorticity_);
    context_.seam.exchange_quads(vorticity_);
    for (int c = 0; c < 3; ++c)
      stages.enqueue_vorticity_confinement(c, static_cast<float>(st.vorticity_confinement), vorticity_,
                                           fields.vel.component(c));
  }
  if (any_body || gust_count > 0 || confines()) context_.seam.exchange(fields.vel);
}

void BodyForces::save_state(StageState& state) {
  state.numbers["forcing_integral"] = {forcing_integral_.begin(), forcing_integral_.end()};
  state.numbers["forcing_acceleration"] = {forcing_acceleration_.begin(), forcing_acceleration_.end()};
}

void BodyForces::restore_state(const StageState& state) {
  const std::vector<double>& integral = state.number(kWindGridState, "forcing_integral", 2);
  const std::vector<double>& acceleration = state.number(kWindGridState, "forcing_acceleration", 2);
  std::copy(integral.begin(), integral.end(), forcing_integral_.begin());
  std::copy(acceleration.begin(), acceleration.end(), forcing_acceleration_.begin());
}

}  // namespace fw::host
