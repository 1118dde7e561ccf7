// The log-law wall stress on rough ground and the tops of solids (solver.wall_roughness_length > 0): the
// wall cells' u and v slowed implicitly by C_w |U| U / h, C_w from the roughness length
// (fluid/SubgridStress.hpp). Applied after the subgrid stage, on a face list made once
// (host/stages/WallFaces).
//
//   fw::host::WallStress wall(context);
//   wall.apply(fields);
#pragma once

#include "host/stages/WallFaces.hpp"
#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class WallStress : public WindPart {
 public:
  explicit WallStress(const WindPartContext& context);
  /// The faces of the wall cells of the rank's block in `setup`'s solids: the list's bytes.
  static std::size_t estimate_device_bytes(const WindGridSetup& setup, const BlockShare& share);

  /// u and v of the wall cells <- the implicit stress over the step's dt; halo exchanged.
  void apply(WindFields& fields);

  const char* stage() const override { return "wall"; }
  std::size_t device_bytes() const override { return FluidStages::wall_faces_bytes(list_); }
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}}; }

  /// The wall faces of this rank's block, from the whole grid's solids.
  static WallFaces block_wall_faces(const WindGridSetup& setup, const BlockShare& share);

 private:
  WindPartContext context_;
  WallFaces list_;
  FluidStages::DeviceWallFaces faces_;
  double drag_coefficient_;  // C_w of the log law at the first cell centre
};

}  // namespace fw::host
