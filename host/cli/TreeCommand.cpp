// `forestwind tree generate` and `forestwind tree modes` (docs/design.md, "Command line").
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/cli/Commands.hpp"
#include "io/JsonWriter.hpp"
#include "io/SkeletonVtk.hpp"
#include "trees/BeamModel.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/QsmImport.hpp"
#include "trees/Skeleton.hpp"
#include "trees/TreeFile.hpp"
#include "trees/TreeGenerator.hpp"
#include "viz/ModeShapes.hpp"

namespace fw::cli {

namespace {

using Clock = std::chrono::steady_clock;

// A .tree file, or else a TreeQSM cylinder table. The readers' errors are base::SourceError, "FILE:LINE: KEY:
// ...", an input error (exit code 2).
trees::Skeleton read_skeleton(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".tree") return trees::read_tree_file(path);
  return trees::read_qsm_cylinders(path);
}

// The axis along which a mode moves the nodes most: the largest of sum u_x^2, sum u_y^2, sum u_z^2 over the
// nodes, with its share of the total. Torsion-dominated modes still show the axis their branches swing in.
struct Direction {
  char axis;
  double share;
};

Direction dominant_direction(const Eigen::MatrixX3d& displacement) {
  const Eigen::Vector3d energy = displacement.colwise().squaredNorm().transpose();
  Eigen::Index axis = 0;
  energy.maxCoeff(&axis);
  const double total = energy.sum();
  return {"xyz"[axis], total > 0.0 ? energy(axis) / total : 0.0};
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int run_tree_generate(const TreeGenerateOptions& options) {
  trees::GeneratorSettings settings;
  settings.preset = options.preset;
  settings.height = options.height;
  settings.seed = options.seed;
  settings.max_element_length = options.max_element_length;
  const trees::Skeleton skeleton = trees::generate_tree(settings);
  trees::write_tree_file(skeleton, options.output);
  std::cout << fmt::format("{}: {} tree, seed {}, {} nodes, height {:.2f} m, crown {:.2f} x {:.2f} m\n",
                           options.output, options.preset, options.seed, skeleton.size(), skeleton.height(),
                           skeleton.bounding_box().sizes().x(), skeleton.bounding_box().sizes().y());
  return 0;
}

int run_tree_modes(const TreeModesOptions& options) {
  const trees::Skeleton skeleton = read_skeleton(options.file);
  const trees::Material material{options.youngs_modulus, options.shear_modulus, options.density};
  material.validate();
  trees::ModalSettings settings;
  settings.mode_count = options.modes;
  settings.damping = trees::Damping::modal_ratio(options.damping_ratio);
  settings.validate();

  const auto start = Clock::now();
  const trees::BeamModel model(skeleton, material);
  const trees::ModalBasis modes = trees::ModalBasis::compute(model, settings);
  const double seconds = seconds_since(start);

  const Eigen::VectorXd hz = modes.frequencies_hz();
  const Eigen::VectorXd zeta = modes.damping_ratios();
  std::vector<Eigen::MatrixX3d> displacements;
  std::vector<Direction> directions;
  for (int i = 0; i < modes.mode_count(); ++i) {
    displacements.push_back(modes.node_displacements(model, i));
    directions.push_back(dominant_direction(displacements.back()));
  }

  if (!options.output_dir.empty()) {
    std::filesystem::create_directories(options.output_dir);
    const std::filesystem::path dir(options.output_dir);
    io::write_skeleton_vtp(dir / "skeleton.vtp", skeleton);
    std::vector<io::ModeShape> shapes;
    for (int i = 0; i < modes.mode_count(); ++i)
      shapes.push_back({hz(i), zeta(i), displacements[std::size_t(i)]});
    io::write_modes_vtp(dir / "modes.vtp", skeleton, shapes);
    viz::draw_mode_shapes(skeleton, shapes, std::filesystem::path(options.file).filename().string())
        .write_png(dir / "modes.png");
  }

  const trees::ModalStatus& status = modes.status();
  if (options.json) {
    io::JsonWriter json;
    json.begin_object();
    json.key("file").value(options.file);
    json.key("nodes").value(skeleton.size());
    json.key("dofs").value(model.dof_count());
    json.key("modes").value(modes.mode_count());
    json.key("seconds").value(seconds);
    json.key("frequencies_hz").values(hz);
    json.key("damping_ratios").values(zeta);
    json.key("dominant_directions").begin_array();
    for (const auto& d : directions) json.value(std::string(1, d.axis));
    json.end_array();
    json.key("solver").begin_object();
    json.key("method").value(status.method);
    json.key("converged").value(status.converged);
    json.key("iterations").value(status.iterations);
    json.key("operations").value(status.operations);
    json.key("max_residual").value(status.max_residual);
    json.end_object();
    json.end_object();
    std::cout << json.str() << "\n";
    return 0;
  }

  std::cout << fmt::format("{}: {} nodes, {} DOFs, height {:.2f} m\n", options.file, skeleton.size(),
                           model.dof_count(), skeleton.height());
  std::cout << fmt::format("material: E {:.3g} Pa, G {:.3g} Pa, rho {:.4g} kg/m^3\n", material.youngs_modulus,
                           material.shear_modulus, material.density);
  std::cout << fmt::format("{:>5}  {:>12}  {:>8}  {}\n", "mode", "Hz", "damping", "dominant direction");
  for (int i = 0; i < modes.mode_count(); ++i) {
    const Direction& d = directions[std::size_t(i)];
    std::cout << fmt::format("{:>5}  {:>12.5f}  {:>8.4f}  {} ({:.0f}%)\n", i + 1, hz(i), zeta(i), d.axis,
                             100.0 * d.share);
  }
  std::cout << fmt::format(
      "{}: {} of {} converged, {} iterations, {} solves, max residual {:.1e}, {:.3f} s\n", status.method,
      status.converged, status.requested, status.iterations, status.operations, status.max_residual, seconds);
  if (!options.output_dir.empty()) {
    std::cout << fmt::format(
        "wrote {0}/skeleton.vtp, {0}/modes.vtp and {0}/modes.png; in ParaView open modes.vtp, apply Warp By "
        "Vector and pick mode_01, mode_02, ... as the vectors\n",
        options.output_dir);
  }
  return 0;
}

}  // namespace fw::cli
