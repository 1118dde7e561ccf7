// The wind grid's kernels, one enqueue_<stage>() each: advection, forces, boundaries, and the ends of the
// projection. Owns no field buffers; host/WindGrid wires them together.
//
//   FluidStages stages(cc, spec);
//   stages.enqueue_pad(vel, padded);                      // ghost layers for interpolation
//   stages.enqueue_advect(0, dt, padded, padded.u, out.u); // one component at a time
//   stages.enqueue_divergence_rhs(mask, vel, b);
//
// Numerics and ghost rules: kernels/common.cl and fluid/ReferenceStages.hpp (the CPU oracle).
#pragma once

#include <array>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/InflowState.hpp"
#include "fluid/UpwindStencil.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/WallFaces.hpp"
#include "kernels/shared_types.h"

namespace fw::host {

/// Face velocity buffers on the device: u (nx+1)*ny*nz, v nx*(ny+1)*nz, w nx*ny*(nz+1) floats, m/s.
struct DeviceVelocity {
  cl::Buffer u, v, w;
  cl::Buffer& component(int c) { return c == 0 ? u : (c == 1 ? v : w); }
};

/// The packed flux orders of upwind advection on the device (fluid::UpwindOrders): a ushort a face per
/// component.
struct DeviceUpwindOrders {
  std::array<cl::Buffer, 3> component;
};

/// Cells first .. first + count - 1 along x, y, z (cell indices); count 0 on an axis: no cell.
struct CellBox {
  std::array<int, 3> first{0, 0, 0};
  std::array<int, 3> count{0, 0, 0};
  bool empty() const { return count[0] <= 0 || count[1] <= 0 || count[2] <= 0; }
};

/// The smallest box holding every cell whose value is non-zero (values: one a cell, x fastest); empty when
/// all are zero. Throws std::invalid_argument when the size is not spec.cell_count().
CellBox nonzero_cell_box(const fluid::GridSpec& spec, const std::vector<float>& values);

/// The kernels' `inflow` buffer (kernels/common.cl inflow_face_value) for a grid `spec`: the nz profile
/// factors, then, when there is a turbulence box (at any sigma, 0 included), its values (3 floats a point)
/// with x slowest: index 3 (k + n_z (j + n_y i)) + c, then room for the prescribed shell
/// (kernels/shared_types.h), which FluidStages fills on the device.
std::vector<float> inflow_buffer_values(const fluid::InflowState& inflow, const fluid::GridSpec& spec);
/// FwStep's turbulence fields from `inflow`: sigma 0 (off) unless inflow.turbulent().
void set_step_turbulence(FwStep& step, const fluid::InflowState& inflow);

class FluidStages {
 public:
  FluidStages(ComputeContext& cc, const fluid::GridSpec& spec);

  /// Bytes the stages allocate for themselves on `spec` (the reductions' partials, a stand-in profile).
  static std::size_t estimate_device_bytes(const fluid::GridSpec& spec);
  /// Bytes allocate_velocity() allocates on `spec`; allocate_padded_velocity(); upload_upwind_orders();
  /// upload_wall_faces(list).
  static std::size_t velocity_bytes(const fluid::GridSpec& spec);
  static std::size_t padded_velocity_bytes(const fluid::GridSpec& spec);
  static std::size_t upwind_orders_bytes(const fluid::GridSpec& spec);
  static std::size_t wall_faces_bytes(const WallFaces& list);
  /// Bytes of one padded component c's buffer (the largest buffer a grid allocates is one of these).
  static std::size_t padded_bytes(const fluid::GridSpec& spec, int c);

  /// What each step passes: dt, time, the ambient wind and the inflow turbulence (FwStep), and the inflow
  /// buffer (inflow_buffer_values: the profile's nz floats, then the turbulence box and the shell). While
  /// the turbulence is on, a new step's inflow or a new buffer re-samples the prescribed shell on the
  /// device (once per step: every kernel then reads prescribed values from it). Throws
  /// std::invalid_argument when the buffer is too short for the step's turbulence.
  void set_step(const FwStep& step);
  void set_profile(cl::Buffer inflow);
  const FwStep& step() const { return step_; }

  DeviceVelocity allocate_velocity();
  cl::NDRange component_rows(int c) const;
  std::size_t padded_count(int c) const;
  cl::NDRange advect_rows(int c) const;
  /// The rows along y whose values outlive a stage that the seam exchanges right after it: a block's own
  /// rows, `count` of them from `first` (its halo rows come from the neighbours). All of them by default; the
  /// advection's back-traces (enqueue_advect) skip the others.
  void set_own_rows(int first, int count);

  /// Padded copies (FW_PAD ghost layers, filled by the boundary rules) are what advection reads.
  DeviceVelocity allocate_padded_velocity();
  void enqueue_pad(int c, cl::Buffer& q, cl::Buffer& padded);
  void enqueue_pad(DeviceVelocity& vel, DeviceVelocity& padded);
  /// out = padded_q (component c) back-traced through padded_vel over dt (negative: forward).
  void enqueue_advect(int c, float dt, DeviceVelocity& padded_vel, cl::Buffer& padded_q, cl::Buffer& out);
  void enqueue_maccormack_correct(int c, DeviceVelocity& padded_vel, cl::Buffer& padded_q,
                                  cl::Buffer& forward, cl::Buffer& back, cl::Buffer& out);
  /// Uploads the flux orders of upwind advection (fluid::upwind_orders), once per grid.
  DeviceUpwindOrders upload_upwind_orders(const fluid::UpwindOrders& orders);
  /// out = base + coef_dt * R(stage) for component c: one Runge-Kutta stage of flux-form upwind advection
  /// (fluid/UpwindStencil.hpp), R from the padded stage velocity (enqueue_pad); base and out unpadded, out
  /// another buffer than base.
  void enqueue_upwind_stage(int c, float coef_dt, DeviceVelocity& padded_stage, DeviceUpwindOrders& orders,
                            cl::Buffer& base, cl::Buffer& out);
  void enqueue_apply_forces(int c, float body_acceleration, cl::Buffer& gusts, int gust_count, cl::Buffer& q);
  void enqueue_vorticity(DeviceVelocity& vel, cl::Buffer& vorticity);
  void enqueue_vorticity_confinement(int c, float epsilon, cl::Buffer& vorticity, cl::Buffer& q);
  void enqueue_diffuse(int c, float nu_dt_over_h2, cl::Buffer& q, cl::Buffer& out);
  /// vel <- vel after implicit canopy drag over step().dt: q / (1 + dt k |u|) on every face, k the drag
  /// density (1/m, one float a cell) and |u| the old speed at the face. `box` must hold every cell of
  /// non-zero k (nonzero_cell_box): only the faces of those cells are touched, through `scratch`.
  void enqueue_canopy_drag(cl::Buffer& drag_density, const CellBox& box, DeviceVelocity& vel,
                           DeviceVelocity& scratch, const fluid::DragLaw& law = {});
  /// Smagorinsky eddy viscosity (fluid/SubgridStress.hpp) into nu_t (one float a cell, m^2/s):
  /// min((C_s h)^2 |S|, cap), 0 in the solid cells of the pressure mask, from the velocity vel (unpadded:
  /// the strain reads no ghost but a periodic twin). cap: fluid::eddy_viscosity_cap(h, step().dt).
  void enqueue_eddy_viscosity(float smagorinsky_constant, float cap, cl::Buffer& mask, DeviceVelocity& vel,
                              cl::Buffer& nu_t);
  /// out = vel + step().dt div(nu grad vel) for each component in flux form (fluid::reference::diffuse_eddy),
  /// the ghosts by the rules of enqueue_diffuse; out must be other buffers than vel. wall_slip: no flux from
  /// a u or v face into the face below it when that one touches a solid.
  void enqueue_diffuse_eddy(bool wall_slip, cl::Buffer& mask, cl::Buffer& nu_t, DeviceVelocity& vel,
                            DeviceVelocity& out);
  /// Deardorff's subgrid energy e (fluid/SubgridTke.hpp; one float a cell, m^2/s^2), the start: energy =
  /// max(floor, (C_m / C_eps) l^2 |S|^2) from the strain of vel (unpadded), 0 in the solid cells of the
  /// pressure mask: shear production in balance with the dissipation.
  void enqueue_tke_equilibrium(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& energy);
  /// The subgrid energy's step 1: nu_t = min(C_m l sqrt(e), cap) per cell (m^2/s), 0 in solid cells;
  /// cap: fluid::eddy_viscosity_cap(h, step().dt).
  void enqueue_tke_viscosity(float cap, cl::Buffer& mask, cl::Buffer& energy, cl::Buffer& nu_t);
  /// Step 2: advected = energy traced back over step().dt along the cell-centred velocity of vel
  /// (semi-Lagrangian, trilinear; inflow sides give fluid::kTkeInflow); advected must not be energy.
  void enqueue_tke_advect(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& energy, cl::Buffer& advected);
  /// Steps 3 and 4: energy = the advected e diffused by 2 nu_t (flux form, capped at cap), produced by
  /// nu_t |S|^2 of vel and by the canopy's wakes, dissipated and drained by the canopy, the sinks implicit,
  /// at least fluid::kTkeFloor (fluid::reference::tke_update). drag_density: the canopy's k per cell (1/m),
  /// or null for none. nu_t is step 1's, from the energy before step 2.
  void enqueue_tke_update(float cap, cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& nu_t,
                          cl::Buffer* drag_density, cl::Buffer& advected, cl::Buffer& energy);
  /// The wall stress's face list on the device, uploaded once (upload_wall_faces).
  struct DeviceWallFaces {
    int count = 0, u_count = 0;
    cl::Buffer faces, weights, stressed;  // WallFaces' arrays, and a float a face for the stressed values
  };
  DeviceWallFaces upload_wall_faces(const WallFaces& list);
  /// u, v <- the implicit log-law wall stress over step().dt, q / (1 + dt C_w weight |U| / h) (see
  /// fluid::reference::wall_stress; drag_coefficient: C_w), on the listed faces only.
  void enqueue_wall_stress(float drag_coefficient, DeviceWallFaces& walls, DeviceVelocity& vel);
  void enqueue_enforce_boundaries(int c, cl::Buffer& mask, cl::Buffer& q);
  void enqueue_divergence_rhs(cl::Buffer& mask, DeviceVelocity& vel, cl::Buffer& b);
  void enqueue_subtract_gradient(int c, cl::Buffer& mask, cl::Buffer& phi, cl::Buffer& q);

  /// Max over fluid cells of |div u|, 1/s (blocks).
  double max_divergence(cl::Buffer& mask, DeviceVelocity& vel);
  /// Max |component| over all faces of the three components, m/s; NaN if any face is NaN (blocks).
  double max_speed_component(DeviceVelocity& vel);
  /// Max |u|, |v| and |w| over the faces of each, m/s; NaN for a component with a NaN face (blocks).
  std::array<double, 3> max_speed_components(DeviceVelocity& vel);

  /// Floats the reductions need for their per-work-item partials.
  std::size_t partial_count() const { return partial_host_.size(); }

 private:
  static std::size_t partial_bound(const fluid::GridSpec& spec);
  /// Bytes of three face arrays (u, v, w) of bytes_per_face each.
  static std::size_t face_arrays_bytes(const fluid::GridSpec& spec, std::size_t bytes_per_face);
  /// Values of component c's padded copy (FW_PAD ghost layers on every side).
  static std::size_t padded_values(const fluid::GridSpec& spec, int c);
  double max_partials(std::size_t count);
  void build_subgrid_kernels();  // on first use: a run without the subgrid or wall stage never builds them
  void build_upwind_kernels();   // on first use, likewise for upwind advection
  void build_tke_kernels();      // on first use, likewise for the subgrid energy
  void refresh_inflow_shell();   // the shell's blocks on every inflow face, unless already fresh

  ComputeContext& cc_;
  fluid::GridSpec spec_;
  FwGrid grid_;
  FwStep step_{};
  std::array<int, 2> own_rows_{0, 0};  // first, count (set_own_rows)
  cl::Buffer profile_, partial_;
  std::vector<float> partial_host_;
  Kernel pad_, advect_[3], maccormack_[3], forces_, vorticity_, confinement_, diffuse_, boundaries_,
      divergence_, max_div_, gradient_, max_abs_, canopy_drag_[3], copy_face_box_, fill_inflow_shell_;
  Kernel eddy_viscosity_, diffuse_eddy_[3], wall_stress_faces_, wall_stress_store_;
  Kernel upwind_stage_[3];
  Kernel tke_equilibrium_, tke_viscosity_, tke_advect_, tke_update_;
  FwTke tke_{};  // the subgrid energy model's factors at this grid's cell size
  bool tke_built_ = false;
  bool subgrid_built_ = false, upwind_built_ = false;
  bool shell_fresh_ = false;  // the shell holds step_'s prescribed values
};

}  // namespace fw::host
