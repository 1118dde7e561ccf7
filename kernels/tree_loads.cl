/* The loads in every tree and the failure check (docs/damage.md; trees/TreeDamage.hpp, whose tree_load and
 * record_load are the CPU reference): per instance, the bending moment at each stem section and the root's
 * turning moment, each against its critical moment, and the tree's damage record. A modal tree's moments come
 * from its modal coordinates through its species' maps (trees/StemLoads.hpp; kernel tree_loads); an element
 * tree's from its joints and its pose (trees/BranchStemLoads.hpp; kernel branch_tree_loads). Both kernels
 * share the record's update (record_tree_load) and what a failed tree does (hold_sections).
 *
 * Work mapping: one tree per loop iteration (FW_FLAT_FOR over instances, or over the element trees).
 *   - tree_loads: its sections and its root are the lanes of FW_LANES-wide vectors (kernels/lanes.cl; the
 *     layout in kernels/shared_types.h FwStem): per block, 4 vector multiply-adds a mode with the mode's q
 *     in every lane, so that the arithmetic runs as SIMD (PoCL does not vectorise a loop inside a
 *     work-item). An instance of scale s: the elastic rows times s^1/2, the weight's times s^3/2, the
 *     critical moments times s^3. It skips the element trees (their species have no modes on the device).
 *   - branch_tree_loads: one walk down the tree's table (parents before children), as the pose's
 *     (tree_branches.cl branch_deform, but in the skeleton frame): every entry's orientation and node
 *     displacement into this work-item's slice of `scratch`, its element's weight into the section it lies
 *     above and, when its joint is at a stem node, its joint moment into that section. Then one walk down the
 *     stem from the top, summing the sections' weights: the moment of the weight above a section about its
 *     node, sum m (u_c - u_j), is the sums' sum m u_c - (sum m) u_j.
 *
 * A tree that has failed, when failures have consequences, takes no load: it is held at rest (its q and qdot,
 * or its joints' angles and rates, zeroed every step, after the step: the deformation and the next step see a
 * tree at rest) and its sections carry nothing.
 *
 * utilisation: per instance its blocks' lanes (from section_offsets[k]): the sections' |M_j| / M_b,j, then
 * the root's M / M_o, then padding.
 *
 * counters: [0] the trees failed since the host last read it (DamageStages::take_new_failures), [1] and [2]
 * every broken and overturned tree so far: a failure adds 1 to [0] and to [its state]. */
#include "branch_common.cl"
#include "lanes.cl"

/* Lane j of a stem's sections (FwStem): its height above the root, and its critical moment (M_b of section
 * j < J, M_o for j = J), at scale 1. */
FW_INLINE float stem_height(__global const float* stem_sections, const int j) {
  return stem_sections[2 * (j / FW_LANES) * FW_LANES + j % FW_LANES];
}
FW_INLINE float stem_critical(__global const float* stem_sections, const int j) {
  return stem_sections[(2 * (j / FW_LANES) + 1) * FW_LANES + j % FW_LANES];
}

/* A failed tree held at rest: its lanes carry nothing, and its record says so. */
FW_INLINE void hold_sections(FwTreeDamage* record, __global float* section_utilisation, const int blocks) {
  for (int b = 0; b < blocks; ++b) lane_store((lanef)(0.0f), 0, section_utilisation + b * FW_LANES);
  record->utilisation = 0.0f;
}

/* Section j's utilisation |M_j| / (M_b,j s^3), stored, and the worst so far. */
FW_INLINE void note_section(const int j, const float moment, __global const float* stem_sections,
                            const float strength_scale, __global float* section_utilisation, float* worst,
                            int* worst_section) {
  const float u = moment / (stem_critical(stem_sections, j) * strength_scale);
  section_utilisation[j] = u;
  if (u > *worst) {
    *worst = u;
    *worst_section = j;
  }
}

/* The step's record (trees/TreeDamage.cpp record_load): the maxima, and the failure of a standing tree whose
 * largest utilisation exceeds 1, by the larger of the worst section's and the overturning's. top: the wind at
 * the tree's top (its highest sample). */
FW_INLINE void record_tree_load(FwTreeDamage* record, const float worst, const int worst_section,
                                const float root_moment, const float overturning, const float time,
                                const float scale, __global const float* stem_sections,
                                __global const float* top, __global int* counters) {
  const float largest = fmax(worst, overturning);
  record->utilisation = largest;
  record->max_utilisation = fmax(record->max_utilisation, largest);
  record->max_base_moment = fmax(record->max_base_moment, root_moment);
  if (record->state == FW_TREE_STANDING && largest > 1.0f) {
    const int breaks = worst_section >= 0 && worst > overturning;
    record->state = breaks ? FW_TREE_BROKEN : FW_TREE_OVERTURNED;
    record->failed_section = breaks ? worst_section : -1;
    record->break_height = breaks ? scale * stem_height(stem_sections, worst_section) : 0.0f;
    record->time = time;
    for (int a = 0; a < 3; ++a) record->top_wind[a] = top[a];
    atomic_inc(&counters[0]);
    atomic_inc(&counters[record->state]);
  }
}

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
      hold_sections(&record, lanes_out, stem.block_count);
      damage[k] = record;
      continue;
    }
    if (m == 0) continue; /* an element tree: branch_tree_loads */
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
    record_tree_load(&record, worst, worst_section, root_moment, overturning, time, tree.scale,
                     sections + stem.section_offset,
                     sampled_wind + 3 * (tree.sample_offset + sp.sample_count - 1), counters);
    damage[k] = record;
  }
}

/* tan(a) / a of the angle a whose square is a2: below a right angle from the series of sin(a) / a and cos(a)
 * in a^2 (the first terms left out, a^14 / 15! and a^16 / 16!, are 4e-10 and 7e-11 there), a few FMAs where
 * PoCL's scalar tan costs about a hundred ns; the library's beyond. The springs' angles stay below their cap,
 * under a right angle. Its float rounding stays under 1.2e-7 / cos(a) (measured from 0 to 90 degrees against
 * tan in double): under 1.3e-7 up to 20 degrees, and near a right angle what the angle's own rounding in
 * float gives tan. */
FW_INLINE float tan_over_angle(const float a2) {
  if (a2 >= FW_SERIES_MAX_ANGLE * FW_SERIES_MAX_ANGLE) {
    const float a = sqrt(a2);
    return tan(a) / a;
  }
  const float sinc =
      1.0f + a2 * (-1.0f / 6 +
                   a2 * (1.0f / 120 +
                         a2 * (-1.0f / 5040 + a2 * (1.0f / 362880 +
                                                    a2 * (-1.0f / 39916800 + a2 * (1.0f / 6227020800.0f))))));
  const float cosine =
      1.0f +
      a2 * (-1.0f / 2 +
            a2 * (1.0f / 24 +
                  a2 * (-1.0f / 720 + a2 * (1.0f / 40320 +
                                            a2 * (-1.0f / 3628800 + a2 * (1.0f / 479001600 +
                                                                          a2 * (-1.0f / 87178291200.0f)))))));
  return sinc / cosine;
}

/* The moment entry e's joint carries at the angle theta, scale s (trees/BranchStemLoads.cpp joint_moment):
 * the rigid bodies' s^3 K_e theta; the springs' s^3 k L^2 tan|theta| along theta. */
FW_INLINE float3 branch_joint_moment(const FwBranch* e, const int model, const float s, const float3 theta) {
  const float s3 = s * s * s;
  if (model == FW_DYNAMICS_SPRINGS)
    return (s3 * e->spring * e->length * e->length * tan_over_angle(dot(theta, theta))) * theta;
  return s3 * mat_vec(joint_stiffness(e), theta);
}

/* The element trees (trees/BranchStemLoads.hpp): per tree of `trees` (BranchStages' table of element trees),
 * its joints (`joints`, FW_JOINT_FLOATS an entry) and its species' table (`branches`, from
 * FwSpecies.skeleton_offset) and stem: `entry_sections`, 2 ints an entry in the table's layout (the section
 * at its joint or -1, the section its element lies above); `axes`, one FwStemAxis a section from
 * FwStem.axis_offset. `scratch`: `scratch_stride` floats a work-item, FW_LOADS_SECTION_FLOATS a section then
 * FW_LOADS_ENTRY_FLOATS an entry. g: gravity, m/s^2. */
__kernel void branch_tree_loads(const int tree_count, const float time, const int consequences,
                                __global const FwBranchTree* trees, __global const FwTreeInstance* instances,
                                __global const FwSpecies* species, __global const FwBranchSpecies* models,
                                __global const FwBranch* branches, __global const int* entry_sections,
                                __global const FwStem* stems, __global const FwStemAxis* axes,
                                __global const float* sections, __global const int* section_offsets,
                                __global const float* sampled_wind, const float g, __global float* joints,
                                __global FwTreeDamage* damage, __global float* utilisation,
                                __global int* counters, __global float* scratch, const int scratch_stride) {
  __global float* work = scratch + get_global_id(0) * (size_t)scratch_stride;
  FW_FLAT_FOR(t, tree_count) {
    const FwBranchTree bt = trees[t];
    const int k = bt.instance;
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const FwStem stem = stems[tree.species];
    const int n = sp.node_count, J = stem.section_count;
    FwTreeDamage record = damage[k];
    __global float* tree_joints = joints + FW_JOINT_FLOATS * bt.entry_offset;
    __global float* section_utilisation = utilisation + section_offsets[k];
    __global const float* stem_sections = sections + stem.section_offset;
    if (record.state != FW_TREE_STANDING && consequences) {
      for (int i = 0; i < FW_JOINT_FLOATS * n; ++i) tree_joints[i] = 0.0f;
      hold_sections(&record, section_utilisation, stem.block_count);
      damage[k] = record;
      continue;
    }
    const int model = models[tree.species].model;
    const float s = tree.scale, s3 = s * s * s;
    __global float* acc = work;                                /* per section: elastic, m u_c, m */
    __global float* pose = work + FW_LOADS_SECTION_FLOATS * J; /* per entry: orientation, u */
    __global const int* where = entry_sections + 2 * sp.skeleton_offset;
    for (int i = 0; i < FW_LOADS_SECTION_FLOATS * J; ++i) acc[i] = 0.0f;
    vstore4((float4)(1.0f, 0.0f, 0.0f, 0.0f), 0, pose);
    vstore3((float3)(0.0f), 0, pose + 4);
    for (int j = 1; j < n; ++j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      const float3 theta = vload3(0, tree_joints + FW_JOINT_FLOATS * j);
      __global const float* parent = pose + FW_LOADS_ENTRY_FLOATS * e.parent_entry;
      __global float* here = pose + FW_LOADS_ENTRY_FLOATS * j;
      const float4 q = quaternion_mul(vload4(0, parent), quaternion_exp(theta));
      const float3 r = s * branch_rest(&e);
      const float3 vr = cross(q.yzw, r);
      const float3 change = 2.0f * q.x * vr + 2.0f * cross(q.yzw, vr);
      const float3 u_parent = vload3(0, parent + 4);
      vstore4(q, 0, here);
      vstore3(u_parent + change, 0, here + 4);
      const int2 section = vload2(j, where);
      /* The element's weight at its centre, which moves by the mean of its ends' displacements. */
      const float mass = s3 * e.mass;
      __global float* weight = acc + FW_LOADS_SECTION_FLOATS * section.y + 3;
      vstore4(vload4(0, weight) + (float4)(mass * (u_parent + 0.5f * change), mass), 0, weight);
      if (section.x >= 0) {
        __global float* elastic = acc + FW_LOADS_SECTION_FLOATS * section.x;
        vstore3(vload3(0, elastic) + branch_joint_moment(&e, model, s, theta), 0, elastic);
      }
    }
    /* Down the stem from the top: the weight above each section about its node, (sum m (u_c - u_j)) x
     * (0, 0, -g), then the bending part normal to its rest axis. */
    float4 above = (float4)(0.0f);
    float worst = 0.0f, root_moment = 0.0f;
    int worst_section = -1;
    for (int j = J - 1; j >= 0; --j) {
      __global const float* a = acc + FW_LOADS_SECTION_FLOATS * j;
      above += vload4(0, a + 3);
      const FwStemAxis axis = axes[stem.axis_offset + j];
      const float3 lever = above.xyz - above.w * vload3(0, pose + FW_LOADS_ENTRY_FLOATS * axis.entry + 4);
      const float3 moment = vload3(0, a) + (float3)(-g * lever.y, g * lever.x, 0.0f);
      const float3 t = (float3)(axis.axis[0], axis.axis[1], axis.axis[2]);
      note_section(j, length(moment - dot(moment, t) * t), stem_sections, s3, section_utilisation, &worst,
                   &worst_section);
      if (j == 0) root_moment = length(moment.xy);
    }
    const float overturning = root_moment / (stem_critical(stem_sections, J) * s3);
    section_utilisation[J] = overturning;
    record_tree_load(&record, worst, worst_section, root_moment, overturning, time, s, stem_sections,
                     sampled_wind + 3 * (tree.sample_offset + sp.sample_count - 1), counters);
    damage[k] = record;
  }
}
