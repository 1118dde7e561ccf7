#include "host/stages/BlockGrid.hpp"

#include "host/runtime/Communicator.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::host {

BlockArray block_array(const fluid::Decomposition& decomposition, int rank, int level, int nz, int halo) {
  const fluid::Block block = decomposition.block(rank);
  const int bx = rank % decomposition.blocks()[0], by = rank / decomposition.blocks()[0];
  const int scale = 1 << level;
  BlockArray a;
  a.extent[2] = nz;
  for (int axis = 0; axis < 2; ++axis) {
    if (block.first[axis] % scale != 0 || block.count[axis] % scale != 0)
      throw std::logic_error(
          fmt::format("block_array: rank {}'s block does not coarsen to level {}", rank, level));
    a.halo_low[axis] = block.halo_low[axis] > 0 ? halo : 0;
    a.halo_high[axis] = block.halo_high[axis] > 0 ? halo : 0;
    a.extent[axis] = block.count[axis] / scale + a.halo_low[axis] + a.halo_high[axis];
    a.origin[axis] = block.first[axis] / scale - a.halo_low[axis];
    std::array<int, 2> below{bx, by}, above{bx, by};
    --below[axis], ++above[axis];
    a.neighbour_low[axis] = a.halo_low[axis] > 0 ? decomposition.rank_of(below[0], below[1]) : -1;
    a.neighbour_high[axis] = a.halo_high[axis] > 0 ? decomposition.rank_of(above[0], above[1]) : -1;
    const int index = axis == 0 ? bx : by, last = decomposition.blocks()[axis] - 1;
    if (index == 0) a.seam_low[axis] = a.neighbour_low[axis];  // a neighbour below block 0: the wrap
    if (index == last) a.seam_high[axis] = a.neighbour_high[axis];
  }
  return a;
}

BlockArray face_array(BlockArray cells, int c) {
  cells.staggered = c;
  return cells;
}

fluid::GridSpec block_spec(const fluid::GridSpec& spec, const fluid::Decomposition& decomposition,
                           const BlockArray& cells) {
  fluid::GridSpec local = spec;
  local.nx = cells.extent[0];
  local.ny = cells.extent[1];
  local.block_offset = cells.origin;  // the domain's origin stays, so positions round as the whole grid's
  local.block_domain = {spec.nx, spec.ny};
  for (int axis = 0; axis < 2; ++axis) {
    if (decomposition.blocks()[axis] == 1) continue;  // not cut: the domain's faces, wrapped if periodic
    if (spec.periodic(axis)) local.block_period[axis] = axis == 0 ? spec.nx : spec.ny;
    for (int side = 0; side < 2; ++side) {
      const bool inside = (side == 0 ? cells.halo_low[axis] : cells.halo_high[axis]) > 0;
      auto& face = local.boundary[std::size_t(2 * axis + side)];
      if (inside || face == fluid::BoundaryType::periodic) face = fluid::BoundaryType::slip;
    }
  }
  return local;
}

std::unique_ptr<WindBlocks> blocks_over(const Communicator* world,
                                        const fluid::Decomposition& decomposition) {
  if (world == nullptr || world->size() == 1) return nullptr;
  return std::make_unique<WindBlocks>(WindBlocks{world, decomposition});
}

const WindBlocks* splitting(const WindBlocks* blocks) {
  return blocks != nullptr && blocks->world != nullptr && blocks->decomposition.splits() ? blocks : nullptr;
}

BlockShare BlockShare::of(const WindBlocks* blocks) {
  if (blocks == nullptr || blocks->world == nullptr) return {};
  return {&blocks->decomposition, blocks->world->rank()};
}

BlockArray BlockShare::block(const fluid::GridSpec& whole) const {
  if (splits()) return block_array(*decomposition, rank, 0, whole.nz, decomposition->halo());
  BlockArray all;
  all.extent = {whole.nx, whole.ny, whole.nz};
  return all;
}

fluid::GridSpec BlockShare::local(const fluid::GridSpec& whole) const {
  return splits() ? block_spec(whole, *decomposition, block(whole)) : whole;
}

}  // namespace fw::host
