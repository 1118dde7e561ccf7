#include "fluid/InflowProfile.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using fw::fluid::InflowProfile;

namespace {

InflowProfile power_law(double reference_height_m, double alpha) {
  InflowProfile p;
  p.type = InflowProfile::Type::power;
  p.reference_height = reference_height_m;
  p.alpha = alpha;
  return p;
}

InflowProfile log_law(double reference_height_m, double z0_m, double d_m) {
  InflowProfile p;
  p.type = InflowProfile::Type::log;
  p.reference_height = reference_height_m;
  p.roughness_length = z0_m;
  p.displacement_height = d_m;
  return p;
}

std::string validation_error(const InflowProfile& p) {
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("InflowProfile: the uniform profile is 1 at every height") {
  const InflowProfile p;  // default: uniform
  REQUIRE(p.type == InflowProfile::Type::uniform);
  CHECK_NOTHROW(p.validate());
  for (double z : {0.0, 0.01, 1.0, 10.0, 250.0}) CHECK(p.shape(z) == 1.0);
}

TEST_CASE("InflowProfile: the power law is 1 at the reference height and 2^alpha at twice it") {
  const InflowProfile p = power_law(10.0, 0.2);
  CHECK_NOTHROW(p.validate());
  // Tolerance: relative 1e-12, rounding of pow in double.
  CHECK(p.shape(10.0) == Approx(1.0).epsilon(1e-12));
  CHECK(p.shape(20.0) == Approx(std::pow(2.0, 0.2)).epsilon(1e-12));
  CHECK(p.shape(5.0) == Approx(std::pow(0.5, 0.2)).epsilon(1e-12));
  CHECK(p.shape(0.0) == 0.0);
  // alpha = 0 is the uniform profile above the floor.
  CHECK(power_law(10.0, 0.0).shape(37.0) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("InflowProfile: the power law grows with height") {
  const InflowProfile p = power_law(10.0, 0.14);
  double previous = p.shape(0.5);
  for (double z = 1.0; z <= 100.0; z += 1.0) {
    const double s = p.shape(z);
    CHECK(s > previous);
    previous = s;
  }
}

TEST_CASE(
    "InflowProfile: the log law is 1 at the reference height and ln((z-d)/z0)/ln((zref-d)/z0) elsewhere") {
  const double z0 = 0.8, d = 12.0, zref = 30.0;
  const InflowProfile p = log_law(zref, z0, d);
  CHECK_NOTHROW(p.validate());
  // Tolerance: relative 1e-12, rounding of log in double.
  CHECK(p.shape(zref) == Approx(1.0).epsilon(1e-12));
  for (double z : {13.0, 15.0, 25.0, 60.0, 200.0}) {
    INFO("z = " << z);
    CHECK(p.shape(z) == Approx(std::log((z - d) / z0) / std::log((zref - d) / z0)).epsilon(1e-12));
  }
  // No displacement: the classic log law.
  const InflowProfile q = log_law(10.0, 0.1, 0.0);
  CHECK(q.shape(10.0) == Approx(1.0).epsilon(1e-12));
  CHECK(q.shape(1.0) == Approx(std::log(10.0) / std::log(100.0)).epsilon(1e-12));  // = 0.5
}

TEST_CASE("InflowProfile: the log law is zero at and below d + z0") {
  // d + z0 = 12.5 m, exact in binary.
  const InflowProfile p = log_law(30.0, 0.5, 12.0);
  CHECK(p.shape(12.5) == 0.0);
  CHECK(p.shape(12.25) == 0.0);
  CHECK(p.shape(5.0) == 0.0);
  CHECK(p.shape(0.0) == 0.0);
  CHECK(p.shape(-3.0) == 0.0);
  CHECK(p.shape(12.6) > 0.0);  // just above
}

TEST_CASE("InflowProfile: validate rejects bad parameters with an 'InflowProfile:' message") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using Catch::Contains;
  using Catch::StartsWith;
  SECTION("reference height") {
    for (double zref : {0.0, -5.0, nan}) {
      INFO("reference_height = " << zref);
      InflowProfile p;
      p.reference_height = zref;
      CHECK_THAT(validation_error(p), StartsWith("InflowProfile:") && Contains("reference_height"));
      CHECK_THAT(validation_error(power_law(zref, 0.2)), StartsWith("InflowProfile:"));
      CHECK_THAT(validation_error(log_law(zref, 0.1, 0.0)), StartsWith("InflowProfile:"));
    }
  }
  SECTION("power-law exponent") {
    CHECK_THAT(validation_error(power_law(10.0, -0.1)), StartsWith("InflowProfile:") && Contains("alpha"));
    CHECK_THAT(validation_error(power_law(10.0, nan)), StartsWith("InflowProfile:") && Contains("alpha"));
    CHECK(validation_error(power_law(10.0, 0.0)).empty());
  }
  SECTION("roughness length") {
    CHECK_THAT(validation_error(log_law(10.0, 0.0, 0.0)),
               StartsWith("InflowProfile:") && Contains("roughness_length"));
    CHECK_THAT(validation_error(log_law(10.0, -0.1, 0.0)),
               StartsWith("InflowProfile:") && Contains("roughness_length"));
  }
  SECTION("displacement height") {
    CHECK_THAT(validation_error(log_law(10.0, 0.1, -1.0)),
               StartsWith("InflowProfile:") && Contains("displacement_height"));
  }
  SECTION("reference height at or below d + z0") {
    CHECK_THAT(validation_error(log_law(10.0, 0.8, 12.0)),
               StartsWith("InflowProfile:") && Contains("must exceed"));
    CHECK_THAT(validation_error(log_law(12.5, 0.5, 12.0)), StartsWith("InflowProfile:"));  // equal
    CHECK(validation_error(log_law(12.6, 0.5, 12.0)).empty());
  }
  SECTION("parameters of other profile types are not checked") {
    InflowProfile p = power_law(10.0, 0.2);
    p.roughness_length = -1.0;
    CHECK(validation_error(p).empty());
  }
}

TEST_CASE("InflowProfile: sample_cell_centres evaluates the shape at (k + 0.5) h") {
  const InflowProfile p = log_law(10.0, 0.1, 1.0);
  const double h = 2.0;
  const auto s = p.sample_cell_centres(6, h);
  REQUIRE(s.size() == 6);
  for (int k = 0; k < 6; ++k) {
    INFO("k = " << k);
    // Exact: the samples are shape() rounded to float.
    CHECK(s[k] == static_cast<float>(p.shape((k + 0.5) * h)));
  }
  CHECK(s[0] == 0.0f);  // z = 1 m <= d + z0 = 1.1 m
  CHECK(s[1] > 0.0f);
  CHECK(p.sample_cell_centres(0, h).empty());
  const auto uniform = InflowProfile{}.sample_cell_centres(3, 0.5);
  CHECK(uniform == std::vector<float>{1.0f, 1.0f, 1.0f});
}
