#include "host/stages/LeafStages.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace fw::host {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

int flutter_code(trees::FlutterModel model) {
  switch (model) {
    case trees::FlutterModel::none:
      return FW_FLUTTER_NONE;
    case trees::FlutterModel::pseudo_branch:
      return FW_FLUTTER_PSEUDO_BRANCH;
    case trees::FlutterModel::stochastic:
      return FW_FLUTTER_STOCHASTIC;
  }
  return FW_FLUTTER_NONE;
}

void store(float out[3], const Eigen::Vector3d& v) {
  for (int a = 0; a < 3; ++a) out[a] = static_cast<float>(v[a]);
}

FwLeafSpecies pack_species(const trees::SpeciesLeaves& leaves, int leaf_offset) {
  const trees::LeafSettings& s = leaves.settings();
  FwLeafSpecies sp{};
  sp.model = flutter_code(s.model);
  sp.leaf_offset = leaf_offset;
  sp.leaf_count = leaves.count();
  sp.side = static_cast<float>(leaves.side());
  sp.lever = static_cast<float>(leaves.lever());
  sp.area = static_cast<float>(s.area);
  sp.mass = static_cast<float>(leaves.mass());
  sp.omega = static_cast<float>(2.0 * std::numbers::pi * s.frequency);
  sp.damping_ratio = static_cast<float>(s.damping_ratio);
  for (int a = 0; a < 3; ++a) sp.amplitude[a] = static_cast<float>(s.amplitudes_deg[a] * kDegree);
  sp.roll_coupling = static_cast<float>(s.roll_coupling);
  sp.reference_speed = static_cast<float>(s.reference_speed);
  sp.flight_drag =
      static_cast<float>(trees::kAirDensity * s.flight_drag_coefficient / (2.0 * s.mass_per_area));
  return sp;
}

FwRestLeaf pack_rest_leaf(const trees::RestLeaf& leaf, const trees::Skeleton& skeleton) {
  FwRestLeaf r{};
  store(r.anchor, leaf.anchor);
  store(r.petiole, leaf.petiole);
  store(r.hinge, leaf.hinge);
  store(r.normal, leaf.normal);
  store(r.tumble_axis, leaf.tumble_axis);
  for (int a = 0; a < 3; ++a) {
    r.phase[a] = static_cast<float>(leaf.phase[a]);
    r.frequency[a] = static_cast<float>(leaf.frequency[a]);
  }
  r.along = static_cast<float>(leaf.along);
  r.strength = static_cast<float>(leaf.strength);
  const auto [parent, child] = skeleton.elements().at(std::size_t(leaf.element));
  r.parent_node = parent;
  r.child_node = child;
  return r;
}

}  // namespace

LeafStages::LeafStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
                       const std::vector<trees::SpeciesLeaves>& species_leaves)
    : cc_(cc) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("LeafStages: ") + e.what());
  }
  if (species_leaves.size() != forest.species().size())
    throw std::invalid_argument(fmt::format("LeafStages: {} leaf sets for {} species", species_leaves.size(),
                                            forest.species().size()));
  grid_ = spec.to_device();

  std::vector<FwLeafSpecies> packed_species;
  std::vector<FwRestLeaf> rest;
  for (std::size_t s = 0; s < species_leaves.size(); ++s) {
    packed_species.push_back(pack_species(species_leaves[s], int(rest.size())));
    for (const auto& leaf : species_leaves[s].leaves())
      rest.push_back(pack_rest_leaf(leaf, forest.species()[s].skeleton()));
  }

  // Flat leaves: per instance its species' leaves, at rest (blade centre and normal in the world).
  std::vector<std::int32_t> first_leaf;
  std::vector<float> position, normal;
  long long total = 0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& tree = forest.instances()[std::size_t(k)];
    const trees::SpeciesLeaves& leaves = species_leaves[std::size_t(tree.species)];
    first_leaf.push_back(static_cast<std::int32_t>(total));
    total += leaves.count();
    if (total > std::numeric_limits<std::int32_t>::max())
      throw std::invalid_argument(
          fmt::format("LeafStages: more than {} leaves", std::numeric_limits<std::int32_t>::max()));
    const Eigen::Matrix3d R = forest.rotation(k);
    for (const auto& leaf : leaves.leaves()) {
      const Eigen::Vector3d centre =
          tree.position + tree.scale * R * (leaf.anchor + leaves.lever() * leaf.petiole);
      const Eigen::Vector3d n = R * leaf.normal;
      for (int a = 0; a < 3; ++a) position.push_back(static_cast<float>(centre[a]));
      position.push_back(0.0f);
      for (int a = 0; a < 3; ++a) normal.push_back(static_cast<float>(n[a]));
      normal.push_back(0.0f);
      leaf_instance_host_.push_back(k);
      side_host_.push_back(static_cast<float>(leaves.side() * tree.scale));
    }
  }
  leaf_count_ = static_cast<int>(total);

  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  leaf_instance_ = cc_.upload(leaf_instance_host_, ro);
  first_leaf_ = cc_.upload(first_leaf, ro);
  instances_ = cc_.upload(forest.pack_instances(), ro);
  leaf_species_ = cc_.upload(packed_species, ro);
  rest_leaves_ = cc_.upload(rest, ro);
  state_ = cc_.upload(std::vector<std::uint8_t>(std::size_t(leaf_count_), FW_LEAF_ATTACHED));
  position_ = cc_.upload(position);
  normal_ = cc_.upload(normal);
  velocity_ = cc_.zero_floats(4 * std::size_t(leaf_count_));
  frame_position_ = cc_.zero_floats(4 * std::size_t(leaf_count_));
  counters_ = cc_.upload(std::vector<std::int32_t>(FW_LEAF_COUNTERS, 0));

  cl::Program program = cc_.build("leaves.cl");
  step_ = Kernel(program, "leaves_step");
  frame_ = Kernel(program, "leaves_frame");
}

void LeafStages::enqueue_step(const FwStep& step, cl::Buffer& mask, DeviceVelocity& vel) {
  frame_ready_ = false;
  if (leaf_count_ == 0) return;
  step_
      .set_args(grid_, step, leaf_count_, leaf_instance_, first_leaf_, instances_, leaf_species_,
                rest_leaves_, mask, vel.u, vel.v, vel.w, state_, position_, velocity_, normal_, counters_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(leaf_count_))));
}

void LeafStages::enqueue_frame(cl::Buffer& displacements) {
  if (leaf_count_ == 0) return;
  frame_
      .set_args(leaf_count_, leaf_instance_, first_leaf_, instances_, leaf_species_, rest_leaves_,
                displacements, state_, position_, frame_position_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(leaf_count_))));
  frame_ready_ = true;
}

LeafSnapshot LeafStages::download() {
  LeafSnapshot snap;
  const std::size_t n = std::size_t(leaf_count_);
  snap.state.resize(n);
  snap.tree_id = leaf_instance_host_;
  snap.side = side_host_;
  if (n == 0) return snap;
  std::vector<float> position4(4 * n), normal4(4 * n);
  cc_.queue().enqueueReadBuffer(state_, CL_FALSE, 0, n, snap.state.data());
  cc_.queue().enqueueReadBuffer(frame_ready_ ? frame_position_ : position_, CL_FALSE, 0,
                                4 * n * sizeof(float), position4.data());
  cc_.queue().enqueueReadBuffer(normal_, CL_TRUE, 0, 4 * n * sizeof(float), normal4.data());
  snap.position.resize(3 * n);
  snap.normal.resize(3 * n);
  for (std::size_t j = 0; j < n; ++j)
    for (int a = 0; a < 3; ++a) {
      snap.position[3 * j + a] = position4[4 * j + a];
      snap.normal[3 * j + a] = normal4[4 * j + a];
    }
  return snap;
}

trees::LeafCounts LeafStages::counts() {
  std::int32_t c[FW_LEAF_COUNTERS] = {};
  cc_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c);
  trees::LeafCounts counts;
  counts.shed = c[FW_LEAF_COUNT_SHED];
  counts.landed = c[FW_LEAF_COUNT_LANDED];
  counts.exited = c[FW_LEAF_COUNT_EXITED];
  counts.flying = counts.shed - counts.landed - counts.exited;
  counts.attached = leaf_count_ - counts.shed;
  return counts;
}

}  // namespace fw::host
