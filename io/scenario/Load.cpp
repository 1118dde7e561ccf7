// load_scenario: the file, its YAML, the top-level keys, then each section in the order the later ones need
// (the domain before the positions in it, the wind before the gusts that travel with it, ...).
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/Scenario.hpp"
#include "io/YamlDocuments.hpp"
#include "io/scenario/Domain.hpp"
#include "io/scenario/Events.hpp"
#include "io/scenario/Forest.hpp"
#include "io/scenario/Obstacles.hpp"
#include "io/scenario/Output.hpp"
#include "io/scenario/Reader.hpp"
#include "io/scenario/Solver.hpp"
#include "io/scenario/Terrain.hpp"
#include "io/scenario/Time.hpp"
#include "io/scenario/Wind.hpp"
#include "io/schema/TopLevelKeys.hpp"

namespace fw::io {

namespace {

std::string read_whole_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    throw ScenarioError(name, 0, "(file)", "a readable scenario file expected, got a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ScenarioError(
        name, 0, "(file)",
        fmt::format("a readable scenario file expected, got '{}' ({})", name,
                    std::filesystem::exists(file, error) ? std::strerror(errno) : "no such file"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(name, 0, "(file)", "a readable scenario file expected, got a read error");
  return text.str();
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) {
  using namespace reader;
  Scenario scenario;
  const std::string name = file.string();
  scenario.file = file;
  scenario.folder = std::filesystem::absolute(file).parent_path().lexically_normal();
  scenario.text = read_whole_file(file);

  std::vector<YAML::Node> documents;
  try {
    documents = load_yaml_documents(scenario.text);
  } catch (const YAML::Exception& error) {
    throw ScenarioError(name, error.mark.is_null() ? 1 : error.mark.line + 1, "(yaml)",
                        "valid YAML expected, got a syntax error: " + error.msg);
  }
  const Loader loader(name, scenario.folder);
  if (documents.size() > 1) {
    loader.fail(Field{documents[1], "(yaml)", line_of(documents[1], 1)},
                fmt::format("one YAML document expected, got {}", documents.size()));
  }
  const Field root{documents.empty() ? YAML::Node() : documents.front(), "", 1};
  if (!root.node.IsMap()) {
    std::vector<std::string> required;
    for (const Key* key : schema::children(""))
      if (key->required) required.emplace_back(key->path);
    loader.expected(root, "a map of scenario keys (" + join(required, ", ") + ", ...)");
  }
  const Section<schema::kTopLevelKeys, ""> top(loader, root);

  const Field scenario_name = top.require<"scenario">();
  scenario.name = loader.text(scenario_name);
  if (scenario.name.find_first_of("/\\") != std::string::npos || scenario.name == "." ||
      scenario.name == ".." ||
      std::any_of(scenario.name.begin(), scenario.name.end(), [](unsigned char c) { return c < 0x20; })) {
    // The name becomes a folder name (out/<scenario>).
    loader.expected(scenario_name, schema::expected(key_of(scenario_name)) +
                                       " usable as a folder name (no / or \\, not . or ..)");
  }
  if (const auto seed = top.get<"seed">()) scenario.seed = loader.seed(*seed);
  read_time(loader, top.require<"time">(), scenario.time);
  read_domain(loader, top.require<"domain">(), scenario.domain);
  // A raster places the run on its site and makes every later position local (io/scenario/Terrain.hpp).
  if (const auto terrain = top.get<"terrain">())
    scenario.terrain = read_terrain(loader, *terrain, scenario.domain);
  const auto boundaries = top.get<"boundaries">();
  if (boundaries)
    read_boundaries(loader, *boundaries, scenario.domain, scenario.boundaries,
                    scenario.ground_roughness_length);
  scenario.wind = read_wind(loader, top.require<"wind">(), scenario.time.end, scenario.domain,
                            scenario.boundaries, scenario.seed);
  if (boundaries)
    resolve_ground_roughness(loader, *boundaries, scenario.domain, scenario.boundaries, scenario.wind.profile,
                             scenario.ground_roughness_length);
  if (const auto events = top.get<"events">()) scenario.events = read_events(loader, *events, scenario.wind);
  if (const auto obstacles = top.get<"obstacles">()) scenario.obstacles = read_obstacles(loader, *obstacles);
  if (const auto forest = top.get<"forest">())
    scenario.forest = read_forest(loader, *forest, scenario.domain, scenario.terrain, scenario.seed);
  if (const auto solver = top.get<"solver">()) read_solver(loader, *solver, scenario.solver);
  const Field output = top.get<"output">().value_or(top.missing<"output">());  // defaults
  scenario.output = read_output(loader, output, scenario.name, scenario.domain, scenario.time.end);
  return scenario;
}

}  // namespace fw::io
