#include "trees/TreeDamage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace fw::trees {

const char* tree_state_name(TreeState state) {
  static constexpr std::array<const char*, 3> kNames{"standing", "broken", "overturned"};
  return kNames.at(std::size_t(state));
}

int CriticalMoments::weakest_section() const {
  return int(std::min_element(breaking.begin(), breaking.end()) - breaking.begin());
}

double CriticalMoments::least() const {
  return std::min(*std::min_element(breaking.begin(), breaking.end()), overturning);
}

CriticalMoments critical_moments(const StemLoads& stem, const TreeStrength& strength) {
  strength.validate();
  CriticalMoments critical;
  for (const StemSection& section : stem.sections())
    critical.breaking.push_back(breaking_moment(strength, section.diameter));
  critical.overturning = overturning_moment(strength, stem.stem_volume());
  return critical;
}

int TreeLoad::worst_section() const {
  if (utilisation.size() == 0) return -1;
  Eigen::Index worst = 0;
  utilisation.maxCoeff(&worst);
  return int(worst);
}

double TreeLoad::largest() const {
  return std::max(utilisation.size() > 0 ? utilisation.maxCoeff() : 0.0, overturning);
}

TreeLoad tree_load(const StemLoads& stem, const CriticalMoments& critical, double scale,
                   const Eigen::VectorXd& q) {
  const StemLoads grown = stem.scaled(scale);
  const double strength_scale = scale * scale * scale;  // d^3 and the stem's volume
  TreeLoad load;
  load.utilisation = grown.bending_moments(q);
  for (Eigen::Index j = 0; j < load.utilisation.size(); ++j)
    load.utilisation(j) /= critical.breaking[std::size_t(j)] * strength_scale;
  load.root_moment = grown.root_moment(q);
  load.overturning = load.root_moment / (critical.overturning * strength_scale);
  return load;
}

StaticCriticalWind static_critical_wind(const SpeciesBasis& species, const CriticalMoments& critical) {
  StaticCriticalWind worst;
  double largest = 0.0;
  const int bands = species.wind().sample_count();
  const Eigen::VectorXd omega_squared = species.modes().omega().cwiseAbs2();
  for (int d = 0; d < kCriticalDirections; ++d) {
    const double angle = 2.0 * std::numbers::pi * d / kCriticalDirections;
    const Eigen::RowVector3d unit_wind(std::cos(angle), std::sin(angle), 0.0);  // 1 m/s
    const Eigen::MatrixX3d wind = unit_wind.replicate(bands, 1);
    const Eigen::VectorXd q = species.wind().modal_forces(wind).cwiseQuotient(omega_squared);
    const TreeLoad load = tree_load(species.stem_loads(), critical, 1.0, q);
    if (load.largest() > largest) {
      largest = load.largest();
      const int section = load.worst_section();
      worst.breaks = section >= 0 && load.utilisation(section) > load.overturning;
      worst.section = worst.breaks ? section : -1;
    }
  }
  worst.speed = largest > 0.0 ? 1.0 / std::sqrt(largest) : 0.0;
  return worst;
}

bool record_load(TreeDamageRecord& record, const TreeLoad& load, double time, const Eigen::Vector3d& top_wind,
                 double scale, const StemLoads& stem) {
  record.utilisation = load.largest();
  record.max_utilisation = std::max(record.max_utilisation, record.utilisation);
  record.max_base_moment = std::max(record.max_base_moment, load.root_moment);
  if (record.state != TreeState::standing || !(record.utilisation > 1.0)) return false;
  const int worst = load.worst_section();
  const bool breaks = worst >= 0 && load.utilisation(worst) > load.overturning;
  record.state = breaks ? TreeState::broken : TreeState::overturned;
  record.failed_section = breaks ? worst : -1;
  record.break_height = breaks ? scale * stem.profile()[std::size_t(worst)].height : 0.0;
  record.time = time;
  record.top_wind = top_wind;
  return true;
}

}  // namespace fw::trees
