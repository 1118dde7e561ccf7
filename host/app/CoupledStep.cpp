#include "host/app/CoupledStep.hpp"

#include "host/runtime/Communicator.hpp"
#include "host/stages/SavedStateNames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <utility>

namespace fw::host {

namespace {

using Clock = std::chrono::steady_clock;

std::string where(long step, double time) {
  return fmt::format("step {} (t = {:.3f} s)", step, time);
}

// Over ranks, the trees whose root's cell column this rank's block holds.
trees::Forest rank_trees(const trees::Forest& forest, const WindGrid& wind, const WindBlocks* blocks) {
  if (blocks == nullptr) return {};
  std::vector<int> mine;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const Eigen::Vector3d& root = forest.instances()[std::size_t(k)].position;
    const float point[3] = {float(root.x()), float(root.y()), float(root.z())};
    if (PointWindAcrossRanks::holder(wind.local_spec(), blocks->decomposition, point) ==
        blocks->world->rank())
      mine.push_back(k);
  }
  return forest.subset(mine);
}

// A copy of `blocks` where they split the grid, for the stages to keep.
std::optional<WindBlocks> over_ranks(const WindBlocks* blocks) {
  if (const WindBlocks* split = splitting(blocks)) return *split;
  return std::nullopt;
}

}  // namespace

CoupledStep::CoupledStep(ComputeContext& cc, const SimulationPlan& plan, const Communicator* world)
    : CoupledStep(cc, plan.wind, plan.forest, plan.coupling, plan.inputs,
                  blocks_over(world, plan.decomposition).get()) {}

CoupledStep::CoupledStep(ComputeContext& cc, WindGridSetup wind, const trees::Forest& forest,
                         CouplingSettings coupling, TimeInputs inputs, const WindBlocks* blocks)
    : cc_(cc),
      inputs_(std::move(inputs)),
      blocks_(over_ranks(blocks)),
      wind_(cc, std::move(wind), this->blocks()),
      rank_forest_(rank_trees(forest, wind_, this->blocks())),
      own_forest_(blocks_ ? &rank_forest_ : &forest),
      trees_(cc, wind_.local_spec(), *own_forest_, this->blocks(), coupling.dynamics),
      tree_count_(forest.instance_count()),
      drag_law_(coupling.drag_law) {
  if (coupling.damage.enabled && has_trees()) {
    trees_.set_damage(*own_forest_, coupling.damage);
    damage_consequences_ = coupling.damage.consequences;
    known_fallen_.assign(std::size_t(own_forest_->instance_count()), false);
    if (damage_consequences_ && !coupling.drag_density.empty())
      standing_canopy_.emplace(wind_.setup().spec, forest, coupling.drag_density);
  }
  if (!coupling.drag_density.empty()) wind_.set_canopy(std::move(coupling.drag_density), coupling.drag_law);
  trees_.set_drag_law(coupling.drag_law);
  trees_.set_integrator(coupling.integrator);
  trees_.set_strong_wind_correction(coupling.strong_wind_correction);
  if (!inputs_.ambient_wind) throw std::invalid_argument("CoupledStep: the time inputs need an ambient wind");
  if (coupling.unresolved.enabled && has_trees())
    trees_.set_unresolved_turbulence(trees::UnresolvedTurbulence(coupling.unresolved),
                                     coupling.unresolved.intensity);
  if (coupling.integrator == trees::ModalIntegrator::semi_implicit)
    integrator_dt_limit_ = forest.semi_implicit_dt_limit();
  const bool any_leaves = std::any_of(coupling.leaves.begin(), coupling.leaves.end(),
                                      [](const trees::SpeciesLeaves& l) { return l.count() > 0; });
  // Over ranks every rank takes part, with or without trees of its own.
  if (any_leaves && has_trees())
    leaves_ =
        std::make_unique<LeafStages>(cc, wind_.local_spec(), *own_forest_, coupling.leaves, this->blocks());
}

LeafStages& CoupledStep::leaves() {
  if (!leaves_) throw std::logic_error("CoupledStep: this forest has no leaves");
  return *leaves_;
}

void CoupledStep::enqueue_frame_deformation() {
  if (!has_trees()) return;
  trees_.enqueue_deform();
  trees_.enqueue_falls(time());
  if (leaves_) leaves_->enqueue_frame(trees_.displacements());
}

void CoupledStep::apply_inputs(double t) {
  wind_.set_ambient(inputs_.ambient_wind(t));
  if (inputs_.turbulence_sigma) wind_.set_turbulence_sigma(inputs_.turbulence_sigma(t));
  if (inputs_.unresolved_intensity && trees_.unresolved_turbulence())
    trees_.set_unresolved_intensity(inputs_.unresolved_intensity(t));
}

SpinUpReport CoupledStep::start(double spin_up) {
  if (!std::isfinite(spin_up) || spin_up < 0.0)
    throw std::invalid_argument(
        fmt::format("CoupledStep: the spin-up must be finite and >= 0 s, got {}", spin_up));
  apply_inputs(0.0);
  wind_.initialise_ambient();
  SpinUpReport report;
  if (spin_up > 0.0) {
    // The initial wind is the inflow profile everywhere, without the stand's shelter, which the canopy
    // drag builds within seconds: the wind spins up before t = 0 so that the trees start in equilibrium
    // with the sheltered wind instead of swinging back from their unsheltered bend. Its clock runs from
    // -spin_up to 0 so that the inflow turbulence streams in continuously and no event (all start at
    // t >= 0) fires; the inputs stay at their t = 0 values (apply_inputs in step_wind reads max(t, 0)).
    // The canopy's drag on the air is the stand's leaf and wood density, not the trees' pose, so the
    // trees need not move meanwhile.
    wind_.set_clock(-spin_up, 0);
    while (time() < -kSpinUpTolerance * spin_up) {
      step_wind(next_step(-time()));  // never past t = 0
      ++report.steps;
    }
    report.seconds = spin_up;
    wind_.set_clock(0.0, 0);
  }
  if (!has_trees()) return report;
  // Every tree starts in equilibrium with the wind at t = 0 (docs/design.md, "Trees"): at rest in a full
  // storm, a tree would first swing far beyond its steady bend, further than linear modes describe.
  trees_.reset_state();
  trees_.enqueue_wind_load(wind_.velocity());
  trees_.enqueue_equilibrium();
  return report;
}

std::map<std::string, StageState> CoupledStep::save_state() {
  std::map<std::string, StageState> states;
  states[saved::kWindStage] = wind_.save_state();
  if (has_trees()) states[saved::kTreesStage] = trees_.save_state();
  if (leaves_) states[saved::kLeavesStage] = leaves_->save_state();
  return states;
}

void CoupledStep::restore_state(const std::map<std::string, StageState>& states) {
  const auto of = [&](const std::string& stage) -> const StageState& {
    const auto at = states.find(stage);
    if (at == states.end())
      throw std::invalid_argument(fmt::format("the saved state has no {} stage: it is another run's", stage));
    return at->second;
  };
  wind_.restore_state(of(saved::kWindStage));
  if (has_trees()) trees_.restore_state(of(saved::kTreesStage));
  if (leaves_) leaves_->restore_state(of(saved::kLeavesStage));
  // The trees that had fallen by the checkpoint leave the air's drag again, all at once: the standing
  // canopy is a function of which trees stand (StandingCanopy), so this is the field the run had.
  if (damage_consequences_) remove_fallen(/*from_records=*/true);
}

void CoupledStep::remove_fallen(bool from_records) {
  DamageStages& damage = *trees_.damage();
  const long long mine = damage.take_new_failures();
  if (!from_records && (blocks_ ? blocks_->world->sum(mine) : mine) == 0) return;
  std::vector<int> fallen;  // whole-forest ids of this rank's trees that fell since the last call
  if (mine > 0 || from_records) {
    const std::vector<trees::TreeDamageRecord> records = damage.download_records();
    for (std::size_t k = 0; k < records.size(); ++k) {
      if (records[k].state == trees::TreeState::standing || known_fallen_[k]) continue;
      known_fallen_[k] = true;
      fallen.push_back(own_forest_->id(int(k)));
    }
  }
  if (blocks_) fallen = joined(blocks_->world->gather_to_all(fallen));
  if (standing_canopy_ && standing_canopy_->fell(fallen))
    wind_.set_canopy(standing_canopy_->drag_density(), drag_law_);
}

CoupledStepReport CoupledStep::step(const NextStep& next) {
  CoupledStepReport report = step_wind(next);
  const double dt = report.wind.dt;
  if (has_trees()) {
    const auto trees_start = Clock::now();
    trees_.enqueue_wind_load(wind_.velocity());
    trees_.enqueue_modal_step(float(dt));
    if (stage_timing_) {
      cc_.finish();
      trees_ms_ += std::chrono::duration<double, std::milli>(Clock::now() - trees_start).count();
    }
    if (trees_.damage()) {
      const auto damage_start = Clock::now();
      trees_.enqueue_damage_check(float(time()));
      if (damage_consequences_) remove_fallen(/*from_records=*/false);
      if (stage_timing_) {
        cc_.finish();
        damage_ms_ += std::chrono::duration<double, std::milli>(Clock::now() - damage_start).count();
      }
    }
  }
  if (leaves_) {
    const auto leaves_start = Clock::now();
    // The wind grid's FwStep of this step: dt, and the time at its start.
    leaves_->enqueue_step(wind_.stages().step(), wind_.pressure().mask(), wind_.velocity());
    if (stage_timing_) {
      cc_.finish();
      leaves_ms_ += std::chrono::duration<double, std::milli>(Clock::now() - leaves_start).count();
    }
  }
  return report;
}

NextStep CoupledStep::next_step(double max_dt) {
  const long next = wind_.steps() + 1;
  // A spin-up's steps (t < 0) hold the inputs at their t = 0 values.
  apply_inputs(std::max(time(), 0.0));
  NextStep chosen;
  const std::array<double, 3> maxima = wind_.max_speed_components();
  chosen.max_speed_components = maxima;
  if (!(std::isfinite(maxima[0]) && std::isfinite(maxima[1]) && std::isfinite(maxima[2])))
    throw SimulationError(fmt::format("{}: field velocity is not finite", where(next, time())));
  chosen.cfl_dt = wind_.cfl_dt(maxima);
  chosen.dt = max_dt < chosen.cfl_dt * (1.0 - kLandingTolerance) ? max_dt : chosen.cfl_dt;
  const double dt = chosen.dt;
  chosen.cfl = wind_.courant_number(maxima, dt);
  const double cfl = chosen.cfl;
  // A scheme with a stability limit blows up past it; the semi-Lagrangian ones only lose accuracy.
  const double scheme_limit = wind_.advection_method().courant_limit;
  const double runaway = std::isfinite(scheme_limit) ? scheme_limit : kRunawayCfl;
  if (wind_.fixed_dt() && cfl > runaway) {
    throw SimulationError(fmt::format(
        "{}: field velocity reaches {:.1f} m/s, Courant number {:.2f} > {} ({}) with the fixed dt {} s; "
        "lower time.dt or use dt: auto",
        where(next, time()), std::max({maxima[0], maxima[1], maxima[2]}), cfl, runaway,
        std::isfinite(scheme_limit) ? wind_.advection_method().name() + "'s stability limit"
                                    : "the runaway limit",
        dt));
  }
  if (dt >= integrator_dt_limit_) {
    throw SimulationError(fmt::format(
        "{}: field tree modes: semi-implicit Euler is unstable at dt = {:.4g} s for the fastest tree mode "
        "(stable below {:.4g} s); lower time.dt or set forest.integrator: exact",
        where(next, time()), dt, integrator_dt_limit_));
  }
  return chosen;
}

CoupledStepReport CoupledStep::step_wind(const NextStep& next) {
  CoupledStepReport report;
  const std::array<double, 3>& maxima = next.max_speed_components;
  report.max_speed_component = std::max({maxima[0], maxima[1], maxima[2]});
  report.cfl = next.cfl;
  report.wind = wind_.step_by(next.dt, maxima);
  return report;
}

trees::DamageCounts CoupledStep::damage_counts() {
  if (!trees_.has_damage()) return {};
  trees::DamageCounts n = trees_.damage()->counts();
  if (blocks_) {
    const Communicator& world = *blocks_->world;
    n.standing = long(world.sum((long long)n.standing));
    n.broken = long(world.sum((long long)n.broken));
    n.overturned = long(world.sum((long long)n.overturned));
  }
  return n;
}

std::vector<trees::TreeDamageRecord> CoupledStep::gather_damage() {
  if (!trees_.has_damage()) return {};
  std::vector<FwTreeDamage> mine = trees_.damage()->download_device_records();
  std::vector<fw_int> ids;
  for (int k = 0; k < own_forest_->instance_count(); ++k) ids.push_back(own_forest_->id(k));
  if (blocks_) {
    const Communicator& world = *blocks_->world;
    const std::vector<FwTreeDamage> all = joined(world.gather(mine));
    const std::vector<fw_int> all_ids = joined(world.gather(ids));
    if (world.rank() != 0) return {};
    mine.assign(std::size_t(tree_count_), FwTreeDamage{});
    for (std::size_t j = 0; j < all.size(); ++j) mine[std::size_t(all_ids[j])] = all[j];
  }
  std::vector<trees::TreeDamageRecord> records;
  records.reserve(mine.size());
  for (const FwTreeDamage& d : mine) records.push_back(to_record(d));
  return records;
}

std::vector<float> CoupledStep::node_utilisation() {
  std::vector<float> nodes(std::size_t(own_forest_->total_nodes()), 0.0f);
  if (!trees_.has_damage()) return nodes;
  DamageStages& damage = *trees_.damage();
  const std::vector<float> sections = damage.download_utilisation();
  for (int k = 0; k < own_forest_->instance_count(); ++k) {
    const trees::StemLoads& stem = own_forest_->species_of(k).stem_loads();
    const std::vector<float> along = stem.along_stem(std::span(sections).subspan(
        std::size_t(damage.section_offset(k)), std::size_t(stem.section_count())));
    for (std::size_t i = 0; i < along.size(); ++i)
      nodes[std::size_t(own_forest_->node_offset(k) + stem.profile()[i].node)] = along[i];
  }
  return nodes;
}

std::vector<std::int32_t> CoupledStep::tree_states() {
  std::vector<std::int32_t> states(std::size_t(own_forest_->instance_count()), 0);
  if (!trees_.has_damage()) return states;
  const std::vector<FwTreeDamage> records = trees_.damage()->download_device_records();
  for (std::size_t k = 0; k < records.size(); ++k) states[k] = records[k].state;
  return states;
}

void CoupledStep::set_stage_timing(bool on) {
  stage_timing_ = on;
  wind_.set_stage_timing(on);
}

std::map<std::string, double> CoupledStep::stage_ms() const {
  std::map<std::string, double> ms = wind_.stage_ms();
  if (has_trees()) ms["trees"] += trees_ms_;
  if (trees_.has_damage()) ms["damage"] += damage_ms_;
  if (leaves_) ms["leaves"] += leaves_ms_;
  return ms;
}

void CoupledStep::reset_stage_ms() {
  wind_.reset_stage_ms();
  trees_ms_ = 0.0;
  damage_ms_ = 0.0;
  leaves_ms_ = 0.0;
}

}  // namespace fw::host
