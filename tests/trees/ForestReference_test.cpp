// trees::ForestReference, the CPU oracle of the trees' device stage: wind sampling, the exact and the
// semi-implicit modal step, and the physics of instances (static response, symmetry, yaw, scale laws).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "tests/support/SmallSpecies.hpp"
#include "trees/ForestReference.hpp"

using namespace fw;

namespace {

trees::SpeciesSettings small_settings(int modes = 8, int samples = 3) {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.modal.damping = trees::Damping::modal_ratio(0.05);
  settings.wind.samples = samples;
  return settings;
}

trees::SpeciesBasis small_species(int modes = 8, int samples = 3) {
  return trees::SpeciesBasis::compute(test::asymmetric_skeleton(), small_settings(modes, samples));
}

// 20 x 20 x 12 cells of 1 m, the domain centred on x = y = 0.
fluid::GridSpec test_grid() {
  fluid::GridSpec spec;
  spec.nx = 20;
  spec.ny = 20;
  spec.nz = 12;
  spec.h = 1.0;
  spec.origin = {-10.0, -10.0, 0.0};
  return spec;
}

// Every face set from a function of its component and world position.
fluid::MacVelocity fill(const fluid::GridSpec& spec,
                        const std::function<double(int, const Eigen::Vector3d&)>& value) {
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const Eigen::Vector3d at(spec.origin[0] + spec.h * (i + (c == 0 ? 0.0 : 0.5)),
                                   spec.origin[1] + spec.h * (j + (c == 1 ? 0.0 : 0.5)),
                                   spec.origin[2] + spec.h * (k + (c == 2 ? 0.0 : 0.5)));
          vel.component(c)[std::size_t(i + ex * (j + ey * k))] = float(value(c, at));
        }
  }
  return vel;
}

fluid::MacVelocity uniform_wind(const fluid::GridSpec& spec, const Eigen::Vector3d& v) {
  return fill(spec, [&](int c, const Eigen::Vector3d&) { return v(c); });
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// Textbook solution of x'' + gamma x' + omega^2 x = f from (x0, v0), at time t.
void analytic_oscillator(double x0, double v0, double f, double omega, double gamma, double t, double& x,
                         double& v) {
  const double a = gamma / 2.0, xs = f / (omega * omega);
  const double y0 = x0 - xs;
  if (a < omega) {  // under-damped
    const double wd = std::sqrt(omega * omega - a * a);
    const double A = y0, B = (v0 + a * y0) / wd;
    x = xs + std::exp(-a * t) * (A * std::cos(wd * t) + B * std::sin(wd * t));
    v = std::exp(-a * t) * ((-a * A + wd * B) * std::cos(wd * t) + (-a * B - wd * A) * std::sin(wd * t));
  } else if (a == omega) {  // critical
    const double B = v0 + a * y0;
    x = xs + (y0 + B * t) * std::exp(-a * t);
    v = (B - a * (y0 + B * t)) * std::exp(-a * t);
  } else {  // over-damped: r1, r2 = -a -+ k
    const double k = std::sqrt(a * a - omega * omega);
    const double r1 = -a + k, r2 = -a - k;
    const double A = (v0 - r2 * y0) / (r1 - r2), B = y0 - A;
    x = xs + A * std::exp(r1 * t) + B * std::exp(r2 * t);
    v = A * r1 * std::exp(r1 * t) + B * r2 * std::exp(r2 * t);
  }
}

}  // namespace

TEST_CASE("ForestReference: MAC sampling is exact for linear fields and clamps outside", "[forest]") {
  const auto spec = test_grid();
  const auto vel = fill(
      spec, [](int c, const Eigen::Vector3d& x) { return 1.0 + c + 0.3 * x(0) - 0.2 * x(1) + 0.1 * x(2); });
  const Eigen::Vector3d inside(1.37, -2.81, 4.6);
  const Eigen::Vector3d v = trees::sample_mac_velocity(spec, vel, inside);
  for (int c = 0; c < 3; ++c) CHECK(v(c) == Approx(1.0 + c + 0.3 * 1.37 + 0.2 * 2.81 + 0.46).epsilon(1e-6));
  // Far above the top: the w lattice ends at the top face (z = 12), u and v at the top cell centres (11.5).
  const Eigen::Vector3d above = trees::sample_mac_velocity(spec, vel, {1.37, -2.81, 40.0});
  CHECK(above(0) == Approx(1.0 + 0.3 * 1.37 + 0.2 * 2.81 + 1.15).epsilon(1e-6));
  CHECK(above(2) == Approx(3.0 + 0.3 * 1.37 + 0.2 * 2.81 + 1.2).epsilon(1e-6));
}

TEST_CASE("ForestReference: the exact step matches the analytic damped oscillator under a step force",
          "[forest]") {
  const double omega = 7.0, f = 3.0, x0 = 0.2, v0 = -1.5;
  // zeta: under-damped, nearly critical on both sides, critical, over-damped, heavily over-damped.
  for (double zeta : {0.0, 0.05, 0.7, 1.0 - 1e-7, 1.0, 1.0 + 1e-7, 1.3, 40.0}) {
    const double gamma = 2.0 * zeta * omega;
    for (double dt : {1e-3, 0.05, 0.4, 3.0}) {
      double q = x0, qdot = v0;
      trees::exact_modal_step(q, qdot, f, omega, gamma, dt);
      double x, v;
      analytic_oscillator(x0, v0, f, omega, gamma, dt, x, v);
      INFO("zeta " << zeta << ", dt " << dt);
      // Near critical damping the textbook forms themselves lose ~1e-7 (cancellation in 1/(r1 - r2)).
      const double tolerance = std::abs(zeta - 1.0) < 1e-3 && zeta != 1.0 ? 1e-6 : 1e-10;
      CHECK(std::abs(q - x) <= tolerance * (std::abs(x) + 1.0));
      CHECK(std::abs(qdot - v) <= tolerance * (std::abs(v) + 1.0));
    }
  }
}

TEST_CASE("ForestReference: exact steps compose and stay finite at any dt", "[forest]") {
  for (double zeta : {0.02, 1.0, 1.0 + 1e-9, 5.0}) {
    const double omega = 30.0, gamma = 2.0 * zeta * omega;
    double q1 = 0.1, v1 = 2.0, q2 = 0.1, v2 = 2.0;
    for (int n = 0; n < 10; ++n) trees::exact_modal_step(q1, v1, -4.0, omega, gamma, 0.01);
    trees::exact_modal_step(q2, v2, -4.0, omega, gamma, 0.1);
    CHECK(q1 == Approx(q2).epsilon(1e-10).margin(1e-14));
    CHECK(v1 == Approx(v2).epsilon(1e-10).margin(1e-12));
    // dt far beyond every time scale: the equilibrium, no overflow.
    trees::exact_modal_step(q2, v2, -4.0, omega, gamma, 1e6);
    CHECK(q2 == Approx(-4.0 / (omega * omega)).epsilon(1e-12));
    CHECK(std::abs(v2) < 1e-12);
  }
}

TEST_CASE("ForestReference: the semi-implicit step converges to the exact one as dt -> 0 (first order)",
          "[forest]") {
  const double omega = 12.0, gamma = 2.0 * 0.05 * omega, f = 5.0, T = 1.0;
  double exact_q = 0.0, exact_v = 0.3;
  trees::exact_modal_step(exact_q, exact_v, f, omega, gamma, T);
  double previous = 0.0;
  for (int steps : {200, 400, 800, 1600, 3200}) {
    double q = 0.0, v = 0.3;
    for (int n = 0; n < steps; ++n) trees::semi_implicit_modal_step(q, v, f, omega, gamma, T / steps);
    const double error = std::abs(q - exact_q);
    INFO(steps << " steps: error " << error);
    if (previous > 0.0) CHECK(error / previous == Approx(0.5).margin(0.1));
    previous = error;
  }
  CHECK(previous < 2e-3 * std::abs(exact_q));  // dt = 3e-4 s, omega dt = 4e-3
}

TEST_CASE("ForestReference: a tree in steady uniform wind settles at q = f / omega^2 of its species",
          "[forest]") {
  const auto spec = test_grid();
  const auto species = small_species();
  const trees::Forest forest({species}, {{0, {0.5, -1.0, 0.0}, 0.0, 1.0}});
  const trees::ForestReference ref(forest);
  const Eigen::Vector3d wind(6.0, -2.0, 0.5);
  const auto vel = uniform_wind(spec, wind);

  // The species' own forces: the same wind at every sample point.
  Eigen::MatrixX3d samples(species.wind().sample_count(), 3);
  for (int s = 0; s < samples.rows(); ++s) samples.row(s) = wind.transpose();
  const Eigen::VectorXd f_species = species.wind().modal_forces(samples);
  const Eigen::VectorXd q_static = f_species.cwiseQuotient(species.modes().omega().cwiseAbs2());

  const Eigen::VectorXd f = ref.modal_forces(spec, vel);
  CHECK(relative(f, f_species) < 1e-6);  // float storage of the wind
  CHECK(relative(ref.static_modal_response(f), q_static) < 1e-6);

  // zeta = 0.05 and omega_1 of a few rad/s: 200 s decays the transient by far more than 1e-9.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(ref.total_modes()), qdot = q;
  for (int n = 0; n < 4000; ++n)
    ref.step(q, qdot, ref.modal_forces(spec, vel), 0.05, trees::ModalIntegrator::exact);
  INFO("omega_1 = " << species.modes().omega()(0));
  CHECK(relative(q, q_static) < 1e-6);
  CHECK(qdot.cwiseAbs().maxCoeff() < 1e-6 * q_static.cwiseAbs().maxCoeff() * species.modes().omega()(0));

  // The linear displacement is the species' node shapes times q.
  const Eigen::VectorXd u_species = species.node_shapes() * q_static;
  const Eigen::MatrixX3d u = ref.displacements(q_static, false);
  for (int n = 0; n < species.skeleton().size(); ++n)
    CHECK((u.row(n).transpose() - u_species.segment<3>(3 * n)).norm() <= 1e-12 * u_species.norm());
}

TEST_CASE("ForestReference: reversing a uniform wind reverses the forces and the static deflection",
          "[forest]") {
  const auto spec = test_grid();
  const trees::Forest forest({small_species()},
                             {{0, {1.0, 2.0, 0.0}, 0.7, 1.1}, {0, {-3.0, -2.0, 0.0}, -2.0, 0.9}});
  const trees::ForestReference ref(forest);
  const Eigen::Vector3d west(7.0, 1.0, -0.3);
  const Eigen::VectorXd from_west = ref.modal_forces(spec, uniform_wind(spec, west));
  const Eigen::VectorXd from_east = ref.modal_forces(spec, uniform_wind(spec, -west));
  CHECK(from_west.cwiseAbs().maxCoeff() > 0.0);
  CHECK((from_west + from_east).cwiseAbs().maxCoeff() == 0.0);  // |v| v is odd in v, exactly
  // Linear deflections only: the strong-wind correction's q~^2 w terms are even in q.
  const Eigen::MatrixX3d u_west = ref.displacements(ref.static_modal_response(from_west), false);
  const Eigen::MatrixX3d u_east = ref.displacements(ref.static_modal_response(from_east), false);
  CHECK((u_west + u_east).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("ForestReference: a mirror-symmetric tree deflects as the mirror image in the mirrored wind",
          "[forest]") {
  // Symmetric under x -> -x: node 2k+4 mirrors node 2k+5 (branches), the trunk (0..3) mirrors itself.
  std::vector<trees::SkeletonNode> nodes = {{-1, {0.0, 0.0, 0.0}, 0.10}, {0, {0.0, 0.0, 1.5}, 0.08},
                                            {1, {0.0, 0.0, 3.0}, 0.06},  {2, {0.0, 0.0, 4.0}, 0.04},
                                            {1, {1.0, 0.0, 2.3}, 0.03},  {1, {-1.0, 0.0, 2.3}, 0.03},
                                            {4, {1.6, 0.3, 2.9}, 0.02},  {5, {-1.6, 0.3, 2.9}, 0.02},
                                            {2, {0.8, -0.2, 3.6}, 0.02}, {2, {-0.8, -0.2, 3.6}, 0.02}};
  const int mirror[] = {0, 1, 2, 3, 5, 4, 7, 6, 9, 8};
  // All modes but one of the 54 DOFs: a complete set of mirror-symmetric and -antisymmetric modes up to the
  // last, so the truncated static response keeps the symmetry.
  const auto species =
      trees::SpeciesBasis::compute(trees::Skeleton::from_nodes(nodes), small_settings(53, 2));
  const auto spec = test_grid();
  const trees::Forest forest({species}, {{0, {0.0, 0.0, 0.0}, 0.0, 1.0}});
  const trees::ForestReference ref(forest);
  const Eigen::Vector3d from_west(8.0, 1.5, 0.4), from_east(-8.0, 1.5, 0.4);
  const Eigen::MatrixX3d uw =
      ref.displacements(ref.static_modal_response(spec, uniform_wind(spec, from_west)));
  const Eigen::MatrixX3d ue =
      ref.displacements(ref.static_modal_response(spec, uniform_wind(spec, from_east)));
  Eigen::MatrixX3d mirrored(uw.rows(), 3);
  for (int n = 0; n < uw.rows(); ++n)
    mirrored.row(mirror[n]) = uw.row(n).cwiseProduct(Eigen::RowVector3d(-1, 1, 1));
  CHECK(uw.row(3).norm() > 0.0);
  CHECK(relative(ue, mirrored) < 1e-6);
}

TEST_CASE("ForestReference: a tree yawed by 90 degrees in a wind turned by 90 degrees feels the same forces",
          "[forest]") {
  const auto spec = test_grid();
  const auto species = small_species();
  // A sheared wind that turns with height: every sample gets its own velocity.
  auto wind = [](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(4.0 + 0.8 * x(2), 0.5 * x(2) - 1.0, 0.2);
  };
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto vel = fill(spec, [&](int c, const Eigen::Vector3d& x) { return wind(x)(c); });
  const auto turned = fill(spec, [&](int c, const Eigen::Vector3d& x) { return (quarter * wind(x))(c); });

  for (double yaw : {0.0, 0.4, -2.5}) {
    const trees::Forest a({species}, {{0, {0.0, 0.0, 0.0}, yaw, 1.0}});
    const trees::Forest b({species}, {{0, {0.0, 0.0, 0.0}, yaw + M_PI / 2, 1.0}});
    const Eigen::VectorXd fa = trees::ForestReference(a).modal_forces(spec, vel);
    const Eigen::VectorXd fb = trees::ForestReference(b).modal_forces(spec, turned);
    INFO("yaw " << yaw);
    // The wind is linear in z, and the turned field is stored in float: agreement to float rounding.
    CHECK(relative(fb, fa) < 1e-6);
    // And the deflection turns with the tree.
    const Eigen::MatrixX3d ua =
        trees::ForestReference(a).displacements(trees::ForestReference(a).static_modal_response(fa));
    const Eigen::MatrixX3d ub =
        trees::ForestReference(b).displacements(trees::ForestReference(b).static_modal_response(fb));
    CHECK(relative(ub, ua * quarter.transpose()) < 1e-6);
  }
}

TEST_CASE("ForestReference: an instance of scale s behaves as the species scaled by s", "[forest]") {
  const auto spec = test_grid();
  const auto species = small_species();
  const auto vel = fill(spec, [](int c, const Eigen::Vector3d& x) {
    return c == 0 ? 5.0 + 0.6 * x(2) + 0.1 * x(1) : (c == 1 ? 1.0 - 0.2 * x(0) : 0.1 * x(2));
  });
  for (double s : {0.6, 1.45}) {
    INFO("scale " << s);
    const trees::Forest instance({species}, {{0, {0.5, 0.25, 0.0}, 0.8, s}});
    const trees::Forest grown({species.scaled(s)}, {{0, {0.5, 0.25, 0.0}, 0.8, 1.0}});
    const trees::ForestReference a(instance), b(grown);
    CHECK(relative(a.omega(), b.omega()) < 1e-14);
    CHECK(relative(a.gamma(), b.gamma()) < 1e-14);
    CHECK(relative(a.sample_positions(), b.sample_positions()) < 1e-14);
    const Eigen::VectorXd fa = a.modal_forces(spec, vel), fb = b.modal_forces(spec, vel);
    CHECK(relative(fa, fb) < 1e-12);
    Eigen::VectorXd qa = Eigen::VectorXd::Zero(a.total_modes()), va = qa, qb = qa, vb = qa;
    for (int n = 0; n < 20; ++n) {
      a.step(qa, va, fa, 0.01, trees::ModalIntegrator::exact);
      b.step(qb, vb, fb, 0.01, trees::ModalIntegrator::exact);
    }
    CHECK(relative(a.displacements(qa), b.displacements(qb)) < 1e-12);

    // A species solved afresh from the grown skeleton: same frequencies, and the same static deflection
    // (which does not depend on the sign each fresh mode happens to get).
    const auto fresh = trees::SpeciesBasis::compute(
        test::asymmetric_skeleton().transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s),
        small_settings());
    const trees::Forest solved({fresh}, {{0, {0.5, 0.25, 0.0}, 0.8, 1.0}});
    const trees::ForestReference c(solved);
    CHECK(relative(c.omega(), a.omega()) < 1e-8);
    CHECK(relative(c.displacements(c.static_modal_response(spec, vel)),
                   a.displacements(a.static_modal_response(fa))) < 1e-6);
  }
}

TEST_CASE("ForestReference: wrong sizes and a bad dt throw invalid_argument", "[forest]") {
  const trees::Forest forest({small_species(6, 1)}, {{0, {0, 0, 0}, 0.0, 1.0}});
  const trees::ForestReference ref(forest);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6), qdot = q, f = q;
  CHECK_THROWS_WITH(ref.step(q, qdot, f, -0.1, trees::ModalIntegrator::exact),
                    "ForestReference: dt must be finite and >= 0, got -0.1");
  Eigen::VectorXd short_f = Eigen::VectorXd::Zero(5);
  CHECK_THROWS_AS(ref.step(q, qdot, short_f, 0.1, trees::ModalIntegrator::exact), std::invalid_argument);
  CHECK_THROWS_AS(ref.displacements(short_f), std::invalid_argument);
  CHECK_THROWS_AS(ref.modal_forces(Eigen::MatrixX3d::Zero(2, 3)), std::invalid_argument);
}
