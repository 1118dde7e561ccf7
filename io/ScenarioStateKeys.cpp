#include "io/ScenarioStateKeys.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <map>
#include <string_view>

#include "base/Fnv1a.hpp"
#include "base/SourceError.hpp"
#include "io/YamlDocuments.hpp"

namespace fw::io {

namespace {

// What a resume may change (docs/design.md "Long runs"): a checkpoint of other blocks is redistributed, and a
// resume does not spin up (the checkpoint holds the wind its run spun up).
constexpr std::array<std::string_view, 5> kFreeKeys = {"scenario", "output", "time.end", "time.spin_up",
                                                       "domain.decomposition"};

bool free_key(const std::string& key) {
  return std::find(kFreeKeys.begin(), kFreeKeys.end(), key) != kFreeKeys.end();
}

// A node as data: scalars by their text, maps with their keys sorted, so that style and comments drop out.
std::string canonical(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence: {
      std::string out = "[";
      for (const YAML::Node& item : node) out += canonical(item) + ",";
      return out + "]";
    }
    case YAML::NodeType::Map: {
      std::map<std::string, std::string> sorted;
      for (const auto& entry : node) sorted[entry.first.Scalar()] = canonical(entry.second);
      std::string out = "{";
      for (const auto& [key, value] : sorted) out += key + ":" + value + ",";
      return out + "}";
    }
    default:
      return "~";
  }
}

std::uint64_t hash_of(const YAML::Node& node) {
  const std::string text = canonical(node);
  base::Fnv1a hash;
  hash.bytes(text.data(), text.size());
  return hash.digest();
}

int line_of(const YAML::Node& key) {
  return key.Mark().line + 1;
}

}  // namespace

std::vector<StateKey> state_keys(const std::string& scenario_text) {
  std::vector<StateKey> keys;
  const YAML::Node root = load_yaml(scenario_text);
  if (!root.IsMap()) return keys;
  for (const auto& top : root) {
    const std::string name = top.first.Scalar();
    if (top.second.IsMap()) {
      for (const auto& entry : top.second) {
        const std::string key = name + "." + entry.first.Scalar();
        if (!free_key(name) && !free_key(key))
          keys.push_back({key, line_of(entry.first), hash_of(entry.second)});
      }
    } else if (!free_key(name)) {
      keys.push_back({name, line_of(top.first), hash_of(top.second)});
    }
  }
  return keys;
}

void require_same_state(const std::vector<StateKey>& saved, const std::vector<StateKey>& current,
                        const std::string& file) {
  static constexpr const char* kExpected =
      "the value the checkpoint was written with (a resume may change only time.end and output)";
  const auto find = [](const std::vector<StateKey>& keys, const std::string& key) {
    return std::find_if(keys.begin(), keys.end(), [&](const StateKey& k) { return k.key == key; });
  };
  for (const StateKey& now : current) {
    const auto before = find(saved, now.key);
    if (before == saved.end()) throw base::SourceError(file, now.line, now.key, kExpected, "a key it lacked");
    if (before->hash != now.hash)
      throw base::SourceError(file, now.line, now.key, kExpected, "a changed value");
  }
  for (const StateKey& before : saved)
    if (find(current, before.key) == current.end())
      throw base::SourceError(file, 0, before.key, kExpected, "no value: the key was removed");
}

}  // namespace fw::io
