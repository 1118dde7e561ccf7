// LeafStages::share_of: the leaves' share of a checkpoint saved over other blocks (LeafStages.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "host/stages/LeafStages.hpp"
#include "host/stages/SavedStateNames.hpp"

namespace fw::host {

namespace {

using namespace saved;

// One leaf of the checkpoint: where it is (its live slot) and its flutter (its tree's slot).
struct LeafRecord {
  std::uint8_t state = FW_LEAF_ATTACHED;
  float slot[std::size(kLeafVectors)][4] = {};  // saved::kLeafVectors
  float drag = 0.0f, side = 0.0f, theta = 0.0f, theta_rate = 0.0f;
};

using LeafKey = std::pair<int, int>;  // tree id, leaf index on its tree

std::map<LeafKey, LeafRecord> leaf_records(const std::vector<SavedShare>& parts,
                                           const std::function<std::size_t(int)>& leaves_of) {
  std::map<LeafKey, LeafRecord> records;
  for (const SavedShare& part : parts) {
    const StageState& s = *part.state;
    const std::vector<double>& slots = s.number("leaves", "slots", 2);
    const std::size_t count = std::size_t(slots[0]);
    std::size_t own = 0;
    for (const int id : part.tree_ids) own += leaves_of(id);
    const std::vector<double>& tree = s.number("leaves", "slot_tree", count);
    const std::vector<double>& leaf = s.number("leaves", "slot_leaf", count);
    const std::vector<double>& side = s.number("leaves", "slot_side", count);
    const std::vector<std::uint8_t> state =
        saved_values<std::uint8_t>(s.bytes("leaves", kLeafState), count, kLeafState);
    std::vector<std::vector<float>> vectors;
    for (const char* name : kLeafVectors)
      vectors.push_back(saved_values<float>(s.bytes("leaves", name), 4 * count, name));
    const std::vector<float> drag = saved_values<float>(s.bytes("leaves", kFlightDrag), count, kFlightDrag);
    const std::vector<float> theta =
        saved_values<float>(s.bytes("leaves", kFlutterAngle), own, kFlutterAngle);
    const std::vector<float> rate = saved_values<float>(s.bytes("leaves", kFlutterRate), own, kFlutterRate);
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

}  // namespace

StageState LeafStages::share_of(const std::vector<SavedShare>& parts, const fluid::GridSpec& spec,
                                const BlockArray& block, const trees::Forest& own, int tree_count,
                                const std::function<std::size_t(int)>& leaves_of, bool takes_counters) {
  if (parts.empty()) throw std::invalid_argument("checkpoint: no parts of the leaves to take a share of");
  const std::map<LeafKey, LeafRecord> records = leaf_records(parts, leaves_of);
  // This rank's own columns, and the cell column of a position as the kernel leaves_leaving computes it
  // (float arithmetic on the device grid's origin and cell size).
  const OwnColumns columns = own_columns(block);
  const FwGrid g = spec.to_device();
  const auto mine = [&](const LeafRecord& r) {
    return columns.holds(int(std::floor((r.slot[0][0] - g.origin[0]) / g.h)),
                         int(std::floor((r.slot[0][1] - g.origin[1]) / g.h)));
  };
  const auto travels = [](const LeafRecord& r) {
    return r.state == FW_LEAF_FLYING || r.state == FW_LEAF_LANDED;
  };

  std::vector<const LeafRecord*> slots;
  std::vector<LeafKey> keys;
  std::vector<bool> moved;
  for (int k = 0; k < own.instance_count(); ++k)
    for (std::size_t i = 0; i < leaves_of(own.id(k)); ++i) {
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
  std::vector<bool> own_tree(std::size_t(tree_count), false);
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
  // The counters' totals (a step's LEAVING and PAST_HALO start at 0).
  std::vector<std::int32_t> counters(FW_LEAF_COUNTERS, 0);
  if (takes_counters)
    for (const SavedShare& part : parts) {
      const std::vector<std::int32_t> c = saved_values<std::int32_t>(
          part.state->bytes("leaves", kLeafCounters), FW_LEAF_COUNTERS, kLeafCounters);
      for (const int n : {FW_LEAF_COUNT_SHED, FW_LEAF_COUNT_LANDED, FW_LEAF_COUNT_EXITED})
        counters[n] += c[n];
    }
  out.buffers[kLeafState] = saved_bytes(state);
  for (std::size_t v = 0; v < std::size(kLeafVectors); ++v)
    out.buffers[kLeafVectors[v]] = saved_bytes(vectors[v]);
  out.buffers[kFlightDrag] = saved_bytes(drag);
  out.buffers[kFlutterAngle] = saved_bytes(theta);
  out.buffers[kFlutterRate] = saved_bytes(rate);
  out.buffers[kLeafCounters] = saved_bytes(counters);
  out.numbers["slots"] = {double(count), double(count)};
  out.numbers["time"] = parts.front().state->number("leaves", "time", 1);
  return out;
}

}  // namespace fw::host
