// Fuzz target: the basis cache's entry reader (trees/BasisCache::load).
// Feeds: the bytes as the body of the cache entry of one fixed species (tests/fuzz/BasisCacheSpecies.hpp),
// sealed here with their FNV-1a checksum as BasisCache::store seals them, so that mutations reach the
// fields behind the seal instead of stopping at it. The seed is the body of the entry the code itself
// writes (make fuzz runs basis_cache_seed).
// Checks: load() returns a basis or nullopt with a reason naming the entry; a basis it returns has the
// species' node and mode counts.
// Clean refusals: nullopt with why_not (load() catches its own errors: a corrupt entry is recomputed).
// Bugs: anything else: a crash, a sanitizer report, an exception out of load(), a hang, a huge
// allocation (load() would catch bad_alloc, so only -malloc_limit_mb sees an oversized size field).
#include <cstdint>
#include <filesystem>
#include <string>

#include "base/SealedRecord.hpp"
#include "tests/fuzz/BasisCacheSpecies.hpp"
#include "tests/fuzz/FuzzSupport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fw::trees::Skeleton skeleton = fw::fuzz::cache_species_skeleton();
  static const fw::trees::SpeciesSettings settings = fw::fuzz::cache_species_settings();
  static const fw::trees::BasisCache cache(fw::fuzz::scratch_folder() / "cache");
  static const std::uint64_t key = fw::trees::BasisCache::key(skeleton, settings);

  fw::base::RecordWriter body;
  body.values(data, size);
  const std::string entry = body.sealed();
  const auto path = cache.entry_path(key);
  fw::fuzz::write_input(path.lexically_relative(fw::fuzz::scratch_folder()).string(),
                        reinterpret_cast<const std::uint8_t*>(entry.data()), entry.size());
  std::string why_not;
  const auto basis = cache.load(skeleton, settings, &why_not);
  if (!basis) {
    if (!why_not.starts_with(path.string() + ":")) fw::fuzz::fail("a refusal without the entry: " + why_not);
  } else if (basis->skeleton().size() != skeleton.size() ||
             basis->modes().mode_count() != settings.modal.mode_count) {
    fw::fuzz::fail("a basis of another size than the species'");
  }
  return 0;
}
