#include "host/app/FrameGather.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "host/runtime/Communicator.hpp"

namespace fw::host {
namespace {

// The faces of component c that rank `rank` sends: along x and y its block's cells (and the domain's last
// face where the block ends the domain), along z every face; [lo, hi) per axis in the domain's indices.
std::array<std::array<int, 2>, 3> own_faces(const fluid::Decomposition& decomposition, int rank, int c,
                                            const std::array<int, 3>& domain) {
  const fluid::Block block = decomposition.block(rank);
  std::array<std::array<int, 2>, 3> range{};
  for (int a = 0; a < 2; ++a) {
    const int lo = block.first[std::size_t(a)], hi = lo + block.count[std::size_t(a)];
    range[std::size_t(a)] = {lo, hi + (c == a && hi == domain[std::size_t(a)] ? 1 : 0)};
  }
  range[2] = {0, domain[2] + (c == 2 ? 1 : 0)};
  return range;
}

// Calls visit(i, j, k) for each face of `range`, in one order on every rank.
template <typename Visit>
void for_each_face(const std::array<std::array<int, 2>, 3>& range, Visit visit) {
  for (int k = range[2][0]; k < range[2][1]; ++k)
    for (int j = range[1][0]; j < range[1][1]; ++j)
      for (int i = range[0][0]; i < range[0][1]; ++i) visit(i, j, k);
}

// The index of face (i, j, k) (the domain's indices) of component c in the domain's face array.
std::size_t domain_face(const std::array<int, 3>& domain, int c, int i, int j, int k) {
  const std::size_t gx = std::size_t(domain[0] + (c == 0 ? 1 : 0)),
                    gy = std::size_t(domain[1] + (c == 1 ? 1 : 0));
  return std::size_t(i) + gx * (std::size_t(j) + gy * std::size_t(k));
}

// The index of face (i, j, k) (the domain's indices) in a rank's face array laid out as `faces`.
std::size_t block_face(const BlockArray& faces, int i, int j, int k) {
  const std::size_t lx = std::size_t(faces.values(0)), ly = std::size_t(faces.values(1));
  return std::size_t(i - faces.origin[0]) + lx * (std::size_t(j - faces.origin[1]) + ly * std::size_t(k));
}

// One leaf as it travels to rank 0.
struct GatheredLeaf {
  std::array<float, 3> position, normal;
  std::int32_t tree, leaf;
  float side;
  std::uint8_t state;
};

}  // namespace

std::optional<io::OutputFrame::Gathered> gather_frame(const io::OutputFrame& frame,
                                                      const fluid::GridSpec& whole, const WindBlocks& blocks,
                                                      const BlockArray& cells, bool leaves) {
  const Communicator& world = *blocks.world;
  const std::array<int, 3> domain{whole.nx, whole.ny, whole.nz};
  const int rank = world.rank();
  std::optional<io::OutputFrame::Gathered> out;
  if (rank == 0) out.emplace().velocity = fluid::MacVelocity(whole);

  for (int c = 0; c < 3; ++c) {
    const std::vector<float>& block = frame.velocity.component(c);
    const BlockArray faces = face_array(cells, c);
    std::vector<float> mine;
    for_each_face(own_faces(blocks.decomposition, rank, c, domain),
                  [&](int i, int j, int k) { mine.push_back(block[block_face(faces, i, j, k)]); });
    const std::vector<std::vector<float>> from = world.gather(mine);
    if (!out) continue;
    // Rank 0 places each rank's faces in the order that rank visited them.
    std::vector<float>& whole_faces = out->velocity.component(c);
    for (int r = 0; r < world.size(); ++r) {
      std::size_t n = 0;
      for_each_face(own_faces(blocks.decomposition, r, c, domain), [&](int i, int j, int k) {
        whole_faces[domain_face(domain, c, i, j, k)] = from[std::size_t(r)][n++];
      });
    }
  }

  if (!leaves) return out;
  const io::LeafFrame& own = frame.leaves;
  std::vector<GatheredLeaf> mine;
  for (std::size_t n = 0; n < own.size_written(); ++n)
    mine.push_back({own.position[n], own.normal[n], own.tree_id[n], own.leaf[n], own.side[n], own.state[n]});
  std::vector<GatheredLeaf> all = joined(world.gather(mine));
  if (!out) return out;
  std::sort(all.begin(), all.end(), [](const GatheredLeaf& a, const GatheredLeaf& b) {
    return a.tree != b.tree ? a.tree < b.tree : a.leaf < b.leaf;
  });
  io::LeafFrame& gathered = out->leaves;
  gathered.counts = own.counts;
  for (const GatheredLeaf& leaf : all) {
    gathered.position.push_back(leaf.position);
    gathered.normal.push_back(leaf.normal);
    gathered.state.push_back(leaf.state);
    gathered.tree_id.push_back(leaf.tree);
    gathered.leaf.push_back(leaf.leaf);
    gathered.side.push_back(leaf.side);
  }
  return out;
}

}  // namespace fw::host
