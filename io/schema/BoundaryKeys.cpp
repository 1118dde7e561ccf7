// The prose docs/scenario.md prints for each key of kBoundaryKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/BoundaryKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "boundaries.west", .description = "West face (x minimum)."},
    {.path = "boundaries.east", .description = "East face (x maximum)."},
    {.path = "boundaries.south", .description = "South face (y minimum)."},
    {.path = "boundaries.north", .description = "North face (y maximum)."},
    {.path = "boundaries.ground",
     .constraint = "no `auto`",
     .description =
         "Bottom face (z minimum). `rough` (the ground only): a rough wall, whose drag on the air is "
         "the log-law wall shear stress of `roughness_length` (see below the table)."},
    {.path = "boundaries.top", .constraint = "no `auto`, no `rough`", .description = "Top face (z maximum)."},
    {.path = "boundaries.roughness_length",
     .default_note = "`wind.profile.roughness_length` with a `log` profile, else `0.1`",
     .constraint = "below `domain.cell_size` / 2; only with `ground: rough`",
     .bounds_why = why::kRoughness,
     .description =
         "Aerodynamic roughness length z0 of a `rough` ground. The first fluid cell above the ground, and "
         "above terrain and other solid cells, feels the log law's wall shear stress `tau / rho = u*^2`, "
         "`u* = kappa \\|U\\| / ln((h / 2) / z0)`, with \\|U\\| that cell's horizontal speed at its centre, "
         "h / 2 above the surface (h = `domain.cell_size`, kappa = 0.41); so z0 must lie below h / 2. "
         "Davenport-Wieringa classes: 0.03 m open flat land, 0.1 m low crops, 0.25 m high crops, 0.5 m "
         "parkland, 1 m forest or suburbs. Under trees that the scenario resolves, give the floor's own "
         "roughness (grass, litter), not the forest's: the trees' drag is already modelled."},
};

}  // namespace

std::span<const KeyDocs> boundary_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
