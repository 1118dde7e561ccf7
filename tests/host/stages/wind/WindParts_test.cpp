// The wind grid's parts (host/stages/wind): each one's device memory, its halo needs, and the advection
// schemes' methods.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fluid/SolidMap.hpp"
#include "host/stages/WindGrid.hpp"
#include "host/stages/wind/MacCormackAdvection.hpp"
#include "host/stages/wind/SemiLagrangianAdvection.hpp"
#include "host/stages/wind/SmagorinskySubgrid.hpp"
#include "host/stages/wind/TkeSubgrid.hpp"
#include "host/stages/wind/Upwind5Advection.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
using B = fluid::BoundaryType;

namespace {

// Everything a part can allocate for: solids (the wall faces, the pressure masks), gusts, vorticity
// confinement, rough walls, and an inflow turbulence box (its values and the prescribed shell).
host::WindGridSetup full_setup(fluid::AdvectionScheme advection, fluid::SubgridModel subgrid) {
  host::WindGridSetup setup;
  setup.spec.nx = 40, setup.spec.ny = 20, setup.spec.nz = 12, setup.spec.h = 1.0;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  setup.settings.advection = advection;
  setup.settings.subgrid = subgrid;
  setup.settings.smagorinsky_constant = subgrid == fluid::SubgridModel::tke ? 0.0 : 0.16;
  setup.settings.wall_roughness_length = 0.05;
  setup.settings.vorticity_confinement = 0.1;
  setup.settings.dt = 0.05;
  setup.ambient = {5.0, 0.0, 0.0};
  setup.gusts.push_back(
      FwGust{0.2f, 2.0f, 3.0f, 4.0f, {6.0f, 8.0f, 4.0f}, {5.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}});
  fluid::SolidMap solids(setup.spec);
  solids.add(fluid::SolidBox{"block", {17.0, 9.0, 2.5}, {6.0, 6.0, 5.0}});
  setup.solid = solids.cells();
  fluid::TurbulenceBoxSpec box;
  box.cells = {16, 8, 8};
  box.spacing = 0.5;
  box.spectrum = {1.0, 2.0};
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  return setup;
}

// The allocation a piece of work makes on the context.
template <typename F>
std::size_t allocated_by(host::ComputeContext& cc, F&& work) {
  const std::size_t before = cc.allocated_bytes();
  work();
  return cc.allocated_bytes() - before;
}

}  // namespace

TEST_CASE("wind parts: each part allocates exactly its class's estimate, and says so") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::WindGridSetup setup = full_setup(fluid::AdvectionScheme::upwind5, fluid::SubgridModel::tke);
  host::RankSeam seam(*cc, setup.spec, nullptr);
  host::StageClock clock(*cc);
  host::FluidStages stages(*cc, seam.local());
  const host::WindPartContext context{*cc, stages, seam, clock, setup};
  const fluid::GridSpec& grid = seam.local();
  const fluid::TurbulenceBoxSpec box = setup.turbulence->spec();

  std::unique_ptr<host::PressureProjection> projection;
  CHECK(allocated_by(*cc, [&] { projection = std::make_unique<host::PressureProjection>(context); }) ==
        host::PressureProjection::estimate_device_bytes(setup.spec, {}));
  CHECK(projection->device_bytes() == host::PressureProjection::estimate_device_bytes(setup.spec, {}));

  std::unique_ptr<host::WindBoundaries> boundaries;
  CHECK(allocated_by(*cc, [&] {
          boundaries = std::make_unique<host::WindBoundaries>(context, projection->mask());
        }) == host::WindBoundaries::estimate_device_bytes(grid, &box));
  CHECK(boundaries->device_bytes() == host::WindBoundaries::estimate_device_bytes(grid, &box));
  // The box's part, as the planner counts it apart from the grid's.
  CHECK(host::WindBoundaries::estimate_device_bytes(grid, &box) ==
        host::WindBoundaries::estimate_device_bytes(grid, nullptr) +
            host::WindBoundaries::turbulence_bytes(grid, box));

  for (auto scheme : {fluid::AdvectionScheme::semi_lagrangian, fluid::AdvectionScheme::maccormack,
                      fluid::AdvectionScheme::upwind5}) {
    const host::AdvectionMethod& method = host::advection_method(scheme);
    INFO("advection " << method.name());
    std::unique_ptr<host::Advection> advection;
    CHECK(allocated_by(*cc, [&] { advection = method.make(context); }) == method.device_bytes(grid));
    CHECK(advection->device_bytes() == method.device_bytes(grid));
  }

  std::unique_ptr<host::BodyForces> forces;
  CHECK(allocated_by(*cc, [&] { forces = std::make_unique<host::BodyForces>(context); }) ==
        host::BodyForces::estimate_device_bytes(grid, setup));
  CHECK(forces->device_bytes() == host::BodyForces::estimate_device_bytes(grid, setup));

  std::unique_ptr<host::SubgridModel> smagorinsky, tke;
  CHECK(allocated_by(*cc, [&] {
          smagorinsky = std::make_unique<host::SmagorinskySubgrid>(context, projection->mask());
        }) == host::SmagorinskySubgrid::estimate_device_bytes(grid));
  CHECK(allocated_by(*cc, [&] { tke = std::make_unique<host::TkeSubgrid>(context, projection->mask()); }) ==
        host::TkeSubgrid::estimate_device_bytes(grid));
  CHECK(tke->device_bytes() == host::TkeSubgrid::estimate_device_bytes(grid));
  // nu_t a cell for Smagorinsky's; nu_t, e and the advected e for the tke model.
  CHECK(host::TkeSubgrid::estimate_device_bytes(grid) ==
        3 * host::SmagorinskySubgrid::estimate_device_bytes(grid));

  std::unique_ptr<host::WallStress> wall;
  CHECK(allocated_by(*cc, [&] { wall = std::make_unique<host::WallStress>(context); }) ==
        host::WallStress::estimate_device_bytes(setup, {}));
  CHECK(wall->device_bytes() > 0);  // the ground and the block's top are walls

  host::CanopySink canopy(context);
  CHECK(canopy.device_bytes() == 0);  // nothing until a canopy is set
  std::vector<float> drag(grid.cell_count(), 0.0f);
  drag[grid.cell_count() / 2] = 0.3f;
  CHECK(allocated_by(*cc, [&] { canopy.set(drag, {}); }) == host::CanopySink::estimate_device_bytes(grid));
  CHECK(canopy.device_bytes() == host::CanopySink::estimate_device_bytes(grid));

  host::MolecularViscosity viscosity(context);
  CHECK(viscosity.device_bytes() == 0);
}

TEST_CASE("WindGrid: the device memory estimate is what the grid allocates, for every scheme and model") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const std::pair<fluid::AdvectionScheme, fluid::SubgridModel> cases[] = {
      {fluid::AdvectionScheme::semi_lagrangian, fluid::SubgridModel::smagorinsky},
      {fluid::AdvectionScheme::maccormack, fluid::SubgridModel::smagorinsky},
      {fluid::AdvectionScheme::upwind5, fluid::SubgridModel::smagorinsky},
      {fluid::AdvectionScheme::upwind5, fluid::SubgridModel::tke}};
  for (const auto& [advection, subgrid] : cases) {
    for (bool bare : {false, true}) {
      host::WindGridSetup setup = full_setup(advection, subgrid);
      if (bare) {  // nothing optional: no solids, gusts, confinement, wall stress, turbulence or subgrid
                   // model
        setup.solid.clear();
        setup.gusts.clear();
        setup.turbulence = nullptr;
        setup.settings.vorticity_confinement = 0.0;
        setup.settings.wall_roughness_length = 0.0;
        setup.settings.smagorinsky_constant = 0.0;
        setup.settings.subgrid = fluid::SubgridModel::smagorinsky;
      }
      INFO("advection " << fluid::to_string(advection) << ", subgrid " << fluid::to_string(subgrid)
                        << (bare ? ", bare" : ", every option"));
      std::unique_ptr<host::WindGrid> wind;
      const std::size_t allocated =
          allocated_by(*cc, [&] { wind = std::make_unique<host::WindGrid>(*cc, setup); });
      CHECK(allocated == host::WindGrid::estimate_device_bytes(setup));
      // The parts' own bytes, the velocity's and the kernels' partials make it up.
      std::size_t parts =
          host::WindGrid::fields_bytes(setup.spec) + host::FluidStages::estimate_device_bytes(setup.spec);
      for (const host::WindPart* part : wind->parts()) parts += part->device_bytes();
      CHECK(parts == allocated);
      // Stepping allocates nothing more.
      CHECK(allocated_by(*cc, [&] {
              wind->initialise_ambient();
              wind->step();
            }) == 0);
    }
  }
}

TEST_CASE(
    "WindGrid: its share of its own checkpoint is the checkpoint, so every array a part saves is one it "
    "declares") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // In one process the share of the one part is the whole grid: a resume over another split moves each
  // array a part declares (WindPart::saved_arrays), so an array saved but not declared would go missing here.
  for (const fluid::SubgridModel subgrid : {fluid::SubgridModel::smagorinsky, fluid::SubgridModel::tke}) {
    INFO("subgrid " << fluid::to_string(subgrid));
    host::WindGrid wind(*cc, full_setup(fluid::AdvectionScheme::upwind5, subgrid));
    wind.initialise_ambient();
    wind.step();
    const host::StageState saved = wind.save_state();
    const host::StageState share = wind.share_of({host::SavedShare{&saved, wind.block(), {}}});
    CHECK(share.numbers == saved.numbers);
    REQUIRE(share.buffers.size() == saved.buffers.size());
    for (const auto& [name, bytes] : saved.buffers) {
      INFO("array " << name);
      REQUIRE(share.buffers.count(name) == 1);
      CHECK(share.buffers.at(name) == bytes);
    }
  }
}

TEST_CASE("advection: each scheme's method answers for its class, picked once by the setting") {
  using fluid::AdvectionScheme;
  const host::AdvectionMethod& semi = host::advection_method(AdvectionScheme::semi_lagrangian);
  const host::AdvectionMethod& maccormack = host::advection_method(AdvectionScheme::maccormack);
  const host::AdvectionMethod& upwind = host::advection_method(AdvectionScheme::upwind5);
  CHECK(semi.scheme == AdvectionScheme::semi_lagrangian);
  CHECK(maccormack.scheme == AdvectionScheme::maccormack);
  CHECK(upwind.scheme == AdvectionScheme::upwind5);
  CHECK(upwind.name() == "upwind5");
  // Only upwind5 has a stability limit; the traced schemes lose accuracy, not stability.
  CHECK(upwind.courant_limit == fluid::kUpwind5CourantLimit);
  CHECK(std::isinf(semi.courant_limit));
  CHECK(std::isinf(maccormack.courant_limit));
  // The halo: upwind5's stencil reaches FW_PAD faces; a trace's corners lie within floor(C) + 1 cells.
  CHECK(upwind.halo_cells(1.2) == FW_PAD);
  CHECK(semi.halo_cells(0.8) == FW_PAD);
  CHECK(maccormack.halo_cells(2.5) == FW_PAD);
  CHECK(semi.halo_cells(4.5) == 5);
  CHECK(upwind.halo_cells(std::numeric_limits<double>::max()) == FW_PAD);
  // Its Courant number: the sum of the components' for the limited scheme, the largest otherwise.
  CHECK(upwind.courant_number({2.0, 1.0, 0.5}, 0.5, 1.0) == Approx(1.75));
  CHECK(semi.courant_number({2.0, 1.0, 0.5}, 0.5, 1.0) == Approx(1.0));
  // The traffic model: only the traced schemes gather.
  CHECK(upwind.gathered_loads_per_face == 0.0);
  CHECK(maccormack.gathered_loads_per_face > semi.gathered_loads_per_face);
}

TEST_CASE("RankSeam: an exchange that no part declared is refused, in one process too") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::WindGridSetup setup =
      full_setup(fluid::AdvectionScheme::semi_lagrangian, fluid::SubgridModel::smagorinsky);
  host::RankSeam seam(*cc, setup.spec, nullptr);
  host::FluidStages stages(*cc, seam.local());
  host::DeviceVelocity vel = stages.allocate_velocity();
  cl::Buffer cells = cc->zero_floats(seam.local().cell_count());
  CHECK_THROWS_AS(seam.exchange(vel), std::logic_error);
  CHECK_THROWS_AS(seam.exchange_cells(cells), std::logic_error);
  seam.declare({host::HaloField::faces, FW_PAD});
  CHECK_NOTHROW(seam.exchange(vel));
  CHECK_NOTHROW(seam.copy_seam(vel));
  CHECK_THROWS_WITH(seam.exchange_cells(cells), Catch::Contains("no part declared"));
  // Alone there is no block edge: any width is within reach.
  CHECK(seam.halo_width() == std::numeric_limits<int>::max());
  CHECK(seam.local().cell_count() == setup.spec.cell_count());
}
