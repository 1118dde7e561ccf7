// The wind grid on an OpenCL device: owns the fields and steps them (advect, forces, project).
//
//   fw::host::WindGridSetup setup;
//   setup.spec = spec;                        // dims, cell size, boundaries (validated here)
//   setup.settings.pressure.tolerance = 1e-3;
//   setup.ambient = {10, 0, 0};               // m/s at the profile's reference height
//   fw::host::WindGrid wind(cc, setup);       // throws std::invalid_argument before allocating anything
//   wind.initialise_ambient();                // start from the inflow profile everywhere, projected
//   for (int n = 0; n < 100; ++n) {
//     fw::host::WindStepReport r = wind.step();   // r.pressure.iterations, r.pressure.relative_residual
//   }
//
// A step: (dt from the CFL number if set) -> the inflow turbulence's box travels ambient * dt -> advect
// (semi-Lagrangian RK2, clamped MacCormack, or flux-form upwind5 by three Runge-Kutta stages) -> body force,
// mean forcing and gusts -> vorticity confinement -> canopy drag (set_canopy) -> Smagorinsky subgrid stress
// (or the tke model's subgrid energy and its eddy viscosity) and log-law wall stress (when set)
// -> viscosity (explicit, sub-stepped) -> prescribed faces (inflow profile + turbulence) -> divergence ->
// pressure solve -> subtract the gradient. Everything stays on the device; only the scalars of reductions
// (residual norms, max speed for the CFL step) and, with a mean forcing, two layers of u and v come back.
//
// Over MPI ranks (WindBlocks, docs/parallel.md) each rank steps its block of the grid with the halo the
// decomposition gives it. The stages compute the block as a grid of its own (block_spec), and the velocity's
// halo is exchanged after every stage that changes it, so that the next stage reads what one process would
// have; maxima and sums are taken over all ranks. The arrays a rank uploads and downloads are its block with
// the halo (block_array, face_array).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "fluid/InflowProfile.hpp"
#include "fluid/InflowState.hpp"
#include "fluid/MacVelocity.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "fluid/WindSettings.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/HaloExchange.hpp"
#include "host/stages/PressureSolver.hpp"
#include "host/stages/StageState.hpp"

namespace fw::host {

/// Holds the horizontal mean wind of the reference-height layer at the ambient wind, for periodic domains
/// that have no inflow to drive them (canopy LES): a uniform body acceleration a = e / tau + (integral of e
/// dt) / tau^2 with e = ambient - layer mean. For a flow whose drag responds slowly this PI controller
/// settles like an oscillator of natural period 2 pi tau and damping ratio 1/2, and its integral part
/// converges to the mean pressure gradient that balances the drag.
struct MeanForcing {
  double relaxation_time = 0.0;  // tau, s; 0: off
};

struct WindGridSetup {
  fluid::GridSpec spec;
  fluid::WindSettings settings;
  fluid::InflowProfile profile;
  std::vector<std::uint8_t> solid;         // one byte a cell, non-zero = solid; empty = no solids
  std::vector<FwGust> gusts;               // travelling gust balls
  std::array<double, 3> ambient{0, 0, 0};  // ambient wind at the reference height, m/s
  /// Unit-sigma synthetic turbulence swept through the inflow faces at the ambient wind (Taylor's frozen
  /// turbulence) and added to the initial field; null: a laminar inflow. Its sigma is set_turbulence_sigma.
  std::shared_ptr<const fluid::TurbulenceBox> turbulence;
  MeanForcing forcing;
};

struct WindStepReport {
  long step = 0;      // index of the step just taken (1-based)
  double time = 0.0;  // simulated time after the step, s
  double dt = 0.0;    // s
  PressureSolveStatus pressure;
  int viscous_substeps = 0;
};

class WindGrid {
 public:
  /// Validates setup (GridSpec, WindSettings, InflowProfile, sizes) and the device memory estimate, then
  /// allocates. Throws std::invalid_argument naming the problem before any allocation. blocks: null in one
  /// process; else this rank steps its block (setup stays the whole grid's).
  WindGrid(ComputeContext& cc, WindGridSetup setup, const WindBlocks* blocks = nullptr);

  /// Throws std::invalid_argument naming the problem in `setup` (GridSpec, WindSettings, InflowProfile,
  /// sizes, gusts, forcing): every check the constructor makes except the device's memory. The planner
  /// calls it, so that `check` finds what `run` would.
  static void validate(const WindGridSetup& setup);
  /// Bytes of device memory a grid needs (fields, temporaries, pressure hierarchy), within a few per cent:
  /// the small buffers (wall faces, gusts, the profile) are left out and the hierarchy is taken as 8/7.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& spec, const fluid::WindSettings& settings,
                                           int row_chunk);
  /// Bytes the inflow turbulence box of `spec` takes on the device (its values, uploaded once): from the
  /// spec, so that a plan prices a box without synthesising it.
  static std::size_t estimate_turbulence_bytes(const fluid::TurbulenceBoxSpec& spec);
  /// Bytes set_canopy allocates for a canopy on `spec` (a drag density per cell).
  static std::size_t estimate_canopy_bytes(const fluid::GridSpec& spec);
  /// Bytes of the grid's largest single buffer: a padded copy of the velocity's largest component (the pad
  /// and the windowed loads' slack make it larger than the component itself).
  static std::size_t estimate_largest_buffer_bytes(const fluid::GridSpec& spec);
  /// Throws std::invalid_argument when `bytes` exceed the device's global memory, or the largest buffer its
  /// largest allocation.
  static void check_fits_device(const fluid::GridSpec& spec, std::size_t bytes, const DeviceInfo& device);

  void set_ambient(const std::array<double, 3>& ambient_m_s);
  /// sigma_u of the inflow turbulence from now on, m/s (finite, >= 0); ignored without a turbulence box.
  void set_turbulence_sigma(double sigma_m_s);
  /// The mean forcing's horizontal body acceleration of the last step, m/s^2 (0 when off).
  std::array<double, 2> forcing_acceleration() const { return forcing_acceleration_; }
  /// Mean u and v of the layer at the profile's reference height (linear between the two nearest cell
  /// layers, solid faces counted as 0), m/s. Blocks: reads two layers of u and v back.
  std::array<double, 2> reference_layer_mean();
  /// Every face set to the ambient profile, then boundaries and one projection.
  void initialise_ambient();
  /// One step of the dt the settings give: fixed, or from the CFL number (which reads max|u| back).
  WindStepReport step();
  /// One step of exactly dt (s, finite and > 0, else std::invalid_argument): for callers that choose dt
  /// themselves (the coupled step lands on the run's end time).
  WindStepReport step_by(double dt);
  /// step_by with the maxima a caller already took (max_speed_components() before the step), so that over
  /// ranks the halo guard does not take them again.
  WindStepReport step_by(double dt, const std::optional<std::array<double, 3>>& maxima);
  /// The CFL time step for the largest |u|, |v| and |w| (m/s): min(max_dt, cfl h / the largest of them,
  /// courant_limit h / their sum), max_dt at rest; the fixed dt when the settings have no CFL number.
  double cfl_dt(const std::array<double, 3>& max_speed_components) const {
    return cfl_dt(setup_.settings, setup_.spec, max_speed_components);
  }
  static double cfl_dt(const fluid::WindSettings& settings, const fluid::GridSpec& spec,
                       const std::array<double, 3>& max_speed_components);
  /// The Courant number of a step of dt that the scheme's stability is measured by: the sum of the
  /// components' Courant numbers for upwind5 (fluid::courant_limit), the largest one otherwise.
  double courant_number(const std::array<double, 3>& max_speed_components, double dt) const;
  bool fixed_dt() const { return !(setup_.settings.cfl > 0.0); }

  double time() const { return time_; }
  long steps() const { return steps_; }
  /// Sets the clock the next step goes on from: the time (s, finite) and the steps taken. For a spin-up
  /// (CoupledStep::start), whose steps run before t = 0 and are not the run's.
  void set_clock(double time, long steps);
  const fluid::GridSpec& spec() const { return setup_.spec; }
  /// The grid this rank's arrays cover: its block with the halo over ranks, else spec().
  const fluid::GridSpec& local_spec() const { return local_; }
  /// This rank's block's cells with the halo (the whole grid in one process).
  const BlockArray& block() const { return block_; }
  const WindGridSetup& setup() const { return setup_; }
  fluid::InflowState inflow_state() const;

  fluid::MacVelocity download_velocity();
  void upload_velocity(const fluid::MacVelocity& vel);
  /// Kinematic pressure p / rho = phi / dt at cell centres, m^2/s^2 (0 in solids).
  std::vector<float> download_pressure();
  /// Max over fluid cells of |div u|, 1/s.
  double max_divergence() { return stages_.max_divergence(pressure_.mask(), vel_); }
  double max_speed_component() { return stages_.max_speed_component(vel_); }
  /// The largest |u|, |v| and |w| over every rank's faces (collective over ranks; NaN when any is).
  std::array<double, 3> max_speed_components() { return global_max_speed_components(); }
  /// Projects the current velocity (divergence -> solve -> gradient) and returns the solve's status.
  PressureSolveStatus project() { return project(vel_); }

  /// What the next step reads (StageState, for checkpoints): the velocity, the pressure solution that
  /// warm-starts the solver, the subgrid energy and eddy viscosity where kept; the time, step count and last
  /// dt, the inflow turbulence's offset and sigma, the ambient wind, the mean forcing's integral. Blocking.
  StageState save_state();
  /// Sets what save_state() saved from a grid of the same setup; throws std::invalid_argument naming what
  /// does not fit.
  void restore_state(const StageState& state);

  /// Canopy drag F = -k |u| u from the drag density k = sum Cd a (1/m, one float a cell, x-fastest; see
  /// fluid/CanopyField), applied implicitly right after the body forces (stage "canopy"). Uploaded once; an
  /// empty or all-zero field turns the drag off, and the step is then exactly the one without a canopy.
  /// Over ranks, collective: every rank passes the whole grid's field (or all an empty one), and the drag is
  /// on for all when any block has some. Throws std::invalid_argument for a wrong size or a negative or
  /// non-finite value.
  /// `law`: how the drag coefficients behind k vary with |u| (fluid/DragLaw.hpp; default constant).
  void set_canopy(std::vector<float> drag_density, const fluid::DragLaw& law = {});
  bool canopy_enabled() const { return canopy_on_; }
  /// The subgrid stage (WindSettings::smagorinsky_constant > 0, or the tke model): an eddy viscosity and its
  /// explicit diffusion, right after the canopy drag. The wall stage (wall_roughness_length > 0): the
  /// implicit log-law stress on the wall cells' u and v, after it. Both off by default; when off they
  /// enqueue nothing and allocate nothing. fluid/SubgridStress.hpp has the numerics, fluid/SubgridTke.hpp
  /// those of the tke model.
  bool subgrid_enabled() const { return subgrid_tke_enabled() || setup_.settings.smagorinsky_constant > 0.0; }
  /// The tke model (WindSettings::subgrid): the subgrid stage first advances each cell's subgrid energy e,
  /// with the canopy's terms where set_canopy put one, and takes nu_t = C_m l sqrt(e) from it.
  bool subgrid_tke_enabled() const { return setup_.settings.subgrid == fluid::SubgridModel::tke; }
  /// The subgrid energy e, m^2/s^2, one float a cell (0 in solids). e starts in equilibrium with the strain
  /// (fluid/SubgridTke.hpp) of the field the next subgrid stage sees, or, when this is asked first, of the
  /// current field. Throws std::logic_error without the tke model.
  std::vector<float> download_subgrid_energy();
  /// Sets e (m^2/s^2, one float a cell, finite and >= 0; solids' values are ignored by the stages) for the
  /// next step, instead of the equilibrium start. Throws std::logic_error without the tke model and
  /// std::invalid_argument for a wrong size or value.
  void upload_subgrid_energy(const std::vector<float>& energy);
  /// The eddy viscosity nu_t the last subgrid stage diffused the velocity with, m^2/s, one float a cell (0 in
  /// solids; 0 everywhere before the first step). With the subgrid stress -2 nu_t S_ij it gives the part of
  /// the turbulent stress the grid does not resolve. Throws std::logic_error without a subgrid stage.
  std::vector<float> download_eddy_viscosity();
  bool wall_stress_enabled() const { return setup_.settings.wall_roughness_length > 0.0; }

  /// When on, each stage ends with a queue finish and its wall time is added to stage_ms() (for benchmarks).
  void set_stage_timing(bool on) { stage_timing_ = on; }
  const std::map<std::string, double>& stage_ms() const { return stage_ms_; }
  void reset_stage_ms() { stage_ms_.clear(); }
  /// What every halo exchange of this grid has sent over ranks, the pressure solver's included, and the
  /// time they took (zero in one process): the benchmark's halo bytes and time per step.
  HaloTraffic halo_traffic() const;

  FluidStages& stages() { return stages_; }
  PressureSolver& pressure() { return pressure_; }
  DeviceVelocity& velocity() { return vel_; }

 private:
  template <typename F>
  void timed(const char* stage, F&& work);
  void advect(float dt);
  void advect_upwind(float dt);
  PressureSolveStatus project(DeviceVelocity& vel);
  void enforce_boundaries(DeviceVelocity& vel);
  void apply_forces();
  void enforce_boundaries() { enforce_boundaries(vel_); }
  void apply_canopy_drag();
  void apply_subgrid_stress(double dt);
  void advance_subgrid_energy(float cap);
  void start_subgrid_energy();
  void apply_wall_stress();
  void update_mean_forcing(double dt);
  void upload_step_inflow();
  /// Fills the halo of every component of vel from the neighbours (nothing in one process).
  void exchange(DeviceVelocity& vel);
  /// Fills the halo of a cell field.
  void exchange_cells(cl::Buffer& field);
  /// Over ranks: throws std::runtime_error naming the step when a semi-Lagrangian back-trace over dt would
  /// reach past the halo (fluid::halo_cells of the step's Courant number above the decomposition's). maxima:
  /// the velocity's, when the step already took them (else they are taken here).
  void check_halo_reach(double dt, const std::optional<std::array<double, 3>>& maxima);
  /// The largest |u|, |v| and |w| over every rank.
  std::array<double, 3> global_max_speed_components();

  ComputeContext& cc_;
  WindGridSetup setup_;
  const Communicator* world_ = &Communicator::alone();
  fluid::Decomposition decomposition_;
  BlockArray block_;       // this rank's cells with the halo (the whole grid in one process)
  fluid::GridSpec local_;  // the grid of block_
  PressureBlocks pressure_blocks_;
  std::array<std::optional<HaloExchange>, 3> face_halo_;  // per velocity component, over several ranks
  std::optional<HaloExchange> cell_halo_;
  std::optional<HaloExchange> vorticity_halo_;  // four floats a cell (vorticity and its magnitude)
  std::vector<float> profile_shape_;            // the profile at the nz cell-centre heights, sampled once
  FluidStages stages_;
  PressureSolver pressure_;
  DeviceVelocity vel_, tmp_, back_, padded_, padded_forward_;
  DeviceUpwindOrders upwind_orders_;  // upwind5's flux orders; allocated for upwind5 only
  cl::Buffer vorticity_, gusts_, profile_;
  double time_ = 0.0, last_dt_ = 0.0;
  double turbulence_sigma_ = 0.0;                     // m/s
  std::array<double, 3> turbulence_offset_{0, 0, 0};  // m, within one box length
  std::array<double, 2> forcing_integral_{0, 0};      // integral of the error, m
  std::array<double, 2> forcing_acceleration_{0, 0};  // m/s^2
  long steps_ = 0;
  cl::Buffer canopy_;   // drag density, one float a cell; valid while canopy_on_
  CellBox canopy_box_;  // the cells of non-zero drag density; empty on a block with none
  fluid::DragLaw drag_law_;
  bool canopy_on_ = false;
  cl::Buffer eddy_viscosity_;                // nu_t, one float a cell, m^2/s; valid while subgrid_enabled()
  FluidStages::DeviceWallFaces wall_faces_;  // the faces of the wall cells; used while wall_stress_enabled()
  double wall_drag_coefficient_ = 0.0;       // C_w of the log law at the first cell centre
  // The tke model's e and the advected e of a step, one float a cell, m^2/s^2; valid while
  // subgrid_tke_enabled(). set: e holds a state (else the next stage starts it at equilibrium).
  cl::Buffer subgrid_energy_, advected_energy_;
  bool subgrid_energy_set_ = false;
  bool stage_timing_ = false;
  std::map<std::string, double> stage_ms_;
  double nested_ms_ = 0.0;  // timed() sections so far, for the stages timed inside others
};

}  // namespace fw::host
