#include "trees/CanopyDrag.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "trees/Foliage.hpp"

namespace fw::trees {

namespace {

struct Elements {
  std::vector<fluid::CanopyElement> elements;
  Foliage foliage;
  double woody_area = 0.0;  // sum of D_e L_e, m^2
};

Elements elements_of(const Skeleton& placed, const WindBasisSettings& settings) {
  ElementDrag drag;
  try {
    drag = ElementDrag::of(placed, settings);  // the same widths the wind basis integrates
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("CanopyDrag: {}", e.what()));
  }
  if (placed.size() < 2) throw std::invalid_argument("CanopyDrag: the skeleton has no elements");
  Elements out;
  const auto& pairs = placed.elements();
  out.elements.reserve(pairs.size());
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    const SkeletonNode& a = placed.node(pairs[e].first);
    const SkeletonNode& b = placed.node(pairs[e].second);
    fluid::CanopyElement c;
    c.start = {a.position.x(), a.position.y(), a.position.z()};
    c.end = {b.position.x(), b.position.y(), b.position.z()};
    c.frontal_area_per_metre = drag.diameter[e] + drag.foliage.leaf_area_per_metre[e];
    c.drag_area_per_metre = drag.drag_width[e];
    out.elements.push_back(c);
    out.woody_area += drag.diameter[e] * (b.position - a.position).norm();
  }
  out.foliage = std::move(drag.foliage);
  return out;
}

}  // namespace

std::vector<fluid::CanopyElement> canopy_elements(const Skeleton& world_skeleton,
                                                  const WindBasisSettings& settings) {
  return elements_of(world_skeleton, settings).elements;
}

ForestCanopy::ForestCanopy(const Forest& forest) : forest_(&forest) {
  species_.reserve(forest.species().size());
  for (const SpeciesBasis& species : forest.species()) {
    Elements parts = elements_of(species.skeleton(), species.settings().wind);
    species_.push_back({std::move(parts.elements), parts.woody_area, parts.foliage.leaf_area,
                        parts.foliage.crown_projected_area});
  }
}

std::vector<fluid::CanopyElement> ForestCanopy::elements(int instance) const {
  if (instance < 0 || instance >= forest_->instance_count()) {
    throw std::invalid_argument(
        fmt::format("CanopyDrag: instance {} outside 0..{}", instance, forest_->instance_count() - 1));
  }
  const TreeInstance& tree = forest_->instances()[std::size_t(instance)];
  const Eigen::Matrix3d rotation = forest_->rotation(instance);
  const double s = tree.scale;
  auto world = [&](const std::array<double, 3>& p) {
    const Eigen::Vector3d x = tree.position + s * (rotation * Eigen::Vector3d(p[0], p[1], p[2]));
    return std::array<double, 3>{x.x(), x.y(), x.z()};
  };
  std::vector<fluid::CanopyElement> out = species_[std::size_t(tree.species)].elements;
  for (fluid::CanopyElement& e : out) {
    e.start = world(e.start);
    e.end = world(e.end);
    e.frontal_area_per_metre *= s;
    e.drag_area_per_metre *= s;
  }
  return out;
}

fluid::CanopyTreeReport ForestCanopy::add(fluid::CanopyField& canopy, int instance) const {
  fluid::CanopyTreeReport report = canopy.add_elements(elements(instance));
  const SpeciesElements& species = species_[std::size_t(forest_->instances()[std::size_t(instance)].species)];
  const double s = forest_->instances()[std::size_t(instance)].scale, area = s * s;
  report.woody_area = species.woody_area * area;
  report.leaf_area = species.leaf_area * area;
  report.crown_projected_area = species.crown_projected_area * area;
  return report;
}

Eigen::AlignedBox3d instance_reach(const Forest& forest, int instance) {
  const TreeInstance& tree = forest.instances().at(std::size_t(instance));
  const Eigen::AlignedBox3d skeleton = forest.species_of(instance).skeleton().bounding_box();
  const Eigen::Matrix3d rotation = forest.rotation(instance);
  Eigen::AlignedBox3d reach;
  for (int corner = 0; corner < 8; ++corner)
    reach.extend(tree.position + tree.scale * rotation *
                                     skeleton.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  return reach;
}

fluid::CellBox cells_around(const fluid::GridSpec& spec, const Eigen::AlignedBox3d& reach) {
  if (reach.isEmpty()) return {};
  return fluid::CellBox::around(spec, {reach.min().x(), reach.min().y(), reach.min().z()},
                                {reach.max().x(), reach.max().y(), reach.max().z()});
}

fluid::CellBox instance_cells(const fluid::GridSpec& spec, const Forest& forest, int instance) {
  return cells_around(spec, instance_reach(forest, instance));
}

}  // namespace fw::trees
