// forest: its switches and storm damage, then the species (io/scenario/Species.cpp), the stands and the
// single trees.
#include "io/scenario/Forest.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "io/scenario/Species.hpp"

namespace fw::io::reader {

namespace {

std::string horizontal_extent(const DomainSettings& domain) {
  const Vec3 top = domain.max_corner();
  return fmt::format("[{}, {}] x [{}, {}] m", domain.origin[0], top[0], domain.origin[1], top[1]);
}

int species_index(const Loader& loader, const Field& field, const std::vector<Species>& species) {
  const std::string name = loader.text(field);
  for (std::size_t i = 0; i < species.size(); ++i)
    if (species[i].name == name) return int(i);
  std::vector<std::string> names;
  for (const Species& s : species) names.push_back(s.name);
  const std::string what = schema::expected(key_of(field));
  loader.expected(
      field, names.empty() ? what + " (forest.species is empty)" : what + ", one of " + join(names, ", "));
}

Vec2 region_corner(const Loader& loader, const Field& field, const DomainSettings& domain) {
  const Vec2 corner = loader.vector<2>(field);
  const Vec3 top = domain.max_corner();
  if (!inside(corner[0], domain.origin[0], top[0]) || !inside(corner[1], domain.origin[1], top[1]))
    loader.expected(field,
                    "a point [x, y] inside the domain's horizontal extent " + horizontal_extent(domain));
  return corner;
}

Stand read_stand(const Loader& loader, const Field& item, const ForestSettings& forest,
                 const DomainSettings& domain, std::uint64_t seed) {
  const Section<schema::kForestKeys, "forest.stands[]"> map(loader, item);
  Stand stand;
  stand.line = stand.leaf_area_index_line = item.line;
  const Field species = map.require<"species">();
  stand.layout.species = species_index(loader, species, forest.species);
  stand.species = forest.species[stand.layout.species].name;

  const Section<schema::kForestKeys, "forest.stands[].region"> region(loader, map.require<"region">());
  const Vec2 min = region_corner(loader, region.require<"min">(), domain);
  const Field max_field = region.require<"max">();
  const Vec2 max = region_corner(loader, max_field, domain);
  if (!(max[0] > min[0]) || !(max[1] > min[1]))
    loader.expected(max_field,
                    fmt::format("a point north-east of min [{}, {}] (x and y both larger)", min[0], min[1]));
  stand.layout.min = {min[0], min[1]};
  stand.layout.max = {max[0], max[1]};

  stand.layout.layout = value(schema::kLayoutWords, schema::kLayouts,
                              std::string(schema::key(schema::kForestKeys, "forest.stands[].layout").word));
  if (const auto layout = map.get<"layout">())
    stand.layout.layout = value(schema::kLayoutWords, schema::kLayouts, loader.word(*layout));
  const Field spacing = map.require<"spacing">();
  stand.layout.spacing = loader.number(spacing);
  stand.layout.scale_min = schema::key(schema::kForestKeys, "forest.stands[].scale.min").number;
  stand.layout.scale_max = schema::key(schema::kForestKeys, "forest.stands[].scale.max").number;
  stand.scale_min_line = stand.scale_max_line = item.line;
  if (const auto scale_field = map.get<"scale">()) {
    const Section<schema::kForestKeys, "forest.stands[].scale"> scale(loader, *scale_field);
    stand.scale_min_line = stand.scale_max_line = scale_field->line;
    if (const auto low = scale.get<"min">()) {
      stand.layout.scale_min = loader.number(*low);
      stand.scale_min_line = low->line;
    }
    if (const auto high = scale.get<"max">()) {
      stand.layout.scale_max = loader.number(*high);
      stand.scale_max_line = high->line;
      if (stand.layout.scale_max < stand.layout.scale_min)
        loader.expected(*high, fmt::format("a number >= scale.min ({})", stand.layout.scale_min));
    } else if (stand.layout.scale_max < stand.layout.scale_min) {
      loader.expected(*scale.get<"min">(),
                      fmt::format("a number <= scale.max ({}, the default)", stand.layout.scale_max));
    }
  }
  if (const auto lai = map.get<"leaf_area_index">()) {
    stand.leaf_area_index = loader.number(*lai);
    stand.leaf_area_index_line = lai->line;
  }
  // Unless the file gives one: the global seed plus the stand's index.
  stand.layout.seed = seed + forest.stands.size();
  if (const auto seed = map.get<"seed">()) stand.layout.seed = loader.seed(*seed);
  try {
    stand.layout.validate();  // what is left to fail: too many trees for the region and spacing
  } catch (const std::invalid_argument& error) {
    loader.expected(spacing, fmt::format("a spacing the region can hold ({})", error.what()));
  }
  return stand;
}

PlacedTreeSettings read_tree(const Loader& loader, const Field& item, const ForestSettings& forest,
                             const DomainSettings& domain, const std::optional<TerrainSettings>& terrain) {
  const Section<schema::kForestKeys, "forest.trees[]"> map(loader, item);
  PlacedTreeSettings tree;
  tree.species_index = species_index(loader, map.require<"species">(), forest.species);
  tree.species = forest.species[tree.species_index].name;

  const Field position = map.require<"position">();
  if (!position.node.IsSequence() || (position.node.size() != 2 && position.node.size() != 3))
    loader.expected(position);
  for (std::size_t i = 0; i < position.node.size(); ++i)
    tree.position[i] = loader.component(position, i, key_of(position));
  const Vec3 top = domain.max_corner();
  if (!inside(tree.position[0], domain.origin[0], top[0]) ||
      !inside(tree.position[1], domain.origin[1], top[1]))
    loader.expected(position,
                    "a position inside the domain's horizontal extent " + horizontal_extent(domain));
  tree.height_given = position.node.size() == 3;
  if (tree.height_given && !inside(tree.position[2], domain.origin[2], top[2])) {
    loader.expected(loader.child(position, position.node[2], position.key + "[2]"),
                    fmt::format("a height inside the domain's [{}, {}] m", domain.origin[2], top[2]));
  }
  if (!tree.height_given) {
    // On the ground: the terrain surface, whose heights count from the domain floor.
    tree.position[2] = domain.origin[2];
    if (terrain) tree.position[2] += terrain->map->height_at(tree.position[0], tree.position[1]);
  }
  if (const auto yaw = map.get<"yaw">()) tree.yaw_rad = radians(loader.number(*yaw));
  tree.scale_line = item.line;
  if (const auto scale = map.get<"scale">()) {
    tree.scale = loader.number(*scale);
    tree.scale_line = scale->line;
  }
  return tree;
}

InventorySettings read_inventory(const Loader& loader, const Field& field, const ForestSettings& forest,
                                 const DomainSettings& domain, const SiteSettings* site) {
  const Section<schema::kForestKeys, "forest.inventory"> map(loader, field);
  InventorySettings inventory;
  inventory.file = loader.readable_file(map.require<"file">());
  if (const auto columns_field = map.get<"columns">()) {
    const Section<schema::kForestKeys, "forest.inventory.columns"> columns(loader, *columns_field);
    InventoryColumns& names = inventory.columns;
    for (auto [name, given] : {std::pair{&names.x, columns.get<"x">()},
                               {&names.y, columns.get<"y">()},
                               {&names.species, columns.get<"species">()},
                               {&names.height, columns.get<"height">()},
                               {&names.dbh, columns.get<"dbh">()},
                               {&names.crown_width, columns.get<"crown_width">()},
                               {&names.id, columns.get<"id">()}})
      if (given) *name = loader.text(*given);
  }
  std::vector<std::string> names;
  for (const Species& species : forest.species) names.push_back(species.name);
  // The file's own errors name its line and column (base::SourceError): they pass through.
  TreeInventory read = read_tree_inventory(inventory.file.string(), inventory.columns, names);
  const std::array<double, 2> origin =
      site ? std::array{site->origin[0], site->origin[1]} : std::array{0.0, 0.0};
  const Vec3 top = domain.max_corner();
  for (InventoryTree& tree : read.trees) {
    const double x = tree.x - origin[0], y = tree.y - origin[1];
    if (!inside(x, domain.origin[0], top[0]) || !inside(y, domain.origin[1], top[1])) {
      inventory.outside.push_back(std::move(tree));
      continue;
    }
    tree.x = x;
    tree.y = y;
    inventory.trees.push_back(std::move(tree));
  }
  return inventory;
}

}  // namespace

ForestSettings read_forest(const Loader& loader, const Field& field, const DomainSettings& domain,
                           const std::optional<TerrainSettings>& terrain, std::uint64_t seed) {
  const Section<schema::kForestKeys, "forest"> map(loader, field);
  ForestSettings forest;
  if (const auto coupling = map.get<"two_way_coupling">())
    forest.two_way_coupling = loader.boolean(*coupling);
  if (const auto integrator = map.get<"integrator">())
    forest.integrator = value(schema::kIntegratorWords, schema::kIntegrators, loader.word(*integrator));
  if (const auto correction = map.get<"strong_wind_correction">())
    forest.strong_wind_correction = loader.boolean(*correction);
  if (const auto law = map.get<"drag_law">()) {
    const Section<schema::kForestKeys, "forest.drag_law"> drag(loader, *law);
    if (const auto exponent = drag.get<"exponent">()) forest.drag_law.exponent = loader.number(*exponent);
    if (const auto speed = drag.get<"reference_speed">())
      forest.drag_law.reference_speed = loader.number(*speed);
  }
  if (const auto damage_field = map.get<"damage">()) {
    const Section<schema::kForestKeys, "forest.damage"> damage(loader, *damage_field);
    forest.damage.line = damage_field->line;
    if (const auto enabled = damage.get<"enabled">()) {
      forest.damage.enabled = loader.boolean(*enabled);
      forest.damage.line = enabled->line;
    }
    if (const auto consequences = damage.get<"consequences">())
      forest.damage.consequences = loader.boolean(*consequences);
  }
  if (const auto species = map.get<"species">())
    for (const Field& item : loader.items(*species))
      forest.species.push_back(read_species(loader, item, forest.species, seed));
  // Damage compares a tree's moments with its species' critical ones: every species needs its strength.
  for (std::size_t i = 0; forest.damage.enabled && i < forest.species.size(); ++i) {
    if (forest.species[i].strength) continue;
    const Field absent{YAML::Node(YAML::NodeType::Null), schema::item_path("forest.species[].strength", i),
                       forest.species[i].line};
    loader.fail(absent,
                fmt::format("{} expected (required: forest.damage.enabled is true on line {}), got nothing",
                            schema::expected(key_of(absent)), forest.damage.line));
  }
  if (const auto stands = map.get<"stands">())
    for (const Field& item : loader.items(*stands))
      forest.stands.push_back(read_stand(loader, item, forest, domain, seed));
  if (const auto trees = map.get<"trees">())
    for (const Field& item : loader.items(*trees))
      forest.trees.push_back(read_tree(loader, item, forest, domain, terrain));
  if (const auto inventory = map.get<"inventory">())
    forest.inventory = read_inventory(loader, *inventory, forest, domain,
                                      terrain && terrain->site ? &*terrain->site : nullptr);
  return forest;
}

}  // namespace fw::io::reader
