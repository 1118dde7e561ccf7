#include "host/stages/WindGrid.hpp"

#include "host/stages/SavedStateNames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "base/ExactSum.hpp"
#include "fluid/SubgridStress.hpp"
#include "fluid/UpwindStencil.hpp"

namespace fw::host {
namespace {

// Validates everything before a single buffer exists (members are built after this returns). Over ranks the
// device holds the rank's block with its halo.
WindGridSetup validated(ComputeContext& cc, WindGridSetup setup, const WindBlocks* blocks) {
  WindGrid::validate(setup);
  const std::size_t box_bytes =
      setup.turbulence ? WindGrid::estimate_turbulence_bytes(setup.turbulence->spec()) : 0;
  fluid::GridSpec held = setup.spec;
  if (blocks && blocks->world && blocks->world->size() > 1) {
    const fluid::Decomposition& d = blocks->decomposition;
    held = block_spec(setup.spec, d, block_array(d, blocks->world->rank(), 0, setup.spec.nz, d.halo()));
  }
  WindGrid::check_fits_device(
      held, WindGrid::estimate_device_bytes(held, setup.settings, cc.row_chunk()) + box_bytes, cc.device());
  return setup;
}

int viscous_substeps(double nu, double dt, double h) {
  if (nu <= 0.0) return 0;
  // Explicit diffusion is stable for nu dt / h^2 <= 1/6 in 3D; keep a margin.
  return std::max(1, static_cast<int>(std::ceil(nu * dt / (h * h) / 0.15)));
}

// The cells a rank holds: its block with the halo over several ranks, else the whole grid.
BlockArray held_cells(const fluid::GridSpec& spec, const Communicator& world,
                      const fluid::Decomposition& decomposition) {
  if (world.size() > 1) return block_array(decomposition, world.rank(), 0, spec.nz, decomposition.halo());
  BlockArray whole;
  whole.extent = {spec.nx, spec.ny, spec.nz};
  return whole;
}

}  // namespace

void WindGrid::validate(const WindGridSetup& setup) {
  setup.spec.validate();
  setup.settings.validate();
  setup.profile.validate();
  if (!setup.solid.empty() && setup.solid.size() != setup.spec.cell_count())
    throw std::invalid_argument(fmt::format("WindGrid: solid map has {} cells, the grid {}",
                                            setup.solid.size(), setup.spec.cell_count()));
  const double z0 = setup.settings.wall_roughness_length;
  const double z1 = fluid::wall_centre_height(setup.spec.h);
  if (z0 > 0.0 && !(z0 < z1))  // the log law needs the first cell's centre above z0
    throw std::invalid_argument(fmt::format(
        "WindGrid: wall_roughness_length must be below h/2 = {} m (the first cell centre's height), got {} m",
        z1, z0));
  if (!(std::isfinite(setup.forcing.relaxation_time) && setup.forcing.relaxation_time >= 0.0))
    throw std::invalid_argument(
        fmt::format("WindGrid: the mean forcing's relaxation time must be >= 0 s, got {}",
                    setup.forcing.relaxation_time));
  for (const FwGust& g : setup.gusts)
    if (!(g.duration > 0.0f) || !(g.radius > 0.0f))
      throw std::invalid_argument("WindGrid: a gust needs a positive duration and radius");
}

std::size_t WindGrid::estimate_turbulence_bytes(const fluid::TurbulenceBoxSpec& spec) {
  // TurbulenceBox::values(): u, v, w a point.
  constexpr std::size_t kComponents = 3;
  return ComputeContext::allocation_bytes(spec.point_count() * kComponents * sizeof(float));
}

std::size_t WindGrid::estimate_canopy_bytes(const fluid::GridSpec& spec) {
  return ComputeContext::allocation_bytes(spec.cell_count() * sizeof(float));
}

std::size_t WindGrid::estimate_device_bytes(const fluid::GridSpec& spec, const fluid::WindSettings& settings,
                                            int row_chunk) {
  const std::size_t faces = spec.u_count() + spec.v_count() + spec.w_count();
  const bool maccormack = settings.advection == fluid::AdvectionScheme::maccormack;
  const bool upwind = settings.advection == fluid::AdvectionScheme::upwind5;
  const std::size_t padded =
      std::size_t(spec.nx + 2 * FW_PAD) * (spec.ny + 2 * FW_PAD) * (spec.nz + 2 * FW_PAD) * 3;
  // Velocity and scratch, the third buffer of MacCormack and upwind5, and the padded copies.
  std::size_t bytes =
      ((maccormack || upwind ? 3 : 2) * faces + (maccormack ? 2 : 1) * padded) * sizeof(float);
  if (upwind) bytes += faces * sizeof(std::uint16_t);  // the flux orders
  if (settings.vorticity_confinement > 0.0) bytes += spec.cell_count() * 4 * sizeof(float);
  if (settings.smagorinsky_constant > 0.0) bytes += spec.cell_count() * sizeof(float);  // nu_t
  if (settings.subgrid == fluid::SubgridModel::tke)
    bytes += 3 * spec.cell_count() * sizeof(float);  // nu_t, e and the advected e
  // Pressure hierarchy: about 1/7 extra for the coarse levels of a 3D grid.
  const std::size_t cells = spec.cell_count();
  const std::size_t levels = cells + cells / 7 + 64;
  bytes += levels * (1 + 2 * sizeof(float)) + cells * 5 * sizeof(float);
  const std::size_t items_x = (std::size_t(spec.nx) + 1 + row_chunk - 1) / std::size_t(row_chunk);
  bytes += 2 * items_x * (std::size_t(spec.ny) + 1) * (std::size_t(spec.nz) + 1) * sizeof(float);
  return bytes;
}

std::size_t WindGrid::estimate_largest_buffer_bytes(const fluid::GridSpec& spec) {
  std::size_t largest = 0;
  for (int c = 0; c < 3; ++c) {  // as FluidStages::allocate_padded_velocity
    const std::size_t padded = std::size_t(spec.nx + (c == 0) + 2 * FW_PAD) *
                               (spec.ny + (c == 1) + 2 * FW_PAD) * (spec.nz + (c == 2) + 2 * FW_PAD);
    largest = std::max(largest, (padded + FW_WINDOW_SLACK) * sizeof(float));
  }
  return largest;
}

void WindGrid::check_fits_device(const fluid::GridSpec& spec, std::size_t bytes, const DeviceInfo& device) {
  const double mib = 1024.0 * 1024.0;
  if (bytes > device.global_memory_bytes)
    throw std::invalid_argument(fmt::format(
        "WindGrid: a {} x {} x {} grid needs about {:.0f} MiB of device memory, but '{}' has {:.0f} MiB",
        spec.nx, spec.ny, spec.nz, bytes / mib, device.device_name, device.global_memory_bytes / mib));
  const std::size_t largest = estimate_largest_buffer_bytes(spec);
  if (largest > device.max_allocation_bytes)
    throw std::invalid_argument(fmt::format(
        "WindGrid: a {} x {} x {} grid needs {:.0f} MiB buffers, but '{}' allocates at most {:.0f} MiB",
        spec.nx, spec.ny, spec.nz, largest / mib, device.device_name, device.max_allocation_bytes / mib));
}

WindGrid::WindGrid(ComputeContext& cc, WindGridSetup setup, const WindBlocks* blocks)
    : cc_(cc),
      setup_(validated(cc, std::move(setup), blocks)),
      world_(blocks && blocks->world ? blocks->world : &Communicator::alone()),
      decomposition_(blocks ? blocks->decomposition : fluid::Decomposition()),
      block_(held_cells(setup_.spec, *world_, decomposition_)),
      local_(world_->size() > 1 ? block_spec(setup_.spec, decomposition_, block_) : setup_.spec),
      pressure_blocks_{world_, decomposition_, decomposition_.halo()},
      profile_shape_(setup_.profile.sample_cell_centres(setup_.spec.nz, setup_.spec.h)),
      stages_(cc, local_),
      pressure_(cc, setup_.spec, fluid::build_pressure_levels(setup_.spec, setup_.solid),
                setup_.settings.pressure, world_->size() > 1 ? &pressure_blocks_ : nullptr) {
  const bool split = world_->size() > 1;
  if (split) {
    for (int c = 0; c < 3; ++c) face_halo_[std::size_t(c)].emplace(cc_, *world_, face_array(block_, c));
    cell_halo_.emplace(cc_, *world_, block_);
    if (setup_.settings.vorticity_confinement > 0.0) {
      // Four floats a cell, interleaved: along x the layout is four times as long, and so are its halos.
      BlockArray quads = block_;
      quads.extent[0] *= 4, quads.halo_low[0] *= 4, quads.halo_high[0] *= 4;
      vorticity_halo_.emplace(cc_, *world_, quads);
    }
  }
  // The block's solids, halo included; the whole grid's in one process.
  const std::vector<std::uint8_t> solid = split && !setup_.solid.empty()
                                              ? block_of(setup_.solid, setup_.spec.nx, setup_.spec.ny, block_)
                                              : setup_.solid;
  vel_ = stages_.allocate_velocity();
  tmp_ = stages_.allocate_velocity();
  padded_ = stages_.allocate_padded_velocity();
  if (setup_.settings.advection == fluid::AdvectionScheme::maccormack) {
    back_ = stages_.allocate_velocity();
    padded_forward_ = stages_.allocate_padded_velocity();
  }
  if (setup_.settings.advection == fluid::AdvectionScheme::upwind5) {
    back_ = stages_.allocate_velocity();
    // The whole grid's orders, cut to the block: a block's edge is no wall to the flux orders.
    fluid::UpwindOrders orders = fluid::upwind_orders(setup_.spec, setup_.solid);
    if (split)
      for (int c = 0; c < 3; ++c)
        orders[std::size_t(c)] = block_of(orders[std::size_t(c)], setup_.spec.nx + (c == 0),
                                          setup_.spec.ny + (c == 1), face_array(block_, c));
    upwind_orders_ = stages_.upload_upwind_orders(orders);
  }
  if (setup_.settings.vorticity_confinement > 0.0)
    vorticity_ = cc_.buffer(local_.cell_count() * 4 * sizeof(float));
  if (subgrid_enabled()) eddy_viscosity_ = cc_.zero_floats(local_.cell_count());
  if (subgrid_tke_enabled()) {
    subgrid_energy_ = cc_.buffer(local_.cell_count() * sizeof(float));
    advected_energy_ = cc_.buffer(local_.cell_count() * sizeof(float));
  }
  if (wall_stress_enabled()) {
    wall_drag_coefficient_ =
        fluid::wall_drag_coefficient(setup_.spec.h, setup_.settings.wall_roughness_length);
    wall_faces_ = stages_.upload_wall_faces(list_wall_faces(local_, fluid::wall_cells(local_, solid)));
  }
  if (!setup_.gusts.empty()) {
    gusts_ = cc_.buffer(setup_.gusts.size() * sizeof(FwGust));
    cc_.queue().enqueueWriteBuffer(gusts_, CL_TRUE, 0, setup_.gusts.size() * sizeof(FwGust),
                                   setup_.gusts.data());
  } else {
    gusts_ = cc_.buffer(sizeof(FwGust));
  }
  const auto inflow = inflow_buffer_values(inflow_state(), local_);
  profile_ = cc_.buffer(inflow.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(profile_, CL_TRUE, 0, inflow.size() * sizeof(float), inflow.data());
  stages_.set_profile(profile_);
  set_ambient(setup_.ambient);
}

void WindGrid::upload_step_inflow() {
  FwStep s = stages_.step();
  const fluid::InflowState inflow = inflow_state();
  for (int a = 0; a < 3; ++a) s.ambient[a] = inflow.ambient[a];
  set_step_turbulence(s, inflow);
  stages_.set_step(s);
}

void WindGrid::set_ambient(const std::array<double, 3>& ambient) {
  setup_.ambient = ambient;
  upload_step_inflow();
}

void WindGrid::set_turbulence_sigma(double sigma) {
  if (!(std::isfinite(sigma) && sigma >= 0.0))
    throw std::invalid_argument(fmt::format("WindGrid: turbulence sigma must be >= 0 m/s, got {}", sigma));
  turbulence_sigma_ = sigma;
  upload_step_inflow();
}

fluid::InflowState WindGrid::inflow_state() const {
  fluid::InflowState state;
  for (int a = 0; a < 3; ++a) state.ambient[a] = static_cast<float>(setup_.ambient[a]);
  state.profile = profile_shape_;
  state.turbulence = setup_.turbulence;
  state.turbulence_sigma = static_cast<float>(turbulence_sigma_);
  for (int a = 0; a < 3; ++a) state.turbulence_offset[a] = static_cast<float>(turbulence_offset_[a]);
  return state;
}

std::array<double, 2> WindGrid::reference_layer_mean() {
  const auto& spec = setup_.spec;
  // Cell-centre layers k0 and k0 + 1 around the reference height, weight t on the upper one.
  const double level = std::clamp(setup_.profile.reference_height / spec.h - 0.5, 0.0, spec.nz - 1.0);
  const int k0 = std::min(static_cast<int>(level), spec.nz - 1), k1 = std::min(k0 + 1, spec.nz - 1);
  const double t = level - k0;
  std::array<double, 2> mean{0, 0};
  for (int c = 0; c < 2; ++c) {
    const BlockArray faces = face_array(block_, c);
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
    cc_.queue().enqueueReadBuffer(vel_.component(c), CL_FALSE, layer * k0 * sizeof(float),
                                  layer * sizeof(float), rows.data());
    cc_.queue().enqueueReadBuffer(vel_.component(c), CL_TRUE, layer * k1 * sizeof(float),
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
    mean[c] = ((1.0 - t) * world_->sum(lower) + t * world_->sum(upper)) / double(distinct);
  }
  return mean;
}

void WindGrid::update_mean_forcing(double dt) {
  const double tau = setup_.forcing.relaxation_time;
  if (!(tau > 0.0)) return;
  const auto mean = reference_layer_mean();
  for (int c = 0; c < 2; ++c) {
    const double error = setup_.ambient[c] - mean[c];
    forcing_integral_[c] += error * dt;
    forcing_acceleration_[c] = error / tau + forcing_integral_[c] / (tau * tau);
  }
}

template <typename F>
void WindGrid::timed(const char* stage, F&& work) {
  if (!stage_timing_) {
    work();
    return;
  }
  // A stage timed inside another (upwind5's stage projections inside "advect") counts for itself only.
  const double nested_before = nested_ms_;
  cc_.finish();  // what the enclosing stage enqueued before this one is the enclosing stage's
  const auto start = std::chrono::steady_clock::now();
  work();
  cc_.finish();
  const double total =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stage_ms_[stage] += total - (nested_ms_ - nested_before);
  nested_ms_ = nested_before + total;
}

void WindGrid::initialise_ambient() {
  const auto& spec = local_;
  const auto inflow = inflow_state();
  fluid::MacVelocity vel(spec);
  // The profile, and the turbulence where there is some, on every face: a turbulent run starts developed.
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    auto& q = vel.component(c);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i)
          q[std::size_t(i) + std::size_t(ex) * (j + std::size_t(ey) * k)] =
              static_cast<float>(inflow.value(spec, c, i, j, k, k));
  }
  upload_velocity(vel);
  enforce_boundaries();
  subgrid_energy_set_ = false;  // a new field: the subgrid energy starts in equilibrium with it
  if (last_dt_ <= 0.0) last_dt_ = setup_.settings.cfl > 0.0 ? setup_.settings.max_dt : setup_.settings.dt;
  project();
}

void WindGrid::advect(float dt) {
  if (setup_.settings.advection == fluid::AdvectionScheme::upwind5) {
    advect_upwind(dt);
    return;
  }
  stages_.enqueue_pad(vel_, padded_);
  for (int c = 0; c < 3; ++c) stages_.enqueue_advect(c, dt, padded_, padded_.component(c), tmp_.component(c));
  if (setup_.settings.advection == fluid::AdvectionScheme::semi_lagrangian) {
    std::swap(vel_, tmp_);
    exchange(vel_);
    return;
  }
  // MacCormack: forward into tmp, backward (from tmp's padded copy) into back, corrected in place in back.
  exchange(tmp_);
  stages_.enqueue_pad(tmp_, padded_forward_);
  for (int c = 0; c < 3; ++c)
    stages_.enqueue_advect(c, -dt, padded_, padded_forward_.component(c), back_.component(c));
  for (int c = 0; c < 3; ++c)
    stages_.enqueue_maccormack_correct(c, padded_, padded_.component(c), tmp_.component(c),
                                       back_.component(c), back_.component(c));
  std::swap(vel_, back_);
  exchange(vel_);
}

void WindGrid::advect_upwind(float dt) {
  // Wicker & Skamarock's three stages from u at the step's start: u1 = u + dt/3 R(u), u2 = u + dt/2 R(u1),
  // u + dt R(u2). Stages alternate between tmp_ and back_; each reads only the padded copy of the one
  // before and u itself. The first two get their prescribed faces back (and, if asked, a projection), as
  // the last does with the rest of the step.
  constexpr float kStageFractions[] = {1.0f / 3.0f, 0.5f, 1.0f};
  DeviceVelocity* stage = &vel_;
  for (int n = 0; n < 3; ++n) {
    stages_.enqueue_pad(*stage, padded_);
    DeviceVelocity& out = n == 1 ? back_ : tmp_;
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_upwind_stage(c, kStageFractions[n] * dt, padded_, upwind_orders_, vel_.component(c),
                                   out.component(c));
    if (n < 2) {
      enforce_boundaries(out);
      if (setup_.settings.stage_projection == fluid::StageProjection::every_stage) project(out);
      exchange(out);
    }
    stage = &out;
  }
  std::swap(vel_, tmp_);
  exchange(vel_);
}

void WindGrid::apply_forces() {
  const auto& st = setup_.settings;
  std::array<double, 3> body = st.body_force;
  for (int c = 0; c < 2; ++c) body[c] += forcing_acceleration_[c];
  const bool any_body = body[0] != 0.0 || body[1] != 0.0 || body[2] != 0.0;
  if (any_body || !setup_.gusts.empty())
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_apply_forces(c, static_cast<float>(body[c]), gusts_,
                                   static_cast<int>(setup_.gusts.size()), vel_.component(c));
  if (st.vorticity_confinement > 0.0) {
    stages_.enqueue_vorticity(vel_, vorticity_);
    if (vorticity_halo_) vorticity_halo_->exchange(vorticity_);  // across a periodic seam, as for nu_t
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_vorticity_confinement(c, static_cast<float>(st.vorticity_confinement), vorticity_,
                                            vel_.component(c));
  }
  if (any_body || !setup_.gusts.empty() || st.vorticity_confinement > 0.0) exchange(vel_);
}

void WindGrid::exchange(DeviceVelocity& vel) {
  for (int c = 0; c < 3; ++c)
    if (face_halo_[std::size_t(c)]) face_halo_[std::size_t(c)]->exchange(vel.component(c));
}

void WindGrid::exchange_cells(cl::Buffer& field) {
  if (cell_halo_) cell_halo_->exchange(field);
}

HaloTraffic WindGrid::halo_traffic() const {
  HaloTraffic total = pressure_.halo_traffic();
  for (const auto& halo : face_halo_)
    if (halo) total += halo->traffic();
  if (cell_halo_) total += cell_halo_->traffic();
  if (vorticity_halo_) total += vorticity_halo_->traffic();
  return total;
}

void WindGrid::set_canopy(std::vector<float> drag_density, const fluid::DragLaw& law) {
  law.validate();
  drag_law_ = law;
  if (world_->size() > 1 && !drag_density.empty() && drag_density.size() == setup_.spec.cell_count())
    drag_density = block_of(drag_density, setup_.spec.nx, setup_.spec.ny, block_);
  bool any = false;
  if (!drag_density.empty()) {
    if (drag_density.size() != local_.cell_count())
      throw std::invalid_argument(fmt::format("WindGrid: canopy drag density has {} cells, the grid {}",
                                              drag_density.size(), local_.cell_count()));
    for (float k : drag_density) {
      if (!std::isfinite(k) || k < 0.0f)
        throw std::invalid_argument(
            fmt::format("WindGrid: canopy drag density must be finite and >= 0, got {}", k));
      any = any || k > 0.0f;
    }
  }
  // Over ranks the drag is on wherever any block has some: a block with none still takes part in the drag
  // step's halo exchange, as its neighbours do, or the ranks' messages pair up with the wrong exchanges. Its
  // density stays zero, as the same cells' are in one process.
  canopy_on_ = world_->max(any ? 1.0 : 0.0) > 0.0;
  if (!canopy_on_) {
    canopy_ = cl::Buffer();
    canopy_box_ = CellBox{};
    return;
  }
  canopy_box_ = nonzero_cell_box(local_, drag_density);
  canopy_ = cc_.buffer(drag_density.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(canopy_, CL_TRUE, 0, drag_density.size() * sizeof(float),
                                 drag_density.data());
}

void WindGrid::apply_canopy_drag() {
  stages_.enqueue_canopy_drag(canopy_, canopy_box_, vel_, tmp_, drag_law_);
  exchange(vel_);
}

void WindGrid::apply_subgrid_stress(double dt) {
  // The strain and the diffusion read the forced velocity with the boundary rules for ghosts; the
  // diffusion writes out of place (into tmp_, free once advection is done), then the fields swap.
  const auto cap = static_cast<float>(fluid::eddy_viscosity_cap(setup_.spec.h, dt));
  if (subgrid_tke_enabled())
    advance_subgrid_energy(cap);
  else
    stages_.enqueue_eddy_viscosity(static_cast<float>(setup_.settings.smagorinsky_constant), cap,
                                   pressure_.mask(), vel_, eddy_viscosity_);
  // A halo cell across a cut periodic seam sees the seam's face n, which a whole grid reads as face 0 there
  // (the two differ between boundary passes): its nu_t is its owner's.
  exchange_cells(eddy_viscosity_);
  stages_.enqueue_diffuse_eddy(wall_stress_enabled(), pressure_.mask(), eddy_viscosity_, vel_, tmp_);
  std::swap(vel_, tmp_);
  exchange(vel_);
}

void WindGrid::apply_wall_stress() {
  stages_.enqueue_wall_stress(static_cast<float>(wall_drag_coefficient_), wall_faces_, vel_);
  exchange(vel_);
}

void WindGrid::enforce_boundaries(DeviceVelocity& vel) {
  for (int c = 0; c < 3; ++c) stages_.enqueue_enforce_boundaries(c, pressure_.mask(), vel.component(c));
  // A cut periodic axis: the whole grid's rule that its face n repeats face 0, across the seam's blocks.
  for (int c = 0; c < 2; ++c)
    if (face_halo_[std::size_t(c)]) face_halo_[std::size_t(c)]->copy_seam(vel.component(c));
}

PressureSolveStatus WindGrid::project(DeviceVelocity& vel) {
  PressureSolveStatus status;
  timed("divergence", [&] { stages_.enqueue_divergence_rhs(pressure_.mask(), vel, pressure_.rhs()); });
  timed("pressure", [&] { status = pressure_.solve(); });
  timed("gradient", [&] {
    for (int c = 0; c < 3; ++c)
      stages_.enqueue_subtract_gradient(c, pressure_.mask(), pressure_.solution(), vel.component(c));
    exchange(vel);
  });
  return status;
}

double WindGrid::cfl_dt(const fluid::WindSettings& st, const fluid::GridSpec& spec,
                        const std::array<double, 3>& maxima) {
  if (!(st.cfl > 0.0)) return st.dt;
  const double largest = std::max({maxima[0], maxima[1], maxima[2]});
  const double sum = maxima[0] + maxima[1] + maxima[2];
  double dt = st.max_dt;
  if (largest > 0.0) dt = std::min(dt, st.cfl * spec.h / largest);
  const double limit = fluid::courant_limit(st.advection);
  if (std::isfinite(limit) && sum > 0.0) dt = std::min(dt, limit * spec.h / sum);
  return dt;
}

double WindGrid::courant_number(const std::array<double, 3>& maxima, double dt) const {
  const double speed = std::isfinite(fluid::courant_limit(setup_.settings.advection))
                           ? maxima[0] + maxima[1] + maxima[2]
                           : std::max({maxima[0], maxima[1], maxima[2]});
  return speed * dt / setup_.spec.h;
}

std::array<double, 3> WindGrid::global_max_speed_components() {
  std::array<double, 3> maxima = stages_.max_speed_components(vel_);
  for (double& m : maxima) m = world_->max(m);  // every face is some rank's, and halos are copies
  return maxima;
}

WindStepReport WindGrid::step() {
  if (!(setup_.settings.cfl > 0.0)) return step_by(setup_.settings.dt);
  const std::array<double, 3> maxima = global_max_speed_components();
  if (!(std::isfinite(maxima[0]) && std::isfinite(maxima[1]) && std::isfinite(maxima[2])))
    throw std::runtime_error(fmt::format("WindGrid: velocity is not finite before step {}", steps_ + 1));
  return step_by(cfl_dt(maxima), maxima);
}

void WindGrid::check_halo_reach(double dt, const std::optional<std::array<double, 3>>& known_maxima) {
  // upwind5's stencil reaches FW_PAD faces whatever dt; its Courant limit is the plan's and cfl_dt's.
  if (world_->size() == 1 || setup_.settings.advection == fluid::AdvectionScheme::upwind5) return;
  const std::array<double, 3> maxima = known_maxima ? *known_maxima : global_max_speed_components();
  const double largest = std::max({maxima[0], maxima[1], maxima[2]});
  const double courant = largest * dt / setup_.spec.h;
  const int halo = decomposition_.halo();
  if (!(fluid::halo_cells(setup_.settings.advection, courant) <= halo))
    throw std::runtime_error(fmt::format(
        "WindGrid: step {}: the velocity's largest component, {:.4g} m/s, carries a back-trace {:.3g} cells "
        "in "
        "dt = {:.4g} s, past the {} cells of halo the ranks exchange (its corners lie up to floor(C) + 1 "
        "cells "
        "away); lower time.dt, or time.cfl with dt: auto",
        steps_ + 1, largest, courant, dt, halo));
}

void WindGrid::set_clock(double time, long steps) {
  if (!std::isfinite(time) || steps < 0)
    throw std::invalid_argument(
        fmt::format("WindGrid: a clock needs a finite time and steps >= 0, got {} s and {}", time, steps));
  time_ = time;
  steps_ = steps;
}

WindStepReport WindGrid::step_by(double dt) {
  return step_by(dt, std::nullopt);
}

WindStepReport WindGrid::step_by(double dt, const std::optional<std::array<double, 3>>& maxima) {
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument(fmt::format("WindGrid: a step needs a finite dt > 0 s, got {}", dt));
  check_halo_reach(dt, maxima);
  const auto& st = setup_.settings;
  const auto& spec = setup_.spec;
  if (setup_.turbulence) {
    // Taylor's hypothesis: the frozen box moves with the ambient wind; the offset stays within one box
    // length so that float positions keep their resolution over long runs.
    for (int a = 0; a < 3; ++a) {
      const double length = setup_.turbulence->cells()[a] * setup_.turbulence->spacing();
      turbulence_offset_[a] = std::fmod(turbulence_offset_[a] + setup_.ambient[a] * dt, length);
    }
  }
  upload_step_inflow();
  FwStep s = stages_.step();
  s.dt = static_cast<float>(dt);
  s.time = static_cast<float>(time_);
  stages_.set_step(s);
  update_mean_forcing(dt);

  WindStepReport report;
  timed("advect", [&] { advect(static_cast<float>(dt)); });
  timed("forces", [&] { apply_forces(); });
  if (canopy_on_) timed("canopy", [&] { apply_canopy_drag(); });
  if (subgrid_enabled()) timed("subgrid", [&] { apply_subgrid_stress(dt); });
  if (wall_stress_enabled()) timed("wall", [&] { apply_wall_stress(); });
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
        exchange(vel_);
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

StageState WindGrid::save_state() {
  StageState state;
  for (int c = 0; c < 3; ++c) state.save(cc_, saved::kVelocity[c], vel_.component(c));
  state.save(cc_, saved::kPressureSolution, pressure_.solution());
  if (subgrid_enabled()) state.save(cc_, saved::kEddyViscosity, eddy_viscosity_);
  if (subgrid_tke_enabled() && subgrid_energy_set_) state.save(cc_, saved::kSubgridEnergy, subgrid_energy_);
  const FwStep& s = stages_.step();
  state.numbers = {
      {"time", {time_}},
      {"last_dt", {last_dt_}},
      {"steps", {double(steps_)}},
      {"step_start", {double(s.time), double(s.dt)}},
      {"ambient", {setup_.ambient.begin(), setup_.ambient.end()}},
      {"turbulence_sigma", {turbulence_sigma_}},
      {"turbulence_offset", {turbulence_offset_.begin(), turbulence_offset_.end()}},
      {"forcing_integral", {forcing_integral_.begin(), forcing_integral_.end()}},
      {"forcing_acceleration", {forcing_acceleration_.begin(), forcing_acceleration_.end()}},
  };
  return state;
}

void WindGrid::restore_state(const StageState& state) {
  static constexpr const char* kStage = "wind grid";
  for (int c = 0; c < 3; ++c) state.restore(cc_, kStage, saved::kVelocity[c], vel_.component(c));
  state.restore(cc_, kStage, saved::kPressureSolution, pressure_.solution());
  if (subgrid_enabled()) state.restore(cc_, kStage, saved::kEddyViscosity, eddy_viscosity_);
  // Without a saved subgrid energy the next stage starts it at equilibrium, as the run that saved it would.
  subgrid_energy_set_ = subgrid_tke_enabled() && state.buffers.count(saved::kSubgridEnergy) > 0;
  if (subgrid_energy_set_) state.restore(cc_, kStage, saved::kSubgridEnergy, subgrid_energy_);
  time_ = state.number(kStage, "time", 1)[0];
  last_dt_ = state.number(kStage, "last_dt", 1)[0];
  steps_ = long(state.number(kStage, "steps", 1)[0]);
  const auto& copy = [&](const char* name, auto& values) {
    const std::vector<double>& saved = state.number(kStage, name, values.size());
    std::copy(saved.begin(), saved.end(), values.begin());
  };
  copy("ambient", setup_.ambient);
  copy("turbulence_offset", turbulence_offset_);
  copy("forcing_integral", forcing_integral_);
  copy("forcing_acceleration", forcing_acceleration_);
  turbulence_sigma_ = state.number(kStage, "turbulence_sigma", 1)[0];
  const std::vector<double>& start = state.number(kStage, "step_start", 2);
  FwStep s = stages_.step();
  s.time = static_cast<float>(start[0]);
  s.dt = static_cast<float>(start[1]);
  stages_.set_step(s);
  upload_step_inflow();
}

fluid::MacVelocity WindGrid::download_velocity() {
  fluid::MacVelocity vel(local_);
  for (int c = 0; c < 3; ++c)
    cc_.queue().enqueueReadBuffer(vel_.component(c), CL_TRUE, 0, vel.component(c).size() * sizeof(float),
                                  vel.component(c).data());
  return vel;
}

void WindGrid::upload_velocity(const fluid::MacVelocity& vel) {
  for (int c = 0; c < 3; ++c) {
    const auto& q = vel.component(c);
    const std::size_t expected = c == 0 ? local_.u_count() : (c == 1 ? local_.v_count() : local_.w_count());
    if (q.size() != expected) throw std::invalid_argument("WindGrid: uploaded velocity has the wrong size");
    cc_.queue().enqueueWriteBuffer(vel_.component(c), CL_TRUE, 0, q.size() * sizeof(float), q.data());
  }
}

std::vector<float> WindGrid::download_pressure() {
  std::vector<float> phi(local_.cell_count());
  cc_.queue().enqueueReadBuffer(pressure_.solution(), CL_TRUE, 0, phi.size() * sizeof(float), phi.data());
  const double inv_dt = last_dt_ > 0.0 ? 1.0 / last_dt_ : 0.0;
  for (auto& p : phi) p = static_cast<float>(p * inv_dt);
  return phi;
}

void WindGrid::start_subgrid_energy() {
  if (subgrid_energy_set_) return;
  stages_.enqueue_tke_equilibrium(pressure_.mask(), vel_, subgrid_energy_);
  exchange_cells(subgrid_energy_);
  subgrid_energy_set_ = true;
}

void WindGrid::advance_subgrid_energy(float cap) {
  // nu_t from e^n (it also diffuses the velocity), then e^n advected into advected_energy_, then the
  // update back into subgrid_energy_; all read the forced velocity.
  start_subgrid_energy();
  stages_.enqueue_tke_viscosity(cap, pressure_.mask(), subgrid_energy_, eddy_viscosity_);
  exchange_cells(eddy_viscosity_);
  stages_.enqueue_tke_advect(pressure_.mask(), vel_, subgrid_energy_, advected_energy_);
  stages_.enqueue_tke_update(cap, pressure_.mask(), vel_, eddy_viscosity_, canopy_on_ ? &canopy_ : nullptr,
                             advected_energy_, subgrid_energy_);
  exchange_cells(subgrid_energy_);
}

std::vector<float> WindGrid::download_subgrid_energy() {
  if (!subgrid_tke_enabled())
    throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
  start_subgrid_energy();
  std::vector<float> energy(local_.cell_count());
  cc_.queue().enqueueReadBuffer(subgrid_energy_, CL_TRUE, 0, energy.size() * sizeof(float), energy.data());
  return energy;
}

std::vector<float> WindGrid::download_eddy_viscosity() {
  if (!subgrid_enabled())
    throw std::logic_error(
        "WindGrid: no eddy viscosity without a subgrid stage (solver.smagorinsky_constant or "
        "solver.subgrid tke)");
  std::vector<float> viscosity(local_.cell_count());
  cc_.queue().enqueueReadBuffer(eddy_viscosity_, CL_TRUE, 0, viscosity.size() * sizeof(float),
                                viscosity.data());
  return viscosity;
}

void WindGrid::upload_subgrid_energy(const std::vector<float>& energy) {
  if (!subgrid_tke_enabled())
    throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
  if (energy.size() != local_.cell_count())
    throw std::invalid_argument(fmt::format("WindGrid: subgrid energy has {} cells, the grid {}",
                                            energy.size(), local_.cell_count()));
  for (float e : energy)
    if (!std::isfinite(e) || e < 0.0f)
      throw std::invalid_argument(fmt::format("WindGrid: subgrid energy must be finite and >= 0, got {}", e));
  cc_.queue().enqueueWriteBuffer(subgrid_energy_, CL_TRUE, 0, energy.size() * sizeof(float), energy.data());
  subgrid_energy_set_ = true;
}

}  // namespace fw::host
