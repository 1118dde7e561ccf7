// The boundaries section of a scenario (docs/scenario.md, "boundaries"): a face's condition as the file
// writes it, and the schema's default per face (io/schema/BoundaryKeys.hpp).
//
//   std::array<fw::io::BoundaryChoice, 6> faces = fw::io::default_boundaries();   // by FW_FACE_*
//   fw::io::to_string(faces[FW_FACE_GROUND]);                                     // "no_slip"
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "io/schema/BoundaryKeys.hpp"

namespace fw::io {

/// A face's boundary condition as written in the file. automatic ("auto", the four sides only): inflow where
/// the ambient wind enters the domain, outflow where it leaves; see WindScenario::grid_spec. rough (the
/// ground only): a slip wall whose lowest fluid cells feel the log-law wall stress of
/// WindScenario::ground_roughness_length.
enum class BoundaryChoice { automatic, inflow, outflow, slip, no_slip, periodic, rough };
std::string to_string(BoundaryChoice choice);  // the word used in the file

/// In the order of schema::kBoundaryWords.
inline constexpr BoundaryChoice kBoundaryChoices[] = {
    BoundaryChoice::automatic, BoundaryChoice::inflow,   BoundaryChoice::outflow, BoundaryChoice::slip,
    BoundaryChoice::no_slip,   BoundaryChoice::periodic, BoundaryChoice::rough};

/// The schema's default per face, indexed by FW_FACE_* (west, east, south, north, ground, top).
constexpr std::array<BoundaryChoice, 6> default_boundaries() {
  const auto choice = [](std::string_view word) {
    return schema::value_of(schema::kBoundaryWords, kBoundaryChoices, word);
  };
  return {choice(schema::key(schema::kBoundaryKeys, "boundaries.west").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.east").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.south").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.north").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.ground").word),
          choice(schema::key(schema::kBoundaryKeys, "boundaries.top").word)};
}

}  // namespace fw::io
