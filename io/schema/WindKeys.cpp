// The prose docs/scenario.md prints for each key of kWindKeys (render_scenario_docs, io/ScenarioSchema.cpp):
// its meaning, and its default, allowed values and limits in words where its type does not say them. Here,
// not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/WindKeys.hpp"

#include "io/schema/BoundReasons.hpp"

#include "fluid/TurbulenceBox.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "wind.speed", .bounds_why = why::kWindSpeed, .description = "Wind speed at `reference_height`."},
    {.path = "wind.direction",
     .constraint = "any value (370 is the same as 10)",
     .bounds_why = why::kDirection,
     .description = "Direction the wind blows FROM, clockwise from north."},
    {.path = "wind.reference_height",
     .bounds_why = why::kAirHeight,
     .description = "Height above the domain floor where the wind has speed `wind.speed`."},
    {.path = "wind.profile",
     .default_note = "`{type: uniform}`",
     .allowed = "keys `type` plus that type's keys",
     .description = "Vertical shape of the wind on inflow faces. A key that belongs to another type is an "
                    "error."},
    {.path = "wind.profile.type",
     .default_note = "required when `profile` is given",
     .description = "`uniform`: shape 1 at every height. `power`: `(z / reference_height)^alpha`. `log`: "
                    "`ln((z - d) / z0) / ln((reference_height - d) / z0)`, and 0 where `z - d <= z0`."},
    {.path = "wind.profile.alpha", .bounds_why = why::kPowerLaw, .description = "Power-law exponent."},
    {.path = "wind.profile.roughness_length",
     .bounds_why = why::kRoughness,
     .description = "Roughness length z0. `reference_height` must exceed `displacement_height + "
                    "roughness_length` (the log law gives no wind below it); the error names "
                    "`displacement_height` when given, else `roughness_length`."},
    {.path = "wind.profile.displacement_height",
     .bounds_why = why::kStructure,
     .description = "Displacement height d (of a canopy, for example)."},
    {.path = "wind.turbulence",
     .default_note = "none (a laminar wind)",
     .allowed = "keys `model`, `intensity` or `sigma`, `length_scale`, `box_size`, `seed`, `unresolved`, "
                "`cutoff_cells`",
     .description = "Synthetic turbulence in the wind. Without it the inflow is the laminar profile alone."},
    {.path = "wind.turbulence.model",
     .description =
         "`von_karman`: homogeneous isotropic turbulence with the von Kármán energy spectrum E(k) of "
         "integral scale `length_scale`. Before the run, a periodic, divergence-free box of velocity "
         "fluctuations is synthesised from random Fourier modes by FFT (FFTW), deterministic from `seed`. "
         "The box is added to the initial wind field, and it is swept through the inflow faces at the "
         "ambient wind (Taylor's frozen turbulence): at time t an inflow face point x carries the mean "
         "profile plus the box's fluctuation at x - U t, U the ambient wind vector at `reference_height`. "
         "The fluctuations' statistics are the same at every height."},
    {.path = "wind.turbulence.intensity",
     .default_note = "required unless `sigma` is given",
     .constraint = "exactly one of `intensity` and `sigma`",
     .bounds_why = why::kIntensity,
     .description = "Turbulence intensity I = sigma_u / U, with U the wind speed `wind.speed` at "
                    "`reference_height`. sigma_u = I U follows `wind.speed` over time, and sigma_v = sigma_w "
                    "= sigma_u (isotropic). For neutral wind over uniform ground, EN 1991-1-4 gives I = 1 / "
                    "ln(z / z0) at height z: 0.17 at 10 m over grass (z0 = 0.03 m), 0.43 over forest (z0 "
                    "= 1 m)."},
    {.path = "wind.turbulence.sigma",
     .default_note = "required unless `intensity` is given",
     .allowed = "each > 0; exactly one of `intensity` and `sigma`",
     .bounds_why = why::kWindSpeed,
     .description =
         "Standard deviations [sigma_u, sigma_v, sigma_w] of the along-wind, across-wind and "
         "vertical fluctuations, fixed over time whatever `wind.speed` does. Unequal values scale "
         "the components of the isotropic box, which leaves a small divergence that the pressure "
         "projection removes; in the atmospheric surface layer sigma_v / sigma_u is about 0.75 and "
         "sigma_w / sigma_u about 0.5."},
    {.path = "wind.turbulence.length_scale",
     .bounds_why = why::kTurbulenceLength,
     .description = "L_u, the longitudinal integral length scale: the integral of the along-wind "
                    "fluctuation's autocorrelation along the wind. The premultiplied spectrum f S_u(f) peaks "
                    "at f = 0.146 U / L_u. EN 1991-1-4 gives L_u = 300 m (z / 200 m)^(0.67 + 0.05 ln z0): "
                    "about 40 m at 10 m over forest, 70 m over grass. The grid resolves eddies of "
                    "`cutoff_cells` cells and more, so L_u should span many cells."},
    {.path = "wind.turbulence.box_size",
     .default_note = "computed: along x and y the smallest power-of-two cell count >= the domain's cells "
                     "and >= 8 `length_scale` / `cell_size`; along z the smallest power of two >= the "
                     "domain's cells; each at least the fewest allowed",
     .constraint =
         "rounded to a whole, even number of cells, at least {0}, per axis; the box has {1} points "
         "per cell along each axis (h / {1} apart, h = `domain.cell_size`), at most {2} points in all",
     .limits = {kMinTurbulenceBoxCells, fluid::kTurbulencePointsPerCell,
                double(fluid::TurbulenceBoxSpec::kMaxPoints)},
     .bounds_why = why::kEarth,
     .description =
         "Extent of the periodic turbulence box along x, y and z, in cells of the grid. Its points are "
         "finer than the cells (see the allowed values), so that every face of an inflow plane sits on a "
         "box point and takes the box's value without interpolation. Turbulence repeats with the box's "
         "period: a point fixed in the inflow sees the same gusts again once the wind has carried the box "
         "one period past it, and the box holds no wavelength longer than itself, so along the wind it "
         "should be several L_u long."},
    {.path = "wind.turbulence.seed",
     .default_note = "global `seed`",
     .description = "Seed of the box's random Fourier amplitudes and of the unresolved forcing. The same "
                    "seed gives the same turbulence."},
    {.path = "wind.turbulence.unresolved",
     .description =
         "With `true`, each tree also feels the turbulence the grid cannot resolve (wavelengths "
         "below `cutoff_cells` cells): Stam's (1997) stochastic modal forcing, random modal forces "
         "with the spectrum's unresolved part, synthesised in the frequency domain, deterministic "
         "per tree from `seed`. With `false`, trees feel only the resolved wind."},
    {.path = "wind.turbulence.cutoff_cells",
     .bounds_why = why::kCells,
     .description =
         "The smallest eddy the grid resolves, in cells: wavelengths below `cutoff_cells` × "
         "`cell_size` (wavenumbers above 2 pi / (`cutoff_cells` h)) belong to the unresolved "
         "forcing. 2 is the grid's Nyquist limit; numerical diffusion damps eddies of a few cells, "
         "so 4 to 8 can be closer to what the grid really carries."},
    {.path = "wind.forcing",
     .default_note = "none; on, with the defaults below, when the four sides are all `periodic`",
     .allowed = "keys `relaxation_time`; only when `west`, `east`, `south` and `north` are all `periodic`",
     .description =
         "A mean body force for a domain whose four sides are all periodic, which has no inflow: "
         "it holds the horizontal mean wind at `reference_height` at `wind.speed` from "
         "`wind.direction`, as a pressure gradient drives the atmosphere, so that the flow neither "
         "decays under the trees' and the ground's drag nor runs away."},
    {.path = "wind.forcing.relaxation_time",
     .bounds_why = why::kRunTime,
     .description = "Time constant tau of the PI controller that sets the force from the difference between "
                    "the target wind and the horizontal mean at `reference_height`. Shorter follows a "
                    "changing `wind.speed` more closely; longer disturbs the turbulence less."},
};

}  // namespace

std::span<const KeyDocs> wind_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
