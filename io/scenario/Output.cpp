// output: the folder, the frames' interval and contents, the leaves in them, and the probes.
#include "io/scenario/Output.hpp"
#include "base/TextNumber.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace fw::io::reader {

namespace {

bool plain_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

/// Where output.directory's default names the scenario.
constexpr std::string_view kScenarioNamePlaceholder = "<scenario>";

void read_vtk(const Loader& loader, const Field& field, OutputSettings& output) {
  const Section<schema::kOutputKeys, "output.vtk"> map(loader, field);
  if (const auto wind = map.get<"wind">()) output.vtk_wind = loader.boolean(*wind);
  if (const auto trees = map.get<"trees">()) output.vtk_trees = loader.boolean(*trees);
  if (const auto every = map.get<"wind_every">()) output.vtk_wind_every = loader.integer(*every);
  if (const auto every = map.get<"trees_every">()) output.vtk_trees_every = loader.integer(*every);
  if (const auto fields = map.get<"fields">()) output.vtk_fields = loader.word_set(*fields);
}

void read_vdb(const Loader& loader, const Field& field, OutputSettings& output) {
  const Section<schema::kOutputKeys, "output.vdb"> map(loader, field);
  if (const auto enabled = map.get<"enabled">()) output.vdb_enabled = loader.boolean(*enabled);
  if (const auto grids = map.get<"grids">()) output.vdb_grids = loader.word_set(*grids);
  if (const auto every = map.get<"every">()) output.vdb_every = loader.integer(*every);
}

void read_leaves(const Loader& loader, const Field& field, OutputSettings& output) {
  const Section<schema::kOutputKeys, "output.leaves"> map(loader, field);
  if (const auto attached = map.get<"attached">()) {
    // A word (all, none) or a stride N >= 1.
    const Key& key = key_of(*attached);
    const std::vector<std::string> words = schema::words(key);
    const bool word = attached->node.IsScalar() &&
                      std::find(words.begin(), words.end(), attached->node.Scalar()) != words.end();
    if (word) {
      output.leaves_attached_stride =
          value(schema::kLeafStrideWords, schema::kLeafStrides, loader.word(*attached));
    } else {
      const auto stride =
          attached->node.IsScalar() ? base::parse_number<long long>(attached->node.Scalar()) : std::nullopt;
      if (!stride || *stride < key.lowest || *stride > key.highest) loader.expected(*attached);
      output.leaves_attached_stride = int(*stride);
    }
  }
  if (const auto vtk = map.get<"vtk">()) output.vtk_leaves = loader.boolean(*vtk);
  if (const auto every = map.get<"every">()) output.leaves_every = loader.integer(*every);
}

/// One item of output.probes, after the probes `earlier`.
Probe read_probe(const Loader& loader, const Field& item, const std::vector<Probe>& earlier,
                 const DomainSettings& domain) {
  const Section<schema::kOutputKeys, "output.probes[]"> map(loader, item);
  Probe probe;
  const Field name = map.require<"name">();
  probe.name = loader.text(name);
  const std::string what = schema::expected(key_of(name));
  if (!plain_name(probe.name)) loader.expected(name, what + " of letters, digits and _");
  for (const Probe& other : earlier)
    if (other.name == probe.name) loader.expected(name, what + " not used before");
  const Field position = map.require<"position">();
  probe.position = loader.vector<3>(position);
  const Vec3 top = domain.max_corner();
  for (int axis = 0; axis < 3; ++axis) {
    if (!inside(probe.position[axis], domain.origin[axis], top[axis])) {
      loader.expected(position, fmt::format("a position inside the domain [{}, {}] x [{}, {}] x [{}, {}] m",
                                            domain.origin[0], top[0], domain.origin[1], top[1],
                                            domain.origin[2], top[2]));
    }
  }
  return probe;
}

/// One item of output.statistics.regions, after the regions `earlier`: a box holding at least one cell
/// centre of the domain.
StatisticsRegion read_region(const Loader& loader, const Field& item,
                             const std::vector<StatisticsRegion>& earlier, const DomainSettings& domain) {
  const Section<schema::kOutputKeys, "output.statistics.regions[]"> map(loader, item);
  StatisticsRegion region;
  const Field name = map.require<"name">();
  region.name = loader.text(name);
  const std::string what = schema::expected(key_of(name));
  if (!plain_name(region.name)) loader.expected(name, what + " of letters, digits and _");
  if (region.name.starts_with(kStandRegionPrefix))
    loader.expected(name, what + " not starting with " + std::string(kStandRegionPrefix) +
                              " (the stands' regions are named so)");
  for (const StatisticsRegion& other : earlier)
    if (other.name == region.name) loader.expected(name, what + " not used before");
  const Field min = map.require<"min">(), max = map.require<"max">();
  region.min = loader.vector<2>(min);
  region.max = loader.vector<2>(max);
  const Vec3 top = domain.max_corner();
  for (int axis = 0; axis < 2; ++axis)
    if (!inside(region.min[axis], domain.origin[axis], top[axis]))
      loader.expected(min, fmt::format("a corner inside the domain [{}, {}] x [{}, {}] m", domain.origin[0],
                                       top[0], domain.origin[1], top[1]));
  for (int axis = 0; axis < 2; ++axis)
    if (!inside(region.max[axis], domain.origin[axis], top[axis]) || !(region.max[axis] > region.min[axis]))
      loader.expected(
          max, fmt::format("a corner inside the domain [{}, {}] x [{}, {}] m, east and north of "
                           "min [{}, {}]",
                           domain.origin[0], top[0], domain.origin[1], top[1], region.min[0], region.min[1]));
  if (domain.cell_size > 0.0)
    for (int axis = 0; axis < 2; ++axis) {
      const auto [first, end] = statistics_cells(region.min[axis], region.max[axis], domain.origin[axis],
                                                 domain.cell_size, domain.cells[axis]);
      if (end <= first)
        loader.expected(
            max, fmt::format("a box holding at least one cell centre (cells are {} m)", domain.cell_size));
    }
  return region;
}

/// The interval of a key that a run writes something at (frames, probe rows, checkpoints), in its range, and
/// short enough that the run writes at most bounds::kMaxRunSteps of them up to `end`: one a step at most.
double run_interval(const Loader& loader, const Field& field, double end) {
  const double interval = loader.number(field);
  if (!(end / interval <= schema::bounds::kMaxRunSteps)) {
    const std::string most = schema::number_text(schema::bounds::kMaxRunSteps);
    loader.expected(
        field, fmt::format("{} and at least time.end / {} = {:.3g} s (a run writes at most one a "
                           "step, and takes at most {} steps)",
                           schema::expected(key_of(field)), most, end / schema::bounds::kMaxRunSteps, most));
  }
  return interval;
}

}  // namespace

OutputSettings read_output(const Loader& loader, const Field& field, const std::string& scenario_name,
                           const DomainSettings& domain, double end) {
  OutputSettings output;
  const Section<schema::kOutputKeys, "output"> map(loader, field);
  std::string directory(schema::key(schema::kOutputKeys, "output.directory").word);
  if (const std::size_t at = directory.find(kScenarioNamePlaceholder); at != std::string::npos)
    directory.replace(at, kScenarioNamePlaceholder.size(), scenario_name);
  if (const auto given = map.get<"directory">()) directory = loader.text(*given);
  // Against the working directory, not the scenario folder: a run writes where it is started.
  output.directory = std::filesystem::absolute(std::filesystem::path(directory)).lexically_normal();
  if (const auto interval = map.get<"interval">()) output.interval = run_interval(loader, *interval, end);
  if (const auto probe_interval = map.get<"probe_interval">()) {
    output.probe_interval = loader.number_or_word(*probe_interval);
    if (output.probe_interval) run_interval(loader, *probe_interval, end);
  }
  if (const auto vtk = map.get<"vtk">()) read_vtk(loader, *vtk, output);
  if (const auto vdb = map.get<"vdb">()) read_vdb(loader, *vdb, output);
  if (const auto leaves = map.get<"leaves">()) read_leaves(loader, *leaves, output);
  if (const auto probes = map.get<"probes">())
    for (const Field& item : loader.items(*probes))
      output.probes.push_back(read_probe(loader, item, output.probes, domain));
  if (const auto statistics = map.get<"statistics">()) {
    const Section<schema::kOutputKeys, "output.statistics"> settings(loader, *statistics);
    StatisticsSettings& s = output.statistics.emplace();
    s.interval = run_interval(loader, settings.require<"interval">(), end);
    s.averaging = s.interval;
    if (const auto averaging = settings.get<"averaging">()) {
      if (const auto seconds = loader.number_or_word(*averaging)) {
        if (!(*seconds <= s.interval))
          loader.expected(*averaging, fmt::format("{} and at most interval ({} s)",
                                                  schema::expected(key_of(*averaging)), s.interval));
        s.averaging = *seconds;
      }
    }
    if (const auto every = settings.get<"sample_every">()) s.sample_every = loader.integer(*every);
    if (const auto every = settings.get<"series_every">()) s.series_every = loader.integer(*every);
    if (const auto stands = settings.get<"stands">()) s.stands = loader.boolean(*stands);
    if (const auto regions = settings.get<"regions">())
      for (const Field& item : loader.items(*regions))
        s.regions.push_back(read_region(loader, item, s.regions, domain));
  }
  if (const auto checkpoint = map.get<"checkpoint">()) {
    const Section<schema::kOutputKeys, "output.checkpoint"> settings(loader, *checkpoint);
    output.checkpoint_interval = run_interval(loader, settings.require<"interval">(), end);
    if (const auto keep = settings.get<"keep">()) output.checkpoints_kept = loader.integer(*keep);
  }
  return output;
}

}  // namespace fw::io::reader
