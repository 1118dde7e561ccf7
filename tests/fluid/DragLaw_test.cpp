// The canopy's drag law (fluid/DragLaw): the factor on the species' drag coefficients.
#include <catch2/catch.hpp>

#include <cmath>

#include "fluid/DragLaw.hpp"

using fw::fluid::DragLaw;

TEST_CASE("DragLaw: a power of the speed over the reference, held below a tenth of it, 1 when constant") {
  const DragLaw law{-0.5, 4.0};
  CHECK(law.factor(4.0) == Approx(1.0));
  CHECK(law.factor(16.0) == Approx(0.5));  // (16 / 4)^-1/2
  CHECK(law.factor(0.4) == Approx(std::sqrt(10.0)));
  CHECK(law.factor(0.0) == law.factor(0.4));  // held at 0.1 U_ref: finite at rest
  CHECK(DragLaw{}.factor(0.0) == 1.0);
  CHECK(DragLaw{}.factor(30.0) == 1.0);
  const FwDragLaw device = law.to_device();
  CHECK(device.exponent == -0.5f);
  CHECK(device.lowest_speed == Approx(0.4f));
  CHECK(device.inverse_reference_speed == Approx(0.25f));
}

TEST_CASE("DragLaw: an exponent outside [-4/3, 0] or a non-positive reference speed is refused") {
  CHECK_NOTHROW(DragLaw{DragLaw::kLowestExponent, 1.0}.validate());
  CHECK_THROWS_WITH((DragLaw{-1.5, 1.0}.validate()), Catch::Contains("exponent"));
  CHECK_THROWS_WITH((DragLaw{0.2, 1.0}.validate()), Catch::Contains("exponent"));
  CHECK_THROWS_WITH((DragLaw{-0.5, 0.0}.validate()), Catch::Contains("reference speed"));
}
