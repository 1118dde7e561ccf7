// The forest section of a scenario (docs/scenario.md, "forest"): the coupling of trees and wind, the
// integrator, the drag law, storm damage, the species (io/settings/Species.hpp), the stands and the trees
// placed by hand. Defaults are the schema's (io/schema/ForestKeys.hpp).
//
//   for (const fw::io::Stand& stand : forest.stands) trees::place_stand(stand.layout, ...);
//   forest.species[forest.trees[0].species_index].name;
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "io/gis/TreeInventory.hpp"
#include "io/schema/ForestKeys.hpp"
#include "io/settings/Radians.hpp"
#include "io/settings/Species.hpp"
#include "trees/ForestLayout.hpp"
#include "trees/ModalIntegrator.hpp"

namespace fw::io {

/// A stand: trees placed by trees::place_stand (yaws uniform at random, scales uniform in [min, max]).
struct Stand {
  std::string species;      ///< a Species::name
  trees::StandSpec layout;  ///< layout.species is the index into ForestSettings::species; region in m
  /// The stand's own leaf area index, m^2/m^2, in (0, trees::StandDensity::kMaxLeafAreaIndex]; nullopt:
  /// the species' canopy.leaf_area_index on every crown.
  std::optional<double> leaf_area_index;
  int line = 0;                  ///< the stand entry's line in the file
  int leaf_area_index_line = 0;  ///< the line of leaf_area_index (the entry's when not given)
  /// The lines of scale.min and scale.max (of scale, or the entry, when not given).
  int scale_min_line = 0, scale_max_line = 0;
};

/// One tree placed by hand.
struct PlacedTreeSettings {
  std::string species;               ///< a Species::name
  int species_index = 0;             ///< into ForestSettings::species
  std::array<double, 3> position{};  ///< m; z from the file, else the ground (terrain) under (x, y)
  bool height_given = false;         ///< whether the file gave z
  /// Counter-clockwise about +z seen from above (the file's degrees, converted).
  double yaw_rad = radians(schema::key(schema::kForestKeys, "forest.trees[].yaw").number);
  double scale = schema::key(schema::kForestKeys, "forest.trees[].scale").number;  ///< > 0
  int scale_line = 0;  ///< the line of scale (of the entry when not given)
};

/// forest.damage (docs/damage.md): whether trees break or overturn, and what a failure does.
struct DamageSettings {
  /// Trees fail at their species' critical moments; every species has a strength then.
  bool enabled = schema::key(schema::kForestKeys, "forest.damage.enabled").flag;
  /// true: a failed tree falls and stops loading the air; false: failures are recorded, trees stay up.
  bool consequences = schema::key(schema::kForestKeys, "forest.damage.consequences").flag;
  /// The line of forest.damage.enabled (of forest.damage when not given; 0 without forest.damage).
  int line = 0;
};

/// forest.inventory (docs/gis.md): a field inventory's trees, read at load.
struct InventorySettings {
  std::filesystem::path file;  ///< resolved against the scenario folder
  InventoryColumns columns;
  /// The rows inside the domain's horizontal extent, in file order, x and y local (the site's origin taken
  /// off); `species` indexes ForestSettings::species.
  std::vector<InventoryTree> trees;
  /// The rows outside it (x and y as the file gives them): counted and reported, never placed.
  std::vector<InventoryTree> outside;
  /// Every tree row of the file.
  int rows() const { return int(trees.size() + outside.size()); }
};

struct ForestSettings {
  /// trees' drag returned to the wind
  bool two_way_coupling = schema::key(schema::kForestKeys, "forest.two_way_coupling").flag;
  /// The modal time step: exact for the force held over a step, or Diener's semi-implicit Euler.
  trees::ModalIntegrator integrator =
      schema::value_of(schema::kIntegratorWords, schema::kIntegrators,
                       schema::key(schema::kForestKeys, "forest.integrator").word);
  /// Diener's (2008, section 5.2) quadratic correction of the linear modal displacement on output frames.
  bool strong_wind_correction = schema::key(schema::kForestKeys, "forest.strong_wind_correction").flag;
  fluid::DragLaw drag_law;  ///< forest.drag_law (validated by the reader's bounds)
  DamageSettings damage;
  std::vector<Species> species;
  std::vector<Stand> stands;
  std::vector<PlacedTreeSettings> trees;
  std::optional<InventorySettings> inventory;
};

}  // namespace fw::io
