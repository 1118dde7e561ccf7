#include "host/stages/WindGrid.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace fw::host {
namespace {

// Validates everything before a single buffer exists (members are built after this returns).
WindGridSetup validated(ComputeContext& cc, WindGridSetup setup) {
  setup.spec.validate();
  setup.settings.validate();
  setup.profile.validate();
  if (!setup.solid.empty() && setup.solid.size() != setup.spec.cell_count())
    throw std::invalid_argument(fmt::format("WindGrid: solid map has {} cells, the grid {}",
                                            setup.solid.size(), setup.spec.cell_count()));
  for (const FwGust& g : setup.gusts)
    if (!(g.duration > 0.0f) || !(g.radius > 0.0f))
      throw std::invalid_argument("WindGrid: a gust needs a positive duration and radius");
  WindGrid::check_fits_device(
      setup.spec, WindGrid::estimate_device_bytes(setup.spec, setup.settings, cc.row_chunk()), cc.device());
  return setup;
}

int viscous_substeps(double nu, double dt, double h) {
  if (nu <= 0.0) return 0;
  // Explicit diffusion is stable for nu dt / h^2 <= 1/6 in 3D; keep a margin.
  return std::max(1, static_cast<int>(std::ceil(nu * dt / (h * h) / 0.15)));
}

}  // namespace

std::size_t WindGrid::estimate_device_bytes(const fluid::GridSpec& spec, const fluid::WindSettings& settings,
                                            int row_chunk) {
  const std::size_t faces = spec.u_count() + spec.v_count() + spec.w_count();
  const bool maccormack = settings.advection == fluid::AdvectionScheme::maccormack;
  const std::size_t padded = std::size_t(spec.nx + 5) * (spec.ny + 5) * (spec.nz + 5) * 3;
  std::size_t bytes = ((maccormack ? 3 : 2) * faces + (maccormack ? 2 : 1) * padded) * sizeof(float);
  if (settings.vorticity_confinement > 0.0) bytes += spec.cell_count() * 4 * sizeof(float);
  // Pressure hierarchy: about 1/7 extra for the coarse levels of a 3D grid.
  const std::size_t cells = spec.cell_count();
  const std::size_t levels = cells + cells / 7 + 64;
  bytes += levels * (1 + 2 * sizeof(float)) + cells * 5 * sizeof(float);
  const std::size_t items_x = (std::size_t(spec.nx) + 1 + row_chunk - 1) / std::size_t(row_chunk);
  bytes += 2 * items_x * (std::size_t(spec.ny) + 1) * (std::size_t(spec.nz) + 1) * sizeof(float);
  return bytes;
}

void WindGrid::check_fits_device(const fluid::GridSpec& spec, std::size_t bytes, const DeviceInfo& device) {
  const double mib = 1024.0 * 1024.0;
  if (bytes > device.global_memory_bytes)
    throw std::invalid_argument(fmt::format(
        "WindGrid: a {} x {} x {} grid needs about {:.0f} MiB of device memory, but '{}' has {:.0f} MiB",
        spec.nx, spec.ny, spec.nz, bytes / mib, device.device_name, device.global_memory_bytes / mib));
  const std::size_t largest = spec.u_count() * sizeof(float);
  if (largest > device.max_allocation_bytes)
    throw std::invalid_argument(fmt::format(
        "WindGrid: a {} x {} x {} grid needs {:.0f} MiB buffers, but '{}' allocates at most {:.0f} MiB",
        spec.nx, spec.ny, spec.nz, largest / mib, device.device_name, device.max_allocation_bytes / mib));
}

WindGrid::WindGrid(ComputeContext& cc, WindGridSetup setup)
    : cc_(cc),
      setup_(validated(cc, std::move(setup))),
      stages_(cc, setup_.spec),
      pressure_(cc, setup_.spec, fluid::build_pressure_levels(setup_.spec, setup_.solid),
                setup_.settings.pressure) {
  vel_ = stages_.allocate_velocity();
  tmp_ = stages_.allocate_velocity();
  padded_ = stages_.allocate_padded_velocity();
  if (setup_.settings.advection == fluid::AdvectionScheme::maccormack) {
    back_ = stages_.allocate_velocity();
    padded_forward_ = stages_.allocate_padded_velocity();
  }
  if (setup_.settings.vorticity_confinement > 0.0)
    omega_ = cc_.buffer(setup_.spec.cell_count() * 4 * sizeof(float));
  if (!setup_.gusts.empty()) {
    gusts_ = cc_.buffer(setup_.gusts.size() * sizeof(FwGust));
    cc_.queue().enqueueWriteBuffer(gusts_, CL_TRUE, 0, setup_.gusts.size() * sizeof(FwGust),
                                   setup_.gusts.data());
  } else {
    gusts_ = cc_.buffer(sizeof(FwGust));
  }
  const auto shape = setup_.profile.sample_cell_centres(setup_.spec.nz, setup_.spec.h);
  profile_ = cc_.buffer(shape.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(profile_, CL_TRUE, 0, shape.size() * sizeof(float), shape.data());
  stages_.set_profile(profile_);
  set_ambient(setup_.ambient);
}

void WindGrid::set_ambient(const std::array<double, 3>& ambient) {
  setup_.ambient = ambient;
  FwStep s = stages_.step();
  for (int a = 0; a < 3; ++a) s.ambient[a] = static_cast<float>(ambient[a]);
  stages_.set_step(s);
}

fluid::InflowState WindGrid::inflow_state() const {
  fluid::InflowState state;
  for (int a = 0; a < 3; ++a) state.ambient[a] = static_cast<float>(setup_.ambient[a]);
  state.profile = setup_.profile.sample_cell_centres(setup_.spec.nz, setup_.spec.h);
  return state;
}

template <typename F>
void WindGrid::timed(const char* stage, F&& work) {
  if (!stage_timing_) {
    work();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  work();
  cc_.finish();
  stage_ms_[stage] +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void WindGrid::initialise_ambient() {
  const auto& spec = setup_.spec;
  const auto inflow = inflow_state();
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    auto& q = vel.component(c);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i)
          q[std::size_t(i) + std::size_t(ex) * (j + std::size_t(ey) * k)] =
              inflow.ambient[c] * inflow.profile[std::min(k, spec.nz - 1)];
  }
  upload_velocity(vel);
  enforce_boundaries();
  if (last_dt_ <= 0.0) last_dt_ = setup_.settings.cfl > 0.0 ? setup_.settings.max_dt : setup_.settings.dt;
  project();
}

void WindGrid::advect(float dt) {
  stages_.enqueue_pad(vel_, padded_);
  for (int c = 0; c < 3; ++c) stages_.enqueue_advect(c, dt, padded_, padded_.component(c), tmp_.component(c));
  if (setup_.settings.advection == fluid::AdvectionScheme::semi_lagrangian) {
    std::swap(vel_, tmp_);
    return;
  }
  // MacCormack: forward into tmp, backward (from tmp's padded copy) into back, corrected in place in back.
  stages_.enqueue_pad(tmp_, padded_forward_);
  for (int c = 0; c < 3; ++c)
    stages_.enqueue_advect(c, -dt, padded_, padded_forward_.component(c), back_.component(c));
  for (int c = 0; c < 3; ++c)
    stages_.enqueue_maccormack_correct(c, padded_, padded_.component(c), tmp_.component(c),
                                       back_.component(c), back_.component(c));
  std::swap(vel_, back_);
}

void WindGrid::apply_forces() {
  const auto& st = setup_.settings;
  const bool body = st.body_force[0] != 0.0 || st.body_force[1] != 0.0 || st.body_force[2] != 0.0;
  if (body || !setup_.gusts.empty())
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_apply_forces(c, static_cast<float>(st.body_force[c]), gusts_,
                                   static_cast<int>(setup_.gusts.size()), vel_.component(c));
  if (st.vorticity_confinement > 0.0) {
    stages_.enqueue_vorticity(vel_, omega_);
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_vorticity_confinement(c, static_cast<float>(st.vorticity_confinement), omega_,
                                            vel_.component(c));
  }
}

void WindGrid::set_canopy(std::vector<float> drag_density) {
  bool any = false;
  if (!drag_density.empty()) {
    if (drag_density.size() != setup_.spec.cell_count())
      throw std::invalid_argument(fmt::format("WindGrid: canopy drag density has {} cells, the grid {}",
                                              drag_density.size(), setup_.spec.cell_count()));
    for (float k : drag_density) {
      if (!std::isfinite(k) || k < 0.0f)
        throw std::invalid_argument(
            fmt::format("WindGrid: canopy drag density must be finite and >= 0, got {}", k));
      any = any || k > 0.0f;
    }
  }
  canopy_on_ = any;
  if (!any) {
    canopy_ = cl::Buffer();
    return;
  }
  canopy_box_ = nonzero_cell_box(setup_.spec, drag_density);
  canopy_ = cc_.buffer(drag_density.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(canopy_, CL_TRUE, 0, drag_density.size() * sizeof(float),
                                 drag_density.data());
}

void WindGrid::apply_canopy_drag() {
  stages_.enqueue_canopy_drag(canopy_, canopy_box_, vel_, tmp_);
}

void WindGrid::enforce_boundaries() {
  for (int c = 0; c < 3; ++c) stages_.enqueue_enforce_boundaries(c, pressure_.mask(), vel_.component(c));
}

PressureSolveStatus WindGrid::project() {
  PressureSolveStatus status;
  timed("divergence", [&] { stages_.enqueue_divergence_rhs(pressure_.mask(), vel_, pressure_.rhs()); });
  timed("pressure", [&] { status = pressure_.solve(); });
  timed("gradient", [&] {
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_subtract_gradient(c, pressure_.mask(), pressure_.solution(), vel_.component(c));
  });
  return status;
}

double WindGrid::cfl_dt(double max_speed_component) const {
  const auto& st = setup_.settings;
  if (!(st.cfl > 0.0)) return st.dt;
  return max_speed_component > 0.0 ? std::min(st.max_dt, st.cfl * setup_.spec.h / max_speed_component)
                                   : st.max_dt;
}

WindStepReport WindGrid::step() {
  double dt = setup_.settings.dt;
  if (setup_.settings.cfl > 0.0) {
    const double vmax = stages_.max_speed_component(vel_);
    if (!std::isfinite(vmax))
      throw std::runtime_error(fmt::format("WindGrid: velocity is not finite before step {}", steps_ + 1));
    dt = cfl_dt(vmax);
  }
  return step_by(dt);
}

WindStepReport WindGrid::step_by(double dt) {
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument(fmt::format("WindGrid: a step needs a finite dt > 0 s, got {}", dt));
  const auto& st = setup_.settings;
  const auto& spec = setup_.spec;
  FwStep s = stages_.step();
  s.dt = static_cast<float>(dt);
  s.time = static_cast<float>(time_);
  stages_.set_step(s);

  WindStepReport report;
  timed("advect", [&] { advect(static_cast<float>(dt)); });
  timed("forces", [&] { apply_forces(); });
  if (canopy_on_) timed("canopy", [&] { apply_canopy_drag(); });
  report.viscous_substeps = viscous_substeps(st.viscosity, dt, spec.h);
  if (report.viscous_substeps > 0) {
    timed("viscosity", [&] {
      const double sub = dt / report.viscous_substeps;
      const float coefficient = static_cast<float>(st.viscosity * sub / (spec.h * spec.h));
      for (int n = 0; n < report.viscous_substeps; ++n) {
        for (int c = 0; c < 3; ++c)
          stages_.enqueue_diffuse(c, coefficient, vel_.component(c), tmp_.component(c));
        std::swap(vel_, tmp_);
        enforce_boundaries();
      }
    });
  }
  timed("boundaries", [&] { enforce_boundaries(); });
  report.pressure = project();
  time_ += dt;
  last_dt_ = dt;
  report.step = ++steps_;
  report.time = time_;
  report.dt = dt;
  return report;
}

fluid::MacVelocity WindGrid::download_velocity() {
  fluid::MacVelocity vel(setup_.spec);
  for (int c = 0; c < 3; ++c)
    cc_.queue().enqueueReadBuffer(vel_.component(c), CL_TRUE, 0, vel.component(c).size() * sizeof(float),
                                  vel.component(c).data());
  return vel;
}

void WindGrid::upload_velocity(const fluid::MacVelocity& vel) {
  for (int c = 0; c < 3; ++c) {
    const auto& q = vel.component(c);
    const std::size_t expected =
        c == 0 ? setup_.spec.u_count() : (c == 1 ? setup_.spec.v_count() : setup_.spec.w_count());
    if (q.size() != expected) throw std::invalid_argument("WindGrid: uploaded velocity has the wrong size");
    cc_.queue().enqueueWriteBuffer(vel_.component(c), CL_TRUE, 0, q.size() * sizeof(float), q.data());
  }
}

std::vector<float> WindGrid::download_pressure() {
  std::vector<float> phi(setup_.spec.cell_count());
  cc_.queue().enqueueReadBuffer(pressure_.solution(), CL_TRUE, 0, phi.size() * sizeof(float), phi.data());
  const double inv_dt = last_dt_ > 0.0 ? 1.0 / last_dt_ : 0.0;
  for (auto& p : phi) p = static_cast<float>(p * inv_dt);
  return phi;
}

}  // namespace fw::host
