// wind.turbulence: the synthetic turbulence box, sized in cells of the grid.
#include "io/scenario/Turbulence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "fluid/TurbulenceBox.hpp"

namespace fw::io::reader {

namespace {

/// The default turbulence box spans this many length scales along x and y.
constexpr double kDefaultBoxLengthScales = 8.0;

}  // namespace

TurbulenceSettings read_turbulence(const Loader& loader, const Field& field, const DomainSettings& domain,
                                   std::uint64_t seed) {
  const Section<schema::kWindKeys, "wind.turbulence"> map(loader, field);  // length_scale is required
  TurbulenceSettings turbulence;
  if (const auto model = map.get<"model">())
    turbulence.model = value(schema::kTurbulenceModelWords, kTurbulenceModels, loader.word(*model));

  // Exactly one of intensity and sigma; with both, the one given second is blamed.
  const auto intensity = map.get<"intensity">();
  const auto sigma = map.get<"sigma">();
  if (intensity && sigma) {
    const bool sigma_second = comes_before(*intensity, *sigma);
    const Field& second = sigma_second ? *sigma : *intensity;
    const Field& first = sigma_second ? *intensity : *sigma;
    loader.fail(second, fmt::format("exactly one of intensity and sigma expected, got both ({} on line {})",
                                    sigma_second ? "intensity" : "sigma", first.line));
  }
  if (!intensity && !sigma) map.require<"intensity">("or sigma (exactly one of intensity and sigma)");
  if (intensity) turbulence.intensity = loader.number(*intensity);
  if (sigma) turbulence.sigma = loader.vector<3>(*sigma);

  turbulence.length_scale = loader.number(map.require<"length_scale">());
  turbulence.seed = seed;
  if (const auto seed = map.get<"seed">()) turbulence.seed = loader.seed(*seed);
  if (const auto unresolved = map.get<"unresolved">()) turbulence.unresolved = loader.boolean(*unresolved);
  if (const auto cutoff = map.get<"cutoff_cells">()) turbulence.cutoff_cells = loader.number(*cutoff);

  // The box counts cells of the grid: a given size rounds to an even count of at least
  // kMinTurbulenceBoxCells; the default takes powers of two (fast FFTs) that cover the domain and, along x
  // and y, kDefaultBoxLengthScales length scales. The fluid::TurbulenceBox that a run builds from it has
  // kTurbulencePointsPerCell points per cell along each axis, and at most TurbulenceBoxSpec::kMaxPoints in
  // all: the limit counts those points, so that a box this accepts is one the run can build.
  const double h = domain.cell_size;
  const double per_cell = fluid::kTurbulencePointsPerCell;
  const double most_points = double(fluid::TurbulenceBoxSpec::kMaxPoints);
  const double fewest_cells = schema::kMinTurbulenceBoxCells;
  const auto box_size = map.get<"box_size">();
  std::array<double, 3> cells{};
  if (box_size) {
    const std::array<double, 3> size = loader.vector<3>(*box_size);
    for (std::size_t axis = 0; axis < 3; ++axis)
      cells[axis] = std::max(fewest_cells, 2.0 * std::round(size[axis] / (2.0 * h)));
  } else {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      double target = domain.cells[axis];
      if (axis < 2) target = std::max(target, kDefaultBoxLengthScales * turbulence.length_scale / h);
      double count = fewest_cells;
      while (count < target && count * per_cell <= most_points) count *= 2.0;
      cells[axis] = count;
    }
  }
  const double points = cells[0] * cells[1] * cells[2] * per_cell * per_cell * per_cell;
  if (!(points <= most_points)) {
    const std::string box = fmt::format("{:.0f} x {:.0f} x {:.0f} cells of {} m, {:.3g} points", cells[0],
                                        cells[1], cells[2], h, points);
    const std::string limit =
        fmt::format("at most {:.0f} points in all, {:.0f} per cell along each axis", most_points, per_cell);
    if (box_size) {
      loader.expected(*box_size, fmt::format("{} of {} (this box is {})", schema::expected(key_of(*box_size)),
                                             limit, box));
    }
    const Field missing = map.missing<"box_size">();
    loader.fail(missing, fmt::format("{} of {} expected (required here: the default box, {:.0f} length_scale "
                                     "along x and y, is {}), got nothing",
                                     schema::expected(key_of(missing)), limit, kDefaultBoxLengthScales, box));
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    turbulence.box_cells[axis] = int(cells[axis]);
    turbulence.box_size[axis] = cells[axis] * h;
  }
  turbulence.box_size_given = box_size.has_value();
  return turbulence;
}

}  // namespace fw::io::reader
