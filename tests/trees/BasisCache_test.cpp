#include "trees/BasisCache.hpp"

#include <catch2/catch.hpp>

#include "tests/support/ScopedEnv.hpp"
#include "tests/support/TempDir.hpp"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using fw::test::TempDir;
using fw::trees::BasisCache;
using fw::trees::CacheOutcome;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::SpeciesBasis;
using fw::trees::SpeciesSettings;

namespace {

// A leaning trunk of 12 nodes with a side branch of 5.
Skeleton cached_tree() {
  std::vector<SkeletonNode> nodes{{-1, {0.0, 0.0, 0.0}, 0.1}};
  for (int k = 1; k <= 11; ++k) nodes.push_back({k - 1, {0.03 * k, 0.0, 0.5 * k}, 0.1 - 0.007 * k});
  for (int k = 1; k <= 5; ++k)
    nodes.push_back({k == 1 ? 5 : 11 + k - 1, {0.15 + 0.3 * k, 0.1 * k, 2.5 + 0.1 * k}, 0.03});
  return Skeleton::from_nodes(std::move(nodes));
}

SpeciesSettings cached_settings() {
  SpeciesSettings settings;
  settings.modal.mode_count = 6;
  settings.wind.samples = 2;
  settings.wind.leaf_area_index = 2.0;  // foliage in the stored projections too
  return settings;
}

void check_same(const SpeciesBasis& a, const SpeciesBasis& b) {
  CHECK(a.modes().omega() == b.modes().omega());
  CHECK(a.modes().shapes() == b.modes().shapes());
  CHECK(a.modes().damping_coefficients() == b.modes().damping_coefficients());
  CHECK(a.wind().projection_matrix() == b.wind().projection_matrix());
  CHECK(a.wind().sample_points() == b.wind().sample_points());
  CHECK(a.node_shapes() == b.node_shapes());
  CHECK(a.stem_loads().elastic() == b.stem_loads().elastic());
  CHECK(a.stem_loads().weight() == b.stem_loads().weight());
  CHECK(a.stem_loads().root_elastic() == b.stem_loads().root_elastic());
  CHECK(a.stem_loads().root_weight() == b.stem_loads().root_weight());
  CHECK(a.stem_loads().arc_length() == b.stem_loads().arc_length());
  CHECK(a.stem_loads().section_indices() == b.stem_loads().section_indices());
  CHECK(a.stem_loads().stem_volume() == b.stem_loads().stem_volume());
  CHECK(a.strong_wind().linear_shapes() == b.strong_wind().linear_shapes());
  CHECK(a.strong_wind().quadratic_shapes() == b.strong_wind().quadratic_shapes());
  CHECK(a.strong_wind().b() == b.strong_wind().b());
  REQUIRE(a.strong_wind().fits().size() == b.strong_wind().fits().size());
  for (std::size_t i = 0; i < a.strong_wind().fits().size(); ++i) {
    CHECK(a.strong_wind().fits()[i].q_max == b.strong_wind().fits()[i].q_max);
    CHECK(a.strong_wind().fits()[i].relative_residual == b.strong_wind().fits()[i].relative_residual);
    CHECK(a.strong_wind().fits()[i].linear_relative_residual ==
          b.strong_wind().fits()[i].linear_relative_residual);
    CHECK(a.strong_wind().fits()[i].shape_change == b.strong_wind().fits()[i].shape_change);
  }
  CHECK(a.settings().wind.leaf_area_index == b.settings().wind.leaf_area_index);
  CHECK(a.settings().wind.leaf_drag_coefficient == b.settings().wind.leaf_drag_coefficient);
  CHECK(a.settings().wind.branch_drag_coefficient == b.settings().wind.branch_drag_coefficient);
  CHECK(a.settings().wind.air_density == b.settings().wind.air_density);
}

std::vector<char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// The entry's trailing checksum (64-bit FNV-1a of every byte before it), recomputed after an edit, so that
// what the loader sees is a well-formed entry and not a corrupt one.
void reseal(std::vector<char>& bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const std::size_t body = bytes.size() - sizeof hash;
  for (std::size_t i = 0; i < body; ++i) {
    hash ^= static_cast<unsigned char>(bytes[i]);
    hash *= 0x100000001b3ULL;
  }
  std::memcpy(bytes.data() + body, &hash, sizeof hash);
}

}  // namespace

TEST_CASE("BasisCache: a stored basis loads back bit for bit") {
  TempDir dir("fw_cache");
  const BasisCache cache(dir.path());
  const Skeleton tree = cached_tree();
  CacheOutcome outcome{};
  const SpeciesBasis first = cache.load_or_compute(tree, cached_settings(), &outcome);
  CHECK(outcome == CacheOutcome::miss);
  CHECK(std::filesystem::exists(cache.entry_path(BasisCache::key(tree, cached_settings()))));
  const SpeciesBasis second = cache.load_or_compute(tree, cached_settings(), &outcome);
  CHECK(outcome == CacheOutcome::hit);
  check_same(first, second);
  CHECK(second.modes().status().converged == first.modes().status().converged);
  CHECK(second.modes().status().method == first.modes().status().method);
  // Only the entry is left in the folder: no temporaries.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
    CHECK(entry.path().extension() == ".fwbasis");
  }
  CHECK(files == 1);
}

TEST_CASE("BasisCache: the key changes with the skeleton, the material and every setting") {
  const Skeleton tree = cached_tree();
  const SpeciesSettings base = cached_settings();
  const auto key = BasisCache::key(tree, base);
  CHECK(BasisCache::key(tree, base) == key);

  std::vector<SkeletonNode> moved = tree.nodes();
  moved[7].radius *= 1.0 + 1e-12;
  CHECK(BasisCache::key(Skeleton::from_nodes(moved), base) != key);

  auto changed = base;
  changed.material.density = 901.0;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.modal.mode_count = 7;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.modal.damping = fw::trees::Damping::modal_ratio(0.03);
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.wind.branch_normal_drag = true;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.wind.samples = 3;
  CHECK(BasisCache::key(tree, changed) != key);
  // Every field of the drag convention changes the projections, so each is in the key.
  changed = base;
  changed.wind.air_density = 1.2;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.wind.branch_drag_coefficient = 1.0;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.wind.leaf_area_index = 2.5;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.wind.leaf_drag_coefficient = 0.3;
  CHECK(BasisCache::key(tree, changed) != key);
  // The strong-wind fit is stored, so its settings are in the key too.
  changed = base;
  changed.strong_wind.samples_per_side = 6;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.strong_wind.reach = 0.4;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.strong_wind.max_slope = 0.5;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.strong_wind.search_points = 101;
  CHECK(BasisCache::key(tree, changed) != key);
  changed = base;
  changed.strong_wind.beta_max = 3.0;
  CHECK(BasisCache::key(tree, changed) != key);
}

TEST_CASE(
    "BasisCache: an entry of format version 4 (a section at every stem node) is recomputed, not misread") {
  TempDir dir("fw_cache");
  const BasisCache cache(dir.path());
  const Skeleton tree = cached_tree();
  const SpeciesBasis fresh = cache.load_or_compute(tree, cached_settings());
  const auto path = cache.entry_path(BasisCache::key(tree, cached_settings()));
  const std::vector<char> good = read_bytes(path);
  REQUIRE(BasisCache::kFormatVersion == 5);
  // What version 4 wrote: the same entry up to the stem's distances along it, then four maps with a section
  // at every stem node but the top, 2 (P - 1) x m twice and 2 x m twice (doubles), then the checksum.
  // Version 5 puts the sections' count (int32) and indices (int32 each) before its 2 J x m maps.
  const fw::trees::StemLoads& loads = fresh.stem_loads();
  const std::size_t m = std::size_t(cached_settings().modal.mode_count);
  const std::size_t p = loads.profile().size(), sections = std::size_t(loads.section_count());
  const std::size_t maps_now = (2 * 2 * sections * m + 2 * 2 * m) * sizeof(double);
  const std::size_t indices = sizeof(std::int32_t) * (1 + sections);
  std::vector<char> old(good.begin(),
                        good.end() - std::ptrdiff_t(maps_now + indices + sizeof(std::uint64_t)));
  old.resize(old.size() + (2 * 2 * (p - 1) * m + 2 * 2 * m) * sizeof(double) + sizeof(std::uint64_t));
  const std::uint32_t version_4 = 4;
  std::memcpy(old.data() + 8, &version_4, sizeof version_4);  // after the 8-byte magic
  reseal(old);
  // An old entry under this key could only appear by copying (the version is hashed into the key), but a
  // reader that skipped the version check would take its checksum-valid bytes for a basis.
  write_bytes(path, old);
  std::string why;
  CHECK_FALSE(cache.load(tree, cached_settings(), &why).has_value());
  CHECK(why.find("another format version") != std::string::npos);
  CacheOutcome outcome{};
  const SpeciesBasis recomputed = cache.load_or_compute(tree, cached_settings(), &outcome);
  CHECK(outcome == CacheOutcome::corrupt_recomputed);
  check_same(fresh, recomputed);
  CHECK(read_bytes(path) == good);

  // And with the version patched to 5, the version 4 layout (here its maps zero) is refused: its first map
  // entry read as the section count is no count of sections.
  std::memcpy(old.data() + 8, &BasisCache::kFormatVersion, sizeof version_4);
  reseal(old);
  write_bytes(path, old);
  CHECK_FALSE(cache.load(tree, cached_settings(), &why).has_value());
  CHECK(why.find("sections do not fit") != std::string::npos);
}

TEST_CASE("BasisCache: a corrupted entry is detected and recomputed") {
  TempDir dir("fw_cache");
  const BasisCache cache(dir.path());
  const Skeleton tree = cached_tree();
  const SpeciesBasis fresh = cache.load_or_compute(tree, cached_settings());
  const auto path = cache.entry_path(BasisCache::key(tree, cached_settings()));
  const std::vector<char> good = read_bytes(path);
  REQUIRE(good.size() > 200);

  SECTION("a flipped byte in the mode shapes") {
    std::vector<char> bad = good;
    bad[good.size() / 2] ^= 0x10;
    write_bytes(path, bad);
  }
  SECTION("a truncated file") {
    write_bytes(path, std::vector<char>(good.begin(), good.begin() + std::ptrdiff_t(good.size() / 3)));
  }
  SECTION("an empty file") {
    write_bytes(path, {});
  }
  SECTION("another species' entry under this key") {
    auto other = cached_settings();
    other.modal.mode_count = 5;
    cache.load_or_compute(tree, other);
    std::filesystem::copy_file(cache.entry_path(BasisCache::key(tree, other)), path,
                               std::filesystem::copy_options::overwrite_existing);
  }

  std::string why;
  CHECK_FALSE(cache.load(tree, cached_settings(), &why).has_value());
  CHECK(why.find(path.string()) == 0);
  CacheOutcome outcome{};
  const SpeciesBasis recomputed = cache.load_or_compute(tree, cached_settings(), &outcome);
  CHECK(outcome == CacheOutcome::corrupt_recomputed);
  check_same(fresh, recomputed);
  // The entry was rewritten and is good again.
  CHECK(read_bytes(path) == good);
  cache.load_or_compute(tree, cached_settings(), &outcome);
  CHECK(outcome == CacheOutcome::hit);
}

TEST_CASE("BasisCache: the default folder follows FORESTWIND_CACHE_DIR, then XDG_CACHE_HOME") {
  {
    fw::test::ScopedEnv cache_dir("FORESTWIND_CACHE_DIR", "/tmp/fw-cache-here");
    CHECK(BasisCache::default_directory() == std::filesystem::path("/tmp/fw-cache-here"));
  }
  fw::test::ScopedEnv cache_dir("FORESTWIND_CACHE_DIR", "");
  fw::test::ScopedEnv xdg("XDG_CACHE_HOME", "/tmp/xdg");
  CHECK(BasisCache::default_directory() == std::filesystem::path("/tmp/xdg/forestwind"));
}

TEST_CASE("BasisCache: a cache folder that cannot be created is reported, the basis still returned") {
  TempDir dir("fw_cache");
  const std::string blocker = dir.write("file", "not a folder");
  const BasisCache cache(std::filesystem::path(blocker) / "cache");
  CacheOutcome outcome{};
  std::string store_error;
  const SpeciesBasis species =
      cache.load_or_compute(cached_tree(), cached_settings(), &outcome, &store_error);
  CHECK(outcome == CacheOutcome::miss);
  CHECK(store_error.find("BasisCache: cannot create the cache folder") == 0);
  CHECK(species.modes().mode_count() == 6);
}
