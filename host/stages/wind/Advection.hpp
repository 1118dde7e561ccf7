// Advection of the wind by itself: one class per scheme behind one interface, and the table that picks the
// class from solver.advection, once, when the grid is made.
//
//   const fw::host::AdvectionMethod& method = fw::host::advection_method(settings.advection);
//   method.courant_limit;                       // what the planner and the CFL step ask of the scheme
//   std::unique_ptr<fw::host::Advection> advection = method.make(context);
//   advection->advect(fields, dt, stage_end);   // fields.vel <- fields.vel advected over dt
//
// The schemes (their numerics in kernels/fluid_advect.cl and kernels/fluid_upwind.cl, their CPU oracles in
// fluid/ReferenceStages.hpp and fluid/UpwindStencil.hpp):
//   semi_lagrangian  SemiLagrangianAdvection: Stam's back-trace, RK2, trilinear;
//   maccormack       MacCormackAdvection: a forward and a backward trace, corrected and clamped;
//   upwind5          Upwind5Advection: flux-form fifth-order upwind in three Runge-Kutta stages.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "fluid/GridSpec.hpp"
#include "fluid/WindSettings.hpp"
#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class Advection : public WindPart {
 public:
  /// What a scheme of several stages does to each stage's velocity but the last: the prescribed faces
  /// back, and a projection if the settings ask for one (WindGrid gives it).
  using StageEnd = std::function<void(DeviceVelocity&)>;

  /// fields.vel <- fields.vel advected over dt (s), its halo exchanged; fields.tmp is overwritten.
  virtual void advect(WindFields& fields, float dt, const StageEnd& stage_end) = 0;
  const char* stage() const override { return "advect"; }
  /// Every scheme reads its padded copies' FW_PAD ghost layers; a trace reaching further is the step's
  /// halo check's to refuse (AdvectionMethod::halo_cells).
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, FW_PAD}}; }

 protected:
  explicit Advection(const WindPartContext& context) : context_(context) {}
  WindPartContext context_;
};

/// What the rest of the program asks of an advection scheme, and how its part is made.
struct AdvectionMethod {
  fluid::AdvectionScheme scheme{};
  /// The Courant number (courant_number) past which the scheme is unstable; infinity for none (the
  /// semi-Lagrangian traces only lose accuracy).
  double courant_limit = 0.0;
  /// Cells of halo a step of this Courant number reads beyond a block's edge.
  int (*halo_cells)(double courant) = nullptr;
  /// Bytes the part allocates on a grid (its padded copies, its extra velocities, its flux orders).
  std::size_t (*device_bytes)(const fluid::GridSpec& grid) = nullptr;
  /// Bytes a step streams per face, neighbours taken as cached (the benchmarks' traffic model).
  double bytes_per_face = 0.0;
  /// Scalar loads a step gathers per face at traced points (0: the scheme reads whole rows).
  double gathered_loads_per_face = 0.0;
  /// The part, over the context's block.
  std::unique_ptr<Advection> (*make)(const WindPartContext& context) = nullptr;

  /// solver.advection's word for it.
  std::string name() const { return fluid::to_string(scheme); }
  /// The Courant number of a step of dt (s) on cells of h (m) for the largest |u|, |v| and |w| (m/s): the
  /// sum of the components' for a scheme with a stability limit (it binds on the sum), the largest one
  /// otherwise.
  double courant_number(const std::array<double, 3>& max_speed_components, double dt, double h) const;
};

/// The method of `scheme`. Every scheme has one.
const AdvectionMethod& advection_method(fluid::AdvectionScheme scheme);

/// A scheme class's method: its static facts (kScheme, kCourantLimit, halo_cells, estimate_device_bytes,
/// kBytesPerFace, kGatheredLoadsPerFace) and its constructor. advection_method's table holds one a class.
template <class Scheme>
AdvectionMethod method_of() {
  return {Scheme::kScheme,
          Scheme::kCourantLimit,
          Scheme::halo_cells,
          Scheme::estimate_device_bytes,
          Scheme::kBytesPerFace,
          Scheme::kGatheredLoadsPerFace,
          [](const WindPartContext& context) -> std::unique_ptr<Advection> {
            return std::make_unique<Scheme>(context);
          }};
}

/// The traffic model's parts (AdvectionMethod::bytes_per_face): padding a face reads it and writes its
/// padded copy; a result is one store.
inline constexpr double kPadBytesPerFace = 4 + 4, kStoreBytesPerFace = 4;

/// The halo a traced step needs: the corners of its back-trace lie up to floor(C) + 1 cells away, and
/// never less than the padded copies' FW_PAD.
int traced_halo_cells(double courant);

}  // namespace fw::host
