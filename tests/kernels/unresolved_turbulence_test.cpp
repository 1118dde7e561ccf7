// The unresolved turbulence on the device (host/ForestStages::set_unresolved_turbulence; kernels
// tree_unresolved_load and tree_unresolved_advance in kernels/tree_wind_load.cl) against the CPU oracle
// trees::ForestReference::unresolved_modal_forces / advance_travelled, and unchanged results when it is off.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "host/stages/ForestStages.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/ForestReference.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/UnresolvedTurbulence.hpp"

using namespace fw;

namespace {

// Tolerances (float32 kernels against the double oracle), relative to the largest entry:
// delta f: the device's sampled wind is ~1e-5 off the oracle's (tests/kernels/forest_stages_test.cpp), and
// delta f goes with |v|^2; the series in float, the read position, the frame and 3S-term dot products add
// a few ulps each;
constexpr double kForceTolerance = 1e-4;
// the modal state after the run: force errors carry into q linearly (as forest_stages_test.cpp);
constexpr double kStateTolerance = 2e-4;
// travelled distance, m: float speed (~1e-5 relative, as the sampled wind) times the distance travelled, and
// the fraction's rounding (~1e-7 points) per step.
constexpr double kTravelTolerance = 1e-4;

trees::SpeciesBasis small_species(const std::string& preset, double height, std::uint64_t seed, int modes,
                                  int samples) {
  trees::GeneratorSettings g;
  g.preset = preset;
  g.height = height;
  g.seed = seed;
  g.iterations = 4;
  g.max_element_length = height;  // one element per drawn segment: a few dozen nodes
  trees::SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.modal.damping = trees::Damping::modal_ratio(0.03);
  settings.wind.samples = samples;
  return trees::SpeciesBasis::compute(trees::generate_tree(g), settings);
}

// 32 x 24 x 14 cells of 1 m, the origin off zero.
fluid::GridSpec test_grid() {
  fluid::GridSpec spec;
  spec.nx = 32;
  spec.ny = 24;
  spec.nz = 14;
  spec.h = 1.0;
  spec.origin = {-4.0, 3.0, -1.0};
  return spec;
}

// A mean flow (6, -2, 0.3) m/s plus a smooth random wave per component: the trees see different winds.
fluid::MacVelocity smooth_wind(const fluid::GridSpec& spec, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double mean[3] = {6.0, -2.0, 0.3};
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const double amplitude = 2.0 * unit(rng), phase = M_PI * unit(rng);
    const double k[3] = {0.4 * unit(rng), 0.4 * unit(rng), 0.4 * unit(rng)};
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    for (int kk = 0; kk < ez; ++kk)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double x = spec.origin[0] + spec.h * (i + (c == 0 ? 0.0 : 0.5));
          const double y = spec.origin[1] + spec.h * (j + (c == 1 ? 0.0 : 0.5));
          const double z = spec.origin[2] + spec.h * (kk + (c == 2 ? 0.0 : 0.5));
          vel.component(c)[std::size_t(i + ex * (j + ey * kk))] =
              float(mean[c] + amplitude * std::sin(k[0] * x + k[1] * y + k[2] * z + phase));
        }
  }
  return vel;
}

// 12 instances of two species (3 and 2 wind samples), yaws all round, scales 0.6 .. 1.5.
trees::Forest test_forest() {
  std::vector<trees::SpeciesBasis> species = {small_species("broadleaf", 6.0, 1, 6, 3),
                                              small_species("conifer", 5.0, 2, 5, 2)};
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> x(-1.0, 26.0), y(5.0, 25.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 12; ++k) trees.push_back({k % 2, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  return trees::Forest(std::move(species), std::move(trees));
}

// A series on the test grid's 1 m cells, short (2^11 points, 102.4 m) so that the run below wraps it.
trees::UnresolvedTurbulenceSettings series_settings() {
  trees::UnresolvedTurbulenceSettings s;
  s.enabled = true;
  s.cell_size = 1.0;
  s.intensity = 0.3;  // large, so that delta f stands well clear of the resolved force's rounding
  s.integral_length = 40.0;
  s.series_length = 1 << 11;
  s.series_spacing = 0.05;
  s.seed = 5;
  return s;
}

double max_abs(const Eigen::VectorXd& v) {
  return v.cwiseAbs().maxCoeff();
}

Eigen::VectorXd to_eigen(const std::vector<float>& v) {
  Eigen::VectorXd out(Eigen::Index(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out(Eigen::Index(i)) = v[i];
  return out;
}

struct Fixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec = test_grid();
  trees::Forest forest = test_forest();
  trees::ForestReference ref{forest};
  fluid::MacVelocity wind = smooth_wind(spec, 23);
  host::DeviceVelocity dwind;

  explicit Fixture(host::ComputeContext& c) : cc(c) { dwind = test::upload_velocity(cc, wind); }
};

}  // namespace

TEST_CASE("tree_unresolved_load: device forces with the forcing on match the CPU oracle over many steps",
          "[forest][unresolved]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  Fixture f(*cc);
  const trees::UnresolvedTurbulenceSettings settings = series_settings();
  const trees::UnresolvedTurbulence series(settings);
  host::ForestStages on(*cc, f.spec, f.forest), off(*cc, f.spec, f.forest);
  on.set_unresolved_turbulence(series, settings.intensity);
  REQUIRE(on.unresolved_turbulence());
  REQUIRE_FALSE(off.unresolved_turbulence());

  const std::vector<int> offsets = series.offsets(f.forest);
  const Eigen::MatrixX3d sampled = f.ref.sample_wind(f.spec, f.wind);
  const Eigen::VectorXd resolved = f.ref.modal_forces(sampled);
  trees::TreeTravel travelled(f.forest.instance_count());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(f.ref.total_modes()), qdot = q;
  // 10 short steps, then 40 of 0.5 s (3.2 m each): ~130 m in all, past the series' 102.4 m period, so the
  // device's whole-point wrap is exercised against the oracle's unwrapped distance.
  std::vector<double> steps(10, 0.02);
  steps.insert(steps.end(), 40, 0.5);
  // Largest differences and entries over the whole run (a step whose delta f happens to be small would
  // otherwise make its own rounding look large).
  double total_diff = 0.0, total_max = 0.0, delta_diff = 0.0, delta_max = 0.0;
  for (double dt : steps) {
    on.enqueue_wind_load(f.dwind);
    off.enqueue_wind_load(f.dwind);
    const Eigen::VectorXd delta =
        f.ref.unresolved_modal_forces(sampled, travelled, series, offsets, settings.intensity);
    const Eigen::VectorXd device_on = to_eigen(on.download_modal_forces());
    const Eigen::VectorXd device_off = to_eigen(off.download_modal_forces());
    total_diff = std::max(total_diff, max_abs(device_on - (resolved + delta)));
    total_max = std::max(total_max, max_abs(resolved + delta));
    // The device's delta f alone: its forces on minus off (the resolved part is the same kernel's, bit for
    // bit).
    delta_diff = std::max(delta_diff, max_abs(device_on - device_off - delta));
    delta_max = std::max(delta_max, max_abs(delta));
    on.enqueue_modal_step(float(dt));
    off.enqueue_modal_step(float(dt));
    f.ref.step(q, qdot, resolved + delta, double(float(dt)), trees::ModalIntegrator::exact);
    f.ref.advance_travelled(travelled, sampled, double(float(dt)));
  }
  const double total_error = total_diff / total_max, delta_error = delta_diff / delta_max;
  const double delta_scale = delta_max / max_abs(resolved);
  const host::ModalState state = on.download_modal_state();
  const double q_error = max_abs(to_eigen(state.q) - q) / max_abs(q);
  const std::vector<double> device_travel = on.download_travelled();
  REQUIRE(device_travel.size() == std::size_t(f.forest.instance_count()));
  double travel_error = 0.0;
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    const double expected = std::fmod(travelled.distance(k), series.period());
    CHECK(travelled.distance(k) > series.period());  // every tree wrapped
    travel_error = std::max(travel_error, std::abs(device_travel[std::size_t(k)] - expected));
  }
  WARN("unresolved turbulence, " << steps.size() << " steps: max |delta f| / max |f| " << delta_scale
                                 << "; max relative error, total force " << total_error << ", delta f "
                                 << delta_error << ", q " << q_error << "; travelled " << travel_error
                                 << " m");
  CHECK(delta_scale > 0.01);  // the forcing is really there
  CHECK(total_error < kForceTolerance);
  CHECK(delta_error < kForceTolerance);
  CHECK(q_error < kStateTolerance);
  CHECK(travel_error < kTravelTolerance);

  // reset_state restarts the travel too.
  on.reset_state();
  for (double x : on.download_travelled()) CHECK(x == 0.0);
  CHECK_THROWS_WITH(on.set_unresolved_turbulence(series, -0.1),
                    "ForestStages: unresolved turbulence intensity must be finite and >= 0, got -0.1");
  CHECK_THROWS_AS(off.set_unresolved_intensity(0.1), std::invalid_argument);
}

TEST_CASE("tree_unresolved_load: with the forcing off the stages are unchanged bit for bit",
          "[forest][unresolved]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  Fixture f(*cc);
  const trees::UnresolvedTurbulence series(series_settings());
  // Never on; on then off; on at intensity 0 (the kernel runs and adds exact zeros).
  host::ForestStages never(*cc, f.spec, f.forest), toggled(*cc, f.spec, f.forest),
      zero(*cc, f.spec, f.forest);
  toggled.set_unresolved_turbulence(series, 0.2);
  toggled.disable_unresolved_turbulence();
  zero.set_unresolved_turbulence(series, 0.0);
  CHECK(toggled.download_travelled().empty());
  for (int n = 0; n < 20; ++n)
    for (host::ForestStages* s : {&never, &toggled, &zero}) {
      s->enqueue_wind_load(f.dwind);
      s->enqueue_modal_step(0.02f);
    }
  const std::vector<float> forces = never.download_modal_forces();
  const host::ModalState state = never.download_modal_state();
  for (host::ForestStages* s : {&toggled, &zero}) {
    const std::vector<float> other = s->download_modal_forces();
    const host::ModalState other_state = s->download_modal_state();
    CHECK(std::memcmp(forces.data(), other.data(), forces.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(state.q.data(), other_state.q.data(), state.q.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(state.qdot.data(), other_state.qdot.data(), state.qdot.size() * sizeof(float)) == 0);
  }
  // And "off" is the resolved oracle (as in forest_stages_test.cpp).
  const Eigen::VectorXd expected = f.ref.modal_forces(f.spec, f.wind);
  CHECK(max_abs(to_eigen(forces) - expected) / max_abs(expected) < kForceTolerance);
}
