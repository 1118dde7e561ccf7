// The prose docs/scenario.md prints for each key of kForestKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/ForestKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "forest.two_way_coupling",
     .description =
         "With `true`, the drag of the trees' branches and leaves slows the wind on the grid. With "
         "`false`, the trees feel the wind but do not affect it."},
    {.path = "forest.integrator",
     .description = "The modal time step. `exact` solves each mode's damped oscillator exactly for the force "
                    "held over the step, stable at any dt. `semi_implicit` is Diener's semi-implicit Euler, "
                    "stable only while dt² ω² + 2 γ dt < 4 for every mode; a run whose dt breaks that stops "
                    "with exit code 1 at that step. Modal species only (`forest.species[].dynamics`)."},
    {.path = "forest.strong_wind_correction",
     .description = "With `true`, output frames show each tree with Diener's (2008, §5.2) quadratic "
                    "correction of its linear modal displacement, fitted per species and mode: a linear mode "
                    "moves every node along a straight line, which stretches the branches as the tree bends "
                    "far, and the correction keeps branch lengths nearly constant under strong wind. It "
                    "changes the written geometry only; the modal dynamics stay linear. With `false`, frames "
                    "show the linear displacement. Modal species only (`forest.species[].dynamics`)."},
    {.path = "forest.drag_law",
     .default_note = "a constant drag coefficient",
     .description = "How the drag coefficients of every species (branches and foliage) vary with the local "
                    "wind speed: C_D(\\|u\\|) = C_D (max(\\|u\\|, 0.1 U_ref) / U_ref)^exponent, the species' "
                    "coefficients holding at U_ref. Leaves and twigs streamline in strong wind (Vogel 1984); "
                    "the air's canopy drag and the trees' modal forces follow the same law."},
    {.path = "forest.drag_law.exponent",
     .bounds_why = why::kVogel,
     .description = "The Vogel exponent: 0 keeps the coefficient constant; plants measure 0 to -4/3 "
                    "(strongly reconfiguring ones)."},
    {.path = "forest.drag_law.reference_speed",
     .bounds_why = why::kWindSpeed,
     .description = "U_ref, where the species' drag coefficients hold."},
    {.path = "forest.damage",
     .default_note = "no damage",
     .description = "Storm damage (docs/damage.md): which trees break or overturn in the wind."},
    {.path = "forest.damage.enabled",
     .description =
         "With `true`, a tree fails when the wind's bending moment reaches its species' critical moment for "
         "stem breakage, M_b = f_knot MOR pi d^3 / 32 at the stem's weakest section, or for overturning, "
         "M_o = C_reg x green density x stem volume (ForestGALES); every species then needs a `strength`. "
         "With `false`, no tree fails."},
    {.path = "forest.damage.consequences",
     .description = "With `true`, a failed tree falls: it no longer loads the air or moves in the wind. With "
                    "`false`, failures are recorded and every tree stays up, so that the wind is the one "
                    "without damage."},
    {.path = "forest.species", .description = "Tree species."},
    {.path = "forest.stands", .description = "Stands: trees scattered over a region."},
    {.path = "forest.trees", .description = "Single trees placed by hand."},
    {.path = "forest.inventory",
     .default_note = "none",
     .description = "The trees of a forest inventory (docs/gis.md): each row one tree, its species' template "
                    "fitted to its measured height and dbh, standing on the ground at its x and y."},
    {.path = "forest.inventory.file",
     .allowed = "a readable CSV with a header: x, y (in the site's CRS; without a site, the run's "
                "coordinates), species, height (m), dbh (m), optionally crown_width (m) and id; relative to "
                "the scenario's folder",
     .description = "The inventory."},
    {.path = "forest.inventory.columns",
     .default_note = "each column by its own name",
     .description = "The header's names of the columns, where the file names them otherwise (lidR writes "
                    "heights as `Z`, say)."},
    {.path = "forest.inventory.columns.x", .default_note = "`x`", .description = "Easting column."},
    {.path = "forest.inventory.columns.y", .default_note = "`y`", .description = "Northing column."},
    {.path = "forest.inventory.columns.species",
     .default_note = "`species`",
     .description = "Species column: names from `forest.species`."},
    {.path = "forest.inventory.columns.height",
     .default_note = "`height`",
     .description = "Height column, m."},
    {.path = "forest.inventory.columns.dbh",
     .default_note = "`dbh`",
     .description = "Column of the stem's diameter 1.3 m above its base, m."},
    {.path = "forest.inventory.columns.crown_width",
     .default_note = "`crown_width` (optional in the file)",
     .description = "Crown width column, m; read and checked (> 0, or empty). The crowns are the "
                    "template's, scaled with the height: the width is not used yet."},
    {.path = "forest.inventory.columns.id",
     .default_note = "`id` (optional in the file: the row's line number without it)",
     .description = "Tree id column, any text: carried into the trees frames and `damage.csv`."},
    {.path = "forest.stands[].species",
     .allowed = "the name of a species in `forest.species`",
     .description = "Species of every tree in the stand."},
    {.path = "forest.stands[].region", .description = "Horizontal rectangle the trees stand in."},
    {.path = "forest.stands[].region.min",
     .allowed = "inside the domain's horizontal extent, edges included",
     .bounds_why = why::kEarth,
     .description = "South-west corner."},
    {.path = "forest.stands[].region.max",
     .allowed = "inside the domain's horizontal extent; x and y both larger than `min`",
     .bounds_why = why::kEarth,
     .description = "North-east corner."},
    {.path = "forest.stands[].layout",
     .description = "`poisson`: a natural stand, with no two trees closer than `spacing` and no gaps much "
                    "wider than twice `spacing`. `grid`: rows and columns `spacing` apart, centred in the "
                    "region."},
    {.path = "forest.stands[].spacing",
     .constraint = "`2 (width / spacing + 1) (depth / spacing + 1)`, a bound on the trees the region holds, "
                   "at most {0}, where width and depth are the region's extents",
     .limits = {double(trees::kMaxTreesPerStand)},
     .bounds_why = why::kEarth,
     .description = "Minimum distance between trees (`poisson`) or exact distance (`grid`)."},
    {.path = "forest.stands[].scale",
     .default_note = "`{min: 1, max: 1}`",
     .description =
         "Range of uniform tree scales. A tree scaled by s is s times as tall, and its frequencies "
         "are divided by s."},
    {.path = "forest.stands[].scale.min",
     .constraint = "<= `scale.max`",
     .bounds_why = why::kTreeScale,
     .description = "Smallest scale."},
    {.path = "forest.stands[].scale.max",
     .constraint = ">= `scale.min`",
     .bounds_why = why::kTreeScale,
     .description = "Largest scale."},
    {.path = "forest.stands[].seed",
     .default_note = "global `seed` + stand index",
     .description = "Seed for positions, yaws and scales. The same seed gives the same stand."},
    {.path = "forest.stands[].leaf_area_index",
     .default_note = "none: the species' `canopy.leaf_area_index` on every crown",
     .bounds_why = why::kLeafAreaIndex,
     .description =
         "The stand's leaf area index as measured in the field: one-sided leaf area of the stand's trees "
         "per m^2 of its region. The stand's trees then carry the species' foliage scaled so that their "
         "leaf area (whole crowns) over the region's area is this figure, in place of the species' "
         "`canopy.leaf_area_index`, which stays for the species' other stands and single trees. Their "
         "leaves are scaled with the foliage. The upper limit is the largest leaf area index of the "
         "field measurements Asner, Scurlock & Hicke (2003) kept after their outlier analysis."},
    {.path = "forest.trees[].species",
     .allowed = "the name of a species in `forest.species`",
     .description = "Species of the tree."},
    {.path = "forest.trees[].position",
     .allowed = "inside the domain, edges included",
     .bounds_why = why::kEarth,
     .description = "Position of the root. Without z, the tree stands on the ground: the terrain surface, "
                    "else the domain floor."},
    {.path = "forest.trees[].yaw",
     .bounds_why = why::kYaw,
     .description = "Rotation about +z, counter-clockwise seen from above."},
    {.path = "forest.trees[].scale",
     .bounds_why = why::kTreeScale,
     .description = "Uniform scale of the species' skeleton."},
};

}  // namespace

std::span<const KeyDocs> forest_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
