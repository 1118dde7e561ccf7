#include "fluid/InflowState.hpp"

#include <algorithm>

#include "kernels/shared_types.h"

namespace fw::fluid {

double InflowState::value(const GridSpec& spec, int c, int i, int j, int k, int level) const {
  const double shape = profile[std::clamp(level, 0, spec.nz - 1)];
  double out = double(ambient[c]) * shape;
  if (turbulent()) {
    const int index[3] = {i + spec.block_offset[0], j + spec.block_offset[1], k};
    double world[3];
    for (int a = 0; a < 3; ++a)
      world[a] = spec.origin[a] + spec.h * (index[a] + (a == c ? 0.0 : 0.5)) - turbulence_offset[a];
    const double taper = std::clamp(shape / double(FW_TURBULENCE_FULL_SHAPE), 0.0, 1.0);
    out += double(turbulence_sigma) * taper * turbulence->sample(world[0], world[1], world[2])[c];
  }
  return out;
}

}  // namespace fw::fluid
