// Everything the simulator needs to know about one tree species, computed once before a run: the skeleton,
// its lowest vibration modes and the wind projection basis (docs/design.md, "Data flow").
//
//   fw::trees::SpeciesSettings settings;
//   settings.material = {1.0e10, 3.85e9, 900.0};
//   settings.modal.mode_count = 20;
//   settings.wind.samples = 3;
//   auto species = fw::trees::SpeciesBasis::compute(skeleton, settings);   // assembly + Spectra + p_i
//   species.modes().frequencies_hz();
//   species.wind().projection_matrix();          // (3 S) x m
//   species.node_shapes();                       // (3 n) x m: nodal translations, for u = Phi q on a device
//   species.strong_wind().corrected_displacement(species.skeleton(), q);   // strong-wind pose of Phi q (3 n)
//   species.stem_loads().bending_moments(q);    // N m at every stem section (trees/StemLoads.hpp)
//   auto instance = species.scaled(1.1);         // one basis serves a whole stand of similar trees
//   auto leafier = species.with_leaf_area_index(4.0);   // the same modes, the wind basis of more foliage
//
// The expensive part (the eigenproblem) is cached on disk by trees/BasisCache.hpp, with the strong-wind fit.
#pragma once

#include <Eigen/Core>

#include <optional>
#include "trees/Material.hpp"
#include "trees/ModalBasis.hpp"

#include "trees/Skeleton.hpp"
#include "trees/StemLoads.hpp"
#include "trees/StrongWindCorrection.hpp"
#include "trees/WindBasis.hpp"

namespace fw::trees {

struct SpeciesSettings {
  Material material = kDefaultWood;  ///< E, G (Pa), rho (kg/m^3): Diener's wood, G = E / 2.6
  ModalSettings modal;               ///< how many modes, damping, solver tolerances
  WindBasisSettings wind;            ///< drag coefficients, leaf area index, wind samples
  StrongWindSettings strong_wind;    ///< the fit of Diener's strong-wind correction (samples, ranges)

  /// Throws std::invalid_argument naming the part (Material, ModalSettings, Damping, WindBasisSettings,
  /// StrongWindSettings).
  void validate() const;
};

/// How long the parts of SpeciesBasis::compute took, s.
struct SpeciesTimings {
  double assembly = 0.0;     ///< BeamModel: element matrices and sparse assembly
  double modes = 0.0;        ///< ModalBasis: factorisation and Lanczos
  double wind = 0.0;         ///< WindBasis
  double strong_wind = 0.0;  ///< StrongWindCorrection::fit
  double stem_loads = 0.0;   ///< StemLoads::compute
};

class SpeciesBasis {
 public:
  /// Assembles the FEM model, solves for the modes and projects the wind. Throws what BeamModel, ModalBasis
  /// (ModalError when the modes do not converge) and WindBasis throw.
  static SpeciesBasis compute(Skeleton skeleton, const SpeciesSettings& settings);

  /// Rebuilds a species from its parts (the disk cache). Without a strong-wind correction it is fitted
  /// (settings.strong_wind); without stem loads they are computed (a BeamModel assembled for them). Throws
  /// std::invalid_argument("SpeciesBasis: ...") when the parts do not fit together (DOFs against the
  /// skeleton, mode, sample and node counts).
  static SpeciesBasis from_parts(Skeleton skeleton, SpeciesSettings settings, ModalBasis modes,
                                 WindBasis wind, std::optional<StrongWindCorrection> strong_wind = {},
                                 std::optional<StemLoads> stem_loads = {});

  const Skeleton& skeleton() const { return skeleton_; }
  const SpeciesSettings& settings() const { return settings_; }
  const ModalBasis& modes() const { return modes_; }
  const WindBasis& wind() const { return wind_; }
  /// Diener's quadratic strong-wind correction of node_shapes() * q (trees/StrongWindCorrection.hpp).
  const StrongWindCorrection& strong_wind() const { return strong_wind_; }
  /// The stem's section moments and the root's turning moment as linear maps of q (trees/StemLoads.hpp).
  const StemLoads& stem_loads() const { return stem_loads_; }
  const SpeciesTimings& timings() const { return timings_; }

  /// Nodal translations of every mode, (3 n) x m, m per unit modal coordinate: rows 3k..3k+2 are node k's
  /// x, y, z; the root's rows are zero. The skeleton displacement is node_shapes() * q.
  const Eigen::MatrixXd& node_shapes() const { return node_shapes_; }

  /// The species grown by s about its root origin (Skeleton::transformed(I, 0, s)), with modes, wind basis,
  /// stem loads and strong-wind correction transformed by the similarity laws instead of recomputed.
  SpeciesBasis scaled(double s) const;

  /// The species with another leaf area index per crown (settings().wind.leaf_area_index; a stand that
  /// gives its own, host/app/plan/ForestPlan.cpp): the modes and the strong-wind correction kept, since
  /// foliage adds drag but neither mass nor stiffness (BeamModel), and the wind basis recomputed with the
  /// new foliage. Throws std::invalid_argument("WindBasisSettings: ...") for a leaf area index that is not
  /// finite and >= 0.
  SpeciesBasis with_leaf_area_index(double leaf_area_index) const;

 private:
  Skeleton skeleton_;
  SpeciesSettings settings_;
  ModalBasis modes_;
  WindBasis wind_;
  Eigen::MatrixXd node_shapes_;
  StrongWindCorrection strong_wind_;
  StemLoads stem_loads_;
  SpeciesTimings timings_;
};

}  // namespace fw::trees
