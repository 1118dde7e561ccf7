#include "trees/BasisCache.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <span>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "base/AtomicFile.hpp"
#include "base/Fnv1a.hpp"
#include "base/SealedRecord.hpp"

namespace fw::trees {

namespace {

constexpr char kMagic[8] = {'F', 'W', 'B', 'A', 'S', 'I', 'S', '\0'};

using base::Fnv1a;

}  // namespace

const char* to_string(CacheOutcome outcome) {
  switch (outcome) {
    case CacheOutcome::hit:
      return "hit";
    case CacheOutcome::miss:
      return "miss";
    case CacheOutcome::corrupt_recomputed:
      return "corrupt_recomputed";
  }
  return "?";
}

BasisCache::BasisCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path BasisCache::default_directory() {
  if (const char* dir = std::getenv("FORESTWIND_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::filesystem::path(xdg) / "forestwind";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "forestwind";
  }
  return ".forestwind-cache";
}

std::uint64_t BasisCache::key(const Skeleton& skeleton, const SpeciesSettings& settings) {
  settings.validate();
  Fnv1a hash;
  hash.value(kFormatVersion);
  hash.value(std::int32_t(skeleton.size()));
  for (const SkeletonNode& node : skeleton.nodes()) {
    hash.value(std::int32_t(node.parent));
    hash.value(node.position.x());
    hash.value(node.position.y());
    hash.value(node.position.z());
    hash.value(node.radius);
  }
  hash.value(settings.material.youngs_modulus);
  hash.value(settings.material.shear_modulus);
  hash.value(settings.material.density);
  const ModalSettings& modal = settings.modal;
  hash.value(std::int32_t(modal.mode_count));
  hash.value(modal.tolerance);
  hash.value(std::int32_t(modal.max_iterations));
  hash.value(std::int32_t(modal.lanczos_vectors));
  hash.value(std::int32_t(modal.damping.model));
  hash.value(std::int32_t(modal.damping.ratios.size()));
  for (double zeta : modal.damping.ratios) hash.value(zeta);
  hash.value(modal.damping.alpha);
  hash.value(modal.damping.beta);
  hash.value(settings.wind.air_density);
  hash.value(settings.wind.branch_drag_coefficient);
  hash.value(settings.wind.leaf_area_index);
  hash.value(settings.wind.leaf_drag_coefficient);
  hash.value(std::int32_t(settings.wind.branch_normal_drag ? 1 : 0));
  hash.value(std::int32_t(settings.wind.samples));
  const StrongWindSettings& strong = settings.strong_wind;
  hash.value(std::int32_t(strong.samples_per_side));
  hash.value(strong.reach);
  hash.value(strong.max_slope);
  hash.value(std::int32_t(strong.search_points));
  hash.value(strong.beta_max);
  return hash.digest();
}

std::filesystem::path BasisCache::entry_path(std::uint64_t key) const {
  return directory_ / fmt::format("{:016x}.fwbasis", key);
}

std::optional<SpeciesBasis> BasisCache::load(const Skeleton& skeleton, const SpeciesSettings& settings,
                                             std::string* why_not) const {
  if (why_not) why_not->clear();
  const std::uint64_t expected_key = key(skeleton, settings);
  const auto path = entry_path(expected_key);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  try {
    base::RecordReader reader(base::open_sealed(std::string_view(bytes.data(), bytes.size())));
    char magic[sizeof kMagic];
    for (char& c : magic) c = reader.value<char>();
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) throw std::runtime_error("not a forestwind basis");
    if (reader.value<std::uint32_t>() != kFormatVersion) throw std::runtime_error("another format version");
    if (reader.value<std::uint64_t>() != expected_key) throw std::runtime_error("the key does not match");
    const int nodes = reader.value<std::int32_t>();
    const int dofs = reader.value<std::int32_t>();
    const int modes = reader.value<std::int32_t>();
    const int samples = reader.value<std::int32_t>();
    if (nodes != skeleton.size() || dofs != 6 * (nodes - 1) || modes != settings.modal.mode_count ||
        samples != settings.wind.samples) {
      throw std::runtime_error("the sizes do not match the species");
    }
    ModalStatus status;
    status.requested = modes;
    status.converged = reader.value<std::int32_t>();
    status.iterations = reader.value<std::int32_t>();
    status.operations = reader.value<std::int32_t>();
    status.max_residual = reader.value<double>();
    status.method = reader.text();

    Eigen::VectorXd omega(modes);
    reader.values(omega.data(), std::size_t(modes));
    Eigen::MatrixXd shapes(dofs, modes);
    reader.values(shapes.data(), std::size_t(dofs) * std::size_t(modes));
    Eigen::MatrixXd projection(3 * samples, modes);
    reader.values(projection.data(), std::size_t(3 * samples) * std::size_t(modes));
    Eigen::MatrixX3d sample_points(samples, 3);
    reader.values(sample_points.data(), std::size_t(samples) * 3);
    Eigen::MatrixXd strong_v(3 * nodes, modes), strong_w(3 * nodes, modes);
    reader.values(strong_v.data(), std::size_t(strong_v.size()));
    reader.values(strong_w.data(), std::size_t(strong_w.size()));
    Eigen::VectorXd strong_b(modes);
    reader.values(strong_b.data(), std::size_t(modes));
    std::vector<StrongWindModeFit> fits(static_cast<std::size_t>(modes));
    for (StrongWindModeFit& fit : fits) {
      fit.q_max = reader.value<double>();
      fit.relative_residual = reader.value<double>();
      fit.linear_relative_residual = reader.value<double>();
      fit.shape_change = reader.value<double>();
    }
    const int stem_nodes = reader.value<std::int32_t>();
    if (stem_nodes < 2 || stem_nodes > nodes) throw std::runtime_error("the stem does not fit the skeleton");
    std::vector<StemSection> profile(static_cast<std::size_t>(stem_nodes));
    for (StemSection& section : profile) {
      section.node = reader.value<std::int32_t>();
      section.height = reader.value<double>();
      section.diameter = reader.value<double>();
    }
    Eigen::VectorXd arc_length(stem_nodes);
    reader.values(arc_length.data(), std::size_t(stem_nodes));
    const int sections = reader.value<std::int32_t>();
    if (sections < 1 || sections >= stem_nodes) throw std::runtime_error("the stem's sections do not fit it");
    std::vector<int> section_indices(static_cast<std::size_t>(sections));
    for (int& index : section_indices) index = reader.value<std::int32_t>();
    const int stem_rows = 2 * sections;
    Eigen::MatrixXd elastic(stem_rows, modes), weight(stem_rows, modes), root_elastic(2, modes),
        root_weight(2, modes);
    for (Eigen::MatrixXd* map : {&elastic, &weight, &root_elastic, &root_weight})
      reader.values(map->data(), std::size_t(map->size()));
    reader.expect_end();

    ModalBasis modal = ModalBasis::from_values(std::move(omega), std::move(shapes), settings.modal.damping,
                                               std::move(status));
    WindBasis wind = WindBasis::from_values(std::move(projection), std::move(sample_points), settings.wind);
    StrongWindCorrection strong = StrongWindCorrection::from_values(std::move(strong_v), std::move(strong_w),
                                                                    std::move(strong_b), std::move(fits));
    StemLoads stem = StemLoads::from_values(std::move(profile), std::move(arc_length),
                                            std::move(section_indices), std::move(elastic), std::move(weight),
                                            std::move(root_elastic), std::move(root_weight));
    return SpeciesBasis::from_parts(skeleton, settings, std::move(modal), std::move(wind), std::move(strong),
                                    std::move(stem));
  } catch (const std::exception& e) {
    if (why_not) *why_not = fmt::format("{}: {}", path.string(), e.what());
    return std::nullopt;
  }
}

void BasisCache::store(const SpeciesBasis& species) const {
  const std::uint64_t entry_key = key(species.skeleton(), species.settings());
  const ModalBasis& modal = species.modes();
  const WindBasis& wind = species.wind();
  base::RecordWriter writer;
  for (char c : kMagic) writer.value(c);
  writer.value(kFormatVersion);
  writer.value(entry_key);
  writer.value(std::int32_t(species.skeleton().size()));
  writer.value(std::int32_t(modal.dof_count()));
  writer.value(std::int32_t(modal.mode_count()));
  writer.value(std::int32_t(wind.sample_count()));
  writer.value(std::int32_t(modal.status().converged));
  writer.value(std::int32_t(modal.status().iterations));
  writer.value(std::int32_t(modal.status().operations));
  writer.value(modal.status().max_residual);
  writer.text(modal.status().method);
  writer.values(modal.omega().data(), std::size_t(modal.omega().size()));
  writer.values(modal.shapes().data(), std::size_t(modal.shapes().size()));
  writer.values(wind.projection_matrix().data(), std::size_t(wind.projection_matrix().size()));
  writer.values(wind.sample_points().data(), std::size_t(wind.sample_points().size()));
  const StrongWindCorrection& strong = species.strong_wind();
  writer.values(strong.linear_shapes().data(), std::size_t(strong.linear_shapes().size()));
  writer.values(strong.quadratic_shapes().data(), std::size_t(strong.quadratic_shapes().size()));
  writer.values(strong.b().data(), std::size_t(strong.b().size()));
  for (const StrongWindModeFit& fit : strong.fits()) {
    writer.value(fit.q_max);
    writer.value(fit.relative_residual);
    writer.value(fit.linear_relative_residual);
    writer.value(fit.shape_change);
  }
  const StemLoads& stem = species.stem_loads();
  writer.value(std::int32_t(stem.profile().size()));
  for (const StemSection& section : stem.profile()) {
    writer.value(std::int32_t(section.node));
    writer.value(section.height);
    writer.value(section.diameter);
  }
  writer.values(stem.arc_length().data(), std::size_t(stem.arc_length().size()));
  writer.value(std::int32_t(stem.section_indices().size()));
  for (const int index : stem.section_indices()) writer.value(std::int32_t(index));
  for (const Eigen::MatrixXd* map :
       {&stem.elastic(), &stem.weight(), &stem.root_elastic(), &stem.root_weight()})
    writer.values(map->data(), std::size_t(map->size()));

  const auto path = entry_path(entry_key);
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error) {
    throw std::runtime_error(fmt::format("BasisCache: cannot create the cache folder {}: {}",
                                         directory_.string(), error.message()));
  }
  base::write_text_atomically("BasisCache", path, writer.sealed());
}

SpeciesBasis BasisCache::load_or_compute(const Skeleton& skeleton, const SpeciesSettings& settings,
                                         CacheOutcome* outcome, std::string* store_error,
                                         std::string* corrupt_reason) const {
  if (store_error) store_error->clear();
  std::string why_not;
  auto cached = load(skeleton, settings, &why_not);
  if (corrupt_reason) *corrupt_reason = why_not;
  if (cached) {
    if (outcome) *outcome = CacheOutcome::hit;
    return std::move(*cached);
  }
  if (outcome) *outcome = why_not.empty() ? CacheOutcome::miss : CacheOutcome::corrupt_recomputed;
  SpeciesBasis species = SpeciesBasis::compute(skeleton, settings);
  try {
    store(species);
  } catch (const std::runtime_error& e) {
    if (store_error) *store_error = e.what();
  }
  return species;
}

}  // namespace fw::trees
