#include "host/stages/DamageStages.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "host/stages/SavedStateNames.hpp"
#include "trees/BranchStemLoads.hpp"
#include "trees/Gravity.hpp"

namespace fw::host {

namespace {

/// The FW_LANES-wide blocks of a stem's lanes: its sections, then the root.
int stem_blocks(const trees::StemLoads& stem) {
  return (stem.section_count() + 1 + FW_LANES - 1) / FW_LANES;
}

std::vector<FwTreeDamage> standing_records(int count) {
  FwTreeDamage standing{};
  standing.state = FW_TREE_STANDING;
  standing.failed_section = -1;
  return std::vector<FwTreeDamage>(std::size_t(count), standing);
}

constexpr int kCounters = 3;  // new failures, broken, overturned

// The falls' tables: each species' tour (2 ints a node) and rest nodes (3 floats a node).
std::size_t fall_bytes(const trees::Forest& forest) {
  std::size_t nodes = 0;
  for (const trees::SpeciesBasis& species : forest.species()) nodes += std::size_t(species.skeleton().size());
  return ComputeContext::allocation_bytes(2 * nodes * sizeof(fw_int)) +
         ComputeContext::allocation_bytes(3 * nodes * sizeof(float));
}

// The element trees' largest skeleton and stem, over the species of `instances` (indices into the forest):
// what each work-item's slice of the loads' scratch holds, floats.
int scratch_stride(const trees::Forest& forest, const std::vector<int>& instances) {
  int stride = 0;
  for (const int k : instances) {
    const trees::SpeciesBasis& basis = forest.species_of(k);
    stride = std::max(stride, FW_LOADS_SECTION_FLOATS * basis.stem_loads().section_count() +
                                  FW_LOADS_ENTRY_FLOATS * basis.skeleton().size());
  }
  return stride;
}

}  // namespace

trees::TreeDamageRecord to_record(const FwTreeDamage& d) {
  trees::TreeDamageRecord r;
  r.state = trees::TreeState(d.state);
  r.failed_section = d.failed_section;
  r.time = d.time;
  r.break_height = d.break_height;
  r.top_wind = Eigen::Vector3d(d.top_wind[0], d.top_wind[1], d.top_wind[2]);
  r.max_utilisation = d.max_utilisation;
  r.max_base_moment = d.max_base_moment;
  r.utilisation = d.utilisation;
  return r;
}

StemPacking StemPacking::of(const trees::Forest& forest, const trees::DamageSettings& settings,
                            bool element_trees) {
  if (settings.strengths.size() != forest.species().size())
    throw std::invalid_argument(fmt::format("DamageStages: {} strengths for {} species",
                                            settings.strengths.size(), forest.species().size()));
  StemPacking p;
  constexpr int kLanes = FW_LANES;
  std::vector<int> lanes_of_species;  // FW_LANES x blocks, per species
  for (std::size_t sp = 0; sp < forest.species().size(); ++sp) {
    const trees::StemLoads& stem = forest.species()[sp].stem_loads();
    const trees::CriticalMoments critical = trees::critical_moments(stem, settings.strengths[sp]);
    const int J = stem.section_count(), m = stem.mode_count();
    const int blocks = stem_blocks(stem);
    p.stems.push_back({J, blocks, fw_int(p.maps.size()), fw_int(p.sections.size()), fw_int(p.axes.size())});
    lanes_of_species.push_back(blocks * kLanes);
    const trees::BranchStem branch_stem = trees::BranchStem::of(forest.species()[sp].skeleton());
    if (branch_stem.section_count() != J)  // both are stem_path's: a bug here
      throw std::logic_error("StemPacking: the element trees' stem is not the modal one");
    for (int j = 0; j < J; ++j) {
      const Eigen::Vector3d& axis = branch_stem.axes()[std::size_t(j)];
      p.axes.push_back({{float(axis.x()), float(axis.y()), float(axis.z())},
                        fw_int(branch_stem.section_entries()[std::size_t(j)])});
    }
    if (element_trees)
      for (std::size_t e = 0; e < branch_stem.joint_sections().size(); ++e)
        p.entry_sections.insert(p.entry_sections.end(), {fw_int(branch_stem.joint_sections()[e]),
                                                         fw_int(branch_stem.element_sections()[e])});
    // Lane j < J: row r of section j (r = 0, 1 the elastic map's pair, 2, 3 the weight's); lane J: the
    // root's; then zeros.
    const auto row = [&](int r, int j) -> Eigen::RowVectorXd {
      const bool elastic = r < 2;
      const Eigen::MatrixXd& map = j < J ? (elastic ? stem.elastic() : stem.weight())
                                         : (elastic ? stem.root_elastic() : stem.root_weight());
      return map.row(2 * (j < J ? j : 0) + r % 2);
    };
    const std::vector<trees::StemSection> sections = stem.sections();
    for (int b = 0; b < blocks; ++b) {
      for (int r = 0; r < 4; ++r)
        for (int i = 0; i < m; ++i)
          for (int lane = 0; lane < kLanes; ++lane) {
            const int j = b * kLanes + lane;
            p.maps.push_back(j <= J ? float(row(r, j)(i)) : 0.0f);
          }
      for (int lane = 0; lane < kLanes; ++lane) {
        const int j = b * kLanes + lane;
        p.sections.push_back(j < J ? float(sections[std::size_t(j)].height) : 0.0f);
      }
      for (int lane = 0; lane < kLanes; ++lane) {
        const int j = b * kLanes + lane;
        p.sections.push_back(j < J ? float(critical.breaking[std::size_t(j)])
                                   : (j == J ? float(critical.overturning) : 1.0f));
      }
    }
  }
  for (int k = 0; k < forest.instance_count(); ++k) {
    p.section_offsets.push_back(p.total_sections);
    p.total_sections += lanes_of_species[std::size_t(forest.instances()[std::size_t(k)].species)];
  }
  return p;
}

DamageStages::DamageStages(ComputeContext& cc, const trees::Forest& forest,
                           const trees::DamageSettings& settings, BranchStages* branches)
    : cc_(cc), settings_(settings) {
  if (!settings.enabled) throw std::invalid_argument("DamageStages: damage is not enabled");
  if (branches && branches->tree_count() > 0) branches_ = branches;
  const StemPacking p = StemPacking::of(forest, settings, branches_ != nullptr);
  instance_count_ = forest.instance_count();
  total_sections_ = p.total_sections;
  section_offsets_ = p.section_offsets;
  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  stems_ = cc_.upload(p.stems, ro);
  maps_ = cc_.upload(p.maps, ro);
  sections_ = cc_.upload(p.sections, ro);
  section_offsets_buffer_ = cc_.upload(p.section_offsets, ro);
  records_ = cc_.upload(standing_records(instance_count_));
  utilisation_ = cc_.zero_floats(std::size_t(total_sections_));
  counters_ = cc_.upload(std::vector<fw_int>(kCounters, 0));
  const cl::Program program = cc_.build("tree_loads.cl");
  loads_ = Kernel(program, "tree_loads");
  // The falls: each species' skeleton tour and rest nodes, in the order of FwSpecies.skeleton_offset.
  std::vector<fw_int> tour;
  std::vector<float> rest;
  for (const trees::SpeciesBasis& species : forest.species()) {
    fall_geometry_.push_back(trees::FallGeometry::of(species));
    for (const int order : trees::skeleton_tour(species.skeleton())) tour.push_back(order);
    for (const trees::SkeletonNode& node : species.skeleton().nodes())
      for (int a = 0; a < 3; ++a) rest.push_back(float(node.position(a)));
  }
  for (const trees::TreeInstance& tree : forest.instances()) {
    instance_species_.push_back(tree.species);
    instance_scale_.push_back(tree.scale);
  }
  tour_ = cc_.upload(tour, ro);
  rest_nodes_ = cc_.upload(rest, ro);
  fall_ = Kernel(cc_.build("tree_fall.cl"), "tree_fall");
  if (!branches_) return;
  axes_ = cc_.upload(p.axes, ro);
  entry_sections_ = cc_.upload(p.entry_sections, ro);
  std::vector<int> element_instances;
  for (const FwBranchTree& tree : branches_->trees()) element_instances.push_back(tree.instance);
  scratch_stride_ = scratch_stride(forest, element_instances);
  // A slice for each item that gets a tree: at most one a tree (as BranchStages' scratch).
  scratch_items_ = cc_.flat_items(element_instances.size());
  scratch_ =
      cc_.zero_floats(std::min(scratch_items_, element_instances.size()) * std::size_t(scratch_stride_));
  branch_loads_ = Kernel(program, "branch_tree_loads");
}

std::size_t DamageStages::estimate_device_bytes(const trees::Forest& forest,
                                                const trees::DamageSettings& settings,
                                                const std::vector<trees::SpeciesDynamics>& dynamics) {
  std::vector<int> element_instances;
  for (int k = 0; k < forest.instance_count(); ++k)
    if (BranchStages::entries_of(forest, dynamics, k) > 0) element_instances.push_back(k);
  const StemPacking p = StemPacking::of(forest, settings, !element_instances.empty());
  const auto bytes = [](std::size_t count, std::size_t size) {
    return ComputeContext::allocation_bytes(count * size);
  };
  std::size_t total = bytes(p.stems.size(), sizeof(FwStem)) + bytes(p.maps.size(), sizeof(float)) +
                      bytes(p.sections.size(), sizeof(float)) +
                      bytes(p.section_offsets.size(), sizeof(fw_int)) +
                      bytes(std::size_t(forest.instance_count()), sizeof(FwTreeDamage)) +
                      bytes(std::size_t(p.total_sections), sizeof(float)) + bytes(kCounters, sizeof(fw_int)) +
                      fall_bytes(forest);
  if (!element_instances.empty())  // the scratch: at most a slice a tree
    total += bytes(p.axes.size(), sizeof(FwStemAxis)) + bytes(p.entry_sections.size(), sizeof(fw_int)) +
             bytes(element_instances.size() * std::size_t(scratch_stride(forest, element_instances)),
                   sizeof(float));
  return total;
}

void DamageStages::enqueue_loads(float time, cl::Buffer& instances, cl::Buffer& species, cl::Buffer& state,
                                 cl::Buffer& sampled_wind) {
  if (instance_count_ == 0) return;
  const fw_int consequences = settings_.consequences ? 1 : 0;
  loads_
      .set_args(instance_count_, time, consequences, instances, species, stems_, maps_, sections_,
                section_offsets_buffer_, sampled_wind, state, records_, utilisation_, counters_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
  if (!branches_) return;
  branch_loads_
      .set_args(branches_->tree_count(), time, consequences, branches_->trees_buffer(), instances, species,
                branches_->models(), branches_->table(), entry_sections_, stems_, axes_, sections_,
                section_offsets_buffer_, sampled_wind, float(trees::kGravity), branches_->joints(), records_,
                utilisation_, counters_, scratch_, fw_int(scratch_stride_))
      .enqueue(cc_, cl::NDRange(scratch_items_));
}

double DamageStages::modal_load_fmas(const trees::Forest& forest) {
  constexpr double kFmasPerModeLane = 4.0;  // two rows of the elastic map and two of the weight's
  double fmas = 0.0;
  for (const trees::TreeInstance& tree : forest.instances()) {
    const trees::StemLoads& stem = forest.species()[std::size_t(tree.species)].stem_loads();
    const int blocks = stem_blocks(stem);
    fmas += kFmasPerModeLane * stem.mode_count() * FW_LANES * blocks;
  }
  return fmas;
}

int DamageStages::take_new_failures() {
  fw_int count = 0;
  cc_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof count, &count);
  if (count != 0) {
    const fw_int zero = 0;
    cc_.queue().enqueueWriteBuffer(counters_, CL_TRUE, 0, sizeof zero, &zero);
  }
  return count;
}

trees::DamageCounts DamageStages::counts() {
  fw_int counters[kCounters] = {};
  cc_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof counters, counters);
  trees::DamageCounts n;
  n.broken = counters[FW_TREE_BROKEN];
  n.overturned = counters[FW_TREE_OVERTURNED];
  n.standing = instance_count_ - n.broken - n.overturned;
  return n;
}

std::vector<FwTreeDamage> DamageStages::download_device_records() {
  std::vector<FwTreeDamage> device(static_cast<std::size_t>(instance_count_));
  if (!device.empty())
    cc_.queue().enqueueReadBuffer(records_, CL_TRUE, 0, device.size() * sizeof(FwTreeDamage), device.data());
  return device;
}

std::vector<trees::TreeDamageRecord> DamageStages::download_records() {
  std::vector<trees::TreeDamageRecord> records;
  for (const FwTreeDamage& d : download_device_records()) records.push_back(to_record(d));
  return records;
}

std::vector<float> DamageStages::download_utilisation() {
  std::vector<float> values(static_cast<std::size_t>(total_sections_));
  if (!values.empty())
    cc_.queue().enqueueReadBuffer(utilisation_, CL_TRUE, 0, values.size() * sizeof(float), values.data());
  return values;
}

void DamageStages::enqueue_falls(double time, cl::Buffer& instances, cl::Buffer& species,
                                 cl::Buffer& displacements) {
  if (!settings_.consequences || instance_count_ == 0) return;
  std::vector<FwFall> falls;
  const std::vector<trees::TreeDamageRecord> records = download_records();
  for (int k = 0; k < instance_count_; ++k) {
    const trees::TreeDamageRecord& record = records[std::size_t(k)];
    if (record.state == trees::TreeState::standing) continue;
    const trees::FallPose pose =
        trees::fall_pose(record, fall_geometry_[std::size_t(instance_species_[std::size_t(k)])],
                         instance_scale_[std::size_t(k)], time);
    falls.push_back({k,
                     pose.pivot,
                     float(std::cos(pose.angle)),
                     float(std::sin(pose.angle)),
                     {float(pose.direction.x()), float(pose.direction.y())},
                     float(pose.drop)});
  }
  if (falls.empty()) return;
  // A frame's falls are few: a buffer of their own, released with the frame.
  cl::Buffer table = cc_.upload(falls, CL_MEM_READ_ONLY);
  fall_.set_args(int(falls.size()), table, instances, species, tour_, rest_nodes_, displacements)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(falls.size())));
}

void DamageStages::save_state(StageState& state) {
  state.save(cc_, saved::kDamage, records_);
}

void DamageStages::restore_state(const StageState& state) {
  state.restore(cc_, saved::kTreesStage, saved::kDamage, records_);
  // The totals follow from the records; nothing failed since the host last read the counter.
  std::vector<fw_int> counters(kCounters, 0);
  for (const FwTreeDamage& d : download_device_records())
    if (d.state != FW_TREE_STANDING) ++counters[std::size_t(d.state)];
  cc_.queue().enqueueWriteBuffer(counters_, CL_TRUE, 0, counters.size() * sizeof(fw_int), counters.data());
}

}  // namespace fw::host
