// The prose docs/scenario.md prints for each key of kSpeciesKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose. And the
// words that only the trees know: the generator's presets, and the strength presets, soil groups and rooting
// depths.
#include "io/schema/SpeciesKeys.hpp"

#include "io/schema/BoundReasons.hpp"

#include "trees/TreeGenerator.hpp"
#include "trees/TreeStrength.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "forest.species[].name",
     .constraint = "unique among the species",
     .description = "Name that stands and trees refer to."},
    {.path = "forest.species[].skeleton", .description = "Where the species' skeleton comes from."},
    {.path = "forest.species[].skeleton.generate",
     .description = "Grow a skeleton with the built-in L-system generator, as `forestwind tree generate` "
                    "does."},
    {.path = "forest.species[].skeleton.generate.preset", .description = "Tree shape."},
    {.path = "forest.species[].skeleton.generate.height",
     .default_note = "`0` (the preset's height: broadleaf 15, conifer 20, palm 12, weeping 10)",
     .constraint = "`0` (the preset's height) or at least {0}",
     .limits = {bounds::kMinTreeHeight},
     .bounds_why = why::kTreeHeight,
     .description = "Height of the generated tree."},
    {.path = "forest.species[].skeleton.generate.seed",
     .default_note = "global `seed` + 1 + species index",
     .description = "Generator seed. The same seed gives the same tree."},
    {.path = "forest.species[].skeleton.file",
     .allowed = "a readable `.tree` file; relative to the scenario's folder",
     .description = "A skeleton in the `.tree` format (`id parent x y z radius` per line, metres)."},
    {.path = "forest.species[].skeleton.qsm",
     .allowed = "a readable TreeQSM cylinder table; relative to the scenario's folder",
     .description = "A scanned tree, as a TreeQSM text export."},
    {.path = "forest.species[].material",
     .constraint =
         "`youngs_modulus` / `density` >= {0} and `shear_modulus` / `density` >= {1} m^2/s^2 (wood: 5e6 "
         "to 3e7 and 5e5 to 3e6; below, a tall tree's modes do not separate)",
     .limits = {bounds::kMinSpecificModulus, bounds::kMinSpecificShearModulus},
     .description = "Wood, isotropic."},
    {.path = "forest.species[].material.youngs_modulus",
     .bounds_why = why::kModulus,
     .description = "Young's modulus E (stretching and bending)."},
    {.path = "forest.species[].material.shear_modulus",
     .bounds_why = why::kModulus,
     .description = "Shear modulus G (torsion)."},
    {.path = "forest.species[].material.density",
     .bounds_why = why::kDensity,
     .description = "Wood density rho."},
    {.path = "forest.species[].dynamics",
     .description =
         "The model that moves the species' trees; all three read the same wind samples, give the air the "
         "same drag and write the same outputs. `modal`: the FEM's lowest vibration modes, driven through "
         "the "
         "wind basis (Diener 2008). `rigid_bodies`: Oliapuram & Kumar (2010, §3.1): each element a rigid "
         "body "
         "rotating about its parent's end against a joint spring of stiffness of the form E I / L, "
         "integrated "
         "implicitly. `springs`: Ota et al. (2004) as Yildiz implements it: each element a quasi-static "
         "cantilever flat spring, k = E b t³ / (4 l³), bent by its own wind load to the angle "
         "atan(deflection / l), capped at `springs.max_angle_deg`, with a stochastic sine on top; no "
         "inertia. "
         "Every species' modes are computed (with the default `modes` for the other two models), because "
         "those models build on the same skeleton, beam model and first frequency."},
    {.path = "forest.species[].modes",
     .constraint = "only for a species whose `dynamics` is `modal`",
     .description = "Modal model."},
    {.path = "forest.species[].modes.count",
     .constraint = "fewer than the skeleton's 6 × (nodes − 1) DOFs",
     .bounds_why = why::kModes,
     .description = "Number of lowest vibration modes kept."},
    {.path = "forest.species[].modes.damping_ratio",
     .bounds_why = why::kDamping,
     .description = "Damping ratio zeta, the same for every mode."},
    {.path = "forest.species[].modes.wind_samples",
     .bounds_why = why::kSamples,
     .description = "Number of height bands per tree. Each band samples the wind separately, which captures "
                    "shear and gust fronts within one crown."},
    {.path = "forest.species[].rigid_bodies",
     .constraint = "only for a species whose `dynamics` is `rigid_bodies`",
     .description = "Articulated rigid branches (`dynamics: rigid_bodies`)."},
    {.path = "forest.species[].rigid_bodies.damping_ratio",
     .bounds_why = why::kDamping,
     .description =
         "Damping ratio zeta of the tree's first mode. The joints' damping is proportional to their "
         "stiffness, C = 2 zeta / omega_1 K with omega_1 the species' first FEM frequency, so that "
         "the slowest sway decays as a modal tree's with the same ratio."},
    {.path = "forest.species[].springs",
     .constraint = "only for a species whose `dynamics` is `springs`",
     .description = "Quasi-static cantilever springs (`dynamics: springs`)."},
    {.path = "forest.species[].springs.max_angle_deg",
     .bounds_why = why::kRightAngle,
     .description = "The largest bend of one element from its parent, theta_max (Yildiz's cap)."},
    {.path = "forest.species[].springs.sway_amplitude",
     .bounds_why = why::kGain,
     .description = "The stochastic sine's amplitude at the largest bend: an element's load is F (1 + a "
                    "sin(2 pi f t + b)), with a = `sway_amplitude` theta / theta_max (a bent element sways "
                    "more) and a random phase b per element."},
    {.path = "forest.species[].springs.sway_frequency",
     .bounds_why = why::kFrequency,
     .description = "f, the stochastic sine's frequency."},
    {.path = "forest.species[].drag_coefficient",
     .bounds_why = why::kDrag,
     .description =
         "Drag coefficient C_D of the branches, as cylinders in cross flow: the drag is 1/2 rho_air "
         "C_D D L \\|u\\| u per element of diameter D and length L, with air density 1.225 kg/m^3. "
         "Used for the wind load on the tree and for its drag on the wind."},
    {.path = "forest.species[].canopy",
     .description = "Foliage: its leaf area and drag. The single leaves of `leaves` sit on it."},
    {.path = "forest.species[].canopy.leaf_area_index",
     .default_note = "`0` (no leaves)",
     .bounds_why = why::kLeafAreaIndex,
     .description = "One-sided leaf area per ground area under the crown. The crown's ground area is the "
                    "horizontal convex hull of the tree's branches (the trunk excluded)."},
    {.path = "forest.species[].canopy.drag_coefficient",
     .bounds_why = why::kDrag,
     .description = "Drag coefficient C_D of the leaves, in the convention of the branches' "
                    "`drag_coefficient`: the drag is 1/2 rho_air C_D A \\|u\\| u per one-sided leaf area A. "
                    "The default 0.4 makes 1/2 C_D = 0.2, the canopy drag coefficient C_d of canopy LES in "
                    "the form C_d a \\|u\\| u (Shaw & Schumann 1992)."},
    {.path = "forest.species[].leaves",
     .default_note = "none (no leaves)",
     .description =
         "Single leaves that flutter in the wind, shed when it pulls harder than their petioles hold, "
         "and fly until they land or leave the domain (docs/leaves.md has the model). They sit on the "
         "canopy's foliage, so the species needs `canopy.leaf_area_index` > 0. Without `leaves` the "
         "species has no single leaves; the canopy's drag is the same either way."},
    {.path = "forest.species[].leaves.model",
     .description =
         "How attached leaves flutter. `pseudo_branch`: each leaf turns about its branch, a damped "
         "oscillator driven by the wind normal to the blade (Oliapuram 2010). `stochastic`: three "
         "sine angles per leaf whose amplitudes grow with the wind speed (Ota et al. 2004). `none`: "
         "no leaves (a winter tree)."},
    {.path = "forest.species[].leaves.area",
     .bounds_why = why::kLeafArea,
     .description =
         "One-sided area a of one leaf (a square blade of side sqrt(a) on a petiole half as long). "
         "The species holds N = round(`fraction` × A_leaf / a) leaves, where A_leaf = "
         "`canopy.leaf_area_index` × the crown's ground area is its one-sided leaf area; every tree "
         "of the species carries the same leaves, scaled and turned with it."},
    {.path = "forest.species[].leaves.fraction",
     .bounds_why = why::kFraction,
     .description = "Share of the foliage's leaves that are simulated. Below 1, a thinned sample of the same "
                    "leaves, each of the real size, for big forests."},
    {.path = "forest.species[].leaves.mass_per_area",
     .bounds_why = why::kLeafMass,
     .description = "Leaf mass per area sigma: a leaf's mass is sigma a."},
    {.path = "forest.species[].leaves.frequency",
     .bounds_why = why::kFrequency,
     .description = "Flutter frequency f_leaf: the natural frequency of the `pseudo_branch` oscillator; for "
                    "`stochastic`, the angles' frequency, with a jitter of ±20% per leaf and angle."},
    {.path = "forest.species[].leaves.damping_ratio",
     .bounds_why = why::kLeafDamping,
     .description = "Damping ratio zeta of the `pseudo_branch` oscillator. Low, so that leaves flutter; the "
                    "air damps their motion too."},
    {.path = "forest.species[].leaves.petiole_strength",
     .bounds_why = why::kPetiole,
     .description =
         "Median petiole strength S. Each leaf draws its own S from a log-normal distribution and "
         "sheds when the wind's normal force on its blade, 1/2 rho C_n a \\|u . n\\| \\|u\\| (C_n = "
         "1.2), exceeds it."},
    {.path = "forest.species[].leaves.strength_spread",
     .bounds_why = why::kSpread,
     .description =
         "Log-standard deviation of the petiole strengths: the wider, the more gradually the leaves "
         "shed as the wind rises (0: all at once)."},
    {.path = "forest.species[].leaves.flight_drag_coefficient",
     .bounds_why = why::kDrag,
     .description =
         "Drag coefficient C_D of a tumbling leaf in flight, per one-sided area. In still air a leaf "
         "falls at sqrt(2 sigma g / (rho C_D)), 1.28 m/s at the defaults."},
    {.path = "forest.species[].leaves.amplitudes",
     .bounds_why = why::kAmplitude,
     .description = "`stochastic` only: the amplitudes of the three angles at and above `reference_speed`, "
                    "about the vertical (W_H), about the branch (W_V) and about the petiole (W_R)."},
    {.path = "forest.species[].leaves.roll_coupling",
     .bounds_why = why::kGain,
     .description = "`stochastic` only: a, the roll angle's share of the horizontal angle (theta_R gains a "
                    "theta_H)."},
    {.path = "forest.species[].leaves.reference_speed",
     .bounds_why = why::kWindSpeed,
     .description =
         "`stochastic` only: U_ref. The angles' amplitudes scale with min(1, \\|u\\| / U_ref), u the "
         "wind at the leaf."},
    {.path = "forest.species[].leaves.seed",
     .default_note = "global `seed` + 2^32 + species index",
     .description =
         "Seed of the leaves' positions, angles and petiole strengths. The same seed gives the same "
         "leaves on every machine."},
    {.path = "forest.species[].strength",
     .default_note = "none",
     .constraint = "`preset`, or all four of `modulus_of_rupture`, `knot_factor`, `green_density` and "
                   "`anchorage`; required for every species when `forest.damage.enabled` is `true`",
     .description =
         "How much the species' trees take before they fail, as ForestGALES models it (Gardiner et al. 2000, "
         "2008; Hale et al. 2015; docs/damage.md has the model). The stem breaks when the bending moment at "
         "its weakest section, of diameter d, reaches M_b = f_knot MOR pi d^3 / 32; the root-soil plate "
         "turns over when the moment at the stem base reaches M_o = C_reg x green density x stem volume. "
         "`preset` gives all four values from ForestGALES's table; the numbers given beside it replace the "
         "preset's."},
    {.path = "forest.species[].strength.preset",
     .default_note = "none",
     .description =
         "A species of ForestGALES's published table (docs/damage.md, \"Presets\"): its modulus of "
         "rupture, knot factor and green density, and its anchorage on `soil` with `rooting`."},
    {.path = "forest.species[].strength.soil",
     .constraint = "only with `preset`, and not beside `anchorage`",
     .description =
         "The soil group of the preset's anchorage, as in the tree-pulling tests of Nicoll et al. (2006): A "
         "free-draining mineral soil, B gleyed mineral soil, C peaty mineral soil, D deep peat. It chooses "
         "C_reg only."},
    {.path = "forest.species[].strength.rooting",
     .constraint = "only with `preset`, and not beside `anchorage`; `shallow` and `deep` on soil `A` only, "
                   "where the table gives them",
     .description = "The rooting depth of the preset's anchorage. It chooses C_reg only."},
    {.path = "forest.species[].strength.modulus_of_rupture",
     .default_note = "the preset's; required without `preset`",
     .bounds_why = why::kModulusOfRupture,
     .description = "MOR: the bending stress in the outer fibres of green wood at which it breaks. A stem "
                    "section of diameter d breaks under the moment f_knot MOR pi d^3 / 32."},
    {.path = "forest.species[].strength.knot_factor",
     .default_note = "the preset's; required without `preset`",
     .bounds_why = why::kKnotFactor,
     .description = "f_knot: the share of clear wood's strength that the stem keeps with its knots (1: no "
                    "loss)."},
    {.path = "forest.species[].strength.green_density",
     .default_note = "the preset's; required without `preset`",
     .bounds_why = why::kGreenDensity,
     .description =
         "Density of the green (fresh, sap-laden) stem wood, which weighs the stem the roots hold: "
         "W_stem = green density x stem volume. Not `material.density`, the wood's in the tree's "
         "motion."},
    {.path = "forest.species[].strength.anchorage",
     .default_note = "the preset's on `soil` with `rooting`; required without `preset`",
     .bounds_why = why::kAnchorage,
     .description =
         "C_reg: the slope through zero of the critical turning moment over the green stem weight in "
         "tree-pulling tests (Nicoll et al. 2006). The roots give way under M_o = C_reg W_stem."},
};

}  // namespace

std::vector<std::string> preset_words() {
  return trees::preset_names();
}

namespace {

// The values of trees/TreeStrength.hpp's enums, in their order; their words are trees' own (preset_name,
// ...).
using trees::RootingDepth, trees::SoilGroup, trees::StrengthPreset;
constexpr StrengthPreset kStrengthPresets[] = {StrengthPreset::sitka_spruce, StrengthPreset::norway_spruce,
                                               StrengthPreset::scots_pine, StrengthPreset::birch};
constexpr SoilGroup kSoilGroups[] = {SoilGroup::A, SoilGroup::B, SoilGroup::C, SoilGroup::D};
constexpr RootingDepth kRootingDepths[] = {RootingDepth::shallow, RootingDepth::mean, RootingDepth::deep};

template <typename Enum, std::size_t N>
std::vector<std::string> names(const Enum (&values)[N], const char* (*name)(Enum)) {
  std::vector<std::string> words;
  for (const Enum value : values) words.emplace_back(name(value));
  return words;
}

}  // namespace

std::vector<std::string> strength_preset_words() {
  return names(kStrengthPresets, trees::preset_name);
}

std::vector<std::string> soil_group_words() {
  return names(kSoilGroups, trees::soil_name);
}

std::vector<std::string> rooting_depth_words() {
  return names(kRootingDepths, trees::rooting_name);
}

std::span<const KeyDocs> species_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
