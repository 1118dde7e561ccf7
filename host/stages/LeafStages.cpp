#include "host/stages/LeafStages.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

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

// The rest-leaf table (FW_REST_* in kernels/shared_types.h): field f of rest leaf r at f * stride + r.
class RestTable {
 public:
  explicit RestTable(int rest_count)
      : stride_(rest_count + FW_LANES), values_(std::size_t(FW_REST_FIELDS) * std::size_t(stride_), 0.0f) {}
  int stride() const { return stride_; }
  const std::vector<float>& values() const { return values_; }

  void set(int field, int r, double value) {
    values_[std::size_t(field) * std::size_t(stride_) + std::size_t(r)] = static_cast<float>(value);
  }
  void set(int field, int r, const Eigen::Vector3d& v) {
    for (int a = 0; a < 3; ++a) set(field + a, r, v[a]);
  }
  void pack(int r, const trees::RestLeaf& leaf) {
    set(FW_REST_ANCHOR, r, leaf.anchor);
    set(FW_REST_PETIOLE, r, leaf.petiole);
    set(FW_REST_HINGE, r, leaf.hinge);
    set(FW_REST_NORMAL, r, leaf.normal);
    set(FW_REST_SWING, r, leaf.hinge.cross(leaf.normal));
    set(FW_REST_TUMBLE_AXIS, r, leaf.tumble_axis);
    for (int a = 0; a < 3; ++a) {
      set(FW_REST_PHASE + a, r, leaf.phase[std::size_t(a)]);
      set(FW_REST_FREQUENCY + a, r, leaf.frequency[std::size_t(a)]);
    }
    set(FW_REST_HINGE_NORMAL, r, leaf.hinge.dot(leaf.normal));
    set(FW_REST_KAPPA, r, leaf.hinge.cross(leaf.petiole).dot(leaf.normal));
    set(FW_REST_ALONG, r, leaf.along);
    set(FW_REST_STRENGTH, r, leaf.strength);
  }

 private:
  int stride_;
  std::vector<float> values_;
};

}  // namespace

std::size_t LeafStages::estimate_device_bytes(const trees::Forest& forest,
                                              const std::vector<trees::SpeciesLeaves>& species_leaves) {
  std::size_t leaves = 0, rest = 0;
  for (const trees::TreeInstance& tree : forest.instances())
    leaves += std::size_t(species_leaves.at(std::size_t(tree.species)).count());
  for (const auto& s : species_leaves) rest += std::size_t(s.count());
  const std::size_t padded = leaves + FW_LANES, instances = std::size_t(forest.instance_count());
  const auto bytes = [](std::size_t count, std::size_t size) {
    return ComputeContext::allocation_bytes(count * size);
  };
  constexpr std::size_t f = sizeof(float), i = sizeof(std::int32_t), float4 = 4 * sizeof(float);
  // Per leaf: instance, site (padded), state, angle, rate, five float4; the sites (at most one a leaf).
  std::size_t total = bytes(leaves, i) + bytes(padded, i) + bytes(padded, 1) + 2 * bytes(padded, f) +
                      5 * bytes(padded, float4) + bytes(leaves, i) + bytes(3 * (leaves + FW_LANES), f);
  // Per instance its first leaf and (one more) first block, the instances, the species and their rest table.
  total += bytes(instances, i) + bytes(instances + 1, i) + bytes(instances, sizeof(FwTreeInstance));
  total += bytes(species_leaves.size(), sizeof(FwLeafSpecies)) + bytes(FW_REST_FIELDS * (rest + FW_LANES), f);
  total += bytes(2 * rest, i) + bytes(FW_LEAF_COUNTERS, i) + bytes(1, f);
  return total;
}

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

  // The species: their parameters and the rest-leaf table with each leaf's element nodes.
  int rest_count = 0;
  for (const auto& leaves : species_leaves) rest_count += leaves.count();
  RestTable rest(rest_count);
  std::vector<FwLeafSpecies> packed_species;
  std::vector<std::int32_t> rest_nodes;
  for (std::size_t s = 0; s < species_leaves.size(); ++s) {
    const int offset = int(rest_nodes.size() / 2);
    packed_species.push_back(pack_species(species_leaves[s], offset));
    const auto& leaves = species_leaves[s].leaves();
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      rest.pack(offset + int(i), leaves[i]);
      const auto [parent, child] =
          forest.species()[s].skeleton().elements().at(std::size_t(leaves[i].element));
      rest_nodes.push_back(parent);
      rest_nodes.push_back(child);
    }
  }
  rest_stride_ = rest.stride();

  // Flat leaves: per instance its species' leaves, each with the site of its rest blade centre (sites in
  // the order the leaves first reach them).
  std::vector<std::int32_t> first_leaf, first_block, leaf_site, site_cells;
  std::unordered_map<int, int> site_of_cell;
  long long total = 0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& tree = forest.instances()[std::size_t(k)];
    const trees::SpeciesLeaves& leaves = species_leaves[std::size_t(tree.species)];
    first_leaf.push_back(static_cast<std::int32_t>(total));
    first_block.push_back(block_count_);
    total += leaves.count();
    block_count_ += (leaves.count() + FW_LANES - 1) / FW_LANES;
    if (total > kMaxLeaves)
      throw std::invalid_argument(fmt::format("LeafStages: more than {} leaves", kMaxLeaves));
    const Eigen::Matrix3d R = forest.rotation(k);
    for (const auto& leaf : leaves.leaves()) {
      const Eigen::Vector3d centre =
          tree.position + tree.scale * R * (leaf.anchor + leaves.lever() * leaf.petiole);
      const std::array<int, 3> cell = spec.cell_holding({centre.x(), centre.y(), centre.z()});
      const int cell_index = cell[0] + spec.nx * (cell[1] + spec.ny * cell[2]);
      const auto [site, added] = site_of_cell.try_emplace(cell_index, int(site_cells.size()));
      if (added) site_cells.push_back(site->first);
      leaf_site.push_back(site->second);
      leaf_instance_host_.push_back(k);
      side_host_.push_back(static_cast<float>(leaves.side() * tree.scale));
    }
  }
  first_block.push_back(block_count_);
  leaf_count_ = static_cast<int>(total);
  instance_count_ = forest.instance_count();
  site_count_ = int(site_cells.size());
  site_stride_ = site_count_ + FW_LANES;

  // Every per-leaf array is padded by FW_LANES values, so that the last leaves' lanes may load past the end.
  const std::size_t padded = std::size_t(leaf_count_) + FW_LANES;
  leaf_site.resize(padded, 0);
  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  leaf_instance_ = cc_.upload(leaf_instance_host_, ro);
  first_leaf_ = cc_.upload(first_leaf, ro);
  first_block_ = cc_.upload(first_block, ro);
  instances_ = cc_.upload(forest.pack_instances(), ro);
  leaf_species_ = cc_.upload(packed_species, ro);
  rest_ = cc_.upload(rest.values(), ro);
  rest_nodes_ = cc_.upload(rest_nodes, ro);
  leaf_site_ = cc_.upload(leaf_site, ro);
  site_cells_ = cc_.upload(site_cells, ro);
  site_wind_ = cc_.zero_floats(3 * std::size_t(site_stride_));
  state_ = cc_.upload(std::vector<std::uint8_t>(padded, FW_LEAF_ATTACHED));
  theta_ = cc_.zero_floats(padded);
  theta_rate_ = cc_.zero_floats(padded);
  position_ = cc_.zero_floats(4 * padded);
  velocity_ = cc_.zero_floats(4 * padded);
  normal_ = cc_.zero_floats(4 * padded);
  frame_position_ = cc_.zero_floats(4 * padded);
  frame_normal_ = cc_.zero_floats(4 * padded);
  counters_ = cc_.upload(std::vector<std::int32_t>(FW_LEAF_COUNTERS, 0));
  no_displacements_ = cc_.zero_floats(1);

  // Denormals flushed: a blade's decayed motion reaches them, and on CPUs they cost a hundred times a float.
  cl::Program program = cc_.build("leaves.cl", "-cl-denorms-are-zero");
  site_wind_kernel_ = Kernel(program, "leaf_site_wind");
  flying_ = Kernel(program, "leaves_flying_step");
  attached_ = Kernel(program, "leaves_attached_step");
  frame_ = Kernel(program, "leaves_frame");
}

void LeafStages::enqueue_step(const FwStep& step, cl::Buffer& mask, DeviceVelocity& vel) {
  frame_ready_ = false;
  time_ = step.time + step.dt;
  if (leaf_count_ == 0) return;
  site_wind_kernel_.set_args(grid_, site_count_, site_cells_, vel.u, vel.v, vel.w, site_stride_, site_wind_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(site_count_))));
  flying_
      .set_args(grid_, step, leaf_count_, leaf_instance_, first_leaf_, instances_, leaf_species_, rest_,
                rest_stride_, mask, vel.u, vel.v, vel.w, state_, position_, velocity_, normal_, counters_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(leaf_count_))));
  attached_
      .set_args(step, block_count_, instance_count_, first_block_, first_leaf_, instances_, leaf_species_,
                rest_, rest_stride_, leaf_site_, site_wind_, site_stride_, state_, theta_, theta_rate_,
                position_, velocity_, normal_, counters_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(block_count_))));
}

void LeafStages::enqueue_blades(cl::Buffer& displacements, bool displaced) {
  frame_
      .set_args(time_, block_count_, instance_count_, first_block_, first_leaf_, instances_, leaf_species_,
                rest_, rest_stride_, rest_nodes_, leaf_site_, site_wind_, site_stride_, cl_int(displaced),
                displacements, state_, theta_, position_, normal_, frame_position_, frame_normal_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(block_count_))));
}

void LeafStages::enqueue_frame(cl::Buffer& displacements) {
  if (leaf_count_ == 0) return;
  enqueue_blades(displacements, true);
  frame_ready_ = true;
}

LeafSnapshot LeafStages::download() {
  LeafSnapshot snap;
  const std::size_t n = std::size_t(leaf_count_);
  snap.state.resize(n);
  snap.tree_id = leaf_instance_host_;
  snap.side = side_host_;
  if (n == 0) return snap;
  if (!frame_ready_) enqueue_blades(no_displacements_, false);
  std::vector<float> position4(4 * n), normal4(4 * n);
  cc_.queue().enqueueReadBuffer(state_, CL_FALSE, 0, n, snap.state.data());
  cc_.queue().enqueueReadBuffer(frame_position_, CL_FALSE, 0, 4 * n * sizeof(float), position4.data());
  cc_.queue().enqueueReadBuffer(frame_normal_, CL_TRUE, 0, 4 * n * sizeof(float), normal4.data());
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
