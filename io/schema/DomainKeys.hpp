// The keys of a scenario's domain section: the wind grid's corner, extent, cell size and blocks over MPI
// ranks.
//
//   schema::key(schema::kDomainKeys, "domain.origin").number;   // 0: io::DomainSettings' default
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// DomainKeys.cpp (domain_docs).
#pragma once

#include <span>

#include "fluid/GridSpec.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

/// How far domain.size may lie from a whole multiple of cell_size, relative to the size.
inline constexpr double kCellMultipleTolerance = 1e-6;

inline constexpr Key kDomainKeys[] = {
    {.path = "domain.origin",
     .type = Type::point3,
     .unit = "m",
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference,
     .number = 0.0},
    {.path = "domain.size",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "domain.cell_size",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "domain.decomposition",
     .type = Type::point2,
     .at_least = 1,
     .at_most = double(fluid::GridSpec::kMaxFaces),
     .noun = "[px, py]"},
};

/// The prose of each key of kDomainKeys (DomainKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by
/// its path.
std::span<const KeyDocs> domain_docs();

}  // namespace fw::io::schema
