#include "host/bench/TreeModelsBench.hpp"

#include <fmt/format.h>

#include <cmath>

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"
#include "host/bench/BestTime.hpp"
#include "host/bench/FmaPeak.hpp"
#include "host/stages/ForestStages.hpp"
#include "io/JsonWriter.hpp"
#include "trees/TreeDamage.hpp"
#include "trees/TreeGenerator.hpp"

namespace fw::bench {
namespace {

constexpr double kWindSpeed = 10.0;  // m/s, along x
constexpr double kSpacing = 8.0;     // m between trees
constexpr double kCellSize = 2.0;    // m
constexpr double kTreeHeight = 15.0;
constexpr float kBenchDt = 0.02f;  // s
// Flops per element and step, counted from kernels/tree_branches.cl: the rigid bodies' recursion up (about
// a dozen 3 x 3 products and an inverse, 27 multiply-adds each) and down; the springs' load, atan and sin.
constexpr double kRigidFlopsPerElement = 1000.0;
constexpr double kSpringFlopsPerElement = 60.0;

// Modal: per tree the m modal forces (3 S multiply-adds each) and m oscillators (~30 flops), over its n
// elements.
double modal_flops_per_element(const TreeModelsBenchOptions& o, int nodes) {
  return (2.0 * 3.0 * o.samples * o.modes + 30.0 * o.modes) / double(nodes);
}

trees::SpeciesBasis bench_species(const TreeModelsBenchOptions& options) {
  trees::GeneratorSettings generator;
  generator.preset = "broadleaf";
  generator.height = kTreeHeight;
  generator.seed = 1;
  trees::SpeciesSettings settings;
  settings.modal.mode_count = options.modes;
  settings.wind.samples = options.samples;
  settings.wind.leaf_area_index = 3.0;
  return trees::SpeciesBasis::compute(trees::generate_tree_with_nodes(generator, options.nodes_per_tree),
                                      settings);
}

}  // namespace

TreeModelsBenchResult run_tree_models_bench(host::ComputeContext& cc, const TreeModelsBenchOptions& options) {
  TreeModelsBenchResult result;
  result.device = cc.device().device_name;
  result.trees = options.trees;
  result.modes = options.modes;
  const int side = int(std::ceil(std::sqrt(double(options.trees))));
  std::vector<trees::TreeInstance> instances;
  for (int k = 0; k < options.trees; ++k)
    instances.push_back({0, {kSpacing * (0.5 + k % side), kSpacing * (0.5 + k / side), 0.0}, 0.3 * k, 1.0});
  const trees::Forest forest({bench_species(options)}, std::move(instances));
  result.nodes_per_tree = forest.species()[0].skeleton().size();
  const double elements = double(forest.total_nodes() - forest.instance_count());

  fluid::GridSpec spec;
  spec.nx = spec.ny = int(std::ceil(kSpacing * side / kCellSize));
  spec.nz = int(std::ceil(1.5 * kTreeHeight / kCellSize));
  spec.h = kCellSize;
  fluid::MacVelocity wind(spec);
  std::fill(wind.component(0).begin(), wind.component(0).end(), float(kWindSpeed));
  host::DeviceVelocity velocity;
  for (int c = 0; c < 3; ++c) velocity.component(c) = cc.upload(wind.component(c));

  result.fma_peak_gfma_s = measure_fma_peak(cc, options.repetitions);
  const trees::TreeDynamics models[] = {trees::TreeDynamics::modal, trees::TreeDynamics::rigid_bodies,
                                        trees::TreeDynamics::springs};
  for (const trees::TreeDynamics model : models) {
    std::vector<trees::SpeciesDynamics> dynamics(1);
    dynamics[0].model = model;
    host::ForestStages stages(cc, spec, forest, nullptr, dynamics);
    TreeModelCase c;
    c.model = trees::dynamics_name(model);
    c.step_ms = 1e3 * best_seconds(cc, options.repetitions, [&] {
                  stages.enqueue_wind_load(velocity);
                  stages.enqueue_modal_step(kBenchDt);
                });
    c.frame_ms = 1e3 * best_seconds(cc, options.repetitions, [&] { stages.enqueue_deform(); });
    // The damage check on the trees the steps above bent. Without consequences, so that a tree that fails
    // keeps being checked as a standing one is.
    trees::DamageSettings damage;
    damage.enabled = true;
    damage.consequences = false;
    damage.strengths.assign(1, trees::strength_preset(trees::StrengthPreset::norway_spruce));
    stages.set_damage(forest, damage);
    c.loads_ms = 1e3 * best_seconds(cc, options.repetitions, [&] { stages.enqueue_damage_check(1.0f); });
    c.loads_ns_per_element = 1e6 * c.loads_ms / elements;
    c.loads_vs_step = c.loads_ms / c.step_ms;
    c.step_ns_per_element = 1e6 * c.step_ms / elements;
    c.frame_ns_per_element = 1e6 * c.frame_ms / elements;
    c.flops_per_element_step = model == trees::TreeDynamics::rigid_bodies ? kRigidFlopsPerElement
                               : model == trees::TreeDynamics::springs
                                   ? kSpringFlopsPerElement
                                   : modal_flops_per_element(options, result.nodes_per_tree);
    // An FMA is 2 flops.
    c.step_fraction_of_peak =
        c.flops_per_element_step * elements / (1e-3 * c.step_ms) / (2e9 * result.fma_peak_gfma_s);
    result.cases.push_back(c);
  }
  for (TreeModelCase& c : result.cases) {
    c.step_vs_modal = c.step_ms / result.cases.front().step_ms;
    c.frame_vs_modal = c.frame_ms / result.cases.front().frame_ms;
  }
  return result;
}

void print_tree_models_bench_table(const TreeModelsBenchResult& r, std::ostream& out) {
  out << fmt::format("tree models on {}: {} trees of {} nodes ({} modes for the modal model)\n", r.device,
                     r.trees, r.nodes_per_tree, r.modes);
  out << fmt::format("{:<14}{:>11}{:>12}{:>9}{:>12}{:>12}{:>9}{:>12}{:>11}{:>12}{:>10}\n", "model", "step ms",
                     "ns/elem", "x modal", "frame ms", "ns/elem", "x modal", "% FMA peak", "loads ms",
                     "ns/elem", "% step");
  for (const TreeModelCase& c : r.cases)
    out << fmt::format(
        "{:<14}{:>11.2f}{:>12.2f}{:>9.2f}{:>12.2f}{:>12.2f}{:>9.2f}{:>12.1f}{:>11.2f}{:>12.2f}{:>10.1f}\n",
        c.model, c.step_ms, c.step_ns_per_element, c.step_vs_modal, c.frame_ms, c.frame_ns_per_element,
        c.frame_vs_modal, 100.0 * c.step_fraction_of_peak, c.loads_ms, c.loads_ns_per_element,
        100.0 * c.loads_vs_step);
  out << fmt::format(
      "FMA peak {:.1f} GFMA/s, measured in this process; a step's flops per element are counted "
      "from the kernels\n",
      r.fma_peak_gfma_s);
}

std::string tree_models_bench_json(const TreeModelsBenchResult& r) {
  io::JsonWriter json;
  json.begin_object();
  json.key("device").value(r.device);
  json.key("trees").value(r.trees);
  json.key("nodes_per_tree").value(r.nodes_per_tree);
  json.key("modes").value(r.modes);
  json.key("fma_peak_gfma_s").value(r.fma_peak_gfma_s);
  json.key("cases").begin_array();
  for (const TreeModelCase& c : r.cases) {
    json.begin_object();
    json.key("model").value(c.model);
    json.key("step_ms").value(c.step_ms);
    json.key("step_ns_per_element").value(c.step_ns_per_element);
    json.key("step_vs_modal").value(c.step_vs_modal);
    json.key("frame_ms").value(c.frame_ms);
    json.key("frame_ns_per_element").value(c.frame_ns_per_element);
    json.key("frame_vs_modal").value(c.frame_vs_modal);
    json.key("flops_per_element_step").value(c.flops_per_element_step);
    json.key("step_fraction_of_peak").value(c.step_fraction_of_peak);
    json.key("loads_ms").value(c.loads_ms);
    json.key("loads_ns_per_element").value(c.loads_ns_per_element);
    json.key("loads_vs_step").value(c.loads_vs_step);
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace fw::bench
