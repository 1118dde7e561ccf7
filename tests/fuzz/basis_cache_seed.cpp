// Writes the seed of the basis cache fuzz target: the body (the entry less its 8-byte checksum) of the
// cache entry that BasisCache::store writes for the fuzzed species, so that the seed follows the format.
//
//   basis_cache_seed FOLDER   # writes FOLDER/entry.body
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include "tests/fuzz/BasisCacheSpecies.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: basis_cache_seed FOLDER\n";
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  const auto skeleton = fw::fuzz::cache_species_skeleton();
  const auto settings = fw::fuzz::cache_species_settings();
  const fw::trees::BasisCache cache(folder / "cache");
  cache.store(fw::trees::SpeciesBasis::compute(skeleton, settings));
  const auto entry_path = cache.entry_path(fw::trees::BasisCache::key(skeleton, settings));
  std::ifstream in(entry_path, std::ios::binary);
  const std::string entry((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr std::size_t kChecksumBytes = sizeof(std::uint64_t);  // the seal the fuzz target adds again
  std::ofstream(folder / "entry.body", std::ios::binary)
      .write(entry.data(), std::streamsize(entry.size() - kChecksumBytes));
  std::filesystem::remove_all(folder / "cache");
  return 0;
}
