#include "trees/Forest.hpp"

#include "trees/ModalIntegrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

namespace fw::trees {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("Forest: " + what);
}

void validate_species(const SpeciesBasis& sp, std::size_t index) {
  const int n = sp.skeleton().size();
  const int m = sp.modes().mode_count();
  const int samples = sp.wind().sample_count();
  if (m < 1) fail(fmt::format("species {}: no modes", index));
  if (samples < 1 || samples > FW_MAX_TREE_SAMPLES)
    fail(fmt::format("species {}: wind samples must be 1..{}, got {}", index, FW_MAX_TREE_SAMPLES, samples));
  if (sp.wind().mode_count() != m)
    fail(fmt::format("species {}: wind basis and modes differ in count", index));
  if (sp.node_shapes().rows() != 3 * n || sp.node_shapes().cols() != m)
    fail(fmt::format("species {}: node shapes are {} x {}, expected {} x {}", index, sp.node_shapes().rows(),
                     sp.node_shapes().cols(), 3 * n, m));
  if (sp.strong_wind().mode_count() != m || sp.strong_wind().node_count() != n)
    fail(fmt::format("species {}: the strong-wind correction has {} modes of {} nodes, expected {} of {}",
                     index, sp.strong_wind().mode_count(), sp.strong_wind().node_count(), m, n));
  for (int i = 0; i < m; ++i) {
    const double w = sp.modes().omega()(i);
    if (!std::isfinite(w) || w <= 0.0)
      fail(fmt::format("species {}: mode {}: omega must be finite and > 0, got {}", index, i, w));
  }
}

void check_int32(long long total, const char* what) {
  if (total > std::numeric_limits<fw_int>::max())
    fail(fmt::format("{} {} exceed 32-bit indexing on the device", total, what));
}

// The strong-wind walk's order: parents before children, and of the nodes whose parent is placed, the
// smallest index first. That is node order itself where every parent has a smaller index than its children
// (the generator's trees), so that the kernel's stores run through a tree's displacements in order instead of
// breadth-first's jumps across the crown.
std::vector<int> walk_order(const Skeleton& skeleton) {
  std::priority_queue<int, std::vector<int>, std::greater<>> ready;
  ready.push(skeleton.root());
  std::vector<int> order;
  order.reserve(std::size_t(skeleton.size()));
  while (!ready.empty()) {
    const int node = ready.top();
    ready.pop();
    order.push_back(node);
    for (int child : skeleton.children(node)) ready.push(child);
  }
  return order;
}

// The strong-wind correction's arrays of one species (ForestPacking: walk, strong_v, strong_w,
// rest_elements), in walk order and in blocks of ForestPacking::kWalkBlock entries.
void pack_strong_wind(const SpeciesBasis& sp, ForestPacking& p) {
  const Skeleton& skeleton = sp.skeleton();
  const std::vector<int> order = walk_order(skeleton);
  const StrongWindCorrection& strong = sp.strong_wind();
  const Eigen::MatrixXd &v = strong.linear_shapes(), &w = strong.quadratic_shapes();
  const int n = skeleton.size(), m = sp.modes().mode_count();
  // Element differences in double, so that the float a kernel reads has no cancellation of its own; the
  // reference walk takes the root's rows as zero (StrongWindCorrection::corrected_deformation), and so do
  // these.
  const auto element = [&](const Eigen::MatrixXd& shapes, int node, int row, int mode) {
    const int parent = skeleton.node(node).parent;
    if (parent < 0) return 0.0;
    const double from = parent == skeleton.root() ? 0.0 : shapes(3 * parent + row, mode);
    return shapes(3 * node + row, mode) - from;
  };
  for (int first = 0; first < n; first += ForestPacking::kWalkBlock) {
    const int count = std::min(ForestPacking::kWalkBlock, n - first);
    for (int i = 0; i < m; ++i)
      for (int a = 0; a < 3; ++a)
        for (int j = first; j < first + count; ++j) {
          p.strong_v.push_back(float(element(v, order[std::size_t(j)], a, i)));
          p.strong_w.push_back(float(element(w, order[std::size_t(j)], a, i)));
        }
    for (int a = 0; a < 3; ++a)
      for (int j = first; j < first + count; ++j) {
        const int node = order[std::size_t(j)], parent = skeleton.node(node).parent;
        p.rest_elements.push_back(
            parent < 0 ? 0.0f : float(skeleton.node(node).position(a) - skeleton.node(parent).position(a)));
      }
  }
  for (int node : order) {
    p.walk.push_back(node);
    p.walk.push_back(skeleton.node(node).parent);
  }
}

}  // namespace

Forest::Forest(std::vector<SpeciesBasis> species, std::vector<TreeInstance> instances)
    : species_(std::move(species)), instances_(std::move(instances)) {
  // 3 n m node-shape floats per species bound the 3 n of its rest elements (ForestPacking) as well.
  long long shape_floats = 0;
  for (std::size_t s = 0; s < species_.size(); ++s) {
    validate_species(species_[s], s);
    shape_floats += species_[s].node_shapes().size();
  }
  check_int32(shape_floats, "node-shape values");

  long long modes = 0, nodes = 0, samples = 0;
  for (std::size_t k = 0; k < instances_.size(); ++k) {
    const TreeInstance& t = instances_[k];
    if (t.species < 0 || std::size_t(t.species) >= species_.size())
      fail(fmt::format("instance {}: species index must be 0..{}, got {}", k, int(species_.size()) - 1,
                       t.species));
    if (!t.position.allFinite())
      fail(fmt::format("instance {}: position must be finite, got ({}, {}, {})", k, t.position.x(),
                       t.position.y(), t.position.z()));
    if (!std::isfinite(t.yaw_rad)) fail(fmt::format("instance {}: yaw must be finite, got {}", k, t.yaw_rad));
    if (!std::isfinite(t.scale) || t.scale <= 0.0)
      fail(fmt::format("instance {}: scale must be finite and > 0, got {}", k, t.scale));
    const SpeciesBasis& sp = species_[std::size_t(t.species)];
    modes += sp.modes().mode_count();
    nodes += sp.skeleton().size();
    samples += sp.wind().sample_count();
    // 2 floats of modal state and 3 of sampled wind / displacement per entry: keep those indices in range.
    check_int32(2 * modes, "modal state values");
    check_int32(3 * nodes, "displacement values");
    check_int32(3 * samples, "sampled wind values");
    mode_offsets_.push_back(int(modes));
    node_offsets_.push_back(int(nodes));
    sample_offsets_.push_back(int(samples));
  }
}

const SpeciesBasis& Forest::species_of(int instance) const {
  return species_.at(std::size_t(instances_.at(std::size_t(instance)).species));
}

Forest Forest::subset(const std::vector<int>& ids) const {
  std::vector<TreeInstance> chosen;
  std::vector<int> original;
  for (int k : ids) {
    if (k < 0 || k >= instance_count())
      fail(fmt::format("subset: instance {} is not one of the {} instances", k, instance_count()));
    chosen.push_back(instances_[std::size_t(k)]);
    original.push_back(id(k));
  }
  Forest part(species_, std::move(chosen));
  part.ids_ = std::move(original);
  return part;
}

Eigen::Matrix3d Forest::rotation(int instance) const {
  const double psi = instances_.at(std::size_t(instance)).yaw_rad;
  Eigen::Matrix3d r;
  r << std::cos(psi), -std::sin(psi), 0.0, std::sin(psi), std::cos(psi), 0.0, 0.0, 0.0, 1.0;
  return r;
}

std::vector<FwTreeInstance> Forest::pack_instances() const {
  std::vector<FwTreeInstance> rows;
  rows.reserve(instances_.size());
  for (int k = 0; k < instance_count(); ++k) {
    const TreeInstance& t = instances_[std::size_t(k)];
    FwTreeInstance row{};
    row.species = t.species;
    row.mode_offset = mode_offset(k);
    row.node_offset = node_offset(k);
    row.sample_offset = sample_offset(k);
    for (int a = 0; a < 3; ++a) row.position[a] = float(t.position(a));
    row.cos_yaw = float(std::cos(t.yaw_rad));
    row.sin_yaw = float(std::sin(t.yaw_rad));
    row.scale = float(t.scale);
    rows.push_back(row);
  }
  return rows;
}

ForestPacking Forest::pack() const {
  ForestPacking p;
  for (const SpeciesBasis& sp : species_) {
    const int n = sp.skeleton().size();
    const int m = sp.modes().mode_count();
    const int samples = sp.wind().sample_count();
    FwSpecies row{};
    row.node_count = n;
    row.mode_count = m;
    row.sample_count = samples;
    row.shape_offset = fw_int(p.node_shapes.size());
    row.projection_offset = fw_int(p.projections.size());
    row.sample_point_offset = fw_int(p.sample_points.size());
    row.modal_offset = fw_int(p.omega.size());
    row.skeleton_offset = fw_int(p.walk.size() / 2);
    p.species.push_back(row);

    const Eigen::MatrixXd& shapes = sp.node_shapes();
    // Mode-major (m rows of 3n): for one mode, consecutive nodes' x y z are contiguous, so the deformation
    // kernel reads 8 nodes of a mode with three vector loads.
    for (int i = 0; i < m; ++i)
      for (int r = 0; r < 3 * n; ++r) p.node_shapes.push_back(float(shapes(r, i)));
    // Mode-major, so that one mode's force is a dot product over 3S contiguous values.
    const Eigen::MatrixXd& proj = sp.wind().projection_matrix();
    for (int i = 0; i < m; ++i)
      for (int r = 0; r < 3 * samples; ++r) p.projections.push_back(float(proj(r, i)));
    const Eigen::MatrixX3d& points = sp.wind().sample_points();
    for (int s = 0; s < samples; ++s)
      for (int a = 0; a < 3; ++a) p.sample_points.push_back(float(points(s, a)));
    const Eigen::VectorXd zeta = sp.modes().damping_ratios();
    for (int i = 0; i < m; ++i) {
      p.omega.push_back(float(sp.modes().omega()(i)));
      p.damping_ratios.push_back(float(zeta(i)));
      p.strong_b.push_back(float(sp.strong_wind().b()(i)));
    }
    pack_strong_wind(sp, p);
  }

  p.instances = pack_instances();
  for (int k = 0; k < instance_count(); ++k) {
    p.mode_instance.insert(p.mode_instance.end(), std::size_t(mode_offset(k + 1) - mode_offset(k)), k);
    p.node_instance.insert(p.node_instance.end(), std::size_t(node_offset(k + 1) - node_offset(k)), k);
  }
  p.total_modes = total_modes();
  p.total_nodes = total_nodes();
  p.total_samples = total_samples();
  return p;
}

Eigen::MatrixX3d Forest::instance_displacements(int k, const Eigen::VectorXd& qk,
                                                bool strong_wind_correction) const {
  const TreeInstance& t = instances().at(std::size_t(k));
  const SpeciesBasis& sp = species_of(k);
  if (qk.size() != sp.modes().mode_count())
    throw std::invalid_argument(fmt::format("Forest: instance {} has {} modes, got {} coordinates", k,
                                            sp.modes().mode_count(), qk.size()));
  // The correction is fitted on the species (scale 1): its q is s^-5/2 times the instance's, and the
  // instance's displacement s times the species'. The length-restoring pass runs here in the species'
  // frame, on the device in the world frame: it commutes with s R, so the two routes check each other.
  const Eigen::Matrix3d r = (strong_wind_correction ? t.scale : std::pow(t.scale, -1.5)) * rotation(k);
  const Eigen::VectorXd local = strong_wind_correction ? sp.strong_wind().corrected_displacement(
                                                             sp.skeleton(), std::pow(t.scale, -2.5) * qk)
                                                       : Eigen::VectorXd(sp.node_shapes() * qk);
  Eigen::MatrixX3d u(sp.skeleton().size(), 3);
  for (int n = 0; n < sp.skeleton().size(); ++n) u.row(n) = (r * local.segment<3>(3 * n)).transpose();
  return u;
}

double Forest::semi_implicit_dt_limit() const {
  double limit = std::numeric_limits<double>::infinity();
  for (int k = 0; k < instance_count(); ++k) {
    const ModalBasis& modes = species_of(k).modes();
    const double scale = instances_[std::size_t(k)].scale;
    for (int i = 0; i < modes.mode_count(); ++i) {
      const double omega = modes.omega()(i) / scale;
      const double gamma = 2.0 * modes.damping_ratios()(i) * omega;
      limit = std::min(limit, trees::semi_implicit_dt_limit(omega, gamma));
    }
  }
  return limit;
}

}  // namespace fw::trees
