// The bounds past which a scenario's number cannot be meant (issue 44): a tree taller than any tree, a wind
// faster than any wind, an end time of more steps than a run can take. Each section's table
// (io/schema/*Keys.hpp) gives its keys' at_least / at_most from here; the docs print with each key why
// (KeyDocs::bounds_why, prose in io/schema/BoundReasons.hpp). The bounds are facts of the world or of a run,
// each with its source, and generous: they refuse slips of the keyboard (1e30 for 30, a missing decimal
// point) before they reach code that would hang, overflow or fail on them, not values a user might mean.
//
//   schema::key(schema::kTimeKeys, "time.cfl").at_most;   // bounds::kMaxCfl
//
// What depends on two keys (the steps of time.end at the step dt gives, a tree's height times its scale)
// the loader and the planner check where both are known; the absolute bounds here hold the rest.
#pragma once

#include "fluid/WindSettings.hpp"

namespace fw::io::schema::bounds {

/// The most steps a run can take: a run steps at least about 1 ms a step even on a tiny grid (tens of kernel
/// launches, and the CFL maximum and the pressure solve's residuals read back every step), so 10^9 steps
/// are 11.6 days of wall time at the least; large-eddy simulations run 10^4 to 10^7 steps. Counts of frames,
/// probe rows and checkpoints are bounded by it too: a run writes at most one of each a step.
inline constexpr double kMaxRunSteps = 1e9;
/// The same count as an integer key's highest (output.vtk.wind_every, output.checkpoint.keep, ...).
inline constexpr int kMaxRunFrames = int(kMaxRunSteps);
/// The longest run, s: kMaxRunSteps of dt: auto's longest step (fluid::WindSettings::max_dt, 1 s), 31.7 years
/// of simulated time; the planner holds the steps of time.end to kMaxRunSteps at the step it plans.
inline constexpr double kMaxRunTime = kMaxRunSteps * fluid::WindSettings{}.max_dt;
/// The longest fixed step, s: weather models step about 6 s per km of cell (60 s at 10 km); a step of an hour
/// resolves no wind. (Large cells can take fixed steps past dt: auto's 1 s cap, which the trees set.)
inline constexpr double kMaxStep = 3600.0;
/// The largest CFL number: past 5 a run with a fixed dt stops as a blow-up in the making
/// (host::CoupledStep::kRunawayCfl, which tests/host/app/CoupledStep_test.cpp holds equal to this).
inline constexpr double kMaxCfl = 5.0;

/// The Earth's equatorial circumference, m (WGS 84: 40,075,017 m): no coordinate of a place on Earth in any
/// map projection, and no extent on it, is larger.
inline constexpr double kEarthCircumference = 4.0075017e7;
/// Heights above the ground in the air, m: the troposphere, where weather happens, ends below 20 km.
inline constexpr double kMaxAirHeight = 2.0e4;
/// The Earth's whole relief, m: from the Challenger Deep (-10,935 m) to Everest (8,849 m), under 20 km.
inline constexpr double kMaxRelief = 2.0e4;
/// The tallest structure, m: the Burj Khalifa is 828 m tall; nothing displaces the wind profile higher.
inline constexpr double kMaxStructureHeight = 1000.0;

/// The tallest tree, m: Hyperion, a coast redwood, 116 m (Sillett, 2006-2019); 150 leaves room for any
/// tree measured.
inline constexpr double kMaxTreeHeight = 150.0;
/// The smallest tree, m: the dwarf willow Salix herbacea grows 1 to 6 cm tall.
inline constexpr double kMinTreeHeight = 0.01;
/// The widest tree scale: the tallest tree is 15,000 times the smallest, so no scale past 1e5 (or below 1e-5)
/// makes a tree of any skeleton. The scaled tree itself must lie between kMinTreeHeight and kMaxTreeHeight,
/// which the planner checks with the skeleton's height.
inline constexpr double kMaxTreeScale = 1e5;
inline constexpr double kMinTreeScale = 1e-5;
static_assert(kMaxTreeScale >= kMaxTreeHeight / kMinTreeHeight &&
              kMinTreeScale <= kMinTreeHeight / kMaxTreeHeight);

/// The fastest wind, m/s: 135 +- 20 m/s measured by Doppler radar in the Bridge Creek-Moore tornado of 1999,
/// the fastest near the ground; the solver's incompressible flow fails from about Mach 0.3 (100 m/s) anyway.
inline constexpr double kMaxWindSpeed = 150.0;
/// Turbulence intensity sigma_u / U: EN 1991-1-4 gives 0.43 at 10 m over forest (z0 = 1 m); intensities
/// near 1 occur only in weak wind under canopies. Twice that is noise, not a wind.
inline constexpr double kMaxTurbulenceIntensity = 2.0;
/// Integral length scale L_u, m: EN 1991-1-4 gives 300 m at 200 m height; ten times the depth of the
/// atmospheric boundary layer (about 1 km) holds any.
inline constexpr double kMaxTurbulenceLength = 1.0e4;
/// The Kolmogorov scale of atmospheric turbulence is about 1 mm: no eddy is smaller, let alone the largest.
inline constexpr double kMinTurbulenceLength = 1.0e-3;
/// Roughness length z0, m: the roughest Davenport-Wieringa class, city centres with high-rises, has
/// z0 >= 2 m; five times that.
inline constexpr double kMaxRoughnessLength = 10.0;
/// The power law's exponent: measured from about 0.1 (open sea) to 0.4 (city centres); a wind that grows
/// faster than linearly with height is no surface layer.
inline constexpr double kMaxPowerLawExponent = 1.0;
/// An angle, degrees, where the angle itself is the input (a yaw): one turn either way holds every angle.
inline constexpr double kMaxYawDeg = 360.0;
/// A wind direction, degrees, which an expression may turn round and round: a million turns (double
/// arithmetic still resolves 1e-7 degree there).
inline constexpr double kMaxDirectionDeg = 3.6e8;

/// Young's and shear moduli, Pa: wood measures 1e9 to 3e10 Pa; 1e6 Pa is rubber, and nothing is stiffer
/// than diamond (1.2e12 Pa).
inline constexpr double kMinModulus = 1.0e6;
inline constexpr double kMaxModulus = 1.2e12;
/// Density, kg/m^3: wood 100 to 1,400; nothing solid is lighter than air (1.2), nothing denser than osmium
/// (22,590).
inline constexpr double kMinDensity = 1.2;
inline constexpr double kMaxDensity = 22590.0;
/// Stiffness over density, m^2/s^2 (the square of a wave's speed along the wood): wood's E / density is 5e6
/// to 3e7 (green oak 1e10 / 1000, balsa 3.4e9 / 160), its G / density 5e5 to 3e6. Five times below the
/// floppiest, a 150 m tree's first mode falls to 0.001 Hz and the modal solve takes seconds, then fails.
inline constexpr double kMinSpecificModulus = 1e6;
inline constexpr double kMinSpecificShearModulus = 1e5;
/// A damping ratio: 1 is critical damping, past which a mode no longer oscillates; ten times it.
inline constexpr double kMaxDampingRatio = 10.0;
/// Modulus of rupture of green wood, Pa: every species' lies within 10 to 150 MPa (ForestGALES's conifers
/// 34 to 46 MPa); a tenth of the weakest and twice the strongest.
inline constexpr double kMinModulusOfRupture = 1.0e6;
inline constexpr double kMaxModulusOfRupture = 3.0e8;
/// Green (fresh, sap-laden) wood density, kg/m^3: about 400 to 1,300 (ForestGALES's conifers 850); balsa, the
/// lightest wood, weighs 100 to 200 kg/m^3 dry.
inline constexpr double kMinGreenDensity = 100.0;
inline constexpr double kMaxGreenDensity = 2000.0;
/// Anchorage C_reg, N m/kg of green stem weight: the tree-pulling regressions of Nicoll et al. (2006) span
/// about 60 to 300 over species, soils and rooting.
inline constexpr double kMinAnchorage = 10.0;
inline constexpr double kMaxAnchorage = 1000.0;
/// Vibration modes of a species: a 15 m broadleaf's 200th mode is at 13.6 Hz (`forestwind tree modes`), near
/// the highest frequency a fine grid's wind carries (U / 2h, 20 Hz at 20 m/s and 0.5 m cells); a thousand
/// lie far above anything the wind drives (and take 40 s to solve for a 1,200-node tree).
inline constexpr int kMaxModes = 1000;
/// A drag coefficient: a flat plate broadside has 2, the highest of any bluff body; five times it.
inline constexpr double kMaxDragCoefficient = 10.0;
/// A frequency of a tree's or a leaf's motion, Hz: trees sway at 0.1 to 5 Hz, leaves flutter at 1 to 20;
/// a step of at least 1 ms resolves nothing past 500 Hz.
inline constexpr double kMaxMotionFrequency = 500.0;
/// A leaf's one-sided area, m^2: the raffia palm's leaves, the largest, are about 25 m x 3 m.
inline constexpr double kMaxLeafArea = 100.0;
/// Leaf mass per area, kg/m^2: leaves measure 0.01 to 0.5; ten times the heaviest.
inline constexpr double kMaxLeafMassPerArea = 5.0;
/// A petiole's strength, N: a leaf's petiole holds 0.01 to a few newtons; 10 kN holds a car.
inline constexpr double kMaxPetioleStrength = 1.0e4;
/// Log-standard deviation of strengths: e^10, a spread of 22,000 times between one sigma and the next.
inline constexpr double kMaxLogSpread = 10.0;
/// A dimensionless gain of one angle on another, or a sway amplitude: ten times a one-to-one coupling.
inline constexpr double kMaxGain = 10.0;

/// The pressure solve's relative residual: 1 is met before the first iteration.
inline constexpr double kMaxTolerance = 1.0;
/// Iterations of the pressure solve a step: multigrid-preconditioned CG takes 5 to 30 (docs/performance.md);
/// a million is a solve that does not converge.
inline constexpr int kMaxSolverIterations = 1000000;
/// Vorticity confinement epsilon, 1/s: its force epsilon h (N x omega) adds about epsilon dt of the local
/// speed each step; at 10 and a step of 0.1 s, the whole speed.
inline constexpr double kMaxVorticityConfinement = 10.0;

}  // namespace fw::io::schema::bounds
