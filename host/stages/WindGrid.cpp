#include "host/stages/WindGrid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fluid/SubgridStress.hpp"
#include "host/stages/SavedStateNames.hpp"

namespace fw::host {
namespace {

// Validates everything before a single buffer exists (members are built after this returns). Over ranks the
// device holds the rank's block with its halo.
WindGridSetup validated(ComputeContext& cc, WindGridSetup setup, const WindBlocks* blocks) {
  WindGrid::validate(setup);
  const BlockShare share = BlockShare::of(blocks);
  WindGrid::check_fits_device(share.local(setup.spec), WindGrid::estimate_device_bytes(setup, share),
                              cc.device());
  return setup;
}

// The whole domain's `array` from every part's own cells or faces: a halo is a copy of its neighbour's, and
// along a staggered axis the face after a block's last cell is the next block's (or the domain's last).
std::vector<float> whole_grid_array(const std::vector<SavedShare>& parts, const fluid::GridSpec& spec,
                                    const GridArray& array) {
  const int c = array.component;
  const int nx = spec.nx + (c == 0 ? 1 : 0), ny = spec.ny + (c == 1 ? 1 : 0), nz = spec.nz + (c == 2 ? 1 : 0);
  std::vector<float> whole(std::size_t(nx) * std::size_t(ny) * std::size_t(nz), 0.0f);
  for (const SavedShare& part : parts) {
    const BlockArray& cells = part.block;
    const BlockArray a = c >= 0 ? face_array(cells, c) : cells;
    const std::vector<float> values =
        saved_values<float>(part.state->bytes(kWindGridState, array.name), a.cells(), array.name);
    OwnColumns own = own_columns(cells);
    if (c == 0 || c == 1) own.hi[std::size_t(c)] += 1;
    const int ex = a.values(0), ey = a.values(1);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const int gi = cells.origin[0] + i, gj = cells.origin[1] + j;
          if (!own.holds(gi, gj)) continue;
          whole[std::size_t(gi) + std::size_t(nx) * (std::size_t(gj) + std::size_t(ny) * k)] =
              values[std::size_t(i) + std::size_t(ex) * (std::size_t(j) + std::size_t(ey) * k)];
        }
  }
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

std::size_t WindGrid::fields_bytes(const fluid::GridSpec& local) {
  return 2 * FluidStages::velocity_bytes(local);  // the velocity and its scratch
}

std::size_t WindGrid::estimate_device_bytes(const WindGridSetup& setup, const BlockShare& share) {
  const fluid::GridSpec local = share.local(setup.spec);
  const fluid::WindSettings& settings = setup.settings;
  std::optional<fluid::TurbulenceBoxSpec> box;
  if (setup.turbulence) box = setup.turbulence->spec();
  return FluidStages::estimate_device_bytes(local) + fields_bytes(local) +
         PressureProjection::estimate_device_bytes(setup.spec, share) +
         WindBoundaries::estimate_device_bytes(local, box ? &*box : nullptr) +
         host::advection_method(settings.advection).device_bytes(local) +
         BodyForces::estimate_device_bytes(local, setup) + subgrid_model_bytes(settings, local) +
         (settings.wall_roughness_length > 0.0 ? WallStress::estimate_device_bytes(setup, share) : 0);
}

std::size_t WindGrid::estimate_largest_buffer_bytes(const fluid::GridSpec& spec) {
  std::size_t largest = 0;
  for (int c = 0; c < 3; ++c) largest = std::max(largest, FluidStages::padded_bytes(spec, c));
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
      advection_method_(host::advection_method(setup_.settings.advection)),
      seam_(cc, setup_.spec, blocks),
      clock_(cc),
      stages_(cc, seam_.local()),
      context_{cc_, stages_, seam_, clock_, setup_},
      fields_{stages_.allocate_velocity(), stages_.allocate_velocity()},
      projection_(context_),
      boundaries_(context_, projection_.mask()),
      advection_(advection_method_.make(context_)),
      forces_(context_),
      canopy_(context_),
      subgrid_(make_subgrid_model(context_, projection_.mask())),
      wall_(setup_.settings.wall_roughness_length > 0.0 ? std::make_unique<WallStress>(context_) : nullptr),
      viscosity_(context_) {
  for (WindPart* part : all_parts())
    for (const HaloNeed& need : part->halo_needs()) seam_.declare(need);
  // Across a cut along y the back-traces skip the halo rows, which the exchange after them replaces.
  const BlockArray& cells = seam_.block();
  stages_.set_own_rows(cells.halo_low[1], cells.extent[1] - cells.halo_low[1] - cells.halo_high[1]);
  set_ambient(setup_.ambient);
}

std::vector<WindPart*> WindGrid::all_parts() {
  std::vector<WindPart*> parts{&boundaries_, advection_.get(), &forces_, &canopy_};
  if (subgrid_) parts.push_back(subgrid_.get());
  if (wall_) parts.push_back(wall_.get());
  parts.push_back(&viscosity_);
  parts.push_back(&projection_);
  return parts;
}

std::vector<const WindPart*> WindGrid::parts() const {
  const std::vector<WindPart*> all = const_cast<WindGrid*>(this)->all_parts();
  return {all.begin(), all.end()};
}

void WindGrid::set_ambient(const std::array<double, 3>& ambient) {
  setup_.ambient = ambient;
  boundaries_.upload_step_inflow();
}

void WindGrid::set_turbulence_sigma(double sigma) {
  boundaries_.set_turbulence_sigma(sigma);
}

void WindGrid::initialise_ambient() {
  upload_velocity(boundaries_.initial_field());
  boundaries_.enforce(fields_.vel);
  if (subgrid_) subgrid_->restart();  // a new field: the subgrid energy starts in equilibrium with it
  if (last_dt_ <= 0.0) last_dt_ = setup_.settings.cfl > 0.0 ? setup_.settings.max_dt : setup_.settings.dt;
  project();
}

HaloTraffic WindGrid::halo_traffic() const {
  HaloTraffic total = projection_.solver().halo_traffic();
  total += seam_.traffic();
  return total;
}

void WindGrid::set_canopy(std::vector<float> drag_density, const fluid::DragLaw& law) {
  canopy_.set(std::move(drag_density), law);
}

void WindGrid::end_advection_stage(DeviceVelocity& stage) {
  boundaries_.enforce(stage);
  if (setup_.settings.stage_projection == fluid::StageProjection::every_stage) projection_.project(stage);
}

double WindGrid::cfl_dt(const fluid::WindSettings& st, const fluid::GridSpec& spec,
                        const std::array<double, 3>& maxima) {
  if (!(st.cfl > 0.0)) return st.dt;
  const double largest = std::max({maxima[0], maxima[1], maxima[2]});
  const double sum = maxima[0] + maxima[1] + maxima[2];
  double dt = st.max_dt;
  if (largest > 0.0) dt = std::min(dt, st.cfl * spec.h / largest);
  const double limit = host::advection_method(st.advection).courant_limit;
  if (std::isfinite(limit) && sum > 0.0) dt = std::min(dt, limit * spec.h / sum);
  return dt;
}

std::array<double, 3> WindGrid::global_max_speed_components() {
  std::array<double, 3> maxima = stages_.max_speed_components(fields_.vel);
  for (double& m : maxima) m = seam_.world().max(m);  // every face is some rank's, and halos are copies
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
  const int halo = seam_.halo_width();
  // A scheme whose reach does not grow with the Courant number needs no maxima to know it fits.
  if (advection_method_.halo_cells(std::numeric_limits<double>::max()) <= halo) return;
  const std::array<double, 3> maxima = known_maxima ? *known_maxima : global_max_speed_components();
  const double largest = std::max({maxima[0], maxima[1], maxima[2]});
  const double courant = largest * dt / setup_.spec.h;
  if (!(advection_method_.halo_cells(courant) <= halo))
    throw std::runtime_error(fmt::format(
        "WindGrid: step {}: the velocity's largest component, {:.4g} m/s, carries a back-trace {:.3g} cells "
        "in dt = {:.4g} s, past the {} cells of halo the ranks exchange (its corners lie up to floor(C) + 1 "
        "cells away); lower time.dt, or time.cfl with dt: auto",
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
  boundaries_.advance(dt);
  FwStep s = stages_.step();
  s.dt = static_cast<float>(dt);
  s.time = static_cast<float>(time_);
  stages_.set_step(s);
  forces_.update_mean_forcing(fields_, dt);

  WindStepReport report;
  const auto end_stage = [this](DeviceVelocity& stage) { end_advection_stage(stage); };
  const auto enforce = [this](DeviceVelocity& vel) { boundaries_.enforce(vel); };
  clock_.time(advection_->stage(), [&] { advection_->advect(fields_, static_cast<float>(dt), end_stage); });
  clock_.time(forces_.stage(), [&] { forces_.apply(fields_); });
  if (canopy_.on()) clock_.time(canopy_.stage(), [&] { canopy_.apply(fields_); });
  if (subgrid_) clock_.time(subgrid_->stage(), [&] { subgrid_->apply(fields_, dt, canopy_.drag_density()); });
  if (wall_) clock_.time(wall_->stage(), [&] { wall_->apply(fields_); });
  report.viscous_substeps = viscosity_.substeps(dt);
  if (report.viscous_substeps > 0)
    clock_.time(viscosity_.stage(), [&] { viscosity_.apply(fields_, dt, enforce); });
  clock_.time(boundaries_.stage(), [&] { boundaries_.enforce(fields_.vel); });
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
  for (int c = 0; c < 3; ++c) state.save(cc_, saved::kVelocity[c], fields_.vel.component(c));
  for (WindPart* part : all_parts()) part->save_state(state);
  const FwStep& s = stages_.step();
  state.numbers["time"] = {time_};
  state.numbers["last_dt"] = {last_dt_};
  state.numbers["steps"] = {double(steps_)};
  state.numbers["step_start"] = {double(s.time), double(s.dt)};
  state.numbers["ambient"] = {setup_.ambient.begin(), setup_.ambient.end()};
  return state;
}

void WindGrid::restore_state(const StageState& state) {
  for (int c = 0; c < 3; ++c)
    state.restore(cc_, kWindGridState, saved::kVelocity[c], fields_.vel.component(c));
  for (WindPart* part : all_parts()) part->restore_state(state);
  time_ = state.number(kWindGridState, "time", 1)[0];
  last_dt_ = state.number(kWindGridState, "last_dt", 1)[0];
  steps_ = long(state.number(kWindGridState, "steps", 1)[0]);
  const std::vector<double>& ambient = state.number(kWindGridState, "ambient", 3);
  std::copy(ambient.begin(), ambient.end(), setup_.ambient.begin());
  const std::vector<double>& start = state.number(kWindGridState, "step_start", 2);
  FwStep s = stages_.step();
  s.time = static_cast<float>(start[0]);
  s.dt = static_cast<float>(start[1]);
  stages_.set_step(s);
  boundaries_.upload_step_inflow();
}

StageState WindGrid::share_of(const std::vector<SavedShare>& parts) const {
  if (parts.empty()) throw std::invalid_argument("checkpoint: no parts of the wind grid to take a share of");
  const StageState& first = *parts.front().state;
  std::vector<GridArray> arrays;
  for (int c = 0; c < 3; ++c) arrays.push_back({saved::kVelocity[c], c});
  for (const WindPart* part : this->parts())
    for (const GridArray& array : part->saved_arrays()) arrays.push_back(array);
  StageState mine;
  mine.numbers = first.numbers;
  for (const GridArray& array : arrays) {
    if (first.buffers.count(array.name) == 0) continue;  // a subgrid energy not yet started
    mine.buffers[array.name] =
        saved_bytes(seam_.cut(whole_grid_array(parts, setup_.spec, array), array.component));
  }
  return mine;
}

fluid::MacVelocity WindGrid::download_velocity() {
  fluid::MacVelocity vel(seam_.local());
  for (int c = 0; c < 3; ++c)
    cc_.queue().enqueueReadBuffer(fields_.vel.component(c), CL_TRUE, 0,
                                  vel.component(c).size() * sizeof(float), vel.component(c).data());
  return vel;
}

void WindGrid::upload_velocity(const fluid::MacVelocity& vel) {
  const fluid::GridSpec& local = seam_.local();
  for (int c = 0; c < 3; ++c) {
    const auto& q = vel.component(c);
    const std::size_t expected = c == 0 ? local.u_count() : (c == 1 ? local.v_count() : local.w_count());
    if (q.size() != expected) throw std::invalid_argument("WindGrid: uploaded velocity has the wrong size");
    cc_.queue().enqueueWriteBuffer(fields_.vel.component(c), CL_TRUE, 0, q.size() * sizeof(float), q.data());
  }
}

std::vector<float> WindGrid::download_pressure() {
  return projection_.download_pressure(last_dt_);
}

std::vector<float> WindGrid::download_subgrid_energy() {
  if (!subgrid_) throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
  return subgrid_->download_subgrid_energy(fields_);
}

void WindGrid::upload_subgrid_energy(const std::vector<float>& energy) {
  if (!subgrid_) throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
  subgrid_->upload_subgrid_energy(energy);
}

WindStatisticsFields WindGrid::statistics_fields() {
  WindStatisticsFields f;
  f.velocity = &fields_.vel;
  f.mask = &projection_.mask();
  if (subgrid_) {
    f.eddy_viscosity = &subgrid_->eddy_viscosity();
    f.subgrid_energy = subgrid_->subgrid_energy();
  }
  f.drag_density = canopy_.drag_density();
  return f;
}

std::vector<float> WindGrid::download_eddy_viscosity() {
  if (!subgrid_)
    throw std::logic_error(
        "WindGrid: no eddy viscosity without a subgrid stage (solver.smagorinsky_constant or "
        "solver.subgrid tke)");
  return subgrid_->download_eddy_viscosity();
}

}  // namespace fw::host
