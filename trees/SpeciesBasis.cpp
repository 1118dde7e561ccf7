#include "trees/SpeciesBasis.hpp"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>
#include <utility>

#include "trees/BeamModel.hpp"

namespace fw::trees {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Gathers the translational rows of Phi node by node: (3 n) x m, root rows zero.
Eigen::MatrixXd gather_node_shapes(const Skeleton& skeleton, const ModalBasis& modes) {
  const int n = skeleton.size();
  Eigen::MatrixXd node_shapes = Eigen::MatrixXd::Zero(3 * n, modes.mode_count());
  for (int node = 0; node < n; ++node) {
    for (int axis = 0; axis < 3; ++axis) {
      const int dof = BeamModel::free_dof_index(skeleton.root(), node, axis);
      if (dof >= 0) node_shapes.row(3 * node + axis) = modes.shapes().row(dof);
    }
  }
  return node_shapes;
}

}  // namespace

void SpeciesSettings::validate() const {
  material.validate();
  modal.validate();
  wind.validate();
  strong_wind.validate();
}

SpeciesBasis SpeciesBasis::compute(Skeleton skeleton, const SpeciesSettings& settings) {
  settings.validate();
  SpeciesTimings timings;
  auto start = Clock::now();
  const BeamModel model(skeleton, settings.material);
  timings.assembly = seconds_since(start);

  start = Clock::now();
  ModalBasis modes = ModalBasis::compute(model, settings.modal);
  timings.modes = seconds_since(start);

  start = Clock::now();
  WindBasis wind = WindBasis::compute(skeleton, model, modes.shapes(), settings.wind);
  timings.wind = seconds_since(start);

  start = Clock::now();
  StemLoads stem_loads = StemLoads::compute(skeleton, model, modes);
  timings.stem_loads = seconds_since(start);

  start = Clock::now();
  SpeciesBasis species =
      from_parts(std::move(skeleton), settings, std::move(modes), std::move(wind), {}, std::move(stem_loads));
  timings.strong_wind = seconds_since(start);  // from_parts fits the correction; the rest is copies
  species.timings_ = timings;
  return species;
}

SpeciesBasis SpeciesBasis::from_parts(Skeleton skeleton, SpeciesSettings settings, ModalBasis modes,
                                      WindBasis wind, std::optional<StrongWindCorrection> strong_wind,
                                      std::optional<StemLoads> stem_loads) {
  const int dofs = 6 * (skeleton.size() - 1);
  if (modes.dof_count() != dofs) {
    throw std::invalid_argument(
        fmt::format("SpeciesBasis: the modes have {} DOFs but the skeleton of {} nodes "
                    "has {}",
                    modes.dof_count(), skeleton.size(), dofs));
  }
  if (wind.mode_count() != modes.mode_count()) {
    throw std::invalid_argument(
        fmt::format("SpeciesBasis: the wind basis has {} modes but the modal basis {}", wind.mode_count(),
                    modes.mode_count()));
  }
  if (wind.sample_count() != settings.wind.samples) {
    throw std::invalid_argument(
        fmt::format("SpeciesBasis: the wind basis has {} samples but the settings ask "
                    "for {}",
                    wind.sample_count(), settings.wind.samples));
  }
  if (strong_wind &&
      (strong_wind->mode_count() != modes.mode_count() || strong_wind->node_count() != skeleton.size())) {
    throw std::invalid_argument(fmt::format(
        "SpeciesBasis: the strong-wind correction has {} modes of {} nodes, expected {} of {}",
        strong_wind->mode_count(), strong_wind->node_count(), modes.mode_count(), skeleton.size()));
  }
  if (stem_loads && stem_loads->mode_count() != modes.mode_count()) {
    throw std::invalid_argument(fmt::format("SpeciesBasis: the stem loads have {} modes, expected {}",
                                            stem_loads->mode_count(), modes.mode_count()));
  }
  SpeciesBasis species;
  species.stem_loads_ = stem_loads
                            ? std::move(*stem_loads)
                            : StemLoads::compute(skeleton, BeamModel(skeleton, settings.material), modes);
  species.node_shapes_ = gather_node_shapes(skeleton, modes);
  species.strong_wind_ =
      strong_wind ? std::move(*strong_wind)
                  : StrongWindCorrection::fit(skeleton, species.node_shapes_, settings.strong_wind);
  species.skeleton_ = std::move(skeleton);
  species.settings_ = std::move(settings);
  species.modes_ = std::move(modes);
  species.wind_ = std::move(wind);
  return species;
}

SpeciesBasis SpeciesBasis::scaled(double s) const {
  ModalBasis modes = modes_.scaled(s);  // validates s
  WindBasis wind = wind_.scaled(s);
  Skeleton skeleton = skeleton_.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s);
  return from_parts(std::move(skeleton), settings_, std::move(modes), std::move(wind), strong_wind_.scaled(s),
                    stem_loads_.scaled(s));
}

SpeciesBasis SpeciesBasis::with_leaf_area_index(double leaf_area_index) const {
  SpeciesSettings settings = settings_;
  settings.wind.leaf_area_index = leaf_area_index;
  settings.wind.validate();
  SpeciesTimings timings;
  auto start = Clock::now();
  const BeamModel model(skeleton_, settings.material);
  timings.assembly = seconds_since(start);
  start = Clock::now();
  WindBasis wind = WindBasis::compute(skeleton_, model, modes_.shapes(), settings.wind);
  timings.wind = seconds_since(start);
  SpeciesBasis species =
      from_parts(skeleton_, std::move(settings), modes_, std::move(wind), strong_wind_, stem_loads_);
  species.timings_ = timings;
  return species;
}

}  // namespace fw::trees
