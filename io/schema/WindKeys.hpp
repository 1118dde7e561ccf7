// The keys of a scenario's wind section: the ambient wind's speed and direction over time, its vertical
// profile, the synthetic turbulence in it (wind.turbulence) and the mean forcing of a periodic domain
// (wind.forcing).
//
//   schema::key(schema::kWindKeys, "wind.profile.alpha").number;   // 0.2
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// WindKeys.cpp (wind_docs).
#pragma once

#include <span>
#include <string_view>

#include "fluid/GridSpec.hpp"
#include "fluid/InflowProfile.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr std::string_view kProfileWords[] = {"uniform", "power", "log"};
inline constexpr fluid::InflowProfile::Type kProfileTypes[] = {
    fluid::InflowProfile::Type::uniform, fluid::InflowProfile::Type::power, fluid::InflowProfile::Type::log};

/// In the order of io::TurbulenceModel.
inline constexpr std::string_view kTurbulenceModelWords[] = {"von_karman"};

/// The fewest cells of wind.turbulence.box_size along an axis (a box given smaller is rounded up to it).
inline constexpr int kMinTurbulenceBoxCells = 4;

inline constexpr Key kWindKeys[] = {
    {.path = "wind.speed",
     .type = Type::expression,
     .unit = "m/s",
     .required = true,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxWindSpeed},
    {.path = "wind.direction",
     .type = Type::expression,
     .unit = "degrees",
     .required = true,
     .at_least = -bounds::kMaxDirectionDeg,
     .at_most = bounds::kMaxDirectionDeg},
    {.path = "wind.reference_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .at_most = bounds::kMaxAirHeight,
     .number = 10.0},
    {.path = "wind.profile"},
    {.path = "wind.profile.type",
     .type = Type::word,
     .required = true,
     .words = kProfileWords,
     .word = "uniform"},
    {.path = "wind.profile.alpha",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxPowerLawExponent,
     .number = 0.2,
     .only_with = "power"},
    {.path = "wind.profile.roughness_length",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kMaxRoughnessLength,
     .only_with = "log"},
    {.path = "wind.profile.displacement_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxStructureHeight,
     .number = 0.0,
     .only_with = "log"},
    {.path = "wind.turbulence"},
    {.path = "wind.turbulence.model",
     .type = Type::word,
     .words = kTurbulenceModelWords,
     .word = "von_karman"},
    {.path = "wind.turbulence.intensity",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxTurbulenceIntensity},
    {.path = "wind.turbulence.sigma",
     .type = Type::point3,
     .unit = "m/s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxWindSpeed,
     .noun = "[sigma_u, sigma_v, sigma_w]"},
    {.path = "wind.turbulence.length_scale",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .at_least = bounds::kMinTurbulenceLength,
     .at_most = bounds::kMaxTurbulenceLength},
    {.path = "wind.turbulence.box_size",
     .type = Type::point3,
     .unit = "m",
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "wind.turbulence.seed", .type = Type::seed},
    {.path = "wind.turbulence.unresolved", .type = Type::boolean, .flag = true},
    {.path = "wind.turbulence.cutoff_cells",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = double(fluid::GridSpec::kMaxFaces),
     .number = 2.0},
    {.path = "wind.forcing"},
    {.path = "wind.forcing.relaxation_time",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime,
     .number = 10.0},
};

/// The prose of each key of kWindKeys (WindKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by its
/// path.
std::span<const KeyDocs> wind_docs();

}  // namespace fw::io::schema
