#include "host/stages/wind/Advection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "host/stages/wind/MacCormackAdvection.hpp"
#include "host/stages/wind/SemiLagrangianAdvection.hpp"
#include "host/stages/wind/Upwind5Advection.hpp"

namespace fw::host {

const AdvectionMethod& advection_method(fluid::AdvectionScheme scheme) {
  // The one place a scheme is looked up: every question about it goes to its method from here.
  static const AdvectionMethod kMethods[] = {method_of<SemiLagrangianAdvection>(),
                                             method_of<MacCormackAdvection>(), method_of<Upwind5Advection>()};
  for (const AdvectionMethod& method : kMethods)
    if (method.scheme == scheme) return method;
  throw std::invalid_argument(fmt::format("advection: no scheme numbered {}", int(scheme)));
}

double AdvectionMethod::courant_number(const std::array<double, 3>& maxima, double dt, double h) const {
  const double speed = std::isfinite(courant_limit) ? maxima[0] + maxima[1] + maxima[2]
                                                    : std::max({maxima[0], maxima[1], maxima[2]});
  return speed * dt / h;
}

int traced_halo_cells(double courant) {
  const double reach = std::floor(std::max(courant, 0.0)) + 1.0;
  return reach > FW_PAD ? int(std::min(reach, double(std::numeric_limits<int>::max()))) : FW_PAD;
}

}  // namespace fw::host
