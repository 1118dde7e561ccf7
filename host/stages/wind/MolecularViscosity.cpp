#include "host/stages/wind/MolecularViscosity.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fw::host {
namespace {

// Explicit diffusion is stable for nu dt / h^2 <= 1/6 in 3D; each sub-step keeps within 0.15.
constexpr double kStableDiffusionNumber = 0.15;

}  // namespace

int MolecularViscosity::substeps(double dt) const {
  const double nu = context_.setup.settings.viscosity, h = context_.setup.spec.h;
  if (nu <= 0.0) return 0;
  return std::max(1, static_cast<int>(std::ceil(nu * dt / (h * h) / kStableDiffusionNumber)));
}

void MolecularViscosity::apply(WindFields& fields, double dt,
                               const std::function<void(DeviceVelocity&)>& boundaries) {
  const int n = substeps(dt);
  if (n == 0) return;
  const double h = context_.setup.spec.h;
  const float coefficient = static_cast<float>(context_.setup.settings.viscosity * (dt / n) / (h * h));
  for (int s = 0; s < n; ++s) {
    for (int c = 0; c < 3; ++c)
      context_.stages.enqueue_diffuse(c, coefficient, fields.vel.component(c), fields.tmp.component(c));
    std::swap(fields.vel, fields.tmp);
    boundaries(fields.vel);
    context_.seam.exchange(fields.vel);
  }
}

}  // namespace fw::host
