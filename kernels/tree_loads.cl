/* The loads in every tree and the failure check (docs/damage.md; trees/TreeDamage.hpp, whose tree_load and
 * record_load are the CPU reference): per instance, the bending moment at each stem section and the root's
 * turning moment from its modal coordinates through its species' maps (trees/StemLoads.hpp), each against
 * its critical moment, and the tree's damage record.
 *
 * Work mapping: one instance per loop iteration (FW_FLAT_FOR over instances); its q stays in cache over the
 * J + 1 rows of 4 dot products of length m. An instance of scale s: the elastic rows times s^1/2, the
 * weight's times s^3/2, the critical moments times s^3.
 *
 * A tree that has failed, when failures have consequences, takes no load: its modes are held at rest (q and
 * qdot zeroed every step, after the modal step: the deformation and the next step see a tree at rest) and
 * its sections carry nothing.
 *
 * counters: [0] the trees failed since the host last read it (DamageStages::take_new_failures), [1] and [2]
 * every broken and overturned tree so far: a failure adds 1 to [0] and to [its state]. */
#include "common.cl"

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
    __global float* section_utilisation = utilisation + section_offsets[k];
    const int m = sp.mode_count;
    if (record.state != FW_TREE_STANDING && consequences) {
      for (int i = 0; i < 2 * m; ++i) modes[i] = 0.0f;
      for (int j = 0; j < stem.section_count; ++j) section_utilisation[j] = 0.0f;
      record.utilisation = 0.0f;
      damage[k] = record;
      continue;
    }
    const float elastic_scale = sqrt(tree.scale);
    const float weight_scale = tree.scale * elastic_scale;
    const float strength_scale = tree.scale * tree.scale * tree.scale;
    float worst = 0.0f, root_moment = 0.0f;
    int worst_section = -1;
    for (int j = 0; j <= stem.section_count; ++j) { /* j == J: the root's turning moment */
      __global const float* row = maps + stem.map_offset + 4 * m * j;
      float e1 = 0.0f, e2 = 0.0f, w1 = 0.0f, w2 = 0.0f;
      for (int i = 0; i < m; ++i) {
        const float q = modes[2 * i];
        e1 = fma(row[i], q, e1);
        e2 = fma(row[m + i], q, e2);
        w1 = fma(row[2 * m + i], q, w1);
        w2 = fma(row[3 * m + i], q, w2);
      }
      const float a = elastic_scale * e1 + weight_scale * w1, b = elastic_scale * e2 + weight_scale * w2;
      const float moment = sqrt(a * a + b * b);
      if (j == stem.section_count) {
        root_moment = moment;
      } else {
        const float u = moment / (sections[stem.section_offset + 2 * j + 1] * strength_scale);
        section_utilisation[j] = u;
        if (u > worst) {
          worst = u;
          worst_section = j;
        }
      }
    }
    const float overturning = root_moment / (stem.overturning * strength_scale);
    const float largest = fmax(worst, overturning);
    record.utilisation = largest;
    record.max_utilisation = fmax(record.max_utilisation, largest);
    record.max_base_moment = fmax(record.max_base_moment, root_moment);
    if (record.state == FW_TREE_STANDING && largest > 1.0f) {
      const int breaks = worst_section >= 0 && worst > overturning;
      record.state = breaks ? FW_TREE_BROKEN : FW_TREE_OVERTURNED;
      record.failed_section = breaks ? worst_section : -1;
      record.break_height = breaks ? tree.scale * sections[stem.section_offset + 2 * worst_section] : 0.0f;
      record.time = time;
      __global const float* top = sampled_wind + 3 * (tree.sample_offset + sp.sample_count - 1);
      for (int a = 0; a < 3; ++a) record.top_wind[a] = top[a];
      atomic_inc(&counters[0]);
      atomic_inc(&counters[record.state]);
    }
    damage[k] = record;
  }
}
