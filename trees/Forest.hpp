// A forest: the species (one modal and wind basis each) and the tree instances that share them
// (docs/design.md, "Numerics: Trees: Instances"), and the packing of everything the device needs into plain
// arrays (Diener 2008, figure 5: instances T, modal parameters P, mode shapes Phi; kernels/shared_types.h).
//
//   std::vector<fw::trees::SpeciesBasis> species = {fw::trees::SpeciesBasis::compute(pine, settings)};
//   std::vector<fw::trees::TreeInstance> trees = {{0, {40.0, 12.0, 0.0}, 0.5, 1.1}};  // species, x, yaw, s
//   fw::trees::Forest forest(std::move(species), std::move(trees));   // validates, throws invalid_argument
//   forest.total_modes();                 // length of the flat modal state
//   fw::trees::ForestPacking packed = forest.pack();   // float32 arrays for host/ForestStages
//
// An instance k of species sp, scale s, yaw psi and root position x places a skeleton-frame point p at
// x + s R(psi) p, R turning counter-clockwise about +z seen from above. Similarity laws (ModalBasis.hpp,
// WindBasis.hpp): omega / s, the damping ratio kept (gamma = 2 zeta omega / s), projections s^1/2 R p_i^s,
// nodal translations s^-3/2 R phi, sample points x + s R p_s, and the strong-wind correction
// s R sum_i (q~_i v_i + q~_i^2 w_i), q~_i = arctan(b_i s^-5/2 q_i) / b_i (trees/StrongWindCorrection.hpp).
//
// Flat numbering: instance k owns the modes [mode_offset(k), mode_offset(k) + m), the nodes
// [node_offset(k), node_offset(k) + n) and the samples [sample_offset(k), sample_offset(k) + S) of the
// flat per-instance arrays, in instance order.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "kernels/shared_types.h"
#include "trees/SpeciesBasis.hpp"

namespace fw::trees {

struct TreeInstance {
  int species = 0;                                     ///< index into Forest::species()
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< world position of the skeleton origin, m
  double yaw_rad = 0.0;  ///< rotation about +z, counter-clockwise seen from above, rad
  double scale = 1.0;    ///< uniform scale s > 0 about the skeleton origin
};

/// Everything the device stage uploads, as float32 / int32 arrays (layouts: kernels/shared_types.h).
struct ForestPacking {
  std::vector<FwSpecies> species;         ///< one per species
  std::vector<FwTreeInstance> instances;  ///< one per instance
  std::vector<float> node_shapes;         ///< per species m x (3n), mode-major: [i * 3n + 3 node + axis], m
  std::vector<float> projections;         ///< per species, mode-major m x (3S), kg^1/2 / m
  std::vector<float> sample_points;       ///< per species S x 3, m, skeleton frame
  std::vector<float> omega;               ///< per species m, rad/s (scale 1)
  std::vector<float> damping_ratios;      ///< per species m, zeta (dimensionless)
  std::vector<fw_int> mode_instance;      ///< #total modes: the instance that owns each flat mode
  std::vector<fw_int> node_instance;      ///< #total nodes: the instance that owns each flat node
  /// The strong-wind correction's arrays per species, for its one kernel (kernels/tree_deform.cl,
  /// tree_deform_strong). walk: the skeleton's walk, n entries from FwSpecies::skeleton_offset, parents
  /// before children (topological_order()), (node, parent) pairs, the root first with parent -1. strong_b:
  /// b_i per mode (FwSpecies::modal_offset, like omega). strong_v, strong_w: Diener's v and w of each entry's
  /// element, node minus parent (the root's rows taken as zero, as the reference walk does; zero for the root
  /// entry), 3 n m floats each from FwSpecies::shape_offset; rest_elements: each entry's rest element from
  /// the parent to the node (skeleton frame, m; zero for the root), 3 n floats from 3
  /// FwSpecies::skeleton_offset. Elements, not positions: the pass needs only differences, and no two nearly
  /// equal floats are subtracted on the device. All three in blocks of kWalkBlock consecutive walk entries
  /// (the last block of a species may be shorter, count entries): rest_elements per block the x of its
  /// entries, then their y, then their z; strong_v and strong_w block-major, per block its m modes one after
  /// the other, each the x, y and z of its entries like that, so that a block's floats are contiguous and one
  /// float8 holds an axis.
  static constexpr int kWalkBlock = 8;
  std::vector<fw_int> walk;
  std::vector<float> strong_v, strong_w, strong_b, rest_elements;
  int total_modes = 0;
  int total_nodes = 0;
  int total_samples = 0;
};

class Forest {
 public:
  Forest() = default;  ///< no species, no trees

  /// Throws std::invalid_argument("Forest: ...") for a species without modes or samples, with more than
  /// FW_MAX_TREE_SAMPLES samples, non-positive or non-finite frequencies, or shapes that do not fit its
  /// skeleton; for an instance with a species index out of range, a non-finite position or yaw, or a scale
  /// that is not finite and > 0; and for flat sizes beyond 32-bit indexing.
  Forest(std::vector<SpeciesBasis> species, std::vector<TreeInstance> instances);

  const std::vector<SpeciesBasis>& species() const { return species_; }
  const std::vector<TreeInstance>& instances() const { return instances_; }
  int instance_count() const { return int(instances_.size()); }
  const SpeciesBasis& species_of(int instance) const;
  /// The forest of the instances `ids` (indices into this one, in the order given) with all its species: a
  /// rank's own trees over MPI ranks. Throws std::invalid_argument("Forest: ...") for an id out of range.
  Forest subset(const std::vector<int>& ids) const;
  /// Instance k's index in the forest this one was cut from by subset() (through every cut), else k: what
  /// outputs call the tree and what seeds its random series.
  int id(int instance) const { return ids_.empty() ? instance : ids_.at(std::size_t(instance)); }

  int mode_offset(int instance) const { return mode_offsets_.at(std::size_t(instance)); }
  int node_offset(int instance) const { return node_offsets_.at(std::size_t(instance)); }
  int sample_offset(int instance) const { return sample_offsets_.at(std::size_t(instance)); }
  int total_modes() const { return mode_offsets_.back(); }
  int total_nodes() const { return node_offsets_.back(); }
  int total_samples() const { return sample_offsets_.back(); }

  /// R(yaw) of an instance: counter-clockwise about +z.
  Eigen::Matrix3d rotation(int instance) const;

  /// The largest stable dt of Diener's semi-implicit Euler over every instance-mode (omega / s and
  /// gamma = 2 zeta omega / s of the instance), s; infinity without trees.
  double semi_implicit_dt_limit() const;

  /// One instance's nodal displacements for its modal coordinates qk (its m modes), computed on the host in
  /// double precision: #nodes by 3, m, world frame. With the strong-wind correction (Diener's quadratic part
  /// and the length-restoring pass, as on the device's output frames) or the linear sum s^-3/2 R Phi q.
  /// Throws std::invalid_argument("Forest: ...") when qk does not have the species' mode count.
  Eigen::MatrixX3d instance_displacements(int instance, const Eigen::VectorXd& qk,
                                          bool strong_wind_correction = true) const;

  /// The float32 arrays of the device stage (host/ForestStages) in the layout of kernels/shared_types.h.
  ForestPacking pack() const;
  /// Only the instance table of pack() (ForestPacking::instances), for stages that need no shapes.
  std::vector<FwTreeInstance> pack_instances() const;

 private:
  std::vector<SpeciesBasis> species_;
  std::vector<TreeInstance> instances_;
  // Prefix sums over the instances: entry k is instance k's first, the last entry the total.
  std::vector<int> mode_offsets_{0}, node_offsets_{0}, sample_offsets_{0};
  std::vector<int> ids_;  // id() per instance; empty for a forest that is not a subset
};

}  // namespace fw::trees
