// A disk cache of species bases, so that a forest of known species starts without solving eigenproblems.
//
//   fw::trees::BasisCache cache(fw::trees::BasisCache::default_directory());
//   fw::trees::CacheOutcome outcome;
//   auto species = cache.load_or_compute(skeleton, settings, &outcome);   // hit, miss or corrupt_recomputed
//
// Key: a 64-bit FNV-1a hash of everything the basis depends on: the format version, every node (parent,
// position, radius, as raw IEEE doubles), the material, the modal settings (count, damping, solver
// tolerances), the wind basis settings (air density, branch and leaf drag coefficients, leaf area index,
// branch-normal drag, samples) and the strong-wind fit settings (samples, reach, slope, search).
// Entry: "<directory>/<key as 16 hex digits>.fwbasis".
//
// Entry layout (binary, little-endian as the host writes it; the cache is per machine):
//   "FWBASIS\0", u32 version, u64 key, i32 nodes, i32 dofs, i32 modes, i32 samples,
//   i32 converged, i32 iterations, i32 operations, f64 max_residual, u32 length + method text,
//   f64 omega[modes], f64 shapes[dofs x modes] (column-major), f64 projection[3 samples x modes],
//   f64 sample_points[samples x 3], the strong-wind correction: f64 v[3 nodes x modes] and
//   f64 w[3 nodes x modes] (column-major), f64 b[modes], per mode f64 q_max, relative residual, linear
//   relative residual and shape change; then u64 FNV-1a checksum of every byte before it.
// An entry that is truncated, has another magic, version, key or sizes, or fails its checksum is corrupt: it
// is reported (corrupt_recomputed) and replaced by a fresh computation. Entries are written under a temporary
// name and renamed, so a crash never leaves a half-written entry under the final name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "trees/SpeciesBasis.hpp"

namespace fw::trees {

enum class CacheOutcome { hit, miss, corrupt_recomputed };

/// "hit", "miss" or "corrupt_recomputed".
const char* to_string(CacheOutcome outcome);

class BasisCache {
 public:
  /// 2: the wind settings became air density, branch and leaf drag coefficients and leaf area index (the
  /// projections of version 1 entries hold no foliage). 3: the strong-wind correction (v, w, b, fits) follows
  /// the sample points. 4: the stem loads (trees/StemLoads.hpp) follow the correction. 5: the stem's sections
  /// (at most kMaxStemSections of its nodes) follow its lengths. The version is part of the key, so an older
  /// entry is never even opened.
  static constexpr std::uint32_t kFormatVersion = 5;

  /// directory: where entries live; created on the first store.
  explicit BasisCache(std::filesystem::path directory);

  /// FORESTWIND_CACHE_DIR if set, else $XDG_CACHE_HOME/forestwind, else $HOME/.cache/forestwind, else
  /// ".forestwind-cache" in the working directory.
  static std::filesystem::path default_directory();

  /// The cache key of a species (see the header comment). Settings are validated first.
  static std::uint64_t key(const Skeleton& skeleton, const SpeciesSettings& settings);

  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path entry_path(std::uint64_t key) const;

  /// The cached basis, or nullopt when there is no entry (why_not = "") or it is corrupt (why_not says how).
  std::optional<SpeciesBasis> load(const Skeleton& skeleton, const SpeciesSettings& settings,
                                   std::string* why_not = nullptr) const;

  /// Writes the entry of `species` atomically. Throws std::runtime_error("BasisCache: ...") naming the path
  /// on an I/O failure.
  void store(const SpeciesBasis& species) const;

  /// load(), else SpeciesBasis::compute() and store(). outcome (optional) says which happened; a corrupt
  /// entry is overwritten, and corrupt_reason (optional) gets load()'s why_not ("PATH: how", "" for a hit or
  /// a miss). A failure to store is not fatal for the caller's run: it is reported through store_error
  /// (optional) and the computed basis is returned.
  SpeciesBasis load_or_compute(const Skeleton& skeleton, const SpeciesSettings& settings,
                               CacheOutcome* outcome = nullptr, std::string* store_error = nullptr,
                               std::string* corrupt_reason = nullptr) const;

 private:
  std::filesystem::path directory_;
};

}  // namespace fw::trees
