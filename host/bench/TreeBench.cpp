#include "host/bench/TreeBench.hpp"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/JsonWriter.hpp"
#include "trees/BeamModel.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/TreeGenerator.hpp"

namespace fw::bench {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string cpu_name() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown CPU";
}

}  // namespace

TreeBenchResult run_tree_bench(const TreeBenchOptions& options) {
  TreeBenchResult result;
  result.cpu = cpu_name();
  const trees::Material wood = trees::kDefaultWood;
  for (const int target : options.target_nodes) {
    TreeBenchCase c;
    c.target_nodes = target;
    trees::GeneratorSettings generator;
    generator.preset = options.preset;
    generator.height = options.height;
    generator.seed = options.seed;
    const trees::Skeleton tree = trees::generate_tree_with_nodes(generator, target, &c.max_element_length);
    c.nodes = tree.size();

    trees::ModalSettings settings;
    settings.mode_count = options.modes;
    const auto start = Clock::now();
    const trees::BeamModel model(tree, wood);
    c.assembly_seconds = seconds_since(start);
    const trees::ModalBasis modes = trees::ModalBasis::compute(model, settings);
    c.seconds = seconds_since(start);

    const trees::ModalStatus& status = modes.status();
    c.dofs = model.dof_count();
    c.modes = modes.mode_count();
    c.factorise_seconds = status.seconds_factorise;
    c.lanczos_seconds = status.seconds_solve;
    c.iterations = status.iterations;
    c.operations = status.operations;
    c.max_residual = status.max_residual;
    const Eigen::VectorXd hz = modes.frequencies_hz();
    c.first_hz = hz(0);
    c.last_hz = hz(hz.size() - 1);

    if (c.dofs <= options.dense_max_dofs) {
      const auto dense_start = Clock::now();
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense{
          Eigen::MatrixXd(model.stiffness()), Eigen::MatrixXd(model.mass()), Eigen::EigenvaluesOnly};
      c.dense_seconds = seconds_since(dense_start);
      if (dense.info() != Eigen::Success)
        throw std::runtime_error("bench trees: the dense eigensolver failed");
      for (int i = 0; i < c.modes; ++i) {
        const double omega = std::sqrt(dense.eigenvalues()(i));
        c.dense_max_relative_diff =
            std::max(c.dense_max_relative_diff, std::abs(modes.omega()(i) - omega) / omega);
      }
    }
    result.cases.push_back(c);
  }
  return result;
}

void print_tree_bench_table(const TreeBenchResult& r, std::ostream& out) {
  out << fmt::format("forestwind bench trees on {} (one thread): assembly + {} lowest modes\n", r.cpu,
                     r.cases.empty() ? 0 : r.cases.front().modes);
  out << fmt::format("{:>7} {:>7} {:>7} {:>9} {:>9} {:>9} {:>9} {:>6} {:>8} {:>10} {:>10} {:>10} {:>8}\n",
                     "nodes", "DOFs", "elem m", "total s", "assemb.", "factor.", "Lanczos", "iters", "resid.",
                     "Hz range", "dense s", "x sparse", "df/f");
  for (const auto& c : r.cases) {
    const std::string range = fmt::format("{:.2f}-{:.1f}", c.first_hz, c.last_hz);
    std::string dense = "-", ratio = "-", diff = "-";
    if (c.dense_seconds > 0.0) {
      dense = fmt::format("{:.2f}", c.dense_seconds);
      ratio = fmt::format("x{:.0f}", c.dense_seconds / c.seconds);
      diff = fmt::format("{:.0e}", c.dense_max_relative_diff);
    }
    out << fmt::format(
        "{:>7} {:>7} {:>7.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>6} {:>8.0e} {:>10} {:>10} "
        "{:>10} {:>8}\n",
        c.nodes, c.dofs, c.max_element_length, c.seconds, c.assembly_seconds, c.factorise_seconds,
        c.lanczos_seconds, c.iterations, c.max_residual, range, dense, ratio, diff);
  }
  out << "dense: Eigen's dense generalized eigensolver (eigenvalues only) on the same K, M, where it fits; "
         "x sparse = dense time / sparse time\n";
}

std::string tree_bench_json(const TreeBenchResult& r) {
  io::JsonWriter json;
  json.begin_object();
  json.key("cpu").value(r.cpu);
  json.key("cases").begin_array();
  for (const auto& c : r.cases) {
    json.begin_object();
    json.key("nodes").value(c.nodes);
    json.key("dofs").value(c.dofs);
    json.key("modes").value(c.modes);
    json.key("seconds").value(c.seconds);
    json.key("target_nodes").value(c.target_nodes);
    json.key("max_element_length_m").value(c.max_element_length);
    json.key("assembly_seconds").value(c.assembly_seconds);
    json.key("factorise_seconds").value(c.factorise_seconds);
    json.key("lanczos_seconds").value(c.lanczos_seconds);
    json.key("iterations").value(c.iterations);
    json.key("operations").value(c.operations);
    json.key("max_residual").value(c.max_residual);
    json.key("first_hz").value(c.first_hz);
    json.key("last_hz").value(c.last_hz);
    if (c.dense_seconds > 0.0) {
      json.key("dense_seconds").value(c.dense_seconds);
      json.key("dense_max_relative_diff").value(c.dense_max_relative_diff);
    } else {
      json.key("dense_seconds").null();
    }
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace fw::bench
