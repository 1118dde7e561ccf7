#include "host/app/OutputWriters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "io/writers/DamageCsvWriter.hpp"
#include "io/writers/LeavesVtkWriter.hpp"
#include "io/writers/ProbesWriter.hpp"
#include "io/writers/TreesVtkWriter.hpp"
#include "io/writers/WindVdbWriter.hpp"
#include "io/writers/WindVtkWriter.hpp"
#include "viz/ViewScriptWriter.hpp"

namespace fw::host {

namespace {

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

io::RunManifest manifest_of(const SimulationPlan& plan, const DeviceInfo& device) {
  io::RunManifest m;
  m.version = FORESTWIND_VERSION;
  m.scenario_name = plan.scenario.name;
  m.scenario_file_name = plan.scenario.file_name;
  m.scenario_text = plan.scenario.text;
  m.seed = plan.scenario.seed;
  m.site = plan.scenario.site;
  m.device = device.device_name;
  m.platform = device.platform_name;
  m.grid = {plan.wind.spec.nx, plan.wind.spec.ny, plan.wind.spec.nz};
  m.cell_size = plan.wind.spec.h;
  m.trees = plan.forest.instance_count();
  m.species = plan.species;
  m.two_way_coupling = plan.two_way_coupling;
  m.leaves = plan.leaf_count > 0;
  m.damage = plan.coupling.damage.enabled && plan.forest.instance_count() > 0;
  m.ranks = plan.decomposition.ranks();
  m.decomposition = plan.decomposition.describe();
  return m;
}

// This rank's wind writer over ranks: its block's solids and canopy, its own cells as the piece, and every
// rank's piece for the .pvti.
std::unique_ptr<io::FrameWriter> wind_pieces(const SimulationPlan& plan,
                                             const std::filesystem::path& directory,
                                             const OutputShare& share) {
  const fluid::GridSpec& spec = plan.wind.spec;
  const auto cut = [&](const auto& whole) {
    return whole.empty() ? std::decay_t<decltype(whole)>{} : block_of(whole, spec.nx, spec.ny, share.block);
  };
  io::WindPieces pieces;
  pieces.rank = share.rank;
  const fluid::Block own = share.decomposition.block(share.rank);
  pieces.piece = {share.block.halo_low, own.count, own.first};  // its cells lie after the low halo
  for (int r = 0; r < share.ranks; ++r) {
    const fluid::Block b = share.decomposition.block(r);
    pieces.extents.push_back(
        {b.first[0], b.first[0] + b.count[0], b.first[1], b.first[1] + b.count[1], 0, spec.nz});
  }
  return std::make_unique<io::WindVtkWriter>(directory, share.local, cut(plan.wind.solid),
                                             cut(plan.canopy_density), plan.output.vtk_fields,
                                             std::move(pieces), plan.scenario.site);
}

// What damage.csv says of each tree that never changes: its place, size and critical moments (its species'
// at scale 1, grown by its scale: lengths s, the critical moments s^3).
std::vector<io::DamageTree> damage_trees(const SimulationPlan& plan) {
  std::vector<io::DamageTree> trees;
  const trees::Forest& forest = plan.forest;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& instance = forest.instances()[std::size_t(k)];
    const SpeciesStrength& strength = *plan.strengths.at(std::size_t(instance.species));
    const double s = instance.scale, volume_scale = s * s * s;
    trees.push_back({forest.id(k), plan.species[std::size_t(instance.species)].species, instance.position.x(),
                     instance.position.y(), s * strength.height, s * strength.dbh,
                     volume_scale * strength.critical.breaking.front(),
                     volume_scale * strength.critical.overturning,
                     plan.tree_ids.empty() ? std::string() : plan.tree_ids.at(std::size_t(forest.id(k)))});
  }
  return trees;
}

// The trees frames' field data: the site, and the inventory's id of every tree of the whole forest.
io::TreesFieldData trees_field_data(const SimulationPlan& plan) {
  return {plan.scenario.site, plan.tree_ids};
}

// A writer that takes every `every`-th frame only.
std::unique_ptr<io::FrameWriter> taking_every(std::unique_ptr<io::FrameWriter> writer, int every) {
  writer->set_every(every);
  return writer;
}

}  // namespace

viz::ViewScriptSettings view_settings(const SimulationPlan& plan) {
  const fluid::GridSpec& spec = plan.wind.spec;
  viz::ViewScriptSettings v;
  v.scenario_name = plan.scenario.name;
  v.origin = spec.origin;
  v.size = {spec.nx * spec.h, spec.ny * spec.h, spec.nz * spec.h};
  v.cell_size = spec.h;
  v.slice_height = viz::default_slice_height(v.origin, v.size, v.cell_size);
  // The speed scale starts at 0 to the ambient wind's peak over the run (at its reference height).
  if (plan.inputs.ambient_wind) {
    constexpr int kSamples = 256;
    double peak = 0.0;  // m/s
    for (int n = 0; n <= kSamples; ++n) {
      const std::array<double, 3> u = plan.inputs.ambient_wind(plan.end_time * n / kSamples);
      peak = std::max(peak, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
    }
    if (peak > 0.0) v.speed_range = std::array<double, 2>{0.0, peak};
  }
  v.wind = plan.output.vtk_wind;
  v.trees = plan.output.vtk_trees && plan.forest.instance_count() > 0;
  v.leaves = plan.output.vtk_leaves && plan.leaf_count > 0;
  return v;
}

bool vdb_holds_leaves(const SimulationPlan& plan) {
  return plan.output.vdb_enabled && plan.leaf_count > 0 && contains(plan.output.vdb_grids, "leaves");
}

std::vector<std::unique_ptr<io::FrameWriter>> make_writers(const SimulationPlan& plan,
                                                           const std::filesystem::path& directory,
                                                           const DeviceInfo& device,
                                                           const std::vector<int>& tip_trees,
                                                           const OutputShare* share) {
  const io::OutputSettings& out = plan.output;
  const bool trees_present = plan.forest.instance_count() > 0;
  const bool leaves_present = plan.leaf_count > 0;
  const bool damage = plan.coupling.damage.enabled && trees_present;
  std::vector<std::unique_ptr<io::FrameWriter>> writers;
  if (share != nullptr) {
    if (out.vtk_wind)
      writers.push_back(taking_every(wind_pieces(plan, directory, *share), out.vtk_wind_every));
    if (out.vtk_trees && trees_present)
      writers.push_back(taking_every(
          std::make_unique<io::TreesVtkWriter>(directory, *share->own_forest, damage, share->rank,
                                               share->ranks, trees_field_data(plan)),
          out.vtk_trees_every));
    if (out.vtk_leaves && leaves_present)
      writers.push_back(taking_every(
          std::make_unique<io::LeavesVtkWriter>(directory, share->rank, share->ranks), out.leaves_every));
    if (share->rank != 0) return writers;
  }
  writers.insert(writers.begin(), std::make_unique<io::ManifestWriter>(directory, manifest_of(plan, device)));
  if (out.vtk_wind && share == nullptr) {
    writers.push_back(taking_every(
        std::make_unique<io::WindVtkWriter>(directory, plan.wind.spec, plan.wind.solid, plan.canopy_density,
                                            out.vtk_fields, std::nullopt, plan.scenario.site),
        out.vtk_wind_every));
  }
  if (out.vtk_trees && trees_present && share == nullptr)
    writers.push_back(taking_every(
        std::make_unique<io::TreesVtkWriter>(directory, plan.forest, damage, trees_field_data(plan)),
        out.vtk_trees_every));
  if (out.vtk_leaves && leaves_present && share == nullptr)
    writers.push_back(taking_every(std::make_unique<io::LeavesVtkWriter>(directory), out.leaves_every));
  if (out.vdb_enabled) {
    writers.push_back(taking_every(
        std::make_unique<io::WindVdbWriter>(directory, plan.wind.spec, plan.wind.solid,
                                            contains(out.vdb_grids, "vel"), contains(out.vdb_grids, "speed"),
                                            vdb_holds_leaves(plan), plan.scenario.site),
        out.vdb_every));
  }
  std::vector<std::string> probe_names;
  for (const auto& probe : out.probes) probe_names.push_back(probe.name);
  if (!probe_names.empty() || !tip_trees.empty())
    writers.push_back(
        std::make_unique<io::ProbesWriter>(directory, std::move(probe_names), tip_trees,
                                           io::CountColumns{leaves_present, plan.coupling.damage.enabled}));
  if (damage) writers.push_back(std::make_unique<io::DamageCsvWriter>(directory, damage_trees(plan)));
  writers.push_back(std::make_unique<viz::ViewScriptWriter>(directory, view_settings(plan)));
  return writers;
}

}  // namespace fw::host
