// One step of the coupled forest: the wind grid and every tree's modes, in one order, with the stability
// checks, on one OpenCL queue (docs/design.md, "Data flow"). The run loop, `bench coupled` and the coupled
// tests all drive this class; none of them repeats the order.
//
//   fw::host::CoupledStep coupled(cc, plan);  // uploads everything; the plan must outlive it
//   coupled.start();                          // the ambient profile at t = 0, projected; trees at rest
//   while (coupled.time() < end) {
//     fw::host::CoupledStepReport r = coupled.step(end - coupled.time());   // never steps past `end`
//   }
//   coupled.enqueue_frame_deformation();      // an output frame: u = Phi q per instance, leaves with it
//
// The time inputs (host/app/TimeInputs.hpp: the ambient wind, the inflow turbulence's sigma_u, the trees'
// unresolved intensity) are applied here, at the time each step starts; no caller feeds them.
//
// A step: choose dt (fixed, or the CFL number from max|u|, capped to land on the caller's limit) -> check it
// -> wind grid step (advect, forces and gusts, canopy drag, projection) -> sample the wind at every tree's
// sample points -> modal forces -> modal step -> with damage, every tree's loads and failure check (a
// failed tree's drag leaves the air: StandingCanopy) -> leaves in the step's new wind (flutter, shedding,
// flight; when there are any). Only the scalars of reductions and the count of new failures come back to
// the host.
//
// Checks, every step, before anything moves (a SimulationError names the step, the time and the field):
//   - the velocity is finite (max|u| is read back each step: the CFL time step needs it, and a fixed dt
//     needs it for the next check; one reduction over the faces costs under 1% of a step);
//   - a fixed dt whose Courant number exceeds the scheme's stability limit (upwind5:
//   AdvectionMethod::courant_limit)
//     or, for the semi-Lagrangian schemes, kRunawayCfl is a blow-up in the making, not a slow run;
//   - Diener's semi-implicit Euler is stable only while dt^2 omega^2 + 2 gamma dt < 4 for every mode.
#pragma once

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/app/CouplingSettings.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/app/StandingCanopy.hpp"
#include "host/app/TimeInputs.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/ForestStages.hpp"
#include "host/stages/LeafStages.hpp"
#include "host/stages/WindGrid.hpp"
#include "trees/Forest.hpp"
#include "trees/ModalIntegrator.hpp"

namespace fw::host {

/// A numerical blow-up: what() names the step, the time and the field.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CoupledStepReport {
  WindStepReport wind;               ///< step index, time after the step, dt, pressure solve
  double max_speed_component = 0.0;  ///< max over faces of |u|, |v|, |w| before the step, m/s
  double cfl = 0.0;                  ///< the step's Courant number (WindGrid::courant_number)
};

/// The next step as chosen before anything moves (CoupledStep::next_step): its dt, and the maxima and
/// checks that chose it.
struct NextStep {
  double dt = 0.0;                               ///< s
  double cfl_dt = 0.0;                           ///< s: the fixed dt, or the CFL dt before any cap
  double cfl = 0.0;                              ///< the step's Courant number at dt
  std::array<double, 3> max_speed_components{};  ///< m/s, before the step
  /// Whether the caller's max_dt cut the step short of cfl_dt (the run's last step, landing on its end).
  bool cut() const { return dt < cfl_dt; }
};

/// What CoupledStep::start's spin-up did: its steps and the simulated seconds they covered.
struct SpinUpReport {
  long steps = 0;
  double seconds = 0.0;
};

class CoupledStep {
 public:
  /// A fixed dt whose CFL number passes this stops a semi-Lagrangian run (which is stable at any CFL
  /// number, but a wind this far past the expected one is a blow-up in the making).
  static constexpr double kRunawayCfl = 5.0;
  /// A spin-up ends when the wind's clock is within this fraction of the spin-up of t = 0 (a sum of dt
  /// may fall short of it by rounding; a last step that short would be a step of nothing).
  static constexpr double kSpinUpTolerance = 1e-9;
  /// A max_dt short of the step's dt by less than this fraction of it is the rounding in a sum of dts (a
  /// fixed dt that divides the end time), not a cut: the step takes its whole dt, as a longer run does.
  static constexpr double kLandingTolerance = 1e-9;

  /// Uploads the wind grid, the canopy drag and the forest. Throws std::invalid_argument when the grid does
  /// not fit the device or a setting is invalid (see WindGrid, ForestStages). `forest` must outlive this.
  /// blocks: null in one process; over ranks this rank steps its block of the wind and the trees whose roots
  /// it holds (own_forest()) with their leaves, and the flying leaves its block holds; every call is
  /// collective.
  CoupledStep(ComputeContext& cc, WindGridSetup wind, const trees::Forest& forest, CouplingSettings coupling,
              TimeInputs inputs, const WindBlocks* blocks = nullptr);
  /// The plan's wind, forest, coupling and time inputs, over the plan's decomposition when `world` has
  /// more than one rank; the plan must outlive this.
  CoupledStep(ComputeContext& cc, const SimulationPlan& plan, const Communicator* world = nullptr);

  /// Applies the time inputs at t = 0 and starts from them: every face on the inflow profile, projected;
  /// every tree in equilibrium with that wind (ForestStages::enqueue_equilibrium). Collective over ranks.
  /// With spin_up > 0 (s, finite) the wind then steps from t = -spin_up to 0 with the inputs held at
  /// their t = 0 values (gusts start at t >= 0, so none fires), and every tree is then put in equilibrium
  /// with the wind it ends on; trees and leaves do not move during it. The steps' dt follows step()'s rule,
  /// the last one lands on t = 0, and the clock is then set to t = 0, step 0: time() and steps() count the
  /// run's steps only.
  SpinUpReport start(double spin_up = 0.0);

  /// Every stage's state by its name ("wind", "trees" with trees, "leaves" with leaves): what a checkpoint
  /// keeps of the step (host/app/RunCheckpoint). Blocking.
  std::map<std::string, StageState> save_state();
  /// Continues from save_state()'s states, instead of start(): the next step is the one that would have
  /// followed. Throws std::invalid_argument naming the stage and value that do not fit this set-up.
  void restore_state(const std::map<std::string, StageState>& states);

  /// One coupled step of at most max_dt seconds (the settings' dt otherwise; max_dt within
  /// kLandingTolerance of it does not cut it), with the time inputs at the step's start. Throws
  /// SimulationError (see the header comment) before the step when a check fails.
  CoupledStepReport step(double max_dt = std::numeric_limits<double>::infinity()) {
    return step(next_step(max_dt));
  }
  /// The next step, chosen and checked but not taken: the time inputs at its start applied, max|u| read
  /// back, dt chosen; throws SimulationError as step() does. For a caller that acts on dt before the step
  /// moves anything (the run loop checkpoints before a last step that its end cuts short). Collective.
  NextStep next_step(double max_dt = std::numeric_limits<double>::infinity());
  /// Takes the step next_step() chose, with nothing stepped in between.
  CoupledStepReport step(const NextStep& next);

  double time() const { return wind_.time(); }
  long steps() const { return wind_.steps(); }
  /// Whether the run has trees (on any rank).
  bool has_trees() const { return tree_count_ > 0; }
  /// The trees this rank steps: the whole forest in one process; over ranks, those whose roots its block
  /// holds (their Forest::id is the whole forest's index).
  const trees::Forest& own_forest() const { return *own_forest_; }
  /// The ranks and their decomposition over several ranks; null in one process.
  const WindBlocks* blocks() const { return blocks_ ? &*blocks_ : nullptr; }
  /// The largest stable dt of the semi-implicit integrator over every instance's modes, s; infinity with
  /// the exact integrator or without trees.
  double integrator_dt_limit() const { return integrator_dt_limit_; }

  /// When on, each stage ends with a queue finish and its wall time is added to stage_ms() (benchmarks and
  /// run.json): the wind grid's stages, "trees" and, with damage, "damage".
  void set_stage_timing(bool on);
  std::map<std::string, double> stage_ms() const;
  void reset_stage_ms();

  WindGrid& wind() { return wind_; }
  ForestStages& trees() { return trees_; }
  bool has_leaves() const { return leaves_ != nullptr; }
  /// The leaf stage; throws std::logic_error without leaves (has_leaves()).
  LeafStages& leaves();
  /// Whether the run checks its trees for damage (forest.damage).
  bool has_damage() const { return trees_.has_damage(); }
  /// The trees by state over every rank (zero without damage). Collective.
  trees::DamageCounts damage_counts();
  /// Every tree's damage record in whole-forest order (Forest::id), on rank 0 and in one process; empty on
  /// the other ranks and without damage. Collective.
  std::vector<trees::TreeDamageRecord> gather_damage();
  /// The stress utilisation of this rank's trees' nodes (one float a node, own_forest() order): a
  /// stem node's section's, 0 on the other nodes (branches are not checked) and without damage.
  std::vector<float> node_utilisation();
  /// Each of this rank's trees' state (trees::TreeState as an int; own_forest() order), all 0 without
  /// damage.
  std::vector<std::int32_t> tree_states();

  /// An output frame's deformation: the trees' displacements (u = Phi q, strong-wind corrected as set), and
  /// the attached leaves moved with them.
  void enqueue_frame_deformation();

 private:
  /// The time inputs at time t: ambient wind, turbulence sigma_u and unresolved intensity where given.
  void apply_inputs(double t);
  /// The trees that failed since the last call, over every rank (whole-forest ids), and their drag out of
  /// the air (consequences). from_records: take every failed tree of the records (a resume), not only the
  /// step's new ones. Collective.
  void remove_fallen(bool from_records);
  /// The wind grid's part of step(next): the report so far.
  CoupledStepReport step_wind(const NextStep& next);

  ComputeContext& cc_;
  TimeInputs inputs_;
  std::optional<WindBlocks> blocks_;  // over several ranks
  WindGrid wind_;
  trees::Forest rank_forest_;  // over ranks, this rank's trees (own_forest_ points here); else empty
  const trees::Forest* own_forest_;
  ForestStages trees_;
  std::unique_ptr<LeafStages> leaves_;  // null without leaves
  int tree_count_ = 0;
  double integrator_dt_limit_ = std::numeric_limits<double>::infinity();
  // Storm damage with consequences: the trees of this rank known to have fallen, and the canopy of the
  // standing ones (with two-way coupling).
  bool damage_consequences_ = false;
  std::vector<bool> known_fallen_;
  std::optional<StandingCanopy> standing_canopy_;
  fluid::DragLaw drag_law_;
  bool stage_timing_ = false;
  double damage_ms_ = 0.0;
  double trees_ms_ = 0.0;
  double leaves_ms_ = 0.0;
};

}  // namespace fw::host
