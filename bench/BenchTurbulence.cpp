#include "bench/BenchTurbulence.hpp"

#include <memory>

#include "fluid/TurbulenceBox.hpp"

namespace fw::bench {

void add_bench_turbulence(host::WindGridSetup& setup, const std::array<int, 3>& grid) {
  fluid::TurbulenceBoxSpec box;
  for (int a = 0; a < 3; ++a) box.cells[a] = 2 * grid[a];  // points every h/2
  box.spacing = 0.5 * setup.spec.h;
  box.spectrum = {1.0, kBenchTurbulenceLengthCells * setup.spec.h};
  box.seed = 1;
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
}

void add_bench_subgrid_stress(host::WindGridSetup& setup) {
  setup.settings.smagorinsky_constant = kBenchSmagorinsky;
  setup.settings.wall_roughness_length = kBenchRoughnessLength;
}

}  // namespace fw::bench
