// The keys of a scenario's boundaries section: the condition of each face of the domain, in the order of
// FW_FACE_* (the loader indexes them so), and the roughness length of a rough ground.
//
//   schema::key(schema::kBoundaryKeys, "boundaries.top").word;   // "slip"
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// BoundaryKeys.cpp (boundary_docs).
#pragma once

#include <span>
#include <string_view>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

/// In the order of io::BoundaryChoice. The four sides take all but the last ("rough"), the ground all but the
/// first ("auto"), the top neither.
inline constexpr std::string_view kBoundaryWords[] = {"auto",    "inflow",   "outflow", "slip",
                                                      "no_slip", "periodic", "rough"};
inline constexpr Words kSideBoundaryWords = Words(kBoundaryWords).first(6);
inline constexpr Words kGroundBoundaryWords = Words(kBoundaryWords).subspan(1);
inline constexpr Words kTopBoundaryWords = Words(kBoundaryWords).subspan(1, 5);

inline constexpr Key kBoundaryKeys[] = {
    {.path = "boundaries.west", .type = Type::word, .words = kSideBoundaryWords, .word = "auto"},
    {.path = "boundaries.east", .type = Type::word, .words = kSideBoundaryWords, .word = "auto"},
    {.path = "boundaries.south", .type = Type::word, .words = kSideBoundaryWords, .word = "auto"},
    {.path = "boundaries.north", .type = Type::word, .words = kSideBoundaryWords, .word = "auto"},
    {.path = "boundaries.ground", .type = Type::word, .words = kGroundBoundaryWords, .word = "no_slip"},
    {.path = "boundaries.top", .type = Type::word, .words = kTopBoundaryWords, .word = "slip"},
    {.path = "boundaries.roughness_length",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .at_most = bounds::kMaxRoughnessLength,
     .number = 0.1},
};

/// The prose of each key of kBoundaryKeys (BoundaryKeys.cpp), which schema::docs (io/ScenarioSchema.hpp)
/// finds by its path.
std::span<const KeyDocs> boundary_docs();

}  // namespace fw::io::schema
