// A species' template fitted to a measured height and dbh (trees/SizeFit.hpp): the fitted tree's size, and
// its f1 against a direct FEM solve of its own skeleton.
#include "trees/SizeFit.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "trees/SpeciesBasis.hpp"
#include "trees/TreeGenerator.hpp"

using fw::trees::SizeFitter;
using fw::trees::SpeciesBasis;

namespace {

SpeciesBasis template_basis(const char* preset, double height) {
  fw::trees::GeneratorSettings generate;
  generate.preset = preset;
  generate.height = height;
  generate.seed = 4;
  fw::trees::SpeciesSettings settings;
  settings.modal.mode_count = 4;
  settings.wind.samples = 3;
  return SpeciesBasis::compute(fw::trees::generate_tree(generate), settings);
}

}  // namespace

TEST_CASE("SizeFit: a fitted tree has the measured height and dbh, and its f1 is a direct solve's",
          "[trees]") {
  const SpeciesBasis spruce = template_basis("conifer", 20.0);
  const SizeFitter fitter(spruce.skeleton().height(), spruce.stem_loads());
  // Measured trees around the template (20 m, dbh 0.32 m, H/dbh 63): slender and stout, short and tall.
  const std::vector<std::pair<double, double>> measured{
      {23.3, 0.29}, {16.2, 0.31}, {27.5, 0.33}, {18.0, 0.21}};
  for (const auto& [height, dbh] : measured) {
    INFO("measured height " << height << " m, dbh " << dbh << " m");
    REQUIRE(fitter.fits(height, dbh));
    const fw::trees::SizeFit fit = fitter.fit(height, dbh);
    // The instance: the class's basis at the scale of the height.
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    const SpeciesBasis girth_class =
        SpeciesBasis::compute(fw::trees::with_girth(spruce.skeleton(), fit.girth), spruce.settings());
    const SpeciesBasis instance = girth_class.scaled(fit.scale);
    // Height exact to rounding; dbh within half a class step (1%), the 1%.
    CHECK(instance.skeleton().height() == Approx(height).epsilon(1e-12));
    CHECK(instance.stem_loads().breast_height_diameter() == Approx(dbh).epsilon(0.01));
    CHECK(fit.dbh == Approx(instance.stem_loads().breast_height_diameter()).epsilon(1e-12));
    // The tree the inventory describes, solved directly: the template grown to the height, its radii to the
    // dbh exactly.
    const SpeciesBasis direct = SpeciesBasis::compute(
        fw::trees::with_girth(spruce.skeleton().transformed(identity, Eigen::Vector3d::Zero(), fit.scale),
                              fitter.needed_girth(height, dbh)),
        spruce.settings());
    const double f1 = instance.modes().frequencies_hz()(0), f1_direct = direct.modes().frequencies_hz()(0);
    // Bending frequencies go as the girth, and the class is within 1% of it: 1% in f1, with a little room
    // for the axial and shear terms that do not follow it (the header's list).
    CHECK(f1 == Approx(f1_direct).epsilon(0.012));
    // The class's cost against the nearest the ladder could not do better than: f1 / f1_direct - 1 tracks
    // fit.girth / needed - 1 (bending), to 0.2%.
    const double girth_error = fit.girth / fitter.needed_girth(height, dbh) - 1.0;
    CHECK(f1 / f1_direct - 1.0 == Approx(girth_error).margin(0.002));
    WARN("fitted " << height << " m, dbh " << dbh << " m: dbh " << fit.dbh << " m, f1 " << f1
                   << " Hz, direct " << f1_direct << " Hz (" << 100.0 * (f1 / f1_direct - 1.0) << "%)");
  }
}

TEST_CASE("SizeFit: girth classes make a 2% ladder, and a dbh past 4 times the template's does not fit",
          "[trees]") {
  CHECK(SizeFitter::girth_of_class(0) == 1.0);
  CHECK(SizeFitter::girth_of_class(1) == Approx(1.02).epsilon(1e-15));
  CHECK(SizeFitter::girth_of_class(-3) == Approx(std::pow(1.02, -3.0)).epsilon(1e-15));
  const SpeciesBasis spruce = template_basis("conifer", 20.0);
  const SizeFitter fitter(spruce.skeleton().height(), spruce.stem_loads());
  const double dbh = spruce.stem_loads().breast_height_diameter();
  CHECK(fitter.fit(20.0, dbh).girth_class == 0);  // the template itself
  CHECK(fitter.fit(20.0, dbh).scale == Approx(1.0).epsilon(1e-12));
  const auto [low, high] = fitter.dbh_range(20.0);
  CHECK(low == Approx(dbh / 4.0).epsilon(1e-12));
  CHECK(high == Approx(dbh * 4.0).epsilon(1e-12));
  CHECK(fitter.fits(20.0, high * 0.999));
  CHECK_FALSE(fitter.fits(20.0, high * 1.001));
  CHECK_FALSE(fitter.fits(20.0, 32.0));  // a dbh in centimetres
  CHECK_THROWS_AS(fw::trees::with_girth(spruce.skeleton(), 0.0), std::invalid_argument);
}
