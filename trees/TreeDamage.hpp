// Which trees fail in a storm (docs/damage.md): each tree's stem loads (trees/StemLoads.hpp) against its
// species' strength (trees/TreeStrength.hpp), step by step, and the record of what happened to it. This is
// the model and its CPU reference; host/stages/DamageStages runs it on the device for every tree.
//
//   fw::trees::CriticalMoments critical = fw::trees::critical_moments(species.stem_loads(), strength);
//   fw::trees::TreeLoad load = fw::trees::tree_load(species.stem_loads(), critical, scale, q);
//   fw::trees::TreeDamageRecord record;                      // standing
//   fw::trees::record_load(record, load, time, top_wind, scale, species.stem_loads());
//   record.state;                                           // standing, broken or overturned
//
// The rule (ForestGALES's criteria, applied every step to the moments the dynamics gives): a tree breaks
// when the bending moment at any stem section exceeds M_b = f_knot MOR pi d^3 / 32 of the section's
// diameter d (its outer-fibre stress exceeds f_knot MOR), and overturns when its root's turning moment
// exceeds M_o = C_reg x green density x stem volume. Utilisation is the applied-to-critical ratio; the first
// step on which the largest exceeds 1 is the failure, whichever of the two is the larger then. For an
// instance of scale s both critical moments scale as s^3 (diameters and volume) and the moments as
// StemLoads::scaled says.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "trees/SpeciesBasis.hpp"
#include "trees/StemLoads.hpp"
#include "trees/TreeStrength.hpp"

namespace fw::trees {

/// What happened to a tree.
enum class TreeState { standing = 0, broken = 1, overturned = 2 };
/// "standing", "broken", "overturned": the words of damage.csv and the trees frames.
const char* tree_state_name(TreeState state);

/// A run's damage model (forest.damage), per forest species.
struct DamageSettings {
  bool enabled = false;      ///< compute the loads and record failures
  bool consequences = true;  ///< a failed tree falls, stops taking load and leaves the air's drag
  /// Per forest species (Forest::species()); every species needs one when enabled.
  std::vector<TreeStrength> strengths;
};

/// A species' critical moments at scale 1, N m.
struct CriticalMoments {
  std::vector<double> breaking;  ///< M_b per stem section (StemLoads::sections()), root first
  double overturning = 0.0;      ///< M_o
  /// The section whose M_b is the least: where a load uniform in stress would break the stem first.
  int weakest_section() const;
  /// The smaller of the least M_b and M_o: what fails first under a moment that is the same at every
  /// section (a load at the top); the report's "fails first".
  double least() const;
};

/// The critical moments of a stem of `strength`. Throws what TreeStrength::validate throws.
CriticalMoments critical_moments(const StemLoads& stem, const TreeStrength& strength);

/// One step's loads of one tree against its critical moments.
struct TreeLoad {
  Eigen::VectorXd utilisation;  ///< |M_j| / M_b,j per section
  double overturning = 0.0;     ///< M_root / M_o
  double root_moment = 0.0;     ///< N m
  int worst_section() const;    ///< the section of the largest utilisation
  double largest() const;       ///< the largest of every section's and the overturning's
};

/// The loads of the instance of scale s (its modal state q) of the species whose scale-1 stem is `stem`.
TreeLoad tree_load(const StemLoads& stem, const CriticalMoments& critical, double scale,
                   const Eigen::VectorXd& q);

/// How many trees stand, broke and overturned.
struct DamageCounts {
  long standing = 0, broken = 0, overturned = 0;
};

/// What happened to one tree over the run.
struct TreeDamageRecord {
  TreeState state = TreeState::standing;
  int failed_section = -1;    ///< the section that broke (broken), else -1
  double time = 0.0;          ///< s: when it failed
  double break_height = 0.0;  ///< m above the root: the broken section's (0 when overturned)
  Eigen::Vector3d top_wind = Eigen::Vector3d::Zero();  ///< m/s at its top when it failed
  double max_utilisation = 0.0;                        ///< the largest utilisation over the run
  double max_base_moment = 0.0;                        ///< N m, the largest root moment over the run
  double utilisation = 0.0;                            ///< the last step's largest
};

/// The model's own static critical wind of a species at scale 1, m/s: the uniform wind over the whole tree
/// (the same in every wind band, horizontal, from the direction that loads it most of kCriticalDirections)
/// whose static modal response (q = f / omega^2) brings the largest utilisation to 1. Utilisation grows as
/// the wind's square (drag |v| v; the weight's moment is linear in q), so it is 1 / sqrt of the utilisation
/// at 1 m/s. No turbulence, no shelter, no drag law: a reference against Hale's and ForestGALES's winds,
/// which are the hour's mean at the canopy top and carry the gusts in their coefficients.
inline constexpr int kCriticalDirections = 16;
struct StaticCriticalWind {
  double speed = 0.0;  ///< m/s
  bool breaks = true;  ///< whether breakage (else overturning) comes first
  int section = -1;    ///< the section that breaks, else -1
};
StaticCriticalWind static_critical_wind(const SpeciesBasis& species, const CriticalMoments& critical);

/// Records a step's load (at time `time`, the wind `top_wind` at the tree's top) in `record`: the maxima,
/// and the failure when the tree is standing and its largest utilisation exceeds 1. scale and stem give
/// the break's height. Returns whether the tree failed on this step.
bool record_load(TreeDamageRecord& record, const TreeLoad& load, double time, const Eigen::Vector3d& top_wind,
                 double scale, const StemLoads& stem);

}  // namespace fw::trees
