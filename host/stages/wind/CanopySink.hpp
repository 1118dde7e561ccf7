// The canopy's drag on the wind, a momentum sink F = -k |u| u from the drag density k = sum Cd a (1/m, a
// float a cell, x fastest; fluid/CanopyField), applied implicitly right after the body forces. Off, and
// holding no memory, until a canopy is set.
//
//   fw::host::CanopySink canopy(context);
//   canopy.set(drag_density, law);     // collective over ranks; an empty or all-zero field turns it off
//   if (canopy.on()) canopy.apply(fields);
#pragma once

#include <vector>

#include "fluid/DragLaw.hpp"
#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class CanopySink : public WindPart {
 public:
  explicit CanopySink(const WindPartContext& context) : context_(context) {}
  /// Bytes a canopy on `grid` takes (a drag density a cell).
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid);

  /// Uploads the whole grid's drag density (or this block's), once. Over ranks, collective: every rank
  /// passes the whole grid's field (or all an empty one), and the drag is on for all when any block has
  /// some. Throws std::invalid_argument for a wrong size or a negative or non-finite value.
  /// `law`: how the drag coefficients behind k vary with |u| (fluid/DragLaw.hpp).
  void set(std::vector<float> drag_density, const fluid::DragLaw& law);
  bool on() const { return on_; }
  /// fields.vel <- the implicit drag over the step's dt on the faces of the cells with drag; halo exchanged.
  void apply(WindFields& fields);
  /// The drag density on the device while on, else null (the tke model's sources read it).
  cl::Buffer* drag_density() { return on_ ? &drag_density_ : nullptr; }

  const char* stage() const override { return "canopy"; }
  std::size_t device_bytes() const override { return on_ ? estimate_device_bytes(context_.seam.local()) : 0; }
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}}; }

 private:
  WindPartContext context_;
  cl::Buffer drag_density_;  // valid while on_
  CellBox box_;              // the cells of non-zero drag density; empty on a block with none
  fluid::DragLaw law_;
  bool on_ = false;
};

}  // namespace fw::host
