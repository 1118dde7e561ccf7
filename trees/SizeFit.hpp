// A species' template fitted to one tree's measured height and dbh (docs/gis.md, "Each tree its size"): a
// forest inventory's tree becomes an instance of a girth class of its species.
//
//   const fw::trees::SizeFitter fitter(spruce.skeleton().height(), spruce.stem_loads());
//   const fw::trees::SizeFit fit = fitter.fit(/*height_m=*/23.4, /*dbh_m=*/0.31);
//   fit.scale;         // a = H / H_T: the instance's uniform scale
//   fit.girth_class;   // k: the basis of with_girth(spruce.skeleton(), girth_of_class(k)) serves it
//   fit.dbh;           // the fitted tree's dbh: within kGirthStep / 2 of 0.31, relative
//
// The fitted tree is the template with its lengths times a = H / H_T (the height follows the measured one)
// and its radii times a g (so does the dbh). That is the instance of scale a of the template with its radii
// times g, and an instance's modes are exact (omega / a, ModalBasis.hpp: a geometric similarity). The girth
// g = dbh / (a d_T(1.3 m / a)), d_T the template's stem diameter at a height, since breast height on the
// fitted tree is 1.3 m / a up the template's stem.
//
// Radii alone do not scale the modes exactly: bending stiffness goes as g^4 and the mass as g^2, so bending
// frequencies go as g, but axial and torsional ones do not change, shear stiffness goes as g^2, and the
// rotary inertia as g^4. So each girth is solved, not scaled: the classes g_k = (1 + kGirthStep)^k, k a whole
// number, one basis each per species, fit the dbh to within kGirthStep / 2 (a basis per tree would be a FEM
// solve per tree). The f1 they cost, against a direct solve of each tree's own skeleton, is measured in
// tests/trees/SizeFit_test.cpp and reported in docs/gis.md.
#pragma once

#include <utility>

#include "trees/Skeleton.hpp"
#include "trees/StemLoads.hpp"

namespace fw::trees {

struct SizeFit {
  double scale = 1.0;   ///< a = H / H_T
  int girth_class = 0;  ///< k
  double girth = 1.0;   ///< g_k = (1 + kGirthStep)^k
  double dbh = 0.0;     ///< the fitted tree's dbh, m: a g_k d_T(1.3 m / a)
};

class SizeFitter {
 public:
  /// The classes' ratio less one: a 2% ladder fits every dbh within 1%.
  static constexpr double kGirthStep = 0.02;
  /// The largest girth either way (4 and 1/4): past it the template's shape (its taper, its crown) no longer
  /// stands for the tree, and a girth class 70 steps from the template is a sign of a wrong column or unit.
  static constexpr double kMaxGirth = 4.0;

  /// The template: its height H_T (m, > 0) and its stem (diameter_at). Throws std::invalid_argument for a
  /// template without height or stem.
  SizeFitter(double template_height, const StemLoads& stem);

  /// The girth a tree of `height_m` needs to have `dbh_m` at breast height (both > 0).
  double needed_girth(double height_m, double dbh_m) const;
  /// Whether needed_girth lies within [1 / kMaxGirth, kMaxGirth].
  bool fits(double height_m, double dbh_m) const;
  /// The dbh range, m, that fits at `height_m`.
  std::pair<double, double> dbh_range(double height_m) const;
  /// The fit of a tree that fits(); its nearest girth class (in log).
  SizeFit fit(double height_m, double dbh_m) const;

  static double girth_of_class(int k);

 private:
  double template_height_;
  StemLoads stem_;  // a copy: the fitter outlives the basis vector it came from
};

/// The skeleton with every radius times `girth` (finite, > 0; else std::invalid_argument), positions kept.
Skeleton with_girth(const Skeleton& skeleton, double girth);

}  // namespace fw::trees
