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
// A step is the order of its parts (host/stages/wind/), each with one job, its own buffers and its own
// saved state:
//   (dt from the CFL number if set) -> WindBoundaries: the inflow turbulence's box travels ambient * dt ->
//   Advection (solver.advection's class: semi-Lagrangian, clamped MacCormack, or upwind5 in three
//   Runge-Kutta stages) -> BodyForces: body force, mean forcing, gusts, vorticity confinement ->
//   CanopySink (set_canopy) -> SubgridModel (Smagorinsky's or the tke model) -> WallStress (log law) ->
//   MolecularViscosity (explicit, sub-stepped) -> WindBoundaries (prescribed faces) ->
//   PressureProjection (divergence, pressure solve, gradient).
// Everything stays on the device; only the scalars of reductions (residual norms, max speed for the CFL
// step) and, with a mean forcing, two layers of u and v come back.
//
// Over MPI ranks (WindBlocks, docs/parallel.md) each rank steps its block of the grid with the halo the
// decomposition gives it, through its RankSeam: the parts compute the block as a grid of its own and
// exchange the halos they declared after each stage that changes them, so that the next stage reads what
// one process would have; maxima and sums are taken over all ranks. The arrays a rank uploads and downloads
// are its block with the halo (block_array, face_array).
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
#include "fluid/InflowState.hpp"
#include "fluid/MacVelocity.hpp"
#include "fluid/WindSettings.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/HaloExchange.hpp"
#include "host/stages/PressureSolver.hpp"
#include "host/stages/RankSeam.hpp"
#include "host/stages/StageState.hpp"
#include "host/stages/wind/Advection.hpp"
#include "host/stages/wind/BodyForces.hpp"
#include "host/stages/wind/CanopySink.hpp"
#include "host/stages/wind/MolecularViscosity.hpp"
#include "host/stages/wind/PressureProjection.hpp"
#include "host/stages/wind/StageClock.hpp"
#include "host/stages/wind/SubgridModel.hpp"
#include "host/stages/wind/WallStress.hpp"
#include "host/stages/wind/WindBoundaries.hpp"
#include "host/stages/wind/WindGridSetup.hpp"

namespace fw::host {

/// The device arrays the wind's statistics read in place (host/stages/PlaneStatistics): the velocity, the
/// cells' mask (FW_MASK_FLUID), and where the grid keeps them the eddy viscosity, the subgrid energy and the
/// canopy's drag density (else null). All over the rank's block with its halo.
struct WindStatisticsFields {
  DeviceVelocity* velocity = nullptr;
  cl::Buffer* mask = nullptr;
  cl::Buffer* eddy_viscosity = nullptr;
  cl::Buffer* subgrid_energy = nullptr;
  cl::Buffer* drag_density = nullptr;
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
  WindGrid(const WindGrid&) = delete;  // the parts hold references into it
  WindGrid& operator=(const WindGrid&) = delete;

  /// Throws std::invalid_argument naming the problem in `setup` (GridSpec, WindSettings, InflowProfile,
  /// sizes, gusts, forcing): every check the constructor makes except the device's memory. The planner
  /// calls it, so that `check` finds what `run` would.
  static void validate(const WindGridSetup& setup);
  /// Bytes of device memory a grid of `setup` allocates on the rank's share of it, exactly: the sum of its
  /// parts' and the velocity's, the turbulence box included when setup.turbulence is set, a canopy not
  /// (CanopySink::estimate_device_bytes, once set_canopy is called).
  static std::size_t estimate_device_bytes(const WindGridSetup& setup, const BlockShare& share = {});
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
  std::array<double, 2> forcing_acceleration() const { return forces_.forcing_acceleration(); }
  /// Mean u and v of the layer at the profile's reference height (linear between the two nearest cell
  /// layers, solid faces counted as 0), m/s. Blocks: reads two layers of u and v back.
  std::array<double, 2> reference_layer_mean() { return forces_.reference_layer_mean(fields_); }
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
  /// solver.advection's method: its stability limit, its halo.
  const AdvectionMethod& advection_method() const { return advection_method_; }
  static double cfl_dt(const fluid::WindSettings& settings, const fluid::GridSpec& spec,
                       const std::array<double, 3>& max_speed_components);
  /// The Courant number of a step of dt that the scheme's stability is measured by
  /// (AdvectionMethod::courant_number).
  double courant_number(const std::array<double, 3>& max_speed_components, double dt) const {
    return advection_method_.courant_number(max_speed_components, dt, setup_.spec.h);
  }
  bool fixed_dt() const { return !(setup_.settings.cfl > 0.0); }

  double time() const { return time_; }
  long steps() const { return steps_; }
  /// Sets the clock the next step goes on from: the time (s, finite) and the steps taken. For a spin-up
  /// (CoupledStep::start), whose steps run before t = 0 and are not the run's.
  void set_clock(double time, long steps);
  const fluid::GridSpec& spec() const { return setup_.spec; }
  /// The grid this rank's arrays cover: its block with the halo over ranks, else spec().
  const fluid::GridSpec& local_spec() const { return seam_.local(); }
  /// This rank's block's cells with the halo (the whole grid in one process).
  const BlockArray& block() const { return seam_.block(); }
  const WindGridSetup& setup() const { return setup_; }
  fluid::InflowState inflow_state() const { return boundaries_.inflow_state(); }

  fluid::MacVelocity download_velocity();
  void upload_velocity(const fluid::MacVelocity& vel);
  /// Kinematic pressure p / rho = phi / dt at cell centres, m^2/s^2 (0 in solids).
  std::vector<float> download_pressure();
  /// Max over fluid cells of |div u|, 1/s.
  double max_divergence() { return stages_.max_divergence(projection_.mask(), fields_.vel); }
  double max_speed_component() { return stages_.max_speed_component(fields_.vel); }
  /// The largest |u|, |v| and |w| over every rank's faces (collective over ranks; NaN when any is).
  std::array<double, 3> max_speed_components() { return global_max_speed_components(); }
  /// Projects the current velocity (divergence -> solve -> gradient) and returns the solve's status.
  PressureSolveStatus project() { return projection_.project(fields_.vel); }

  /// What the next step reads (StageState, for checkpoints): the velocity, the pressure solution that
  /// warm-starts the solver, the subgrid energy and eddy viscosity where kept; the time, step count and last
  /// dt, the inflow turbulence's offset and sigma, the ambient wind, the mean forcing's integral. Blocking.
  StageState save_state();
  /// Sets what save_state() saved from a grid of the same setup; throws std::invalid_argument naming what
  /// does not fit.
  void restore_state(const StageState& state);
  /// This rank's state from a checkpoint saved over other blocks (`parts`: every saved rank's wind stage,
  /// block and trees, SavedShare): the velocity and each part's saved arrays (WindPart::saved_arrays) put
  /// together over the domain from every block's own values and cut to this rank's block with its halo; the
  /// numbers as saved (the same on every rank). What restore_state then reads.
  StageState share_of(const std::vector<SavedShare>& parts) const;

  /// Canopy drag F = -k |u| u from the drag density k = sum Cd a (1/m, one float a cell, x-fastest; see
  /// fluid/CanopyField), applied implicitly right after the body forces (stage "canopy"). Uploaded once; an
  /// empty or all-zero field turns the drag off, and the step is then exactly the one without a canopy.
  /// Over ranks, collective: every rank passes the whole grid's field (or all an empty one), and the drag is
  /// on for all when any block has some. Throws std::invalid_argument for a wrong size or a negative or
  /// non-finite value.
  /// `law`: how the drag coefficients behind k vary with |u| (fluid/DragLaw.hpp; default constant).
  void set_canopy(std::vector<float> drag_density, const fluid::DragLaw& law = {});
  bool canopy_enabled() const { return canopy_.on(); }
  /// The subgrid stage (WindSettings::smagorinsky_constant > 0, or the tke model): an eddy viscosity and its
  /// explicit diffusion, right after the canopy drag. The wall stage (wall_roughness_length > 0): the
  /// implicit log-law stress on the wall cells' u and v, after it. Both off by default; when off they
  /// enqueue nothing and allocate nothing. fluid/SubgridStress.hpp has the numerics, fluid/SubgridTke.hpp
  /// those of the tke model.
  bool subgrid_enabled() const { return subgrid_ != nullptr; }
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
  bool wall_stress_enabled() const { return wall_ != nullptr; }
  /// What the wind's statistics read, in place.
  WindStatisticsFields statistics_fields();

  /// When on, each stage ends with a queue finish and its wall time is added to stage_ms() (for benchmarks).
  void set_stage_timing(bool on) { clock_.set_on(on); }
  const std::map<std::string, double>& stage_ms() const { return clock_.ms(); }
  void reset_stage_ms() { clock_.reset(); }
  /// What every halo exchange of this grid has sent over ranks, the pressure solver's included, and the
  /// time they took (zero in one process): the benchmark's halo bytes and time per step.
  HaloTraffic halo_traffic() const;

  /// The parts, in the step's order: each one's device bytes, halo needs and stage (tests, the report).
  std::vector<const WindPart*> parts() const;
  /// Bytes of the velocity and its scratch, which the grid owns and every part steps.
  static std::size_t fields_bytes(const fluid::GridSpec& local);

  FluidStages& stages() { return stages_; }
  PressureSolver& pressure() { return projection_.solver(); }
  DeviceVelocity& velocity() { return fields_.vel; }

 private:
  std::vector<WindPart*> all_parts();
  /// Every face's rule (WindBoundaries), and between the stages of a Runge-Kutta scheme a projection too
  /// when solver.stage_projection asks for one.
  void end_advection_stage(DeviceVelocity& stage);
  /// Over ranks: throws std::runtime_error naming the step when the step's Courant number carries a
  /// back-trace past the halo (AdvectionMethod::halo_cells above the seam's halo_width). maxima: the
  /// velocity's, when the step already took them (else they are taken here).
  void check_halo_reach(double dt, const std::optional<std::array<double, 3>>& maxima);
  /// The largest |u|, |v| and |w| over every rank.
  std::array<double, 3> global_max_speed_components();

  ComputeContext& cc_;
  WindGridSetup setup_;
  const AdvectionMethod& advection_method_;
  RankSeam seam_;
  StageClock clock_;
  FluidStages stages_;
  WindPartContext context_;  // the references above, for the parts
  WindFields fields_;
  PressureProjection projection_;
  WindBoundaries boundaries_;
  std::unique_ptr<Advection> advection_;
  BodyForces forces_;
  CanopySink canopy_;
  std::unique_ptr<SubgridModel> subgrid_;  // null: no subgrid model
  std::unique_ptr<WallStress> wall_;       // null: no wall stress
  MolecularViscosity viscosity_;
  double time_ = 0.0, last_dt_ = 0.0;
  long steps_ = 0;
};

}  // namespace fw::host
