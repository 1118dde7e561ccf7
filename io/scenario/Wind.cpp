// wind: speed and direction over time, the vertical profile, and the mean forcing of a periodic domain
// (wind.turbulence has io/scenario/Turbulence.cpp).
#include "io/scenario/Wind.hpp"

#include <fmt/format.h>

#include <cmath>

#include "io/scenario/Turbulence.hpp"
#include "io/schema/TopLevelKeys.hpp"
#include "kernels/shared_types.h"

namespace fw::io::reader {

namespace {

/// Every value of the expression over the run is finite and in its key's range (its sign, at_least,
/// at_most).
void check_time_series(const Loader& loader, const Field& field, const Expression& expression, double end) {
  const Key& key = key_of(field);
  const bool non_negative = key.bound == Bound::non_negative;
  // Sampled densely over the run so that a formula that goes bad mid-run fails at load, not at step 10^5.
  const int samples = expression.is_constant() ? 1 : 1001;
  for (int i = 0; i < samples; ++i) {
    const double t = samples == 1 ? 0.0 : end * i / (samples - 1);
    const double value = expression(t);
    if (!std::isfinite(value) || (non_negative && value < 0.0) || !(value >= key.at_least) ||
        !(value <= key.at_most)) {
      const std::string range = number_expected(key).substr(std::string_view("a number").size());
      loader.expected(field, fmt::format("a finite value{} for 0 <= t <= {} s (it gives {} at t = {} s)",
                                         range, end, value, t));
    }
  }
}

bool sides_periodic(const std::array<BoundaryChoice, 6>& boundaries) {
  for (const int face : {FW_FACE_WEST, FW_FACE_EAST, FW_FACE_SOUTH, FW_FACE_NORTH})
    if (boundaries[face] != BoundaryChoice::periodic) return false;
  return true;
}

}  // namespace

WindSource read_wind(const Loader& loader, const Field& field, double end, const DomainSettings& domain,
                     const std::array<BoundaryChoice, 6>& boundaries, std::uint64_t seed) {
  WindSource wind;
  const Section<schema::kWindKeys, "wind"> map(loader, field);
  const Field speed = map.require<"speed">();
  wind.speed = loader.expression(speed);
  check_time_series(loader, speed, wind.speed, end);
  const Field direction = map.require<"direction">();
  wind.direction = loader.expression(direction);
  check_time_series(loader, direction, wind.direction, end);
  if (const auto height = map.get<"reference_height">()) wind.reference_height = loader.number(*height);

  wind.profile = fluid::InflowProfile{};
  wind.profile.type = value(schema::kProfileWords, schema::kProfileTypes,
                            std::string(schema::key(schema::kWindKeys, "wind.profile.type").word));
  wind.profile.alpha = schema::key(schema::kWindKeys, "wind.profile.alpha").number;
  wind.profile.displacement_height =
      schema::key(schema::kWindKeys, "wind.profile.displacement_height").number;
  wind.profile.reference_height = wind.reference_height;
  if (const auto profile_field = map.get<"profile">()) {
    // The allowed keys depend on the type, so read the type first.
    const Section<schema::kWindKeys, "wind.profile"> any(loader, *profile_field);
    const std::string type = loader.word(any.require<"type">());
    const Section<schema::kWindKeys, "wind.profile"> profile(loader, *profile_field, &type);
    wind.profile.type = value(schema::kProfileWords, schema::kProfileTypes, type);
    if (const auto alpha = profile.get<"alpha">()) wind.profile.alpha = loader.number(*alpha);
    if (const auto roughness = profile.get<"roughness_length">())
      wind.profile.roughness_length = loader.number(*roughness);
    const auto displacement = profile.get<"displacement_height">();
    if (displacement) wind.profile.displacement_height = loader.number(*displacement);
    if (wind.profile.type == fluid::InflowProfile::Type::log) {
      // The log law is only defined above d + z0, and the reference height is where it equals `speed`.
      const double floor = wind.profile.displacement_height + wind.profile.roughness_length;
      if (!(wind.reference_height > floor)) {
        loader.expected(
            displacement ? *displacement : profile.require<"roughness_length">(),
            fmt::format(
                "displacement_height + roughness_length (now {} m) below wind.reference_height ({} m)", floor,
                wind.reference_height));
      }
    }
  }

  if (const auto turbulence = map.get<"turbulence">())
    wind.turbulence = read_turbulence(loader, *turbulence, domain, seed);

  // A domain without inflow (all four sides periodic) is driven by the mean forcing, given or not.
  const bool periodic = sides_periodic(boundaries);
  if (const auto forcing_field = map.get<"forcing">()) {
    if (!periodic) {
      int open = FW_FACE_WEST;
      while (boundaries[open] == BoundaryChoice::periodic) ++open;
      const std::vector<std::string> faces =
          schema::child_names(schema::key(schema::kTopLevelKeys, "boundaries").path);
      loader.expected(
          *forcing_field,
          fmt::format("forcing only in a domain whose west, east, south and north are all periodic "
                      "(boundaries.{} is '{}')",
                      faces[open], to_string(boundaries[open])));
    }
    const Section<schema::kWindKeys, "wind.forcing"> forcing(loader, *forcing_field);
    wind.forcing = ForcingSettings{};
    if (const auto tau = forcing.get<"relaxation_time">())
      wind.forcing->relaxation_time = loader.number(*tau);
  } else if (periodic) {
    wind.forcing = ForcingSettings{};
  }
  return wind;
}

}  // namespace fw::io::reader
