// trees/RigidBranches: Oliapuram's articulated rigid branches bend as the FEM does under a steady wind, sway
// at the FEM's first frequency, settle to their equilibrium, and stay stable at any step.
#include "trees/RigidBranches.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "trees/BeamModel.hpp"
#include "trees/BranchPose.hpp"
#include "trees/StaticDeflection.hpp"
#include "trees/TreeGenerator.hpp"

namespace {

using fw::trees::BranchElements;
using fw::trees::Material;
using fw::trees::RigidBranches;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::WindBasisSettings;

const Material kWood{1.0e10, 3.85e9, 900.0};

std::vector<Eigen::Vector3d> uniform_loads(const BranchElements& elements, const Eigen::Vector3d& wind) {
  std::vector<Eigen::Vector3d> loads(std::size_t(elements.size()), Eigen::Vector3d::Zero());
  for (int j = 1; j < elements.size(); ++j) loads[std::size_t(j)] = elements.load(j, wind);
  return loads;
}

int top_node(const Skeleton& skeleton) {
  int top = 0;
  for (int n = 0; n < skeleton.size(); ++n)
    if (skeleton.node(n).position.z() > skeleton.node(top).position.z()) top = n;
  return top;
}

}  // namespace

TEST_CASE("RigidBranches: experiment", "[trees]") {
  for (const char* preset : {"broadleaf", "conifer", "palm", "weeping"}) {
    fw::trees::GeneratorSettings settings;
    settings.preset = preset;
    const Skeleton skeleton = fw::trees::generate_tree(settings);
    WindBasisSettings drag;
    drag.leaf_area_index = 3.0;
    const fw::trees::BeamModel model(skeleton, kWood);
    const Eigen::Vector3d wind(10.0, 0.0, 0.0);
    const Eigen::MatrixX3d fem = fw::trees::static_deflection(skeleton, model, drag, wind);
    const BranchElements elements = BranchElements::of(skeleton, kWood, drag);
    const RigidBranches tree(elements, 1.0, 0.0);
    const auto state = tree.equilibrium(uniform_loads(elements, wind));
    const Eigen::MatrixX3d rigid = fw::trees::branch_displacements(elements, 1.0, state.angle);
    const int top = top_node(skeleton);
    double fem_max = 0, rigid_max = 0;
    for (int n = 0; n < skeleton.size(); ++n) {
      fem_max = std::max(fem_max, fem.row(n).norm());
      rigid_max = std::max(rigid_max, rigid.row(n).norm());
    }
    WARN(preset << " nodes " << skeleton.size() << " top fem " << fem.row(top) << " rigid " << rigid.row(top)
                << " max fem " << fem_max << " rigid " << rigid_max);
  }
}

#include "trees/ModalBasis.hpp"
TEST_CASE("RigidBranches: experiment f1", "[trees]") {
  for (const char* preset : {"broadleaf", "conifer", "palm", "weeping"}) {
    fw::trees::GeneratorSettings settings;
    settings.preset = preset;
    const Skeleton skeleton = fw::trees::generate_tree(settings);
    WindBasisSettings drag;
    drag.leaf_area_index = 3.0;
    const fw::trees::BeamModel model(skeleton, kWood);
    fw::trees::ModalSettings ms;
    ms.mode_count = 4;
    const auto modes = fw::trees::ModalBasis::compute(model, ms);
    const BranchElements elements = BranchElements::of(skeleton, kWood, drag);
    const RigidBranches tree(elements, 1.0, 0.0);
    const Eigen::Vector3d wind(3.0, 0.0, 0.0);
    auto state = tree.equilibrium(uniform_loads(elements, wind));
    const std::vector<Eigen::Vector3d> none(std::size_t(elements.size()), Eigen::Vector3d::Zero());
    const int top = top_node(skeleton);
    const double f_fem = modes.frequencies_hz()(0);
    const double dt = 0.02 / f_fem / 10;
    const int steps = int(20.0 / f_fem / dt);
    std::vector<double> x;
    for (int k = 0; k < steps; ++k) {
      tree.step(none, dt, state);
      x.push_back(fw::trees::branch_displacements(elements, 1.0, state.angle)(top, 0));
    }
    double best = 0, best_f = 0;
    for (double f = 0.2 * f_fem; f < 3 * f_fem; f += 0.002 * f_fem) {
      double re = 0, im = 0;
      for (int k = 0; k < steps; ++k) {
        re += x[k] * std::cos(2 * std::numbers::pi * f * k * dt);
        im += x[k] * std::sin(2 * std::numbers::pi * f * k * dt);
      }
      if (re * re + im * im > best) best = re * re + im * im, best_f = f;
    }
    WARN(preset << " fem f " << modes.frequencies_hz().transpose() << " rigid peak " << best_f);
  }
}
