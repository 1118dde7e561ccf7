// The keys of a scenario's forest section but its species' (io/schema/SpeciesKeys.hpp): the coupling of trees
// and wind, the integrator, the drag law, storm damage, the items of forest.stands and forest.trees, and the
// forest inventory.
//
//   schema::key(schema::kForestKeys, "forest.stands[].layout").word;   // "poisson"
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// ForestKeys.cpp (forest_docs).
#pragma once

#include <span>
#include <string_view>

#include "fluid/DragLaw.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"
#include "trees/ForestLayout.hpp"
#include "trees/ModalIntegrator.hpp"
#include "trees/StandDensity.hpp"

namespace fw::io::schema {

inline constexpr std::string_view kIntegratorWords[] = {"exact", "semi_implicit"};
inline constexpr trees::ModalIntegrator kIntegrators[] = {trees::ModalIntegrator::exact,
                                                          trees::ModalIntegrator::semi_implicit};

inline constexpr std::string_view kLayoutWords[] = {"poisson", "grid"};
inline constexpr trees::StandLayout kLayouts[] = {trees::StandLayout::poisson, trees::StandLayout::grid};

inline constexpr Key kForestKeys[] = {
    {.path = "forest.two_way_coupling", .type = Type::boolean, .flag = true},
    {.path = "forest.integrator", .type = Type::word, .words = kIntegratorWords, .word = "exact"},
    {.path = "forest.strong_wind_correction", .type = Type::boolean, .flag = true},
    {.path = "forest.drag_law"},
    {.path = "forest.drag_law.exponent",
     .type = Type::number,
     .at_least = fluid::DragLaw::kLowestExponent,
     .at_most = 0.0,
     .number = fluid::DragLaw{}.exponent},
    {.path = "forest.drag_law.reference_speed",
     .type = Type::number,
     .unit = "m/s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxWindSpeed,
     .number = fluid::DragLaw{}.reference_speed},
    {.path = "forest.damage"},
    {.path = "forest.damage.enabled", .type = Type::boolean, .flag = false},
    {.path = "forest.damage.consequences", .type = Type::boolean, .flag = true},
    {.path = "forest.species", .type = Type::list, .noun = "a list of species"},
    {.path = "forest.stands", .type = Type::list, .noun = "a list of stands"},
    {.path = "forest.trees", .type = Type::list, .noun = "a list of trees"},
    {.path = "forest.inventory"},
    {.path = "forest.inventory.file", .type = Type::file, .required = true, .noun = "a file path (CSV)"},
    {.path = "forest.inventory.columns"},
    {.path = "forest.inventory.columns.x", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.y", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.species", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.height", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.dbh", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.crown_width", .type = Type::text, .noun = "a column name"},
    {.path = "forest.inventory.columns.id", .type = Type::text, .noun = "a column name"},
    // forest.stands[]
    {.path = "forest.stands[].species", .type = Type::text, .required = true, .noun = "a species name"},
    {.path = "forest.stands[].region", .required = true},
    {.path = "forest.stands[].region.min",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "forest.stands[].region.max",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "forest.stands[].layout", .type = Type::word, .words = kLayoutWords, .word = "poisson"},
    {.path = "forest.stands[].spacing",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "forest.stands[].scale"},
    {.path = "forest.stands[].scale.min",
     .type = Type::number,
     .at_least = bounds::kMinTreeScale,
     .at_most = bounds::kMaxTreeScale,
     .number = 1.0},
    {.path = "forest.stands[].scale.max",
     .type = Type::number,
     .at_least = bounds::kMinTreeScale,
     .at_most = bounds::kMaxTreeScale,
     .number = 1.0},
    {.path = "forest.stands[].seed", .type = Type::seed},
    {.path = "forest.stands[].leaf_area_index",
     .type = Type::number,
     .unit = "m^2/m^2",
     .bound = Bound::positive,
     .at_most = trees::StandDensity::kMaxLeafAreaIndex},
    // forest.trees[]
    {.path = "forest.trees[].species", .type = Type::text, .required = true, .noun = "a species name"},
    {.path = "forest.trees[].position",
     .type = Type::point2_or_3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "forest.trees[].yaw",
     .type = Type::number,
     .unit = "degrees",
     .at_least = -bounds::kMaxYawDeg,
     .at_most = bounds::kMaxYawDeg,
     .number = 0.0},
    {.path = "forest.trees[].scale",
     .type = Type::number,
     .at_least = bounds::kMinTreeScale,
     .at_most = bounds::kMaxTreeScale,
     .number = 1.0},
};

/// The prose of each key of kForestKeys (ForestKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by
/// its path.
std::span<const KeyDocs> forest_docs();

}  // namespace fw::io::schema
