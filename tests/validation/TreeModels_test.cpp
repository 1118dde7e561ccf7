// The three tree models against the FEM (docs/tree-models.md): on the broadleaf preset and on a tree read
// through the TreeQSM importer, the static tip deflection under a uniform wind, the first natural frequency
// from a release, and the standard deviation of the tip in a turbulent wind, each model's figure printed for
// the table. The CPU references are the device's oracles (tests/kernels/tree_branches_test.cpp), so these are
// the device's figures too.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <vector>

#include "tests/support/BranchModels.hpp"
#include "trees/BeamModel.hpp"
#include "trees/BranchPose.hpp"
#include "trees/ForestReference.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/QsmImport.hpp"
#include "trees/RigidBranches.hpp"
#include "trees/SpringBranches.hpp"
#include "trees/StaticDeflection.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/WindBasis.hpp"

namespace {

using fw::test::spectral_peak;
using fw::test::top_node;

using fw::trees::BranchElements;
using fw::trees::Skeleton;

const fw::trees::Material kWood{1.0e10, 3.85e9, 900.0};
constexpr double kLeafAreaIndex = 3.0;
constexpr double kDampingRatio = 0.05;
constexpr int kModes = 20;

// A tree as a scanner's QSM gives it: a generated broadleaf whose every node is moved at random by up to a
// fifth of its element's length (scanned branches are crooked), written as a TreeQSM cylinder table (one
// cylinder per element, radius its end node's) and read back through the importer.
Skeleton qsm_tree(const std::filesystem::path& folder) {
  fw::trees::GeneratorSettings settings;
  settings.preset = "broadleaf";
  settings.height = 11.0;
  settings.seed = 41;
  const Skeleton grown = fw::trees::generate_tree(settings);
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::Vector3d> position(std::size_t(grown.size()));
  std::vector<int> cylinder_of(std::size_t(grown.size()), 0);  // 1-based cylinder ending at each node
  position[std::size_t(grown.root())] = grown.node(grown.root()).position;
  std::filesystem::create_directories(folder);
  const std::filesystem::path path = folder / "scanned_cyl.txt";
  std::ofstream out(path);
  out << "radius length start_x start_y start_z axis_x axis_y axis_z parent extension added UnmodRadius\n";
  int cylinder = 0;
  for (const auto& [parent, child] : grown.elements()) {
    const Eigen::Vector3d rest = grown.node(child).position - grown.node(parent).position;
    const Eigen::Vector3d wobble(unit(rng), unit(rng), unit(rng));
    position[std::size_t(child)] =
        position[std::size_t(parent)] + rest + 0.2 * rest.norm() * wobble / std::sqrt(3.0);
    const Eigen::Vector3d axis = position[std::size_t(child)] - position[std::size_t(parent)];
    cylinder_of[std::size_t(child)] = ++cylinder;
    const Eigen::Vector3d& start = position[std::size_t(parent)];
    out << grown.node(child).radius << ' ' << axis.norm() << ' ' << start.x() << ' ' << start.y() << ' '
        << start.z() << ' ' << axis.x() << ' ' << axis.y() << ' ' << axis.z() << ' '
        << cylinder_of[std::size_t(parent)] << " 0 0 " << grown.node(child).radius << '\n';
  }
  out.close();
  return fw::trees::read_qsm_cylinders(path.string());
}

// The tip's along-wind displacement under each model, for one tree.
struct ModelTree {
  Skeleton skeleton;
  fw::trees::WindBasisSettings drag;
  fw::trees::BeamModel model;
  fw::trees::ModalBasis modes;
  fw::trees::WindBasis basis;
  BranchElements elements;
  int top;

  explicit ModelTree(Skeleton s)
      : skeleton(std::move(s)),
        drag(foliage()),
        model(skeleton, kWood),
        modes(fw::trees::ModalBasis::compute(model, modal_settings())),
        basis(fw::trees::WindBasis::compute(skeleton, model, modes.shapes(), drag)),
        elements(BranchElements::of(skeleton, kWood, drag)),
        top(top_node(skeleton)) {}

  static fw::trees::WindBasisSettings foliage() {
    fw::trees::WindBasisSettings drag;
    drag.leaf_area_index = kLeafAreaIndex;
    return drag;
  }
  static fw::trees::ModalSettings modal_settings() {
    fw::trees::ModalSettings settings;
    settings.mode_count = kModes;
    settings.damping = fw::trees::Damping::modal_ratio(kDampingRatio);
    return settings;
  }

  std::vector<Eigen::Vector3d> loads(const Eigen::Vector3d& wind) const {
    return fw::test::uniform_loads(elements, wind);
  }
  // The modal tip (linear, x) of modal coordinates q.
  double modal_tip(const Eigen::VectorXd& q) const {
    const int row = model.free_dof_of(top, 0);
    return modes.shapes().row(row).dot(q);
  }
  Eigen::VectorXd modal_forces(const Eigen::Vector3d& wind) const {
    Eigen::MatrixX3d samples(basis.sample_count(), 3);
    for (int s = 0; s < basis.sample_count(); ++s) samples.row(s) = wind.transpose();
    return basis.modal_forces(samples);
  }
  double pose_tip(const std::vector<Eigen::Vector3d>& angles) const {
    return fw::trees::branch_displacements(elements, 1.0, angles)(top, 0);
  }
};

double standard_deviation(const std::vector<double>& x) {
  double mean = 0.0, square = 0.0;
  for (double v : x) mean += v;
  mean /= double(x.size());
  for (double v : x) square += (v - mean) * (v - mean);
  return std::sqrt(square / double(x.size()));
}

// A uniform wind U + u'(t) along x: u' a sum of 200 cosines from 0.02 to 4 Hz with the von Karman spectrum
// of intensity 0.2 and length scale 50 m, random phases. The same for every element: the models, not the
// sampling, are compared.
struct TurbulentWind {
  double mean = 10.0;
  std::vector<double> frequency, amplitude, phase;
  TurbulentWind() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> turn(0.0, 2.0 * std::numbers::pi);
    constexpr double kIntensity = 0.2, kLength = 50.0, kLow = 0.02, kHigh = 4.0;
    constexpr int kCount = 200;
    const double df = (kHigh - kLow) / kCount, sigma = kIntensity * mean;
    for (int k = 0; k < kCount; ++k) {
      const double f = kLow + (k + 0.5) * df;
      const double n = f * kLength / mean;
      const double spectrum = 4.0 * sigma * sigma * kLength / mean / std::pow(1.0 + 70.8 * n * n, 5.0 / 6.0);
      frequency.push_back(f);
      amplitude.push_back(std::sqrt(2.0 * spectrum * df));
      phase.push_back(turn(rng));
    }
  }
  Eigen::Vector3d at(double t) const {
    double u = mean;
    for (std::size_t k = 0; k < frequency.size(); ++k)
      u += amplitude[k] * std::cos(2.0 * std::numbers::pi * frequency[k] * t + phase[k]);
    return {u, 0.0, 0.0};
  }
};

void compare(const char* name, const ModelTree& tree) {
  const double f1 = tree.modes.frequencies_hz()(0);
  const fw::trees::RigidBranches rigid(tree.elements, 1.0,
                                       fw::trees::rigid_damping(kDampingRatio, tree.modes.omega()(0)));
  fw::trees::SpringSettings springs;
  springs.sway_amplitude = 0.0;  // the sine is a look, not a response to the wind
  const std::vector<double> phases = fw::trees::spring_phases(0, tree.elements.size());

  // Static tip along a uniform 10 m/s wind.
  const Eigen::Vector3d wind(10.0, 0.0, 0.0);
  const double fem = fw::trees::static_deflection(tree.skeleton, tree.model, tree.drag, wind)(tree.top, 0);
  const Eigen::VectorXd q_static = tree.modal_forces(wind).cwiseQuotient(tree.modes.omega().cwiseAbs2());
  const double modal = tree.modal_tip(q_static);
  const double rigid_tip = tree.pose_tip(rigid.equilibrium(tree.loads(wind)).angle);
  const double spring_tip =
      tree.pose_tip(fw::trees::spring_angles(tree.elements, springs, 1.0, tree.loads(wind), phases, 0.0));
  WARN(name << " (" << tree.skeleton.size() << " nodes): static tip along a uniform 10 m/s wind: FEM " << fem
            << " m, modal (" << kModes << " modes) " << modal << " m, rigid bodies " << rigid_tip
            << " m, springs " << spring_tip << " m");
  // The 10% for the rigid bodies; the modal truncation loses the higher modes' share.
  CHECK(rigid_tip == Approx(fem).epsilon(0.10));
  CHECK(modal == Approx(fem).epsilon(0.10));

  // Released from the bend of a 3 m/s wind, no damping: the tip's spectral peak.
  {
    fw::trees::RigidBranches free(tree.elements, 1.0, 0.0);
    auto state = free.equilibrium(tree.loads({3.0, 0.0, 0.0}));
    const std::vector<Eigen::Vector3d> none(std::size_t(tree.elements.size()), Eigen::Vector3d::Zero());
    const double dt = 1.0 / (50.0 * f1);
    std::vector<double> tip;
    for (int k = 0; k < 1000; ++k) {
      free.step(none, dt, state);
      tip.push_back(tree.pose_tip(state.angle));
    }
    const double peak = spectral_peak(tip, dt, 0.2 * f1, 3.0 * f1, 0.002 * f1);
    WARN(name << ": FEM f1 " << f1 << " Hz (f2 " << tree.modes.frequencies_hz()(1)
              << " Hz), rigid bodies' released tip peaks at " << peak << " Hz; springs have no inertia");
    CHECK(peak == Approx(f1).epsilon(0.10));
  }

  // Turbulent wind, 300 s at dt 0.02 s after 30 s to settle: the tip's standard deviation.
  const TurbulentWind turbulence;
  constexpr double dt = 0.02;
  constexpr int kSettle = 1500, kSteps = 15000;
  Eigen::VectorXd q = q_static * (turbulence.at(0.0).x() * turbulence.at(0.0).x() / 100.0), qdot = q * 0.0;
  auto state = rigid.equilibrium(tree.loads(turbulence.at(0.0)));
  std::vector<double> modal_tip, rigid_series, spring_series;
  const Eigen::VectorXd omega = tree.modes.omega(), gamma = 2.0 * kDampingRatio * omega;
  for (int n = 0; n < kSettle + kSteps; ++n) {
    const double t = n * dt;
    const Eigen::Vector3d v = turbulence.at(t);
    const Eigen::VectorXd f = tree.modal_forces(v);
    for (int i = 0; i < kModes; ++i) fw::trees::exact_modal_step(q(i), qdot(i), f(i), omega(i), gamma(i), dt);
    rigid.step(tree.loads(v), dt, state);
    if (n < kSettle) continue;
    modal_tip.push_back(tree.modal_tip(q));
    rigid_series.push_back(tree.pose_tip(state.angle));
    spring_series.push_back(
        tree.pose_tip(fw::trees::spring_angles(tree.elements, springs, 1.0, tree.loads(v), phases, t)));
  }
  const double modal_sd = standard_deviation(modal_tip);
  WARN(name << ": tip standard deviation in a 10 m/s wind of intensity 0.2: modal " << modal_sd
            << " m, rigid bodies " << standard_deviation(rigid_series) << " m ("
            << standard_deviation(rigid_series) / modal_sd << " x), springs "
            << standard_deviation(spring_series) << " m (" << standard_deviation(spring_series) / modal_sd
            << " x)");
  CHECK(standard_deviation(rigid_series) > 0.0);
}

}  // namespace

TEST_CASE("validation: the tree models against the FEM on the broadleaf preset and a TreeQSM tree",
          "[validation][trees]") {
  fw::trees::GeneratorSettings broadleaf;
  broadleaf.preset = "broadleaf";
  compare("broadleaf preset", ModelTree(fw::trees::generate_tree(broadleaf)));
  compare("TreeQSM tree", ModelTree(qsm_tree(std::filesystem::temp_directory_path() / "fw_tree_models")));
}

// A scanned tree is not in the repository (none with an open licence was found): this runs the same
// comparison on a TreeQSM cylinder table named by FORESTWIND_QSM_TREE, by hand (docs/tree-models.md, "A
// scanned tree").
TEST_CASE(
    "validation: the tree models against the FEM on a scanned TreeQSM tree named by FORESTWIND_QSM_TREE",
    "[.][validation][scanned]") {
  const char* path = std::getenv("FORESTWIND_QSM_TREE");
  if (path == nullptr || *path == '\0') FAIL("set FORESTWIND_QSM_TREE to a TreeQSM cylinder table");
  compare("scanned TreeQSM tree", ModelTree(fw::trees::read_qsm_cylinders(path)));
}
