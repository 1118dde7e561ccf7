#include "host/app/CheckpointRedistribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

#include "host/runtime/Communicator.hpp"
#include "host/stages/BranchStages.hpp"
#include "host/stages/SavedStateNames.hpp"

namespace fw::host {

namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace saved;

const StageState& stage_of(const RunSnapshot& part, const char* stage) {
  const auto at = part.stages.find(stage);
  if (at == part.stages.end())
    throw std::invalid_argument(
        fmt::format("checkpoint: a part has no {} stage: it is another run's", stage));
  return at->second;
}

// `count` values of T from the start of saved bytes.
template <typename T>
std::vector<T> values_of(const Bytes& bytes, std::size_t count, const std::string& name) {
  if (bytes.size() < count * sizeof(T))
    throw std::invalid_argument(
        fmt::format("checkpoint: the saved \"{}\" holds {} bytes, {} expected: it is "
                    "another run's",
                    name, bytes.size(), count * sizeof(T)));
  std::vector<T> values(count);
  if (count > 0) std::memcpy(values.data(), bytes.data(), count * sizeof(T));
  return values;
}

// A buffer's bytes as the device allocates it: at least ComputeContext::kMinimumBufferBytes.
template <typename T>
Bytes bytes_of(const std::vector<T>& values) {
  Bytes bytes(std::max(values.size() * sizeof(T), ComputeContext::kMinimumBufferBytes), 0);
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), values.size() * sizeof(T));
  return bytes;
}

// The whole domain's array `name` of the wind grid (face array of component c, or cells for c < 0) from
// every part's own values.
std::vector<float> whole_wind_array(const std::vector<RunSnapshot>& parts, const fluid::GridSpec& spec,
                                    const std::string& name, int c) {
  const int nx = spec.nx + (c == 0 ? 1 : 0), ny = spec.ny + (c == 1 ? 1 : 0), nz = spec.nz + (c == 2 ? 1 : 0);
  std::vector<float> whole(std::size_t(nx) * std::size_t(ny) * std::size_t(nz), 0.0f);
  for (const RunSnapshot& part : parts) {
    const BlockArray& cells = part.block;
    const BlockArray a = c >= 0 ? face_array(cells, c) : cells;
    const std::vector<float> values =
        values_of<float>(stage_of(part, kWindStage).bytes("wind grid", name), a.cells(), name);
    // The part's own cells, and along a staggered axis the face above the last (shared or the domain's).
    std::array<int, 2> lo{}, hi{};
    for (int axis = 0; axis < 2; ++axis) {
      lo[std::size_t(axis)] = cells.origin[std::size_t(axis)] + cells.halo_low[std::size_t(axis)];
      hi[std::size_t(axis)] = cells.origin[std::size_t(axis)] + cells.extent[std::size_t(axis)] -
                              cells.halo_high[std::size_t(axis)] + (c == axis ? 1 : 0);
    }
    const int ex = a.values(0), ey = a.values(1);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ey; ++j) {
        const int gj = cells.origin[1] + j;
        if (gj < lo[1] || gj >= hi[1]) continue;
        for (int i = 0; i < ex; ++i) {
          const int gi = cells.origin[0] + i;
          if (gi < lo[0] || gi >= hi[0]) continue;
          whole[std::size_t(gi) + std::size_t(nx) * (std::size_t(gj) + std::size_t(ny) * k)] =
              values[std::size_t(i) + std::size_t(ex) * (std::size_t(j) + std::size_t(ey) * k)];
        }
      }
  }
  return whole;
}

StageState wind_state(const std::vector<RunSnapshot>& parts, const fluid::GridSpec& spec,
                      const BlockArray& cells) {
  const StageState& first = stage_of(parts.front(), kWindStage);
  StageState state;
  state.numbers = first.numbers;  // the time, offsets and integrals: the same on every rank
  for (int c = 0; c < 3; ++c) {
    const std::vector<float> whole = whole_wind_array(parts, spec, kVelocity[c], c);
    state.buffers[kVelocity[c]] = bytes_of(
        block_of(whole, spec.nx + (c == 0 ? 1 : 0), spec.ny + (c == 1 ? 1 : 0), face_array(cells, c)));
  }
  for (const char* name : kWindCellArrays) {
    if (first.buffers.count(name) == 0) continue;
    state.buffers[name] =
        bytes_of(block_of(whole_wind_array(parts, spec, name, -1), spec.nx, spec.ny, cells));
  }
  return state;
}

// Per tree (Forest::id) of every part, its slice of a per-instance buffer of `per_tree(id)` floats.
template <typename PerTree>
std::map<int, std::vector<float>> tree_slices(const std::vector<RunSnapshot>& parts, const std::string& name,
                                              PerTree per_tree) {
  std::map<int, std::vector<float>> slices;
  for (const RunSnapshot& part : parts) {
    std::size_t count = 0;
    for (const int id : part.tree_ids) count += per_tree(id);
    const std::vector<float> values =
        values_of<float>(stage_of(part, kTreesStage).bytes("trees", name), count, name);
    std::size_t at = 0;
    for (const int id : part.tree_ids) {
      slices[id].assign(values.begin() + long(at), values.begin() + long(at + per_tree(id)));
      at += per_tree(id);
    }
  }
  return slices;
}

StageState trees_state(const std::vector<RunSnapshot>& parts, const trees::Forest& forest,
                       const std::vector<trees::SpeciesDynamics>& dynamics, const trees::Forest& own) {
  const auto modal = [&](int id) {
    return 2 * std::size_t(forest.mode_offset(id + 1) - forest.mode_offset(id));
  };
  const auto travel = [](int) { return ForestStages::kTravelFloats; };
  StageState state;
  const auto gather = [&](const std::string& name, auto per_tree) {
    const std::map<int, std::vector<float>> slices = tree_slices(parts, name, per_tree);
    std::vector<float> mine;
    for (int k = 0; k < own.instance_count(); ++k) {
      const auto at = slices.find(own.id(k));
      if (at == slices.end())
        throw std::invalid_argument(
            fmt::format("checkpoint: no part holds tree {}: it is another run's", own.id(k)));
      mine.insert(mine.end(), at->second.begin(), at->second.end());
    }
    state.buffers[name] = bytes_of(mine);
  };
  // An element model's tree: its joints, one entry a node; a modal tree has none.
  const auto joints = [&](int id) {
    return FW_JOINT_FLOATS * std::size_t(BranchStages::entries_of(forest, dynamics, id));
  };
  gather(kModalState, modal);
  const StageState& first = stage_of(parts.front(), kTreesStage);
  if (first.buffers.count(kTravelled) > 0) gather(kTravelled, travel);
  // Storm damage: each tree's record, moved as its bytes (the ints among them too).
  const auto record = [](int) { return sizeof(FwTreeDamage) / sizeof(float); };
  if (first.buffers.count(kDamage) > 0) gather(kDamage, record);
  if (first.buffers.count(kJointState) > 0) {
    gather(kJointState, joints);
    // The springs' clock is the run's time, the same on every rank.
    state.numbers[kBranchClock] = first.number("trees", kBranchClock, 1);
  }
  return state;
}

// One leaf of the checkpoint: where it is (its live slot) and its flutter (its tree's slot).
struct LeafRecord {
  std::uint8_t state = FW_LEAF_ATTACHED;
  float slot[std::size(kLeafVectors)][4] = {};  // saved::kLeafVectors
  float drag = 0.0f, side = 0.0f, theta = 0.0f, theta_rate = 0.0f;
};

using LeafKey = std::pair<int, int>;  // tree id, leaf index on its tree

// The leaves of tree `id` of the plan's forest (its species' count).
std::size_t leaves_of(const SimulationPlan& plan, int id) {
  const int species = plan.forest.instances()[std::size_t(id)].species;
  return std::size_t(plan.coupling.leaves[std::size_t(species)].count());
}

std::map<LeafKey, LeafRecord> leaf_records(const std::vector<RunSnapshot>& parts,
                                           const SimulationPlan& plan) {
  std::map<LeafKey, LeafRecord> records;
  for (const RunSnapshot& part : parts) {
    const StageState& s = stage_of(part, kLeavesStage);
    const std::vector<double>& slots = s.number("leaves", "slots", 2);
    const std::size_t count = std::size_t(slots[0]);
    std::size_t own = 0;
    for (const int id : part.tree_ids) own += leaves_of(plan, id);
    const std::vector<double>& tree = s.number("leaves", "slot_tree", count);
    const std::vector<double>& leaf = s.number("leaves", "slot_leaf", count);
    const std::vector<double>& side = s.number("leaves", "slot_side", count);
    const Bytes state = values_of<std::uint8_t>(s.bytes("leaves", kLeafState), count, kLeafState);
    std::vector<std::vector<float>> vectors;
    for (const char* name : kLeafVectors)
      vectors.push_back(values_of<float>(s.bytes("leaves", name), 4 * count, name));
    const std::vector<float> drag = values_of<float>(s.bytes("leaves", kFlightDrag), count, kFlightDrag);
    const std::vector<float> theta = values_of<float>(s.bytes("leaves", kFlutterAngle), own, kFlutterAngle);
    const std::vector<float> rate = values_of<float>(s.bytes("leaves", kFlutterRate), own, kFlutterRate);
    for (std::size_t j = 0; j < count; ++j) {
      LeafRecord& r = records[{int(tree[j]), int(leaf[j])}];
      if (j < own) {
        r.theta = theta[j];
        r.theta_rate = rate[j];
      }
      if (state[j] == FW_LEAF_MOVED) continue;
      r.state = state[j];
      for (std::size_t v = 0; v < std::size(kLeafVectors); ++v) std::copy_n(&vectors[v][4 * j], 4, r.slot[v]);
      r.drag = drag[j];
      r.side = float(side[j]);
    }
  }
  return records;
}

StageState leaves_state(const std::vector<RunSnapshot>& parts, const SimulationPlan& plan,
                        const trees::Forest& own, int rank, int ranks) {
  const std::map<LeafKey, LeafRecord> records = leaf_records(parts, plan);
  // This rank's own columns (domain cell indices), and the cell column of a position as the kernel
  // leaves_leaving computes it (float arithmetic on the device grid's origin and cell size).
  const fluid::GridSpec& spec = plan.wind.spec;
  std::array<int, 2> lo{0, 0}, hi{spec.nx, spec.ny};
  if (ranks > 1) {
    const fluid::Block block = plan.decomposition.block(rank);
    for (int a = 0; a < 2; ++a) {
      lo[std::size_t(a)] = block.first[std::size_t(a)];
      hi[std::size_t(a)] = block.first[std::size_t(a)] + block.count[std::size_t(a)];
    }
  }
  const FwGrid g = spec.to_device();
  const auto mine = [&](const LeafRecord& r) {
    const int i = int(std::floor((r.slot[0][0] - g.origin[0]) / g.h));
    const int j = int(std::floor((r.slot[0][1] - g.origin[1]) / g.h));
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1];
  };
  const auto travels = [](const LeafRecord& r) {
    return r.state == FW_LEAF_FLYING || r.state == FW_LEAF_LANDED;
  };

  std::vector<const LeafRecord*> slots;
  std::vector<LeafKey> keys;
  std::vector<bool> moved;
  for (int k = 0; k < own.instance_count(); ++k)
    for (std::size_t i = 0; i < leaves_of(plan, own.id(k)); ++i) {
      const LeafKey key{own.id(k), int(i)};
      const auto at = records.find(key);
      if (at == records.end())
        throw std::invalid_argument(
            fmt::format("checkpoint: no part holds leaf {} of tree {}: it is another run's", i, own.id(k)));
      slots.push_back(&at->second);
      keys.push_back(key);
      moved.push_back(travels(at->second) && !mine(at->second));
    }
  const std::size_t own_count = slots.size();
  std::vector<bool> own_tree(plan.forest.instance_count(), false);
  for (int k = 0; k < own.instance_count(); ++k) own_tree[std::size_t(own.id(k))] = true;
  for (const auto& [key, record] : records)  // in (tree, leaf) order
    if (!own_tree[std::size_t(key.first)] && travels(record) && mine(record)) {
      slots.push_back(&record);
      keys.push_back(key);
      moved.push_back(false);
    }

  const std::size_t count = slots.size(), padded = count + FW_LANES, own_padded = own_count + FW_LANES;
  std::vector<std::uint8_t> state(padded, 0);
  std::vector<std::vector<float>> vectors(std::size(kLeafVectors), std::vector<float>(4 * padded, 0.0f));
  std::vector<float> drag(padded, 0.0f), theta(own_padded, 0.0f), rate(own_padded, 0.0f);
  StageState out;
  std::vector<double>& tree = out.numbers["slot_tree"];
  std::vector<double>& leaf = out.numbers["slot_leaf"];
  std::vector<double>& side = out.numbers["slot_side"];
  for (std::size_t j = 0; j < count; ++j) {
    const LeafRecord& r = *slots[j];
    state[j] = moved[j] ? std::uint8_t(FW_LEAF_MOVED) : r.state;
    for (std::size_t v = 0; v < std::size(kLeafVectors); ++v) std::copy_n(r.slot[v], 4, &vectors[v][4 * j]);
    drag[j] = r.drag;
    if (j < own_count) {
      theta[j] = r.theta;
      rate[j] = r.theta_rate;
    }
    tree.push_back(keys[j].first);
    leaf.push_back(keys[j].second);
    side.push_back(r.side);
  }
  // The counters' totals on rank 0 (a step's LEAVING and PAST_HALO start at 0).
  std::vector<std::int32_t> counters(FW_LEAF_COUNTERS, 0);
  if (rank == 0)
    for (const RunSnapshot& part : parts) {
      const std::vector<std::int32_t> c = values_of<std::int32_t>(
          stage_of(part, kLeavesStage).bytes("leaves", kLeafCounters), FW_LEAF_COUNTERS, kLeafCounters);
      for (const int n : {FW_LEAF_COUNT_SHED, FW_LEAF_COUNT_LANDED, FW_LEAF_COUNT_EXITED})
        counters[n] += c[n];
    }
  out.buffers[kLeafState] = bytes_of(state);
  for (std::size_t v = 0; v < std::size(kLeafVectors); ++v)
    out.buffers[kLeafVectors[v]] = bytes_of(vectors[v]);
  out.buffers[kFlightDrag] = bytes_of(drag);
  out.buffers[kFlutterAngle] = bytes_of(theta);
  out.buffers[kFlutterRate] = bytes_of(rate);
  out.buffers[kLeafCounters] = bytes_of(counters);
  out.numbers["slots"] = {double(count), double(count)};
  out.numbers["time"] = stage_of(parts.front(), kLeavesStage).number("leaves", "time", 1);
  return out;
}

}  // namespace

RunSnapshot redistribute_checkpoint(const std::vector<RunSnapshot>& parts, CoupledStep& coupled,
                                    const SimulationPlan& plan) {
  if (parts.empty()) throw std::invalid_argument("checkpoint: no parts to redistribute");
  const WindBlocks* blocks = coupled.blocks();
  const int rank = blocks ? blocks->world->rank() : 0, ranks = blocks ? blocks->world->size() : 1;
  const RunSnapshot& first = parts.front();
  RunSnapshot mine;
  mine.time = first.time;
  mine.step = first.step;
  mine.progress = first.progress;
  mine.state_keys = first.state_keys;
  mine.ranks = ranks;
  mine.decomposition = plan.decomposition.describe();
  mine.block = coupled.wind().block();
  const trees::Forest& own = coupled.own_forest();
  for (int k = 0; k < own.instance_count(); ++k) mine.tree_ids.push_back(own.id(k));
  mine.stages[kWindStage] = wind_state(parts, plan.wind.spec, mine.block);
  if (first.stages.count(kTreesStage) > 0)
    mine.stages[kTreesStage] = trees_state(parts, plan.forest, plan.coupling.dynamics, own);
  if (first.stages.count(kLeavesStage) > 0)
    mine.stages[kLeavesStage] = leaves_state(parts, plan, own, rank, ranks);
  return mine;
}

}  // namespace fw::host
