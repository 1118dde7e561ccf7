// The loads in every tree and which trees fail, on the OpenCL device, every step (docs/damage.md;
// trees/TreeDamage.hpp is the model and its CPU reference, kernels/tree_loads.cl the kernel).
//
//   fw::host::DamageStages damage(cc, forest, settings);      // uploads the stems' maps, every tree standing
//   for (...) {
//     trees.enqueue_modal_step(dt);
//     damage.enqueue_loads(time_after_step, trees);          // utilisations, records, failures
//     if (damage.take_new_failures() > 0) ...                 // blocking: a count read back
//   }
//   std::vector<fw::trees::TreeDamageRecord> records = damage.download_records();
//
// ForestStages owns one when the run asks for damage (ForestStages::set_damage). The state it carries from
// step to step is each tree's FwTreeDamage record, saved with the trees' stage ("damage").
//
// The modal trees' loads come from their modal state (kernel tree_loads); the element trees' (rigid_bodies,
// springs: trees/BranchStemLoads.hpp) from the joints of the forest's BranchStages (kernel
// branch_tree_loads), which a failed element tree's zero when failures have consequences.
#pragma once

#include <vector>

#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BranchStages.hpp"
#include "host/stages/StageState.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/TreeDamage.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/TreeFall.hpp"

namespace fw::host {

/// The stems of a forest as the device reads them (kernels/shared_types.h FwStem, FwStemAxis).
struct StemPacking {
  std::vector<FwStem> stems;            ///< one per species
  std::vector<float> maps;              ///< per species 4 m FW_LANES floats a block
  std::vector<float> sections;          ///< per species 2 FW_LANES floats a block: heights, critical moments
  std::vector<FwStemAxis> axes;         ///< per species J (trees::BranchStem)
  std::vector<fw_int> section_offsets;  ///< per instance, its first lane in the flat utilisation
  /// With element trees: per species 2 ints an entry of its skeleton (trees::BranchStem's joint and element
  /// sections), species after species as FwSpecies.skeleton_offset lays them out; else empty.
  std::vector<fw_int> entry_sections;
  int total_sections = 0;  ///< lanes of every instance: its blocks x FW_LANES
  /// Packs the stems and critical moments of every species (settings.strengths, one per species), and with
  /// `element_trees` every species' entry sections. Throws std::invalid_argument("DamageStages: ...") when a
  /// strength is missing or invalid.
  static StemPacking of(const trees::Forest& forest, const trees::DamageSettings& settings,
                        bool element_trees = false);
};

/// A device record as the model's (trees/TreeDamage.hpp).
trees::TreeDamageRecord to_record(const FwTreeDamage& record);

class DamageStages {
 public:
  /// Uploads the packing of `forest` and a standing record for every tree. `settings.enabled` must be true
  /// (std::invalid_argument otherwise, and for what StemPacking::of throws). branches: the forest's element
  /// models' stage (ForestStages::branches()), whose trees' loads come from their joints; null when every
  /// species is modal. It must outlive this stage.
  DamageStages(ComputeContext& cc, const trees::Forest& forest, const trees::DamageSettings& settings,
               BranchStages* branches = nullptr);

  /// Bytes of device memory the constructor allocates (at most), for the forest under `dynamics` (one per
  /// species; empty: all modal).
  static std::size_t estimate_device_bytes(const trees::Forest& forest, const trees::DamageSettings& settings,
                                           const std::vector<trees::SpeciesDynamics>& dynamics = {});

  /// The multiply-adds of one tree_loads pass over the modal trees of `forest` (4 a mode, lane and block:
  /// the elastic and weight maps' two rows), for benchmarks' ratio to the FMA peak.
  static double modal_load_fmas(const trees::Forest& forest);

  const trees::DamageSettings& settings() const { return settings_; }
  int total_sections() const { return total_sections_; }

  /// The step's loads and failure check at `time` (s, after the step), from the modal state and sampled
  /// wind of the forest's buffers (ForestStages: instances, species, state, sampled wind), and from the
  /// element trees' joints.
  void enqueue_loads(float time, cl::Buffer& instances, cl::Buffer& species, cl::Buffer& state,
                     cl::Buffer& sampled_wind);
  /// The trees that failed since the last call (blocking: reads and zeroes the device's counter).
  int take_new_failures();
  /// This stage's trees by state (blocking: two counters read back).
  trees::DamageCounts counts();

  /// Every tree's record (blocking), as the device holds it, and as the model's record.
  std::vector<FwTreeDamage> download_device_records();
  std::vector<trees::TreeDamageRecord> download_records();
  /// Every stem section's utilisation of the last step (blocking), flat: instance k's J sections from
  /// section_offset(k), then its root's (overturning) and the padding of its lanes.
  std::vector<float> download_utilisation();
  int section_offset(int instance) const { return section_offsets_.at(std::size_t(instance)); }

  /// An output frame's falls at `time` (s), after the modal deformation: every failed tree's nodes in its
  /// fall's pose (trees/TreeFall.hpp), when failures have consequences; nothing otherwise. Blocking (the
  /// records come back to compute the poses).
  void enqueue_falls(double time, cl::Buffer& instances, cl::Buffer& species, cl::Buffer& displacements);

  /// The records, for checkpoints: saved under saved::kDamage.
  void save_state(StageState& state);
  void restore_state(const StageState& state);

 private:
  ComputeContext& cc_;
  trees::DamageSettings settings_;
  int instance_count_ = 0;
  int total_sections_ = 0;
  std::vector<fw_int> section_offsets_;
  cl::Buffer stems_, maps_, sections_, section_offsets_buffer_, records_, utilisation_;
  cl::Buffer counters_;                             // kernels/tree_loads.cl: new failures, broken, overturned
  std::vector<trees::FallGeometry> fall_geometry_;  // per species
  std::vector<int> instance_species_;               // per instance
  std::vector<double> instance_scale_;              // per instance
  cl::Buffer tour_, rest_nodes_;                    // kernels/tree_fall.cl
  Kernel loads_, fall_;
  // The element trees (kernels/tree_loads.cl branch_tree_loads): their stage, the stems' axes and entry
  // sections, and the kernel's scratch (a slice of scratch_stride_ floats a work-item).
  BranchStages* branches_ = nullptr;
  cl::Buffer axes_, entry_sections_, scratch_;
  std::size_t scratch_items_ = 0;
  int scratch_stride_ = 0;
  Kernel branch_loads_;
};

}  // namespace fw::host
