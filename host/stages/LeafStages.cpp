#include "host/stages/LeafStages.hpp"

#include "host/stages/SavedStateNames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "host/runtime/Communicator.hpp"

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
  // Per leaf: site (padded), state, angle, rate, flight drag, leaving slot, six float4; the sites (at most
  // one a leaf): their centres and their wind.
  std::size_t total = bytes(padded, i) + bytes(padded, 1) + 3 * bytes(padded, f) + bytes(padded, i) +
                      6 * bytes(padded, float4) + bytes(3 * leaves, f) +
                      PointWindOnDevice::estimate_device_bytes(leaves);
  // Per instance its first leaf and (one more) first block, the instances, the species and their rest table.
  total += bytes(instances, i) + bytes(instances + 1, i) + bytes(instances, sizeof(FwTreeInstance));
  total += bytes(species_leaves.size(), sizeof(FwLeafSpecies)) + bytes(FW_REST_FIELDS * (rest + FW_LANES), f);
  total += bytes(2 * rest, i) + bytes(FW_LEAF_COUNTERS, i) + bytes(1, f);
  return total;
}

LeafStages::LeafStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
                       const std::vector<trees::SpeciesLeaves>& species_leaves, const WindBlocks* blocks)
    : cc_(cc),
      blocks_(splitting(blocks)),
      world_(blocks_ != nullptr ? blocks_->world : &Communicator::alone()),
      spec_(spec) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("LeafStages: ") + e.what());
  }
  if (species_leaves.size() != forest.species().size())
    throw std::invalid_argument(fmt::format("LeafStages: {} leaf sets for {} species", species_leaves.size(),
                                            forest.species().size()));
  grid_ = spec.to_device();
  const std::array<int, 2> domain = spec.domain_cells();
  own_hi_ = domain;
  if (blocks_ != nullptr) {
    const fluid::Block own = blocks_->decomposition.block(blocks_->world->rank());
    for (int a = 0; a < 2; ++a) {
      own_lo_[std::size_t(a)] = own.first[std::size_t(a)];
      own_hi_[std::size_t(a)] = own.first[std::size_t(a)] + own.count[std::size_t(a)];
    }
  }

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

  // Own leaves: per instance its species' leaves, each with the site of its rest blade centre: the centre of
  // the domain's cell that holds it (sites in the order the leaves first reach them), the same point on any
  // rank.
  std::vector<std::int32_t> first_leaf, first_block, leaf_site;
  std::vector<float> site_positions;
  std::unordered_map<long long, int> site_of_cell;
  long long total = 0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& tree = forest.instances()[std::size_t(k)];
    const trees::SpeciesLeaves& leaves = species_leaves[std::size_t(tree.species)];
    first_leaf.push_back(static_cast<std::int32_t>(total));
    own_first_slot_.emplace(forest.id(k), int(total));
    first_block.push_back(block_count_);
    total += leaves.count();
    block_count_ += (leaves.count() + FW_LANES - 1) / FW_LANES;
    if (total > kMaxLeaves)
      throw std::invalid_argument(fmt::format("LeafStages: more than {} leaves", kMaxLeaves));
    const Eigen::Matrix3d R = forest.rotation(k);
    for (int i = 0; i < leaves.count(); ++i) {
      const trees::RestLeaf& leaf = leaves.leaves()[std::size_t(i)];
      const Eigen::Vector3d centre =
          tree.position + tree.scale * R * (leaf.anchor + leaves.lever() * leaf.petiole);
      const std::array<int, 3> cell = spec.domain_cell_holding({centre.x(), centre.y(), centre.z()});
      const long long cell_index =
          cell[0] + (long long)domain[0] * (cell[1] + (long long)domain[1] * cell[2]);
      const auto [site, added] = site_of_cell.try_emplace(cell_index, int(site_positions.size() / 3));
      if (added)
        for (int a = 0; a < 3; ++a)
          site_positions.push_back(
              static_cast<float>(spec.origin[std::size_t(a)] + spec.h * (cell[std::size_t(a)] + 0.5)));
      leaf_site.push_back(site->second);
      slot_tree_.push_back(forest.id(k));
      slot_leaf_.push_back(i);
      slot_side_.push_back(static_cast<float>(leaves.side() * tree.scale));
    }
  }
  first_block.push_back(block_count_);
  own_count_ = static_cast<int>(total);
  slot_count_ = own_count_;
  instance_count_ = forest.instance_count();
  leaf_total_ = world_->sum(total);

  // Every per-leaf array is padded by FW_LANES values, so that the last leaves' lanes may load past the end.
  const std::size_t padded = std::size_t(own_count_) + FW_LANES;
  leaf_site.resize(padded, 0);
  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  first_leaf_ = cc_.upload(first_leaf, ro);
  first_block_ = cc_.upload(first_block, ro);
  instances_ = cc_.upload(forest.pack_instances(), ro);
  leaf_species_ = cc_.upload(packed_species, ro);
  rest_ = cc_.upload(rest.values(), ro);
  rest_nodes_ = cc_.upload(rest_nodes, ro);
  leaf_site_ = cc_.upload(leaf_site, ro);
  site_positions_ = cc_.upload(site_positions, ro);
  sites_.emplace(cc_, spec, blocks_, site_positions_, int(site_positions.size() / 3));
  theta_ = cc_.zero_floats(padded);
  theta_rate_ = cc_.zero_floats(padded);
  frame_position_ = cc_.zero_floats(4 * padded);
  frame_normal_ = cc_.zero_floats(4 * padded);
  reserve_slots(own_count_);
  counters_ = cc_.upload(std::vector<std::int32_t>(FW_LEAF_COUNTERS, 0));
  no_displacements_ = cc_.zero_floats(1);

  // Denormals flushed: a blade's decayed motion reaches them, and on CPUs they cost a hundred times a float.
  cl::Program program = cc_.build("leaves.cl", "-cl-denorms-are-zero");
  flying_ = Kernel(program, "leaves_flying_step");
  attached_ = Kernel(program, "leaves_attached_step");
  frame_ = Kernel(program, "leaves_frame");
  leaving_kernel_ = Kernel(program, "leaves_leaving");
  pack_ = Kernel(program, "leaves_pack");
  unpack_ = Kernel(program, "leaves_unpack");
}

void LeafStages::reserve_slots(int slots) {
  if (slots <= slot_capacity_ && slot_capacity_ > 0) return;
  // Grow by half again, so that a stream of arriving leaves copies each slot a bounded number of times.
  allocate_slots(std::max(slots, slot_capacity_ + slot_capacity_ / 2));
}

void LeafStages::allocate_slots(int capacity) {
  const std::size_t padded = std::size_t(capacity) + FW_LANES;
  const int kept = std::min(slot_count_, capacity);
  const auto grown = [&](cl::Buffer& old, std::size_t value_bytes) {
    cl::Buffer fresh = cc_.buffer(padded * value_bytes);
    cc_.queue().enqueueFillBuffer(fresh, std::uint8_t(0), 0, padded * value_bytes);
    if (slot_capacity_ > 0 && kept > 0)
      cc_.queue().enqueueCopyBuffer(old, fresh, 0, 0, std::size_t(kept) * value_bytes);
    old = fresh;
  };
  // A fresh slot holds zeros: FW_LEAF_ATTACHED, which only the own leaves' kernels step.
  grown(state_, 1);
  for (cl::Buffer* b : {&position_, &velocity_, &normal_, &flight_}) grown(*b, 4 * sizeof(float));
  grown(flight_drag_, sizeof(float));
  grown(leaving_, sizeof(std::int32_t));
  slot_capacity_ = capacity;
}

StageState LeafStages::save_state() {
  StageState state;
  for (const auto& [name, buffer] : state_buffers()) state.save(cc_, name, *buffer);
  state.numbers["time"] = {double(time_)};
  state.numbers["slots"] = {double(slot_count_), double(slot_capacity_)};
  state.numbers["slot_tree"].assign(slot_tree_.begin(), slot_tree_.end());
  state.numbers["slot_leaf"].assign(slot_leaf_.begin(), slot_leaf_.end());
  state.numbers["slot_side"].assign(slot_side_.begin(), slot_side_.end());
  return state;
}

void LeafStages::restore_state(const StageState& state) {
  static constexpr const char* kStage = "leaves";
  const std::vector<double>& slots = state.number(kStage, "slots", 2);
  const int count = int(slots[0]), capacity = int(slots[1]);
  if (count < own_count_ || capacity < count)
    throw std::invalid_argument(fmt::format(
        "leaves: the saved state has {} slots, and this run's trees have {} leaves: it is another run's",
        count, own_count_));
  if (capacity != slot_capacity_) allocate_slots(capacity);
  slot_count_ = count;
  for (const auto& [name, buffer] : state_buffers()) state.restore(cc_, kStage, name, *buffer);
  const auto copy = [&](const char* name, auto& values) {
    const std::vector<double>& saved = state.number(kStage, name, std::size_t(count));
    values.assign(saved.begin(), saved.end());
  };
  copy("slot_tree", slot_tree_);
  copy("slot_leaf", slot_leaf_);
  copy("slot_side", slot_side_);
  // The free slots are the arrived ones whose leaf moved on, as the saving run had them.
  free_slots_.clear();
  if (count > own_count_) {
    std::vector<std::uint8_t> states(std::size_t(count - own_count_));
    cc_.queue().enqueueReadBuffer(state_, CL_TRUE, std::size_t(own_count_), states.size(), states.data());
    for (std::size_t m = 0; m < states.size(); ++m)
      if (states[m] == FW_LEAF_MOVED) free_slots_.push_back(own_count_ + int(m));
  }
  time_ = float(state.number(kStage, "time", 1)[0]);
  frame_ready_ = false;
}

std::vector<std::pair<const char*, cl::Buffer*>> LeafStages::state_buffers() {
  using namespace saved;
  return {{kFlutterAngle, &theta_},      {kFlutterRate, &theta_rate_},  {kLeafState, &state_},
          {kLeafVectors[0], &position_}, {kLeafVectors[1], &velocity_}, {kLeafVectors[2], &normal_},
          {kLeafVectors[3], &flight_},   {kFlightDrag, &flight_drag_},  {kLeafCounters, &counters_}};
}

void LeafStages::enqueue_step(const FwStep& step, cl::Buffer& mask, DeviceVelocity& vel) {
  frame_ready_ = false;
  time_ = step.time + step.dt;
  if (leaf_total_ == 0) return;
  sites_->enqueue_sample(vel);
  if (slot_count_ > 0)
    flying_
        .set_args(grid_, step, slot_count_, mask, vel.u, vel.v, vel.w, flight_, flight_drag_, state_,
                  position_, velocity_, normal_, counters_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(slot_count_))));
  if (own_count_ > 0)
    attached_
        .set_args(step, block_count_, instance_count_, first_block_, first_leaf_, instances_, leaf_species_,
                  rest_, rest_stride_, leaf_site_, sites_->wind(), state_, theta_, theta_rate_, position_,
                  velocity_, normal_, flight_, flight_drag_, counters_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(block_count_))));
  if (blocks_ != nullptr) move_leaves();
}

void LeafStages::read_counters(std::int32_t (&c)[FW_LEAF_COUNTERS]) {
  cc_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof(c), c);
}

void LeafStages::move_leaves() {
  const Communicator& world = *world_;
  if (slot_count_ > 0)
    leaving_kernel_
        .set_args(grid_, slot_count_, own_lo_[0], own_hi_[0], own_lo_[1], own_hi_[1], state_, position_,
                  leaving_, counters_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(slot_count_))));
  std::int32_t c[FW_LEAF_COUNTERS] = {};
  read_counters(c);
  if (c[FW_LEAF_COUNT_PAST_HALO] > 0)
    throw std::runtime_error(
        fmt::format("LeafStages: a flying leaf's step on rank {} reached past its block's halo: the leaf "
                    "moved faster than the wind's Courant number, which sizes the halo, allows for",
                    world.rank()));
  const int leaving = c[FW_LEAF_COUNT_LEAVING];
  std::vector<std::vector<MovingLeaf>> to_each = world.lists<MovingLeaf>();
  if (leaving > 0) {
    const std::int32_t reset = 0;
    cc_.queue().enqueueWriteBuffer(counters_, CL_TRUE, FW_LEAF_COUNT_LEAVING * sizeof(std::int32_t),
                                   sizeof(reset), &reset);
    // The kernel listed the slots in no order, and so they leave; the ranks they reach sort them.
    std::vector<std::int32_t> slots(static_cast<std::size_t>(leaving));
    cc_.queue().enqueueReadBuffer(leaving_, CL_FALSE, 0, slots.size() * sizeof(std::int32_t), slots.data());
    cl::Buffer packed_leaves = cc_.buffer(slots.size() * FW_LEAF_PACKED_FLOATS * sizeof(float));
    pack_
        .set_args(leaving, leaving_, state_, position_, velocity_, normal_, flight_, flight_drag_,
                  packed_leaves)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(slots.size())));
    std::vector<float> packed(slots.size() * FW_LEAF_PACKED_FLOATS);
    cc_.queue().enqueueReadBuffer(packed_leaves, CL_TRUE, 0, packed.size() * sizeof(float), packed.data());
    for (std::size_t n = 0; n < slots.size(); ++n) {
      const float* values = &packed[n * FW_LEAF_PACKED_FLOATS];
      const int j = slots[n];
      const int holder = PointWindAcrossRanks::holder(spec_, blocks_->decomposition, values);
      if (holder == world.rank()) {
        // The device's float and the host's double put the leaf on either side of a cut: it stays.
        const auto state = static_cast<std::uint8_t>(values[3]);
        cc_.queue().enqueueWriteBuffer(state_, CL_TRUE, std::size_t(j), 1, &state);
        continue;
      }
      if (j >= own_count_) free_slots_.push_back(j);  // leaves_pack marked it FW_LEAF_MOVED
      MovingLeaf leaf;
      leaf.tree = slot_tree_[std::size_t(j)];
      leaf.leaf = slot_leaf_[std::size_t(j)];
      leaf.side = slot_side_[std::size_t(j)];
      std::copy_n(values, FW_LEAF_PACKED_FLOATS, leaf.packed);
      to_each[std::size_t(holder)].push_back(leaf);
    }
  }
  // Every rank takes part, whether leaves leave it or not.
  std::vector<MovingLeaf> arrived = joined(world.exchange(to_each));
  if (arrived.empty()) return;
  // New slots in the order of the leaves in one process (tree, then leaf), whichever rank sent them.
  std::sort(arrived.begin(), arrived.end(), [](const MovingLeaf& a, const MovingLeaf& b) {
    return a.tree != b.tree ? a.tree < b.tree : a.leaf < b.leaf;
  });
  // A leaf of an own tree to its own slot; the others to the freed slots, lowest first, then to new ones past
  // the last: in one order on every run of a split.
  const std::size_t n = arrived.size();
  arrivals_ += static_cast<long long>(n);
  std::sort(free_slots_.begin(), free_slots_.end());
  std::vector<std::int32_t> slots(n);
  std::size_t reused = 0;
  int appended = 0;
  for (std::size_t m = 0; m < n; ++m) {
    if (const auto own = own_first_slot_.find(arrived[m].tree); own != own_first_slot_.end())
      slots[m] = own->second + arrived[m].leaf;
    else if (reused < free_slots_.size())
      slots[m] = free_slots_[reused++];
    else
      slots[m] = slot_count_ + appended++;
  }
  free_slots_.erase(free_slots_.begin(), free_slots_.begin() + std::ptrdiff_t(reused));
  reserve_slots(slot_count_ + appended);
  slot_count_ += appended;
  slot_tree_.resize(std::size_t(slot_count_));
  slot_leaf_.resize(std::size_t(slot_count_));
  slot_side_.resize(std::size_t(slot_count_));
  std::vector<float> packed(n * FW_LEAF_PACKED_FLOATS);
  for (std::size_t m = 0; m < n; ++m) {
    const std::size_t j = std::size_t(slots[m]);
    slot_tree_[j] = arrived[m].tree;
    slot_leaf_[j] = arrived[m].leaf;
    slot_side_[j] = arrived[m].side;
    std::copy_n(arrived[m].packed, FW_LEAF_PACKED_FLOATS, &packed[m * FW_LEAF_PACKED_FLOATS]);
  }
  cl::Buffer slot_list = cc_.upload(slots, CL_MEM_READ_ONLY);
  cl::Buffer packed_leaves = cc_.upload(packed, CL_MEM_READ_ONLY);
  unpack_
      .set_args(int(n), slot_list, packed_leaves, state_, position_, velocity_, normal_, flight_,
                flight_drag_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(n)));
}

void LeafStages::enqueue_blades(cl::Buffer& displacements, bool displaced) {
  frame_
      .set_args(time_, block_count_, instance_count_, first_block_, first_leaf_, instances_, leaf_species_,
                rest_, rest_stride_, rest_nodes_, leaf_site_, sites_->wind(), cl_int(displaced),
                displacements, state_, theta_, position_, normal_, frame_position_, frame_normal_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(block_count_))));
}

void LeafStages::enqueue_frame(cl::Buffer& displacements) {
  if (own_count_ == 0) return;
  enqueue_blades(displacements, true);
  frame_ready_ = true;
}

LeafSnapshot LeafStages::download() {
  LeafSnapshot snap;
  const std::size_t own = std::size_t(own_count_), slots = std::size_t(slot_count_);
  if (slots == 0) return snap;
  if (own > 0 && !frame_ready_) enqueue_blades(no_displacements_, false);
  // Own leaves from the frame's blades, the leaves sent here (never attached) from where they are.
  std::vector<std::uint8_t> state(slots);
  std::vector<float> position4(4 * slots), normal4(4 * slots);
  constexpr std::size_t float4 = 4 * sizeof(float);
  auto& q = cc_.queue();
  q.enqueueReadBuffer(state_, CL_FALSE, 0, slots, state.data());
  if (own > 0) {
    q.enqueueReadBuffer(frame_position_, CL_FALSE, 0, own * float4, position4.data());
    q.enqueueReadBuffer(frame_normal_, CL_FALSE, 0, own * float4, normal4.data());
  }
  if (slots > own) {
    q.enqueueReadBuffer(position_, CL_FALSE, own * float4, (slots - own) * float4, &position4[4 * own]);
    q.enqueueReadBuffer(normal_, CL_FALSE, own * float4, (slots - own) * float4, &normal4[4 * own]);
  }
  q.finish();
  for (std::size_t j = 0; j < slots; ++j) {
    if (state[j] == FW_LEAF_MOVED) continue;
    snap.state.push_back(state[j]);
    snap.tree_id.push_back(slot_tree_[j]);
    snap.leaf.push_back(slot_leaf_[j]);
    snap.side.push_back(slot_side_[j]);
    for (int a = 0; a < 3; ++a) {
      snap.position.push_back(position4[4 * j + a]);
      snap.normal.push_back(normal4[4 * j + a]);
    }
  }
  return snap;
}

trees::LeafCounts LeafStages::counts() {
  std::int32_t c[FW_LEAF_COUNTERS] = {};
  read_counters(c);
  const auto total = [&](int counter) { return world_->sum((long long)c[counter]); };
  trees::LeafCounts counts;
  counts.shed = long(total(FW_LEAF_COUNT_SHED));
  counts.landed = long(total(FW_LEAF_COUNT_LANDED));
  counts.exited = long(total(FW_LEAF_COUNT_EXITED));
  counts.flying = counts.shed - counts.landed - counts.exited;
  counts.attached = long(leaf_total_) - counts.shed;
  return counts;
}

}  // namespace fw::host
