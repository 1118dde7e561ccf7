#include "host/stages/SavedShare.hpp"

namespace fw::host {

OwnColumns own_columns(const BlockArray& cells) {
  OwnColumns own;
  for (std::size_t axis = 0; axis < 2; ++axis) {
    own.lo[axis] = cells.origin[axis] + cells.halo_low[axis];
    own.hi[axis] = cells.origin[axis] + cells.extent[axis] - cells.halo_high[axis];
  }
  return own;
}

}  // namespace fw::host
