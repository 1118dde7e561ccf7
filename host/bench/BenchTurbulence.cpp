#include "host/bench/BenchTurbulence.hpp"

#include <memory>

#include "fluid/TurbulenceBox.hpp"

namespace fw::bench {

void add_bench_turbulence(host::WindGridSetup& setup, const std::array<int, 3>& grid) {
  fluid::TurbulenceBoxSpec box;
  // As a run's plan builds it (host/app/plan/TurbulencePlan.cpp): points every h / kTurbulencePointsPerCell.
  for (int a = 0; a < 3; ++a) box.cells[a] = fluid::kTurbulencePointsPerCell * grid[a];
  box.spacing = setup.spec.h / fluid::kTurbulencePointsPerCell;
  box.spectrum = {1.0, kBenchTurbulenceLengthCells * setup.spec.h};
  box.seed = 1;
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
}

void add_bench_subgrid_stress(host::WindGridSetup& setup) {
  setup.settings.smagorinsky_constant = kBenchSmagorinsky;
  setup.settings.wall_roughness_length = kBenchRoughnessLength;
}

}  // namespace fw::bench
