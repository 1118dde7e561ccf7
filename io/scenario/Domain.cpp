// domain and boundaries: the wind grid and the condition on each face.
#include "io/scenario/Domain.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "fluid/GridSpec.hpp"
#include "fluid/SubgridStress.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/TopLevelKeys.hpp"
#include "kernels/shared_types.h"

namespace fw::io::reader {

void read_domain(const Loader& loader, const Field& field, DomainSettings& domain) {
  const Section<schema::kDomainKeys, "domain"> map(loader, field);
  domain.origin_line = field.line;
  if (const auto origin = map.get<"origin">()) {
    domain.origin = loader.vector<3>(*origin);
    domain.origin_line = origin->line;
  }
  const Field size = map.require<"size">();
  domain.size = loader.vector<3>(size);
  constexpr std::size_t kVertical = 2;
  if (!(domain.size[kVertical] <= schema::bounds::kMaxAirHeight)) {  // the air's extent, not the Earth's
    loader.expected(loader.child(size, size.node[kVertical], fmt::format("{}[{}]", size.key, kVertical)),
                    fmt::format("{}, the height at most {} m", number_expected(key_of(size)),
                                schema::bounds::kMaxAirHeight));
  }
  const Field cell_size = map.require<"cell_size">();
  domain.cell_size = loader.number(cell_size);
  double total = 1.0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double cells = domain.size[axis] / domain.cell_size;
    const double whole = std::round(cells);
    const double tolerance = schema::kCellMultipleTolerance * domain.size[axis];
    if (whole < 1.0 || std::abs(whole * domain.cell_size - domain.size[axis]) > tolerance) {
      loader.expected(
          loader.child(size, size.node[axis], fmt::format("{}[{}]", size.key, axis)),
          fmt::format("a whole multiple of cell_size ({} m) along {}", domain.cell_size, axis_name(axis)));
    }
    if (whole > double(std::numeric_limits<int>::max())) total = std::numeric_limits<double>::infinity();
    domain.cells[axis] = int(std::min(whole, double(std::numeric_limits<int>::max())));
    total *= whole;
  }
  domain.decomposition_line = field.line;
  if (const auto blocks = map.get<"decomposition">()) {
    const auto given = loader.vector<2>(*blocks);
    std::array<int, 2> whole{1, 1};
    for (std::size_t axis = 0; axis < 2; ++axis) {
      if (given[axis] != std::round(given[axis]) || given[axis] > double(std::numeric_limits<int>::max()))
        loader.expected(loader.child(*blocks, blocks->node[axis], fmt::format("{}[{}]", blocks->key, axis)),
                        fmt::format("a whole number of blocks along {}", axis_name(axis)));
      whole[axis] = int(given[axis]);
    }
    domain.decomposition = whole;
    domain.decomposition_line = blocks->line;
  }
  // Face arrays hold (nx + 1)(ny + 1)(nz + 1) values at most, indexed by 32-bit ints on the device.
  const double faces = (domain.cells[0] + 1.0) * (domain.cells[1] + 1.0) * (domain.cells[2] + 1.0);
  if (!(total < std::numeric_limits<double>::infinity()) || faces > double(fluid::GridSpec::kMaxFaces)) {
    loader.expected(cell_size,
                    fmt::format("a cell size giving (nx + 1)(ny + 1)(nz + 1) <= {} (size / cell_size "
                                "gives {:.3g} cells)",
                                fluid::GridSpec::kMaxFaces, total));
  }
}

void read_boundaries(const Loader& loader, const Field& field, const DomainSettings& domain,
                     std::array<BoundaryChoice, 6>& boundaries, double& ground_roughness_length) {
  const Section<schema::kBoundaryKeys, "boundaries"> map(loader, field);
  // Indexed by FW_FACE_*, as the schema lists the faces (tests/io/ScenarioSchema_test.cpp checks it).
  const std::array<std::optional<Field>, 6> given = {map.get<"west">(),   map.get<"east">(),
                                                     map.get<"south">(),  map.get<"north">(),
                                                     map.get<"ground">(), map.get<"top">()};
  const std::vector<std::string> faces =
      schema::child_names(schema::key(schema::kTopLevelKeys, "boundaries").path);
  const std::string rough = to_string(BoundaryChoice::rough);
  for (int face = 0; face < 6; ++face) {
    if (!given[face]) continue;
    const Field& choice = *given[face];
    if (face != FW_FACE_GROUND && choice.node.IsScalar() && choice.node.Scalar() == rough)
      loader.expected(choice, schema::expected(key_of(choice)) + " (rough is for the ground only)");
    boundaries[face] = value(schema::kBoundaryWords, kBoundaryChoices, loader.word(choice));
  }
  if (const auto roughness = map.get<"roughness_length">()) {
    const double z0 = loader.number(*roughness);
    if (boundaries[FW_FACE_GROUND] != BoundaryChoice::rough) {
      loader.expected(*roughness, fmt::format("nothing unless boundaries.ground is rough (it is '{}')",
                                              to_string(boundaries[FW_FACE_GROUND])));
    }
    const double first_centre = fluid::wall_centre_height(domain.cell_size);
    if (!(z0 < first_centre)) {
      loader.expected(*roughness,
                      fmt::format("{} below cell_size / 2 = {} m (the log law is evaluated at the "
                                  "first cell centre)",
                                  schema::expected(key_of(*roughness)), first_centre));
    }
    ground_roughness_length = z0;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int low = 2 * axis, high = 2 * axis + 1;
    const bool low_periodic = boundaries[low] == BoundaryChoice::periodic;
    const bool high_periodic = boundaries[high] == BoundaryChoice::periodic;
    if (low_periodic != high_periodic) {
      const int face = low_periodic ? low : high, other = low_periodic ? high : low;
      loader.expected(
          *given[face],
          fmt::format("periodic on both {} and {} (a pair), or neither; {} is '{}', so not periodic",
                      faces[low], faces[high], faces[other], to_string(boundaries[other])));
    }
    const int cells = domain.cells[axis];
    if (low_periodic && cells > 1 && cells % 2 != 0) {
      loader.expected(*given[low], fmt::format("periodic only along an axis with an even cell count; {} has "
                                               "{} cells",
                                               axis_name(axis), cells));
    }
  }
}

void resolve_ground_roughness(const Loader& loader, const Field& boundaries_field,
                              const DomainSettings& domain, const std::array<BoundaryChoice, 6>& boundaries,
                              const fluid::InflowProfile& profile, double& ground_roughness_length) {
  if (boundaries[FW_FACE_GROUND] != BoundaryChoice::rough || ground_roughness_length > 0.0) return;
  const bool from_profile = profile.type == fluid::InflowProfile::Type::log;
  const double z0 = from_profile ? profile.roughness_length
                                 : schema::key(schema::kBoundaryKeys, "boundaries.roughness_length").number;
  const double first_centre = fluid::wall_centre_height(domain.cell_size);
  if (!(z0 < first_centre)) {
    const Field missing =
        Section<schema::kBoundaryKeys, "boundaries">(loader, boundaries_field).missing<"roughness_length">();
    const std::string default_text =
        from_profile ? fmt::format("the default, wind.profile.roughness_length, is {} m", z0)
                     : fmt::format("the default without a log profile is {} m", z0);
    loader.fail(missing,
                fmt::format("{} below cell_size / 2 = {} m expected (required here: {}), got nothing",
                            schema::expected(key_of(missing)), first_centre, default_text));
  }
  ground_roughness_length = z0;
}

}  // namespace fw::io::reader
