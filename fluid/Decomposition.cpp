#include "fluid/Decomposition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fw::fluid {
namespace {

constexpr const char* kAxisNames[2] = {"x", "y"};

// The thinnest block: as wide as the halo (a halo then comes from the next block only), and two cells, so
// that a block's first coarse level of the pressure hierarchy is its own.
int min_block_cells(int halo) {
  return std::max(halo, 2);
}

// Cells of each block along one axis of n cells cut into p blocks on multiples of `alignment`.
std::vector<int> block_counts(int n, int p, int alignment) {
  const long long units = n / alignment;
  std::vector<int> counts;
  long long previous = 0;
  for (int b = 1; b <= p; ++b) {
    const long long cut = (2 * b * units + p) / (2 * p);  // round(b units / p), halves up
    counts.push_back(int((cut - previous) * alignment));
    previous = cut;
  }
  return counts;
}

// The alignment along an axis, or a DecompositionError saying why the axis cannot take p blocks: of the
// alignments that leave every block at least min_block_cells (and, on a periodic axis, even), the one whose
// largest block is smallest (the best balance), the larger alignment on a tie.
int axis_alignment(const GridSpec& spec, int axis, int p, int halo) {
  if (p == 1) return 1;
  const int n = axis == 0 ? spec.nx : spec.ny;
  const int need = min_block_cells(halo);
  int best = 0, best_largest = 0, odd_block = 0;
  for (int alignment = Decomposition::kMaxAlignment; alignment >= 1; alignment /= 2) {
    if (n % alignment != 0) continue;
    const auto counts = block_counts(n, p, alignment);
    if (*std::min_element(counts.begin(), counts.end()) < need) continue;
    if (spec.periodic(axis)) {
      const auto odd = std::find_if(counts.begin(), counts.end(), [](int c) { return c % 2 != 0; });
      if (odd != counts.end()) {
        odd_block = *odd;
        continue;
      }
    }
    const int largest = *std::max_element(counts.begin(), counts.end());
    if (best == 0 || largest < best_largest) best = alignment, best_largest = largest;
  }
  if (best > 0) return best;
  if (odd_block > 0)
    throw DecompositionError(fmt::format(
        "{} blocks along the periodic {} axis of {} cells leave a block of {} cells; every block of a "
        "periodic "
        "axis needs an even count (the red-black colouring and the pressure hierarchy pair cells across the "
        "wrap)",
        p, kAxisNames[axis], n, odd_block));
  throw DecompositionError(fmt::format(
      "{} blocks along {} need at least {} cells each ({} in all: the halo is {} cells), but {} has {}: more "
      "ranks than the grid can be split into",
      p, kAxisNames[axis], need, p * need, halo, kAxisNames[axis], n));
}

}  // namespace

Decomposition Decomposition::make(const GridSpec& spec, int ranks,
                                  std::optional<std::array<int, 2>> requested, int halo) {
  if (ranks < 1) throw DecompositionError(fmt::format("{} ranks: at least 1 expected", ranks));
  if (halo < 1) throw DecompositionError(fmt::format("a halo of {} cells: at least 1 expected", halo));
  if (requested) {
    const auto [px, py] = *requested;
    if (px < 1 || py < 1 || (long long)px * py != ranks)
      throw DecompositionError(
          fmt::format("{} x {} blocks for {} ranks: the blocks must multiply to the ranks", px, py, ranks));
    Decomposition d;
    d.spec_ = spec;
    d.blocks_ = {px, py};
    d.halo_ = halo;
    d.alignment_ = {axis_alignment(spec, 0, px, halo), axis_alignment(spec, 1, py, halo)};
    return d;
  }
  std::optional<Decomposition> best;
  std::string last_reason;
  // Fewest blocks along x first, so that a tie goes to cuts across y: a block's halo there is whole rows
  // of x, which the device copies as few long runs (a cut across x copies three floats a row), and the
  // kernels' rows along x stay whole. Measured on bench wind 128x128x64 over 2 ranks: 1 x 2 blocks step in
  // 36.6 ms, 2 x 1 in 41.4 ms (docs/parallel.md, "The split's speed").
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px != 0) continue;
    try {
      Decomposition d = make(spec, ranks, std::array<int, 2>{px, ranks / px}, halo);
      if (!best || d.halo_cells() < best->halo_cells()) best = d;
    } catch (const DecompositionError& e) {
      last_reason = e.what();
    }
  }
  if (!best)
    throw DecompositionError(
        fmt::format("no split of {} ranks into x-y blocks fits the {} x {} grid (the last "
                    "tried: {})",
                    ranks, spec.nx, spec.ny, last_reason));
  return *best;
}

int Decomposition::cut(int axis, int b) const {
  const int n = axis == 0 ? spec_.nx : spec_.ny;
  const long long units = n / alignment_[axis];
  const int p = blocks_[axis];
  return int((2 * b * units + p) / (2 * p) * alignment_[axis]);
}

Block Decomposition::block(int rank) const {
  if (rank < 0 || rank >= ranks())
    throw std::out_of_range(fmt::format("Decomposition: rank {} of {}", rank, ranks()));
  const std::array<int, 2> index{rank % blocks_[0], rank / blocks_[0]};
  Block block;
  for (int a = 0; a < 2; ++a) {
    block.first[a] = cut(a, index[a]);
    block.count[a] = cut(a, index[a] + 1) - block.first[a];
    std::array<int, 2> below = index, above = index;
    --below[a], ++above[a];
    const int low = rank_of(below[0], below[1]), high = rank_of(above[0], above[1]);
    block.halo_low[a] = low >= 0 && blocks_[a] > 1 ? halo_ : 0;
    block.halo_high[a] = high >= 0 && blocks_[a] > 1 ? halo_ : 0;
  }
  return block;
}

int Decomposition::rank_of(int bx, int by) const {
  std::array<int, 2> index{bx, by};
  for (int a = 0; a < 2; ++a) {
    if (index[a] >= 0 && index[a] < blocks_[a]) continue;
    if (!spec_.periodic(a)) return -1;
    index[a] = (index[a] % blocks_[a] + blocks_[a]) % blocks_[a];
  }
  return index[0] + blocks_[0] * index[1];
}

int Decomposition::rank_holding(int i, int j) const {
  std::array<int, 2> index{0, 0};
  const std::array<int, 2> cell{i, j};
  for (int a = 0; a < 2; ++a)
    while (index[a] + 1 < blocks_[a] && cut(a, index[a] + 1) <= cell[a]) ++index[a];
  return index[0] + blocks_[0] * index[1];
}

long long Decomposition::halo_cells() const {
  long long cells = 0;
  for (int r = 0; r < ranks(); ++r) {
    const Block b = block(r);
    cells += ((long long)b.extent(0) * b.extent(1) - (long long)b.count[0] * b.count[1]) * spec_.nz;
  }
  return cells;
}

std::string Decomposition::describe() const {
  std::array<std::string, 2> extent;
  for (int a = 0; a < 2; ++a) {
    int lo = std::numeric_limits<int>::max(), hi = 0;
    for (int b = 0; b < blocks_[a]; ++b) {
      const int count = cut(a, b + 1) - cut(a, b);
      lo = std::min(lo, count);
      hi = std::max(hi, count);
    }
    extent[a] = lo == hi ? std::to_string(lo) : fmt::format("{}-{}", lo, hi);
  }
  return fmt::format("{} x {} blocks of {} x {} x {} cells", blocks_[0], blocks_[1], extent[0], extent[1],
                     spec_.nz);
}

}  // namespace fw::fluid
