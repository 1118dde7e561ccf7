#include "trees/SizeFit.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace fw::trees {

SizeFitter::SizeFitter(double template_height, const StemLoads& stem)
    : template_height_(template_height), stem_(stem) {
  if (!(template_height > 0.0) || !std::isfinite(template_height) || !(stem.breast_height_diameter() > 0.0))
    throw std::invalid_argument(fmt::format(
        "SizeFitter: a template with a height and a stem expected, got {} m tall", template_height));
}

double SizeFitter::needed_girth(double height_m, double dbh_m) const {
  const double a = height_m / template_height_;
  return dbh_m / (a * stem_.diameter_at(StemLoads::kBreastHeight / a));
}

bool SizeFitter::fits(double height_m, double dbh_m) const {
  const double g = needed_girth(height_m, dbh_m);
  return g >= 1.0 / kMaxGirth && g <= kMaxGirth;
}

std::pair<double, double> SizeFitter::dbh_range(double height_m) const {
  const double a = height_m / template_height_;
  const double d = a * stem_.diameter_at(StemLoads::kBreastHeight / a);
  return {d / kMaxGirth, d * kMaxGirth};
}

SizeFit SizeFitter::fit(double height_m, double dbh_m) const {
  SizeFit fit;
  fit.scale = height_m / template_height_;
  const double g = needed_girth(height_m, dbh_m);
  fit.girth_class = int(std::lround(std::log(g) / std::log1p(kGirthStep)));
  fit.girth = girth_of_class(fit.girth_class);
  fit.dbh = fit.scale * fit.girth * stem_.diameter_at(StemLoads::kBreastHeight / fit.scale);
  return fit;
}

double SizeFitter::girth_of_class(int k) {
  return std::pow(1.0 + kGirthStep, double(k));
}

Skeleton with_girth(const Skeleton& skeleton, double girth) {
  if (!(girth > 0.0) || !std::isfinite(girth))
    throw std::invalid_argument(fmt::format("with_girth: a finite girth > 0 expected, got {}", girth));
  std::vector<SkeletonNode> nodes = skeleton.nodes();
  for (SkeletonNode& node : nodes) node.radius *= girth;
  return Skeleton::from_nodes(std::move(nodes));
}

}  // namespace fw::trees
