#include "tests/support/LeafRun.hpp"

#include "fluid/SolidMap.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "trees/Foliage.hpp"

namespace fw::test {

namespace {
constexpr double kLeafAreaIndex = 3.0;
}  // namespace

LeafRun::LeafRun(double speed, fluid::AdvectionScheme advection) {
  using B = fluid::BoundaryType;
  wind.spec.nx = 48;
  wind.spec.ny = 16;
  wind.spec.nz = 16;
  wind.spec.h = 1.0;
  wind.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  wind.settings.cfl = 0.8;
  wind.settings.max_dt = 0.1;
  wind.settings.advection = advection;
  wind.ambient = {speed, 0.0, 0.0};
  fluid::SolidMap solids(wind.spec);
  solids.add(fluid::SolidBox{"block", {30.0, 8.0, 2.0}, {6.0, 16.0, 4.0}});
  wind.solid = solids.cells();
  const trees::SpeciesBasis species = small_species("broadleaf", 8.0, 3, 5, 6, 2, kLeafAreaIndex);
  trees::LeafSettings leaves;
  leaves.area = 0.01;             // m^2: big leaves, a few thousand a tree
  leaves.petiole_strength = 0.3;  // N: the median leaf goes near 12 m/s
  leaves.strength_spread = 0.8;
  coupling.leaves = {trees::SpeciesLeaves::generate(
      species.skeleton(), trees::Foliage::of(species.skeleton(), kLeafAreaIndex), leaves)};
  forest = trees::Forest({species}, {{0, {8.0, 5.0, 0.0}, 0.4, 1.0}, {0, {12.0, 11.0, 0.0}, 2.0, 1.1}});
}

}  // namespace fw::test
