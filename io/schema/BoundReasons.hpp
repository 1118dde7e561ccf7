// Why a value past a bound of io/schema/Bounds.hpp cannot be meant, in the words docs/scenario.md prints
// beside each key's allowed values (KeyDocs::bounds_why). Prose, so only the section .cpp files that hold
// their keys' docs include it, not the readers of the keys.
#pragma once

#include <string_view>

namespace fw::io::schema::why {

inline constexpr std::string_view kRunSteps =
    "a run takes at most 10^9 steps: at the 1 ms a step takes at least (tens of kernel launches and the "
    "read-backs of every step), 11.6 days";
inline constexpr std::string_view kRunTime =
    "no run lasts longer than 10^9 steps of `dt: auto`'s longest step, 1 s (31.7 years of simulated time)";
inline constexpr std::string_view kStep =
    "weather models step about 6 s per km of cell (60 s at 10 km); a step of an hour resolves no wind";
inline constexpr std::string_view kCfl =
    "past 5 a run with a fixed `dt` stops at the step as a blow-up in the making";
inline constexpr std::string_view kEarth =
    "the Earth's circumference, 40,075 km: no coordinate or extent on it in any projection is larger";
inline constexpr std::string_view kAirHeight = "the troposphere, where weather happens, ends below 20 km";
inline constexpr std::string_view kRelief =
    "the Earth's relief, from the Challenger Deep (-10,935 m) to Everest (8,849 m), spans under 20 km";
inline constexpr std::string_view kStructure =
    "the tallest structure, the Burj Khalifa, is 828 m tall: nothing displaces the wind higher";
inline constexpr std::string_view kTreeHeight =
    "the tallest tree, the redwood Hyperion, is 116 m tall; the smallest, the dwarf willow, 1 to 6 cm";
inline constexpr std::string_view kTreeScale =
    "the tallest tree is 15,000 times the smallest, so no scale past these makes a tree; the scaled tree "
    "itself "
    "must lie between 0.01 m and 150 m (checked with its skeleton's height)";
inline constexpr std::string_view kWindSpeed =
    "the fastest wind measured near the ground is 135 +- 20 m/s (a tornado, 1999), and the solver's "
    "incompressible flow fails from about 100 m/s (Mach 0.3)";
inline constexpr std::string_view kIntensity =
    "EN 1991-1-4 gives 0.43 at 10 m over forest; intensities near 1 occur only in weak wind under canopies";
inline constexpr std::string_view kTurbulenceLength =
    "no eddy is smaller than the Kolmogorov scale of the air, about 1 mm, and ten times the boundary "
    "layer's depth (1 km) holds the largest";
inline constexpr std::string_view kRoughness =
    "five times the roughest terrain class, city centres with high-rises (z0 >= 2 m, Davenport-Wieringa)";
inline constexpr std::string_view kPowerLaw =
    "measured exponents run from 0.1 (open sea) to 0.4 (city centres); a wind growing faster than linearly "
    "with height is no surface layer";
inline constexpr std::string_view kYaw = "one turn either way holds every angle";
inline constexpr std::string_view kDirection =
    "a million turns, for an expression that turns the wind round and round";
inline constexpr std::string_view kModulus =
    "wood measures 1e9 to 3e10 Pa: 1e6 Pa is rubber, and nothing is stiffer than diamond (1.2e12 Pa)";
inline constexpr std::string_view kDensity =
    "wood is 100 to 1,400 kg/m^3: no solid is lighter than air (1.2) or denser than osmium (22,590)";
inline constexpr std::string_view kModulusOfRupture = "green wood of every species breaks at 10 to 150 MPa";
inline constexpr std::string_view kKnotFactor = "1 is clear wood: knots only weaken a stem";
inline constexpr std::string_view kGreenDensity =
    "green wood weighs about 400 to 1,300 kg/m^3; balsa, the lightest wood, 100 to 200 dry";
inline constexpr std::string_view kAnchorage =
    "tree-pulling regressions span about 60 to 300 N m/kg over species, soils and rooting (Nicoll et al. "
    "2006)";
inline constexpr std::string_view kDamping =
    "ten times critical damping (1), past which a motion no longer oscillates";
inline constexpr std::string_view kModes =
    "a 15 m broadleaf's 200th mode is at 13.6 Hz, near the highest frequency a fine grid's wind carries (U / "
    "2h: "
    "20 Hz at 20 m/s and 0.5 m cells); its thousandth lies far above";
inline constexpr std::string_view kDrag =
    "five times a flat plate broadside (2), the highest drag coefficient of a bluff body";
inline constexpr std::string_view kFrequency =
    "trees sway at 0.1 to 5 Hz and leaves flutter at 1 to 20 Hz; a step of 1 ms or more resolves nothing "
    "past 500 Hz";
inline constexpr std::string_view kLeafArea = "the largest leaves, the raffia palm's, are about 25 m x 3 m";
inline constexpr std::string_view kLeafMass = "leaves weigh 0.01 to 0.5 kg/m^2; ten times the heaviest";
inline constexpr std::string_view kPetiole = "petioles hold 0.01 N to a few newtons; 10 kN holds a car";
inline constexpr std::string_view kSpread = "a spread of e^10, 22,000 times from one sigma to the next";
inline constexpr std::string_view kGain = "ten times a one-to-one coupling";
inline constexpr std::string_view kTolerance = "a relative residual of 1 is met before the first iteration";
inline constexpr std::string_view kIterations =
    "the multigrid-preconditioned solve takes 5 to 30 iterations; a million is a solve that does not "
    "converge";
inline constexpr std::string_view kConfinement =
    "the force adds about epsilon dt of the local velocity difference each step: at 10 and a step of 0.1 s, "
    "all of it";
inline constexpr std::string_view kBlocks = "a block holds at least one cell of the grid's fewer than 2^31";
inline constexpr std::string_view kEvery =
    "a run writes at most one frame a step, and takes at most 10^9 steps";
inline constexpr std::string_view kKeep =
    "a run writes at most one checkpoint a step, and takes at most 10^9";
inline constexpr std::string_view kLeafStride = "no tree carries more leaves than the leaf stage holds";
inline constexpr std::string_view kIntervals =
    "no run lasts longer than 31.7 years; and `time.end` / this interval, the frames, rows or checkpoints "
    "the run writes, at most 10^9, one a step";

inline constexpr std::string_view kCells =
    "no axis of the grid has more cells than its fewer than 2^31 faces";
inline constexpr std::string_view kVogel = "plants measure Vogel exponents from 0 to -4/3 (Vogel 1984)";
inline constexpr std::string_view kLeafAreaIndex =
    "the largest leaf area index that field measurements give is 18 (Asner, Scurlock & Hicke 2003)";
inline constexpr std::string_view kSamples = "the trees' kernels hold at most 16 wind samples a tree";
inline constexpr std::string_view kRightAngle =
    "a bend of a right angle or more has no meaning for one element turning about its base";
inline constexpr std::string_view kFraction = "1 simulates every leaf of the foliage";
inline constexpr std::string_view kLeafDamping = "at critical damping (1) a leaf no longer flutters";
inline constexpr std::string_view kAmplitude = "a quarter turn either way holds every attitude of a blade";
inline constexpr std::string_view kSmagorinsky =
    "C_s >= 1 makes the subgrid length C_s h longer than the cell it stands for";

}  // namespace fw::io::schema::why
