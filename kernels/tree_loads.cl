/* The loads in every tree and the failure check (docs/damage.md; trees/TreeDamage.hpp, whose tree_load and
 * record_load are the CPU reference): per instance, the bending moment at each stem section and the root's
 * turning moment from its modal coordinates through its species' maps (trees/StemLoads.hpp), each against
 * its critical moment, and the tree's damage record.
 *
 * Work mapping: one instance per loop iteration (FW_FLAT_FOR over instances). Its sections and its root are
 * the lanes of FW_LANES-wide vectors (kernels/lanes.cl; the layout in kernels/shared_types.h FwStem): per
 * block, 4 vector multiply-adds a mode with the mode's q in every lane, so that the arithmetic runs as SIMD
 * (PoCL does not vectorise a loop inside a work-item). An instance of scale s: the elastic rows times s^1/2,
 * the weight's times s^3/2, the critical moments times s^3.
 *
 * A tree that has failed, when failures have consequences, takes no load: its modes are held at rest (q and
 * qdot zeroed every step, after the modal step: the deformation and the next step see a tree at rest) and
 * its sections carry nothing.
 *
 * utilisation: per instance its blocks' lanes (from section_offsets[k]): the sections' |M_j| / M_b,j, then
 * the root's M / M_o, then padding.
 *
 * counters: [0] the trees failed since the host last read it (DamageStages::take_new_failures), [1] and [2]
 * every broken and overturned tree so far: a failure adds 1 to [0] and to [its state]. */
#include "lanes.cl"

__kernel void tree_loads(const int instance_count, const float time, const int consequences,
                         __global const FwTreeInstance* instances, __global const FwSpecies* species,
                         __global const FwStem* stems, __global const float* maps,
                         __global const float* sections, __global const int* section_offsets,
                         __global const float* sampled_wind, __global float* state,
                         __global FwTreeDamage* damage, __global float* utilisation, __global int* counters) {
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const FwStem stem = stems[tree.species];
    FwTreeDamage record = damage[k];
    __global float* modes = state + 2 * tree.mode_offset;
    __global float* lanes_out = utilisation + section_offsets[k];
    const int m = sp.mode_count;
    if (record.state != FW_TREE_STANDING && consequences) {
      for (int i = 0; i < 2 * m; ++i) modes[i] = 0.0f;
      for (int b = 0; b < stem.block_count; ++b) lane_store((lanef)(0.0f), 0, lanes_out + b * FW_LANES);
      record.utilisation = 0.0f;
      damage[k] = record;
      continue;
    }
    const float elastic_scale = sqrt(tree.scale);
    const float weight_scale = tree.scale * elastic_scale;
    const float strength_scale = tree.scale * tree.scale * tree.scale;
    float worst = 0.0f, overturning = 0.0f, root_moment = 0.0f;
    int worst_section = -1;
    for (int b = 0; b < stem.block_count; ++b) {
      __global const float* block = maps + stem.map_offset + 4 * m * FW_LANES * b;
      lanef e1 = (lanef)(0.0f), e2 = (lanef)(0.0f), w1 = (lanef)(0.0f), w2 = (lanef)(0.0f);
      for (int i = 0; i < m; ++i) {
        const lanef q = (lanef)(modes[2 * i]);
        e1 = fma(lane_load(0, block + i * FW_LANES), q, e1);
        e2 = fma(lane_load(0, block + (m + i) * FW_LANES), q, e2);
        w1 = fma(lane_load(0, block + (2 * m + i) * FW_LANES), q, w1);
        w2 = fma(lane_load(0, block + (3 * m + i) * FW_LANES), q, w2);
      }
      const lanef a = elastic_scale * e1 + weight_scale * w1, c = elastic_scale * e2 + weight_scale * w2;
      const lanef moment = sqrt(a * a + c * c);
      const lanef critical =
          lane_load(0, sections + stem.section_offset + (2 * b + 1) * FW_LANES) * strength_scale;
      const lanef u = moment / critical;
      lane_store(u, 0, lanes_out + b * FW_LANES);
      float lane_u[FW_LANES], lane_moment[FW_LANES];
      lane_store(u, 0, lane_u);
      lane_store(moment, 0, lane_moment);
      for (int lane = 0; lane < FW_LANES; ++lane) {
        const int j = b * FW_LANES + lane;
        if (j < stem.section_count && lane_u[lane] > worst) {
          worst = lane_u[lane];
          worst_section = j;
        } else if (j == stem.section_count) {
          overturning = lane_u[lane];
          root_moment = lane_moment[lane];
        }
      }
    }
    const float largest = fmax(worst, overturning);
    record.utilisation = largest;
    record.max_utilisation = fmax(record.max_utilisation, largest);
    record.max_base_moment = fmax(record.max_base_moment, root_moment);
    if (record.state == FW_TREE_STANDING && largest > 1.0f) {
      const int breaks = worst_section >= 0 && worst > overturning;
      record.state = breaks ? FW_TREE_BROKEN : FW_TREE_OVERTURNED;
      record.failed_section = breaks ? worst_section : -1;
      const int lane = worst_section % FW_LANES, b = worst_section / FW_LANES;
      record.break_height =
          breaks ? tree.scale * sections[stem.section_offset + 2 * b * FW_LANES + lane] : 0.0f;
      record.time = time;
      __global const float* top = sampled_wind + 3 * (tree.sample_offset + sp.sample_count - 1);
      for (int a = 0; a < 3; ++a) record.top_wind[a] = top[a];
      atomic_inc(&counters[0]);
      atomic_inc(&counters[record.state]);
    }
    damage[k] = record;
  }
}
