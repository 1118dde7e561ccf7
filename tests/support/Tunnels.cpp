#include "tests/support/Tunnels.hpp"

#include <memory>
#include <numbers>

#include "fluid/SolidMap.hpp"
#include "fluid/TurbulenceBox.hpp"

namespace fw::test {

using B = fluid::BoundaryType;

host::WindGridSetup tunnel(fluid::AdvectionScheme scheme) {
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 32, spec.ny = 16, spec.nz = 8, spec.h = 1.0;
  spec.origin = {-4.0, 2.0, 0.0};
  spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::no_slip, B::slip};
  fluid::SolidMap solids(spec);
  solids.add(fluid::SolidBox{"box", {12.0, 10.0, 2.0}, {6.0, 5.0, 4.0}, 30.0 * std::numbers::pi / 180.0});
  solids.add(fluid::SolidCylinder{"mast", {20.0, 6.0, 0.0}, 1.5, 6.0});
  setup.solid = solids.cells();
  setup.settings.advection = scheme;
  setup.settings.cfl = 0.8;
  setup.settings.max_dt = 0.5;
  setup.ambient = {6.0, 1.0, 0.0};
  return setup;
}

host::WindGridSetup periodic_channel() {
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 32, spec.ny = 16, spec.nz = 8, spec.h = 1.0;
  spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::no_slip, B::slip};
  setup.settings.advection = fluid::AdvectionScheme::maccormack;
  setup.settings.smagorinsky_constant = 0.16;
  setup.settings.vorticity_confinement = 0.2;
  setup.settings.dt = 0.2;
  setup.forcing.relaxation_time = 5.0;
  setup.ambient = {4.0, 0.0, 0.0};
  FwGust gust{};
  gust.start = 0.0f, gust.duration = 2.0f, gust.peak_speed = 3.0f, gust.radius = 4.0f;
  gust.center[0] = 8.0f, gust.center[1] = 8.0f, gust.center[2] = 4.0f;
  gust.travel[0] = 4.0f, gust.direction[0] = 1.0f;
  setup.gusts = {gust};
  return setup;
}

host::WindBlocks blocks_of(const host::WindGridSetup& setup, std::array<int, 2> blocks,
                           const host::Communicator& world) {
  return {&world, fluid::Decomposition::make(
                      setup.spec, world.size(), blocks,
                      host::advection_method(setup.settings.advection).halo_cells(setup.settings.cfl))};
}

host::WindGridSetup turbulent_tunnel() {
  host::WindGridSetup setup = tunnel(fluid::AdvectionScheme::upwind5);
  setup.spec.boundary[FW_FACE_GROUND] = B::slip;  // the rough floor's stress is the wall stage's
  setup.settings.subgrid = fluid::SubgridModel::tke;
  setup.settings.wall_roughness_length = 0.1;
  setup.settings.vorticity_confinement = 0.2;
  fluid::TurbulenceBoxSpec box;
  box.cells = {64, 32, 16};
  box.spacing = 0.5;
  box.spectrum = {1.0, 6.0};
  box.seed = 5;
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  return setup;
}

std::vector<float> canopy_in_cells(const fluid::GridSpec& spec, std::array<int, 3> first,
                                   std::array<int, 3> end, float density) {
  std::vector<float> k(spec.cell_count(), 0.0f);
  for (int z = first[2]; z < end[2]; ++z)
    for (int y = first[1]; y < end[1]; ++y)
      for (int x = first[0]; x < end[0]; ++x)
        k[x + std::size_t(spec.nx) * (y + std::size_t(spec.ny) * z)] = density;
  return k;
}

std::vector<float> tunnel_canopy(const fluid::GridSpec& spec) {
  return canopy_in_cells(spec, {6, 3, 0}, {26, 13, 5}, 0.3f);
}

}  // namespace fw::test
