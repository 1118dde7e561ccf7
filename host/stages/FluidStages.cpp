#include "host/stages/FluidStages.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "fluid/SubgridStress.hpp"
#include "fluid/SubgridTke.hpp"

namespace fw::host {
namespace {}  // namespace

std::vector<float> inflow_buffer_values(const fluid::InflowState& inflow, const fluid::GridSpec& spec) {
  std::vector<float> values = inflow.profile;
  if (!inflow.turbulence) return values;
  // Whatever sigma is now (it may be raised later), the box goes in with x slowest: the inflow plane is swept
  // along x, so the points that one step's ghosts sample lie in two contiguous slabs that stay in cache.
  const fluid::TurbulenceBox& box = *inflow.turbulence;
  const auto n = box.cells();
  const std::vector<float>& source = box.values();  // x fastest
  values.reserve(values.size() + source.size());
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const std::size_t point =
            std::size_t(i) + std::size_t(n[0]) * (std::size_t(j) + std::size_t(n[1]) * k);
        for (int c = 0; c < 3; ++c) values.push_back(source[3 * point + c]);
      }
  values.resize(values.size() + std::size_t(fw_shell_face_offset(spec.nx, spec.ny, spec.nz, 6)), 0.0f);
  return values;
}

namespace {
// Whether two steps prescribe the same inflow (the fields kernels/inflow_shell.cl reads).
bool same_inflow(const FwStep& a, const FwStep& b) {
  bool same = a.turbulence_sigma == b.turbulence_sigma && a.turbulence_spacing == b.turbulence_spacing;
  for (int n = 0; n < 3; ++n)
    same = same && a.ambient[n] == b.ambient[n] && a.turbulence_offset[n] == b.turbulence_offset[n] &&
           a.turbulence_cells[n] == b.turbulence_cells[n];
  return same;
}
}  // namespace

void set_step_turbulence(FwStep& step, const fluid::InflowState& inflow) {
  step.turbulence_sigma = inflow.turbulent() ? inflow.turbulence_sigma : 0.0f;
  for (int a = 0; a < 3; ++a) {
    step.turbulence_offset[a] = inflow.turbulence_offset[a];
    step.turbulence_cells[a] = inflow.turbulence ? inflow.turbulence->cells()[a] : 1;
  }
  step.turbulence_spacing = inflow.turbulence ? static_cast<float>(inflow.turbulence->spacing()) : 1.0f;
}

std::size_t FluidStages::partial_bound(const fluid::GridSpec& spec) {
  // max_divergence's partials over the cells, max_speed_components' over each component's faces.
  std::size_t most = ComputeContext::reduction_groups_bound(spec.nx, spec.ny, spec.nz);
  for (int c = 0; c < 3; ++c)
    most = std::max(most, ComputeContext::reduction_groups_bound(spec.nx + (c == 0), spec.ny + (c == 1),
                                                                 spec.nz + (c == 2)));
  return most;
}

std::size_t FluidStages::estimate_device_bytes(const fluid::GridSpec& spec) {
  // The partials, and the flat profile that stands in until set_profile.
  return ComputeContext::allocation_bytes(partial_bound(spec) * sizeof(float)) +
         ComputeContext::allocation_bytes(std::size_t(spec.nz) * sizeof(float));
}

std::size_t FluidStages::face_arrays_bytes(const fluid::GridSpec& spec, std::size_t bytes_per_face) {
  return ComputeContext::allocation_bytes(spec.u_count() * bytes_per_face) +
         ComputeContext::allocation_bytes(spec.v_count() * bytes_per_face) +
         ComputeContext::allocation_bytes(spec.w_count() * bytes_per_face);
}

std::size_t FluidStages::velocity_bytes(const fluid::GridSpec& spec) {
  return face_arrays_bytes(spec, sizeof(float));
}

std::size_t FluidStages::padded_velocity_bytes(const fluid::GridSpec& spec) {
  std::size_t bytes = 0;
  for (int c = 0; c < 3; ++c) bytes += ComputeContext::allocation_bytes(padded_bytes(spec, c));
  return bytes;
}

std::size_t FluidStages::padded_values(const fluid::GridSpec& spec, int c) {
  return std::size_t(spec.nx + (c == 0) + 2 * FW_PAD) * (spec.ny + (c == 1) + 2 * FW_PAD) *
         (spec.nz + (c == 2) + 2 * FW_PAD);
}

std::size_t FluidStages::padded_bytes(const fluid::GridSpec& spec, int c) {
  // Advection reads the copies through windowed loads (kernels/lanes.cl), which run a little past the end.
  return (padded_values(spec, c) + FW_WINDOW_SLACK) * sizeof(float);
}

std::size_t FluidStages::upwind_orders_bytes(const fluid::GridSpec& spec) {
  return face_arrays_bytes(spec, sizeof(std::uint16_t));
}

std::size_t FluidStages::wall_faces_bytes(const WallFaces& list) {
  if (list.size() == 0) return 0;
  return ComputeContext::allocation_bytes(list.faces.size() * sizeof(std::int32_t)) +
         2 * ComputeContext::allocation_bytes(list.weights.size() * sizeof(float));
}

FluidStages::FluidStages(ComputeContext& cc, const fluid::GridSpec& spec)
    : cc_(cc), spec_(spec), grid_(spec.to_device()), own_rows_{0, spec.ny} {
  const std::size_t most = partial_bound(spec_);
  partial_host_.resize(most);
  partial_ = cc_.buffer(most * sizeof(float));
  std::vector<float> flat(static_cast<std::size_t>(spec.nz), 1.0f);
  profile_ = cc_.buffer(flat.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(profile_, CL_TRUE, 0, flat.size() * sizeof(float), flat.data());

  pad_ = Kernel(cc_.build("fluid_ghosts.cl"), "pad_component");
  cl::Program advect = cc_.build("fluid_advect.cl");
  for (int c = 0; c < 3; ++c) {
    const char* axis[] = {"u", "v", "w"};
    advect_[c] = Kernel(advect, std::string("advect_") + axis[c], RowItems::lanes);
    maccormack_[c] = Kernel(advect, std::string("maccormack_correct_") + axis[c], RowItems::lanes);
  }
  cl::Program forces = cc_.build("fluid_forces.cl");
  forces_ = Kernel(forces, "apply_forces");
  vorticity_ = Kernel(forces, "vorticity");
  confinement_ = Kernel(forces, "vorticity_confinement");
  diffuse_ = Kernel(forces, "diffuse");
  for (int c = 0; c < 3; ++c) canopy_drag_[c] = Kernel(forces, std::string("canopy_drag_") + "uvw"[c]);
  copy_face_box_ = Kernel(forces, "copy_face_box");
  boundaries_ = Kernel(cc_.build("fluid_boundaries.cl"), "enforce_boundaries");
  fill_inflow_shell_ = Kernel(cc_.build("inflow_shell.cl"), "fill_inflow_shell");
  cl::Program project = cc_.build("fluid_project.cl");
  divergence_ = Kernel(project, "divergence_rhs");
  max_div_ = Kernel(project, "max_divergence");
  gradient_ = Kernel(project, "subtract_gradient");
  max_abs_ = Kernel(project, "max_abs");
}

void FluidStages::set_step(const FwStep& step) {
  shell_fresh_ = shell_fresh_ && same_inflow(step, step_);
  step_ = step;
  refresh_inflow_shell();
}

void FluidStages::set_profile(cl::Buffer inflow) {
  profile_ = std::move(inflow);
  shell_fresh_ = false;
  refresh_inflow_shell();
}

void FluidStages::refresh_inflow_shell() {
  if (step_.turbulence_sigma == 0.0f || shell_fresh_) return;
  const std::size_t box =
      3 * std::size_t(step_.turbulence_cells[0]) * step_.turbulence_cells[1] * step_.turbulence_cells[2];
  const std::size_t needed =
      std::size_t(spec_.nz) + box + std::size_t(fw_shell_face_offset(spec_.nx, spec_.ny, spec_.nz, 6));
  const std::size_t held = profile_.getInfo<CL_MEM_SIZE>() / sizeof(float);
  if (held < needed)
    throw std::invalid_argument(fmt::format(
        "FluidStages: the inflow buffer holds {} floats; the turbulence needs {} (profile, box and shell: "
        "inflow_buffer_values)",
        held, needed));
  for (int f = 0; f < 6; ++f) {
    if (grid_.bc[f] != FW_BC_INFLOW) continue;
    const int a = f / 2, b1_cells = a == 0 ? spec_.ny : spec_.nx;
    const std::size_t lines = std::size_t(fw_shell_span(b1_cells)) * FW_SHELL_LAYERS;
    fill_inflow_shell_.set_args(grid_, step_, f, profile_).enqueue(cc_, cl::NDRange(lines, 3));
  }
  shell_fresh_ = true;
}

DeviceVelocity FluidStages::allocate_velocity() {
  DeviceVelocity vel;
  vel.u = cc_.buffer(spec_.u_count() * sizeof(float));
  vel.v = cc_.buffer(spec_.v_count() * sizeof(float));
  vel.w = cc_.buffer(spec_.w_count() * sizeof(float));
  cc_.queue().enqueueFillBuffer(vel.u, 0.0f, 0, spec_.u_count() * sizeof(float));
  cc_.queue().enqueueFillBuffer(vel.v, 0.0f, 0, spec_.v_count() * sizeof(float));
  cc_.queue().enqueueFillBuffer(vel.w, 0.0f, 0, spec_.w_count() * sizeof(float));
  return vel;
}

cl::NDRange FluidStages::component_rows(int c) const {
  return cc_.rows(spec_.nx + (c == 0), spec_.ny + (c == 1), spec_.nz + (c == 2));
}

std::size_t FluidStages::padded_count(int c) const {
  return padded_values(spec_, c);
}

cl::NDRange FluidStages::advect_rows(int c) const {
  const int ex = spec_.nx + (c == 0);
  return cl::NDRange(std::size_t((ex + FW_LANES - 1) / FW_LANES), std::size_t(spec_.ny + (c == 1)),
                     std::size_t(spec_.nz + (c == 2)));
}

DeviceVelocity FluidStages::allocate_padded_velocity() {
  DeviceVelocity vel;
  for (int c = 0; c < 3; ++c) {
    const std::size_t bytes = padded_bytes(spec_, c);
    vel.component(c) = cc_.buffer(bytes);
    cc_.queue().enqueueFillBuffer(vel.component(c), 0.0f, 0, bytes);
  }
  return vel;
}

void FluidStages::enqueue_pad(int c, cl::Buffer& q, cl::Buffer& padded) {
  pad_.set_args(grid_, step_, profile_, c, q, padded)
      .enqueue(cc_, cc_.rows(spec_.nx + (c == 0) + 2 * FW_PAD, spec_.ny + (c == 1) + 2 * FW_PAD,
                             spec_.nz + (c == 2) + 2 * FW_PAD));
}

void FluidStages::enqueue_pad(DeviceVelocity& vel, DeviceVelocity& padded) {
  for (int c = 0; c < 3; ++c) enqueue_pad(c, vel.component(c), padded.component(c));
}

void FluidStages::set_own_rows(int first, int count) {
  if (first < 0 || count < 1 || first + count > spec_.ny)
    throw std::invalid_argument(fmt::format("FluidStages: own rows {} .. {} outside the grid's {}", first,
                                            first + count - 1, spec_.ny));
  own_rows_ = {first, count};
}

void FluidStages::enqueue_advect(int c, float dt, DeviceVelocity& pv, cl::Buffer& pq, cl::Buffer& out) {
  // The own rows only: their halo rows, a sixth of a block cut across y 3 cells deep each side, would be
  // traced only to be replaced by the neighbours'. The v faces between blocks are computed by both.
  cl::NDRange rows = advect_rows(c);
  const std::size_t count = std::size_t(own_rows_[1] + (c == 1));
  advect_[c]
      .set_args(grid_, dt, pv.u, pv.v, pv.w, pq, out)
      .enqueue_from(cc_, cl::NDRange(0, std::size_t(own_rows_[0]), 0), cl::NDRange(rows[0], count, rows[2]));
}

void FluidStages::enqueue_maccormack_correct(int c, DeviceVelocity& pv, cl::Buffer& pq, cl::Buffer& forward,
                                             cl::Buffer& back, cl::Buffer& out) {
  maccormack_[c]
      .set_args(grid_, step_.dt, pv.u, pv.v, pv.w, pq, forward, back, out)
      .enqueue(cc_, advect_rows(c));
}

void FluidStages::build_upwind_kernels() {
  if (upwind_built_) return;
  cl::Program program = cc_.build("fluid_upwind.cl");
  for (int c = 0; c < 3; ++c)
    upwind_stage_[c] = Kernel(program, std::string("upwind_stage_") + "uvw"[c], RowItems::lanes);
  upwind_built_ = true;
}

DeviceUpwindOrders FluidStages::upload_upwind_orders(const fluid::UpwindOrders& orders) {
  DeviceUpwindOrders device;
  const std::size_t counts[3] = {spec_.u_count(), spec_.v_count(), spec_.w_count()};
  for (int c = 0; c < 3; ++c) {
    if (orders[c].size() != counts[c])
      throw std::invalid_argument(
          fmt::format("FluidStages: {} upwind orders for component {}, the grid has {} faces",
                      orders[c].size(), c, counts[c]));
    const std::size_t bytes = orders[c].size() * sizeof(std::uint16_t);
    device.component[c] = cc_.buffer(bytes);
    cc_.queue().enqueueWriteBuffer(device.component[c], CL_TRUE, 0, bytes, orders[c].data());
  }
  return device;
}

void FluidStages::enqueue_upwind_stage(int c, float coef_dt, DeviceVelocity& pv, DeviceUpwindOrders& orders,
                                       cl::Buffer& base, cl::Buffer& out) {
  build_upwind_kernels();
  upwind_stage_[c]
      .set_args(grid_, coef_dt, pv.u, pv.v, pv.w, orders.component[c], base, out)
      .enqueue(cc_, advect_rows(c));
}

void FluidStages::enqueue_apply_forces(int c, float body_acceleration, cl::Buffer& gusts, int gust_count,
                                       cl::Buffer& q) {
  forces_.set_args(grid_, step_, c, body_acceleration, gusts, gust_count, q).enqueue(cc_, component_rows(c));
}

void FluidStages::enqueue_vorticity(DeviceVelocity& vel, cl::Buffer& vorticity) {
  vorticity_.set_args(grid_, vel.u, vel.v, vel.w, vorticity)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_vorticity_confinement(int c, float epsilon, cl::Buffer& vorticity, cl::Buffer& q) {
  confinement_.set_args(grid_, step_, c, epsilon, vorticity, q).enqueue(cc_, component_rows(c));
}

void FluidStages::enqueue_diffuse(int c, float nu_dt_over_h2, cl::Buffer& q, cl::Buffer& out) {
  diffuse_.set_args(grid_, step_, profile_, c, nu_dt_over_h2, q, out).enqueue(cc_, component_rows(c));
}

void FluidStages::enqueue_canopy_drag(cl::Buffer& drag_density, const CellBox& box, DeviceVelocity& vel,
                                      DeviceVelocity& scratch, const fluid::DragLaw& law) {
  if (box.empty()) return;
  // Faces of component c next to the box's cells: one more along c (the far face of the last cell). A box
  // that reaches a periodic seam along c drags the seam's face, which is face 0 and face n at once: then
  // every face along c, so that both copies are dragged alike, as a block cut there drags its own.
  auto face_box = [&](int c) {
    cl_int4 first{}, count{};
    for (int a = 0; a < 3; ++a) {
      first.s[a] = box.first[a];
      count.s[a] = box.count[a] + (a == c ? 1 : 0);
    }
    const int n = spec_.cells_along(c);
    if (spec_.periodic(c) && (box.first[c] == 0 || box.first[c] + box.count[c] == n)) {
      first.s[c] = 0;
      count.s[c] = n + 1;
    }
    return std::pair{first, count};
  };
  // Out of place: each component's |u| needs the other two before the drag touched them.
  for (int c = 0; c < 3; ++c) {
    const auto [first, count] = face_box(c);
    canopy_drag_[c]
        .set_args(grid_, step_, first, count, law.to_device(), drag_density, vel.u, vel.v, vel.w,
                  scratch.component(c))
        .enqueue(cc_, cc_.rows(count.s[0], count.s[1], count.s[2]));
  }
  for (int c = 0; c < 3; ++c) {
    const auto [first, count] = face_box(c);
    copy_face_box_.set_args(grid_, c, first, count, scratch.component(c), vel.component(c))
        .enqueue(cc_, cc_.rows(count.s[0], count.s[1], count.s[2]));
  }
}

void FluidStages::build_subgrid_kernels() {
  if (subgrid_built_) return;
  cl::Program program = cc_.build("subgrid_stress.cl");
  eddy_viscosity_ = Kernel(program, "eddy_viscosity");
  for (int c = 0; c < 3; ++c) diffuse_eddy_[c] = Kernel(program, std::string("diffuse_eddy_") + "uvw"[c]);
  wall_stress_faces_ = Kernel(program, "wall_stress_faces");
  wall_stress_store_ = Kernel(program, "wall_stress_store");
  subgrid_built_ = true;
}

void FluidStages::enqueue_eddy_viscosity(float smagorinsky_constant, float cap, cl::Buffer& mask,
                                         DeviceVelocity& vel, cl::Buffer& nu_t) {
  build_subgrid_kernels();
  const float cs_h = smagorinsky_constant * static_cast<float>(spec_.h);
  eddy_viscosity_.set_args(grid_, cs_h * cs_h, cap, mask, vel.u, vel.v, vel.w, nu_t)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_diffuse_eddy(bool wall_slip, cl::Buffer& mask, cl::Buffer& nu_t,
                                       DeviceVelocity& vel, DeviceVelocity& out) {
  build_subgrid_kernels();
  for (int c = 0; c < 3; ++c)
    diffuse_eddy_[c]
        .set_args(grid_, step_, profile_, int(wall_slip), mask, nu_t, vel.component(c), out.component(c))
        .enqueue(cc_, component_rows(c));
}

void FluidStages::build_tke_kernels() {
  if (tke_built_) return;
  cl::Program program = cc_.build("subgrid_tke.cl");
  tke_equilibrium_ = Kernel(program, "tke_equilibrium");
  tke_viscosity_ = Kernel(program, "tke_viscosity");
  tke_advect_ = Kernel(program, "tke_advect");
  tke_update_ = Kernel(program, "tke_update");
  tke_ = fluid::tke_device_parameters(spec_.h);
  tke_built_ = true;
}

void FluidStages::enqueue_tke_equilibrium(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& energy) {
  build_tke_kernels();
  tke_equilibrium_.set_args(grid_, tke_, mask, vel.u, vel.v, vel.w, energy)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_tke_viscosity(float cap, cl::Buffer& mask, cl::Buffer& energy, cl::Buffer& nu_t) {
  build_tke_kernels();
  tke_viscosity_.set_args(grid_, tke_, cap, mask, energy, nu_t)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_tke_advect(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& energy,
                                     cl::Buffer& advected) {
  build_tke_kernels();
  tke_advect_.set_args(grid_, step_, tke_, mask, vel.u, vel.v, vel.w, energy, advected)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_tke_update(float cap, cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& nu_t,
                                     cl::Buffer* drag_density, cl::Buffer& advected, cl::Buffer& energy) {
  build_tke_kernels();
  // Without a canopy the kernel reads no drag; nu_t stands in for the argument.
  cl::Buffer& drag = drag_density ? *drag_density : nu_t;
  tke_update_
      .set_args(grid_, step_, tke_, cap, int(drag_density != nullptr), mask, vel.u, vel.v, vel.w, nu_t, drag,
                advected, energy)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

FluidStages::DeviceWallFaces FluidStages::upload_wall_faces(const WallFaces& list) {
  DeviceWallFaces walls;
  walls.count = list.size();
  walls.u_count = list.u_count;
  if (walls.count == 0) return walls;
  walls.faces = cc_.buffer(list.faces.size() * sizeof(std::int32_t));
  walls.weights = cc_.buffer(list.weights.size() * sizeof(float));
  walls.stressed = cc_.buffer(list.weights.size() * sizeof(float));
  cc_.queue().enqueueWriteBuffer(walls.faces, CL_TRUE, 0, list.faces.size() * sizeof(std::int32_t),
                                 list.faces.data());
  cc_.queue().enqueueWriteBuffer(walls.weights, CL_TRUE, 0, list.weights.size() * sizeof(float),
                                 list.weights.data());
  return walls;
}

void FluidStages::enqueue_wall_stress(float drag_coefficient, DeviceWallFaces& walls, DeviceVelocity& vel) {
  if (walls.count == 0) return;
  build_subgrid_kernels();
  const float drag_per_length = drag_coefficient / static_cast<float>(spec_.h);
  const cl::NDRange entries(cc_.flat_items(std::size_t(walls.count)));
  wall_stress_faces_
      .set_args(step_, walls.count, walls.u_count, drag_per_length, walls.faces, walls.weights, vel.u, vel.v,
                walls.stressed)
      .enqueue(cc_, entries);
  wall_stress_store_.set_args(walls.count, walls.u_count, walls.faces, walls.stressed, vel.u, vel.v)
      .enqueue(cc_, entries);
}

CellBox nonzero_cell_box(const fluid::GridSpec& spec, const std::vector<float>& values) {
  if (values.size() != spec.cell_count())
    throw std::invalid_argument(
        fmt::format("nonzero_cell_box: {} values for a grid of {} cells", values.size(), spec.cell_count()));
  std::array<int, 3> lo{spec.nx, spec.ny, spec.nz}, hi{-1, -1, -1};
  std::size_t id = 0;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i, ++id) {
        if (values[id] == 0.0f) continue;
        const int at[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], at[a]);
          hi[a] = std::max(hi[a], at[a]);
        }
      }
  CellBox box;
  if (hi[0] < 0) return box;
  for (int a = 0; a < 3; ++a) {
    box.first[a] = lo[a];
    box.count[a] = hi[a] - lo[a] + 1;
  }
  return box;
}

void FluidStages::enqueue_enforce_boundaries(int c, cl::Buffer& mask, cl::Buffer& q) {
  boundaries_.set_args(grid_, step_, profile_, c, mask, q).enqueue(cc_, component_rows(c));
}

void FluidStages::enqueue_divergence_rhs(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& b) {
  divergence_.set_args(grid_, mask, vel.u, vel.v, vel.w, b)
      .enqueue(cc_, cc_.rows(spec_.nx, spec_.ny, spec_.nz));
}

void FluidStages::enqueue_subtract_gradient(int c, cl::Buffer& mask, cl::Buffer& phi, cl::Buffer& q) {
  gradient_.set_args(grid_, c, mask, phi, q).enqueue(cc_, component_rows(c));
}

double FluidStages::max_partials(std::size_t count) {
  cc_.queue().enqueueReadBuffer(partial_, CL_TRUE, 0, count * sizeof(float), partial_host_.data());
  double m = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    if (std::isnan(partial_host_[i])) return NAN;
    m = std::max(m, double(partial_host_[i]));
  }
  return m;
}

double FluidStages::max_divergence(cl::Buffer& mask, DeviceVelocity& vel) {
  const ReductionRange r = cc_.reduction_rows(spec_.nx, spec_.ny, spec_.nz);
  max_div_.set_args(grid_, mask, vel.u, vel.v, vel.w, partial_).enqueue(cc_, r.global, r.local);
  return max_partials(r.groups);
}

std::array<double, 3> FluidStages::max_speed_components(DeviceVelocity& vel) {
  std::array<double, 3> m{};
  for (int c = 0; c < 3; ++c) {
    const int extent_x = spec_.nx + (c == 0), extent_y = spec_.ny + (c == 1), extent_z = spec_.nz + (c == 2);
    const ReductionRange r = cc_.reduction_rows(extent_x, extent_y, extent_z);
    max_abs_.set_args(extent_x, extent_y, vel.component(c), partial_).enqueue(cc_, r.global, r.local);
    m[c] = max_partials(r.groups);
  }
  return m;
}

double FluidStages::max_speed_component(DeviceVelocity& vel) {
  const std::array<double, 3> m = max_speed_components(vel);
  if (std::isnan(m[0]) || std::isnan(m[1]) || std::isnan(m[2])) return NAN;
  return std::max({m[0], m[1], m[2]});
}

}  // namespace fw::host
