#include "host/stages/RankSeam.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::host {
namespace {

const char* field_name(HaloField field) {
  switch (field) {
    case HaloField::faces:
      return "the velocity's faces";
    case HaloField::cells:
      return "a cell field";
    case HaloField::cell_quads:
      return "a field of four floats a cell";
  }
  return "?";
}

}  // namespace

RankSeam::RankSeam(ComputeContext& cc, const fluid::GridSpec& whole, const WindBlocks* blocks)
    : cc_(cc),
      whole_(whole),
      world_(blocks && blocks->world ? blocks->world : &Communicator::alone()),
      decomposition_(blocks ? blocks->decomposition : fluid::Decomposition()),
      share_{blocks && blocks->world ? &decomposition_ : nullptr, world_->rank()},
      block_(share_.block(whole)),
      local_(share_.local(whole)),
      pressure_blocks_{world_, decomposition_, decomposition_.halo()} {}

void RankSeam::declare(const HaloNeed& need) {
  if (need.width > halo_width())
    throw std::invalid_argument(
        fmt::format("RankSeam: a part reads {} cells of {} beyond its block, but the ranks exchange {}",
                    need.width, field_name(need.field), halo_width()));
  if (!declared_.insert(need.field).second || !share_.splits()) return;
  switch (need.field) {
    case HaloField::faces:
      for (int c = 0; c < 3; ++c) faces_[std::size_t(c)].emplace(cc_, *world_, face_array(block_, c));
      break;
    case HaloField::cells:
      cells_.emplace(cc_, *world_, block_);
      break;
    case HaloField::cell_quads: {
      // Four floats a cell, interleaved: along x the layout is four times as long, and so are its halos.
      BlockArray quads = block_;
      quads.extent[0] *= 4, quads.halo_low[0] *= 4, quads.halo_high[0] *= 4;
      quads_.emplace(cc_, *world_, quads);
      break;
    }
  }
}

void RankSeam::require(HaloField field, const char* what) const {
  if (!declared_.count(field))
    throw std::logic_error(fmt::format(
        "RankSeam: {} of {} asked for, but no part declared that it exchanges it", what, field_name(field)));
}

void RankSeam::exchange(DeviceVelocity& vel) {
  require(HaloField::faces, "an exchange");
  for (int c = 0; c < 3; ++c)
    if (faces_[std::size_t(c)]) faces_[std::size_t(c)]->exchange(vel.component(c));
}

void RankSeam::exchange_cells(cl::Buffer& field) {
  require(HaloField::cells, "an exchange");
  if (cells_) cells_->exchange(field);
}

void RankSeam::exchange_quads(cl::Buffer& field) {
  require(HaloField::cell_quads, "an exchange");
  if (quads_) quads_->exchange(field);
}

void RankSeam::copy_seam(DeviceVelocity& vel) {
  require(HaloField::faces, "the periodic seam's copy");
  for (int c = 0; c < 2; ++c)
    if (faces_[std::size_t(c)]) faces_[std::size_t(c)]->copy_seam(vel.component(c));
}

HaloTraffic RankSeam::traffic() const {
  HaloTraffic total;
  for (const auto& halo : faces_)
    if (halo) total += halo->traffic();
  if (cells_) total += cells_->traffic();
  if (quads_) total += quads_->traffic();
  return total;
}

}  // namespace fw::host
