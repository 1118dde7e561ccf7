#include "trees/WindBasis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "trees/BeamElement.hpp"
#include "trees/BeamModel.hpp"
#include "trees/Skeleton.hpp"

namespace fw::trees {

namespace {

// Antiderivatives in t = s / L of the shape functions, without the factor L from ds = L dt.
struct ShapeAntiderivatives {
  double l1, l2, h1, h2, h3, h4;  // h2, h4 without their factor L
};

ShapeAntiderivatives antiderivatives(double t) {
  const double t2 = t * t;
  const double t3 = t2 * t;
  const double t4 = t3 * t;
  return {t - 0.5 * t2,      0.5 * t2,
          t - t3 + 0.5 * t4, 0.5 * t2 - 2.0 * t3 / 3.0 + 0.25 * t4,
          t3 - 0.5 * t4,     0.25 * t4 - t3 / 3.0};
}

}  // namespace

Eigen::Matrix<double, 3, 12> integrated_shape_functions(double length, double s0, double s1) {
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw std::invalid_argument(
        fmt::format("WindBasis: element length must be finite and positive, got {}", length));
  }
  if (!(s0 >= 0.0) || !(s0 <= s1) || !(s1 <= length)) {
    throw std::invalid_argument(fmt::format(
        "WindBasis: integration range must satisfy 0 <= s0 <= s1 <= L = {}, got [{}, {}]", length, s0, s1));
  }
  const double L = length;
  const ShapeAntiderivatives a = antiderivatives(s0 / L);
  const ShapeAntiderivatives b = antiderivatives(s1 / L);
  const double l1 = L * (b.l1 - a.l1);
  const double l2 = L * (b.l2 - a.l2);
  const double h1 = L * (b.h1 - a.h1);
  const double h2 = L * L * (b.h2 - a.h2);
  const double h3 = L * (b.h3 - a.h3);
  const double h4 = L * L * (b.h4 - a.h4);

  Eigen::Matrix<double, 3, 12> n = Eigen::Matrix<double, 3, 12>::Zero();
  n(0, 0) = l1;  // ux_a
  n(0, 6) = l2;  // ux_b
  // x-y plane: rz = +uy'.
  n(1, 1) = h1;
  n(1, 5) = h2;
  n(1, 7) = h3;
  n(1, 11) = h4;
  // x-z plane: ry = -uz', so the slope functions enter with a minus sign.
  n(2, 2) = h1;
  n(2, 4) = -h2;
  n(2, 8) = h3;
  n(2, 10) = -h4;
  return n;
}

void WindBasisSettings::validate() const {
  const std::pair<const char*, double> fields[] = {
      {"air_density (rho_air, kg/m^3)", air_density},
      {"branch_drag_coefficient (C_D of the wood)", branch_drag_coefficient},
      {"leaf_area_index (one-sided leaf area / crown hull area)", leaf_area_index},
      {"leaf_drag_coefficient (C_D of the foliage)", leaf_drag_coefficient}};
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value) || !(value >= 0.0)) {
      throw std::invalid_argument(
          fmt::format("WindBasisSettings: {} must be finite and >= 0, got {}", name, value));
    }
  }
  if (samples < 1) {
    throw std::invalid_argument(fmt::format("WindBasisSettings: samples must be >= 1, got {}", samples));
  }
}

namespace {

// The load operator G (6 n) x (3 S), node-major, and the sample points S x 3 (header comment).
struct Assembled {
  Eigen::MatrixXd load;
  Eigen::MatrixX3d sample_points;
};

Assembled assemble(const Skeleton& skeleton, const WindBasisSettings& settings) {
  const ElementDrag element_drag = ElementDrag::of(skeleton, settings);  // validates the settings
  if (skeleton.size() < 2) throw std::invalid_argument("WindBasis: the skeleton has no elements");
  const int bands = settings.samples;
  const double z_root = skeleton.node(skeleton.root()).position.z();
  double z_top = z_root;
  for (const auto& node : skeleton.nodes()) z_top = std::max(z_top, node.position.z());
  const double height = z_top - z_root;
  // A flat tree (no node above the root) cannot be split by height: everything goes to band 0.
  const bool split = bands > 1 && height > 0.0;
  const double half_rho = 0.5 * settings.air_density;

  Assembled out;
  out.load = Eigen::MatrixXd::Zero(6 * Eigen::Index(skeleton.size()), 3 * bands);
  // Centroid weights per band: the drag width w (m) and, for a tree without any drag, the diameter D.
  Eigen::MatrixX2d weight = Eigen::MatrixX2d::Zero(bands, 2);  // int w ds, int D ds per band, m^2
  std::array<Eigen::MatrixX3d, 2> moment = {Eigen::MatrixX3d::Zero(bands, 3),
                                            Eigen::MatrixX3d::Zero(bands, 3)};  // int w x ds, int D x ds
  std::vector<double> cuts;

  const auto& elements = skeleton.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto [parent, child] = elements[e];
    const SkeletonNode& a = skeleton.node(parent);
    const SkeletonNode& b = skeleton.node(child);
    const double length = (b.position - a.position).norm();
    const double diameter = element_drag.diameter[e];
    const double leaf = element_drag.foliage.leaf_area_per_metre[e];
    const double drag_width = element_drag.drag_width[e];
    const Eigen::Matrix3d frame = element_frame(a.position, b.position);

    // A_e = 1/2 rho (C_Db D P_e + C_Df lambda I), symmetric (N s^2 / m^4 = kg/m^3 x m).
    Eigen::Matrix3d wood = Eigen::Matrix3d::Identity();
    if (settings.branch_normal_drag) {
      const Eigen::Vector3d axis = frame.row(0).transpose();
      wood -= axis * axis.transpose();
    }
    const Eigen::Matrix3d drag =
        half_rho * (settings.branch_drag_coefficient * diameter * wood +
                    settings.leaf_drag_coefficient * leaf * Eigen::Matrix3d::Identity());
    // R_e A_e: maps the global |v| v to the local force per length, which (int N ds)^T spreads onto the DOFs.
    const Eigen::Matrix3d to_local = frame * drag;

    // Pieces of the element between band borders, as fractions t of its length.
    cuts.assign({0.0, 1.0});
    const double za = a.position.z();
    const double zb = b.position.z();
    if (split) {
      for (int k = 1; k < bands; ++k) {
        const double border = z_root + height * k / bands;
        if ((border - za) * (border - zb) < 0.0) cuts.push_back((border - za) / (zb - za));
      }
      std::sort(cuts.begin(), cuts.end());
    }

    for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
      const double t0 = cuts[piece];
      const double t1 = cuts[piece + 1];
      if (!(t1 > t0)) continue;
      const double tm = 0.5 * (t0 + t1);
      const Eigen::Vector3d middle = a.position + tm * (b.position - a.position);
      int band = 0;
      if (split) {
        // Decided at the piece's middle, which lies strictly inside one band; parts below the root go to 0.
        band = std::clamp(int(std::floor((middle.z() - z_root) / height * bands)), 0, bands - 1);
      }

      const Eigen::Matrix<double, 3, 12> integral =
          integrated_shape_functions(length, t0 * length, t1 * length);
      // G_e = T_e^T (int N ds)^T R_e A_e, block by block of T_e = diag(R, R, R, R); block 0, 1 are node a's
      // translations and rotations, 2, 3 node b's.
      for (int block = 0; block < 4; ++block) {
        const int node = block < 2 ? parent : child;
        const Eigen::Index row = 6 * Eigen::Index(node) + 3 * (block % 2);
        out.load.block<3, 3>(row, 3 * band) +=
            frame.transpose() * integral.middleCols<3>(3 * block).transpose() * to_local;
      }

      const double piece_length = (t1 - t0) * length;
      const double w[2] = {drag_width * piece_length, diameter * piece_length};
      for (int kind = 0; kind < 2; ++kind) {
        weight(band, kind) += w[kind];
        moment[std::size_t(kind)].row(band) += w[kind] * middle.transpose();  // exact: w constant, x linear
      }
    }
  }

  // Drag-weighted centroids; diameter-weighted when nothing drags (all coefficients 0).
  const int kind = weight.col(0).sum() > 0.0 ? 0 : 1;
  const Eigen::MatrixX3d& m = moment[std::size_t(kind)];
  const Eigen::RowVector3d centroid = m.colwise().sum() / weight.col(kind).sum();
  out.sample_points.resize(bands, 3);
  for (int band = 0; band < bands; ++band) {
    out.sample_points.row(band) =
        weight(band, kind) > 0.0 ? Eigen::RowVector3d(m.row(band) / weight(band, kind)) : centroid;
  }
  return out;
}

}  // namespace

ElementDrag ElementDrag::of(const Skeleton& skeleton, const WindBasisSettings& settings) {
  settings.validate();
  ElementDrag drag;
  drag.foliage = Foliage::of(skeleton, settings.leaf_area_index);
  const auto& elements = skeleton.elements();
  drag.diameter.reserve(elements.size());
  drag.drag_width.reserve(elements.size());
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const double diameter =
        skeleton.node(elements[e].first).radius + skeleton.node(elements[e].second).radius;
    drag.diameter.push_back(diameter);
    drag.drag_width.push_back(settings.branch_drag_coefficient * diameter +
                              settings.leaf_drag_coefficient * drag.foliage.leaf_area_per_metre[e]);
  }
  return drag;
}

Eigen::MatrixXd WindBasis::load_operator(const Skeleton& skeleton, const WindBasisSettings& settings) {
  return assemble(skeleton, settings).load;
}

Eigen::VectorXd WindBasis::squared_wind(const Eigen::MatrixX3d& wind) {
  Eigen::VectorXd stacked(3 * wind.rows());
  for (Eigen::Index s = 0; s < wind.rows(); ++s) {
    stacked.segment<3>(3 * s) = wind.row(s).norm() * wind.row(s).transpose();
  }
  return stacked;
}

WindBasis WindBasis::compute(const Skeleton& skeleton, const BeamModel& model, const Eigen::MatrixXd& shapes,
                             const WindBasisSettings& settings) {
  settings.validate();
  if (model.node_count() != skeleton.size()) {
    throw std::invalid_argument(fmt::format("WindBasis: the model has {} nodes but the skeleton has {}",
                                            model.node_count(), skeleton.size()));
  }
  if (shapes.rows() != model.dof_count()) {
    throw std::invalid_argument(fmt::format("WindBasis: shapes must have model.dof_count() = {} rows, got {}",
                                            model.dof_count(), shapes.rows()));
  }
  if (!shapes.allFinite()) throw std::invalid_argument("WindBasis: shapes contain non-finite values");

  Assembled assembled = assemble(skeleton, settings);
  // G_free: the rows of the model's free DOFs (the clamped root's load does no work on the modes).
  Eigen::MatrixXd free_load(model.dof_count(), assembled.load.cols());
  for (int node = 0; node < skeleton.size(); ++node) {
    for (int local = 0; local < 6; ++local) {
      const int dof = model.free_dof_of(node, local);
      if (dof >= 0) free_load.row(dof) = assembled.load.row(6 * Eigen::Index(node) + local);
    }
  }
  WindBasis basis;
  basis.settings_ = settings;
  basis.projection_ = free_load.transpose() * shapes;  // p_i^s = G_s,free^T phi_i
  basis.sample_points_ = std::move(assembled.sample_points);
  return basis;
}

WindBasis WindBasis::from_values(Eigen::MatrixXd projection, Eigen::MatrixX3d sample_points,
                                 WindBasisSettings settings) {
  settings.validate();
  if (sample_points.rows() != settings.samples) {
    throw std::invalid_argument(
        fmt::format("WindBasis: sample_points must have settings.samples = {} rows, got {}", settings.samples,
                    sample_points.rows()));
  }
  if (projection.rows() != 3 * Eigen::Index(settings.samples)) {
    throw std::invalid_argument(fmt::format("WindBasis: projection must have 3 * samples = {} rows, got {}",
                                            3 * settings.samples, projection.rows()));
  }
  if (!projection.allFinite())
    throw std::invalid_argument("WindBasis: projection contains non-finite values");
  if (!sample_points.allFinite()) {
    throw std::invalid_argument("WindBasis: sample_points contain non-finite values");
  }
  WindBasis basis;
  basis.projection_ = std::move(projection);
  basis.sample_points_ = std::move(sample_points);
  basis.settings_ = settings;
  return basis;
}

Eigen::Vector3d WindBasis::projection(int sample, int mode) const {
  if (sample < 0 || sample >= sample_count()) {
    throw std::out_of_range(fmt::format("WindBasis: sample {} outside 0..{}", sample, sample_count() - 1));
  }
  if (mode < 0 || mode >= mode_count()) {
    throw std::out_of_range(fmt::format("WindBasis: mode {} outside 0..{}", mode, mode_count() - 1));
  }
  return projection_.block<3, 1>(3 * sample, mode);
}

Eigen::VectorXd WindBasis::modal_forces(const Eigen::MatrixX3d& wind) const {
  if (wind.rows() != sample_count()) {
    throw std::invalid_argument(fmt::format("WindBasis: wind must have one row per sample ({}), got {} rows",
                                            sample_count(), wind.rows()));
  }
  // Stack |v_s| v_s into one 3S vector; then f = P^T w is a single product.
  return projection_.transpose() * squared_wind(wind);
}

WindBasis WindBasis::scaled(double s) const {
  if (!std::isfinite(s) || !(s > 0.0)) {
    throw std::invalid_argument(fmt::format("WindBasis: scale must be finite and positive, got {}", s));
  }
  WindBasis basis;
  basis.projection_ = std::sqrt(s) * projection_;
  basis.sample_points_ = s * sample_points_;
  basis.settings_ = settings_;
  return basis;
}

}  // namespace fw::trees
