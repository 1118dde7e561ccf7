// The prose docs/scenario.md prints for each key of kDomainKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/DomainKeys.hpp"

#include "io/schema/BoundReasons.hpp"

#include "fluid/GridSpec.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "domain.origin",
     .bounds_why = why::kEarth,
     .description = "The minimum (south-west, bottom) corner. Its z is the domain floor. With a "
                    "`terrain.raster` it is in the raster's CRS, x and y of the corner and the floor's "
                    "elevation, and the scenario's other positions count from it (docs/gis.md)."},
    {.path = "domain.size",
     .constraint = "each a whole multiple of `cell_size` (to {0} relative), at least one cell; z at most {1} "
                   "(the troposphere, where weather happens, ends below 20 km)",
     .limits = {kCellMultipleTolerance, bounds::kMaxAirHeight},
     .bounds_why = why::kEarth,
     .description = "Extent along x, y and z."},
    {.path = "domain.cell_size",
     .constraint = "(nx + 1)(ny + 1)(nz + 1) <= {0}",
     .limits = {double(fluid::GridSpec::kMaxFaces)},
     .bounds_why = why::kEarth,
     .description = "Cell edge h. The grid has `size / cell_size` cells along each axis."},
    {.path = "domain.decomposition",
     .default_note = "chosen: the split of the ranks that exchanges the fewest halo cells",
     .constraint = "whole numbers whose product is the number of ranks (`mpirun -np`)",
     .bounds_why = why::kBlocks,
     .description = "Blocks along x and y of a run over MPI ranks, one block a rank (docs/parallel.md). "
                    "Ignored by a run in one process."},
};

}  // namespace

std::span<const KeyDocs> domain_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
