/* Skeleton deformation for output frames: u_node = s^-3/2 R sum_i phi_node_i q_i per instance node, world
 * frame, m (Diener 2008, eq. 10). Reference: trees/ForestReference.cpp displacements.
 *
 * Work mapping: one block of 8 consecutive flat nodes per loop iteration (FW_FLAT_FOR over the blocks). Node
 * shapes are stored mode-major (trees/Forest.hpp), so for one mode the x y z of 8 consecutive nodes are 24
 * contiguous floats: three vload8 and three float8 multiply-adds with the same q_i. Eight nodes in flight
 * keep the FMA pipelines busy where one node's three sums would wait on each other's latency. A block whose
 * nodes belong to two instances (at most one per instance boundary) takes the per-node path, which does the
 * same fma()s in the same order: a node's bits do not depend on where the blocks fall, so a tree gives the
 * same frame whichever trees come before it (over MPI ranks, a rank holds only some of them).
 *
 * The strong-wind correction (trees/StrongWindCorrection.hpp) is Diener's fitted quadratic correction,
 * followed by a projection that restores each element's rest length exactly, output frames only. Both in one
 * kernel, tree_deform_strong, which never forms Diener's displacements themselves: the projection needs only
 * each element's Diener image, delta = u_c - u_p = sum_i q~_i dv_i + q~_i^2 dw_i, dv and dw the elements'
 * differences of Diener's v and w (Diener 2008, section 5.2: q~_i = atan(b_i s^-5/2 q_i) / b_i, v and w
 * fitted on the species at scale 1, whose modal coordinate is s^-5/2 times the instance's), packed per
 * species in walk order (trees/Forest.hpp, ForestPacking). From delta, in the species' frame, each element's
 * change e = L unit(r + delta) - r (r its rest element, L = |r|), and then parents before children
 * u'_c = u'_p + s R e, the root staying put: the corrected displacement, turned and grown into the
 * instance's (the projection commutes with s R, as in Forest::instance_displacements).
 *
 * Work mapping of tree_deform_strong: FW_STRONG_TREES consecutive instances per loop iteration (FW_FLAT_FOR
 * over the groups), walking their species' walk in blocks of 8 entries: a block's dv and dw for one mode are
 * six float8 (x, y, z lanes), loaded once for every tree of the group, and each tree's 8 elements are three
 * float8 sums. A node depends on all its ancestors, so a tree is never split between work-items; the walk
 * puts parents before children and, where a skeleton's numbering allows it, follows node order, so that the
 * stores run through each tree's displacements in order. A group whose instances are not all of one species
 * goes one tree at a time through the same code, the same operations in the same order: a node's bits do not
 * depend on its neighbours.
 *
 * tree_deform stays the linear path, for frames with the correction off. Reference: trees/ForestReference.cpp
 * displacements. */
#include "common.cl"

FW_INLINE void store_displacement(__global float* displacements, const size_t n, const FwTreeInstance* tree,
                                  const float x, const float y, const float z) {
  /* s^-3/2: translations of the M_s-normalised modes of the scaled tree (trees/ModalBasis.hpp). */
  const float factor = 1.0f / (tree->scale * sqrt(tree->scale));
  const float cs = tree->cos_yaw, sn = tree->sin_yaw;
  displacements[3 * n] = factor * (cs * x - sn * y);
  displacements[3 * n + 1] = factor * (sn * x + cs * y);
  displacements[3 * n + 2] = factor * z;
}

__kernel void tree_deform(const int total_nodes, __global const int* node_instance,
                          __global const FwTreeInstance* instances, __global const FwSpecies* species,
                          __global const float* node_shapes, __global const float* state,
                          __global float* displacements) {
  const int blocks = (total_nodes + 7) / 8;
  FW_FLAT_FOR(b, blocks) {
    const int first = 8 * (int)b;
    const int count = min(8, total_nodes - first);
    const int k = node_instance[first];
    if (count == 8 && node_instance[first + 7] == k) {
      const FwTreeInstance tree = instances[k];
      const FwSpecies sp = species[tree.species];
      if (sp.mode_count == 0) continue; /* an element tree: kernels/tree_branches.cl poses it */
      const int m = sp.mode_count, row = 3 * sp.node_count;
      __global const float* phi = node_shapes + sp.shape_offset + 3 * (first - tree.node_offset);
      __global const float* q = state + 2 * tree.mode_offset;
      float8 a0 = (float8)(0.0f), a1 = (float8)(0.0f), a2 = (float8)(0.0f);
      for (int i = 0; i < m; ++i) {
        const float8 qi = (float8)(q[2 * i]);
        __global const float* p = phi + i * row;
        a0 = fma(vload8(0, p), qi, a0);
        a1 = fma(vload8(1, p), qi, a1);
        a2 = fma(vload8(2, p), qi, a2);
      }
      float sum[24];
      vstore8(a0, 0, sum);
      vstore8(a1, 1, sum);
      vstore8(a2, 2, sum);
      for (int j = 0; j < 8; ++j) {
        store_displacement(displacements, (size_t)(first + j), &tree, sum[3 * j], sum[3 * j + 1],
                           sum[3 * j + 2]);
      }
    } else {
      for (int n = first; n < first + count; ++n) {
        const FwTreeInstance tree = instances[node_instance[n]];
        const FwSpecies sp = species[tree.species];
        if (sp.mode_count == 0) continue;
        const int m = sp.mode_count, row = 3 * sp.node_count;
        __global const float* phi = node_shapes + sp.shape_offset + 3 * (n - tree.node_offset);
        __global const float* q = state + 2 * tree.mode_offset;
        float x = 0.0f, y = 0.0f, z = 0.0f;
        for (int i = 0; i < m; ++i) {
          const float qi = q[2 * i];
          x = fma(phi[i * row], qi, x);
          y = fma(phi[i * row + 1], qi, y);
          z = fma(phi[i * row + 2], qi, z);
        }
        store_displacement(displacements, (size_t)n, &tree, x, y, z);
      }
    }
  }
}

/* From here on, the strong-wind path: its arithmetic is spelled out (fma() where fused), so that a tree
 * deformed alone and one deformed with others of its species round alike. */
#pragma OPENCL FP_CONTRACT OFF

/* Trees of one species deformed together by one work-item: each block of dv and dw loaded serves them all.
 * A species' dv and dw (3 n m floats each, 2 MB at 3,446 nodes x 25 modes) outgrow a core's L2 cache, so a
 * tree alone streams them from the L3 cache, which then bounds the kernel (as it bounds tree_deform's node
 * shapes). Four trees share that stream with their 12 float8 sums in registers; two and eight were slower
 * (bench coupled, 10,000 trees, docs/performance.md). */
#define FW_STRONG_TREES 4

/* Lanes of a walk block (float8); a block of fewer entries (a species' last) fills the rest with zeros. */
#define FW_WALK_BLOCK 8

/* trees/Skeleton.hpp kMinElementLength, m in the species' frame: an element whose Diener image is shorter has
 * no direction of its own and keeps its rest direction, as in the reference walk. */
#define FW_MIN_ELEMENT_LENGTH 1e-9f

/* q~ = atan(b q) / b, and q for b = 0 (a mode fitted without any reparametrisation). */
FW_INLINE float strong_wind_amplitude(const float q, const float b) {
  return b > 0.0f ? atan(b * q) / b : q;
}

/* `count` consecutive floats as the first lanes of a float8; count is FW_WALK_BLOCK but in a species' last
 * block, and a constant after inlining. */
FW_INLINE float8 load_lanes(__global const float* p, const int count) {
  if (count == FW_WALK_BLOCK) return vload8(0, p);
  float lanes[FW_WALK_BLOCK] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int j = 0; j < count; ++j) lanes[j] = p[j];
  return vload8(0, lanes);
}

/* q~_i and q~_i^2 of every mode of `tree` into its 2 m floats of `amplitudes` (read back by the same
 * work-item): the arctan is paid once per mode, not per node. s^-5/2 turns the instance's modal coordinate
 * into the species'. */
FW_INLINE void strong_amplitudes(const FwTreeInstance* tree, const FwSpecies* sp,
                                 __global const float* strong_b, __global const float* state,
                                 __global float* amplitudes) {
  const float to_species = 1.0f / (tree->scale * tree->scale * sqrt(tree->scale));
  for (int i = 0; i < sp->mode_count; ++i) {
    const int j = tree->mode_offset + i;
    const float t = strong_wind_amplitude(to_species * state[2 * j], strong_b[sp->modal_offset + i]);
    amplitudes[2 * j] = t;
    amplitudes[2 * j + 1] = t * t;
  }
}

/* One walk block (walk entries first .. first + count - 1 of the species) of `trees` instances of species sp
 * (instances[0 .. trees - 1]); `trees` and `count` are constants after inlining. Per tree: Diener's element
 * delta = sum_i q~_i dv_i + q~_i^2 dw_i in the species' frame, its length-restoring change
 * e = L unit(r + delta) - r, turned and grown into the world, and u'_c = u'_p + s R e along the block's
 * entries, whose parents come earlier in the walk and so are final already. */
FW_INLINE void deform_strong_block(const int trees, const int count, const int first,
                                   const FwTreeInstance* instances, const FwSpecies* sp,
                                   __global const int* walk, __global const float* strong_v,
                                   __global const float* strong_w, __global const float* rest_elements,
                                   __global const float* amplitudes, __global float* displacements) {
  const int m = sp->mode_count;
  /* Block-major: the block's m modes of 3 count floats (x lanes, y lanes, z lanes) follow the blocks before
   * it, each of 3 FW_WALK_BLOCK m floats. */
  const int block_offset = sp->shape_offset + 3 * first * m;
  __global const float* rest = rest_elements + 3 * (sp->skeleton_offset + first);
  const float8 rx = load_lanes(rest, count), ry = load_lanes(rest + count, count),
               rz = load_lanes(rest + 2 * count, count);
  float8 ax[FW_STRONG_TREES], ay[FW_STRONG_TREES], az[FW_STRONG_TREES];
#pragma unroll
  for (int g = 0; g < trees; ++g) ax[g] = ay[g] = az[g] = (float8)(0.0f);
  for (int i = 0; i < m; ++i) {
    __global const float* pv = strong_v + block_offset + 3 * count * i;
    __global const float* pw = strong_w + block_offset + 3 * count * i;
    const float8 vx = load_lanes(pv, count), vy = load_lanes(pv + count, count),
                 vz = load_lanes(pv + 2 * count, count);
    const float8 wx = load_lanes(pw, count), wy = load_lanes(pw + count, count),
                 wz = load_lanes(pw + 2 * count, count);
#pragma unroll
    for (int g = 0; g < trees; ++g) {
      __global const float* t = amplitudes + 2 * (instances[g].mode_offset + i);
      const float8 ti = (float8)(t[0]), t2 = (float8)(t[1]);
      ax[g] = fma(vx, ti, fma(wx, t2, ax[g]));
      ay[g] = fma(vy, ti, fma(wy, t2, ay[g]));
      az[g] = fma(vz, ti, fma(wz, t2, az[g]));
    }
  }
  /* L = |r|: the rest element's length as rounded here (at rest delta = 0 and e = 0 whatever L is). */
  const float8 rest_length = sqrt(rx * rx + ry * ry + rz * rz);
  /* Each tree's changes s R e, turned and grown into the world: x lanes, y lanes, z lanes. */
  float e[FW_STRONG_TREES][3 * FW_WALK_BLOCK];
#pragma unroll
  for (int g = 0; g < trees; ++g) {
    const float8 dx = rx + ax[g], dy = ry + ay[g], dz = rz + az[g];
    const float8 d_length = sqrt(dx * dx + dy * dy + dz * dz);
    /* L unit(r + delta) - r without the cancellation of two nearly equal vectors (see the reference walk,
     * trees/StrongWindCorrection.cpp): (L / |d|) delta - (2 r.delta + delta.delta) / (|d| (L + |d|)) r. */
    const float8 along = rest_length / d_length;
    const float8 shorten =
        (2.0f * (rx * ax[g] + ry * ay[g] + rz * az[g]) + (ax[g] * ax[g] + ay[g] * ay[g] + az[g] * az[g])) /
        (d_length * (rest_length + d_length));
    /* An element whose Diener image has collapsed keeps its rest direction: no change. */
    const int8 keep = d_length >= (float8)(FW_MIN_ELEMENT_LENGTH);
    const float8 ex = select((float8)(0.0f), along * ax[g] - shorten * rx, keep);
    const float8 ey = select((float8)(0.0f), along * ay[g] - shorten * ry, keep);
    const float8 ez = select((float8)(0.0f), along * az[g] - shorten * rz, keep);
    const float s = instances[g].scale, cs = instances[g].cos_yaw, sn = instances[g].sin_yaw;
    vstore8(s * (cs * ex - sn * ey), 0, e[g]);
    vstore8(s * (sn * ex + cs * ey), 1, e[g]);
    vstore8(s * ez, 2, e[g]);
  }
  /* u'_c = u'_p + s R e along the entries, the trees side by side so that their sums do not wait on each
   * other. Where the parent is the entry just before (along a branch, most entries), its sum is taken from
   * the register rather than read back from the store just made, whose round trip would chain every node to
   * the last. Either way the same float is added. */
  __global const int* steps = walk + 2 * (sp->skeleton_offset + first);
  float3 sum[FW_STRONG_TREES];
  int previous = -1;
  for (int j = 0; j < count; ++j) {
    const int2 step = vload2(j, steps); /* (node, parent) */
#pragma unroll
    for (int g = 0; g < trees; ++g) {
      __global float* u = displacements + 3 * (size_t)instances[g].node_offset;
      if (step.y < 0) {
        sum[g] = (float3)(0.0f); /* x'_root = x_root */
      } else {
        const float3 parent = step.y == previous ? sum[g] : vload3(step.y, u);
        sum[g] = parent + (float3)(e[g][j], e[g][FW_WALK_BLOCK + j], e[g][2 * FW_WALK_BLOCK + j]);
      }
      vstore3(sum[g], step.x, u);
    }
    previous = step.x;
  }
}

/* The corrected deformation of `trees` instances of species sp, instances[0 .. trees - 1] (a constant after
 * inlining): their amplitudes, then the walk block by block. */
FW_INLINE void deform_strong_trees(const int trees, const FwTreeInstance* instances, const FwSpecies* sp,
                                   __global const int* walk, __global const float* strong_v,
                                   __global const float* strong_w, __global const float* strong_b,
                                   __global const float* rest_elements, __global const float* state,
                                   __global float* amplitudes, __global float* displacements) {
  if (sp->mode_count == 0) return; /* element trees: kernels/tree_branches.cl poses them */
#pragma unroll
  for (int g = 0; g < trees; ++g) strong_amplitudes(&instances[g], sp, strong_b, state, amplitudes);
  const int n = sp->node_count, full = n - n % FW_WALK_BLOCK;
  for (int first = 0; first < full; first += FW_WALK_BLOCK)
    deform_strong_block(trees, FW_WALK_BLOCK, first, instances, sp, walk, strong_v, strong_w, rest_elements,
                        amplitudes, displacements);
  if (full < n)
    deform_strong_block(trees, n - full, full, instances, sp, walk, strong_v, strong_w, rest_elements,
                        amplitudes, displacements);
}

/* One group of FW_STRONG_TREES consecutive instances per loop iteration: together when they share a
 * species, else one by one. Either way a tree's nodes see the same operations in the same order, so its
 * bits do not depend on its neighbours. `amplitudes` (2 floats an instance-mode) is this kernel's scratch. */
__kernel void tree_deform_strong(const int instance_count, __global const FwTreeInstance* instances,
                                 __global const FwSpecies* species, __global const int* walk,
                                 __global const float* strong_v, __global const float* strong_w,
                                 __global const float* strong_b, __global const float* rest_elements,
                                 __global const float* state, __global float* amplitudes,
                                 __global float* displacements) {
  const int groups = (instance_count + FW_STRONG_TREES - 1) / FW_STRONG_TREES;
  FW_FLAT_FOR(group, groups) {
    const int first = FW_STRONG_TREES * (int)group;
    const int count = min(FW_STRONG_TREES, instance_count - first);
    FwTreeInstance trees[FW_STRONG_TREES];
    bool shared = count == FW_STRONG_TREES;
    for (int g = 0; g < count; ++g) {
      trees[g] = instances[first + g];
      shared = shared && trees[g].species == trees[0].species;
    }
    if (shared) {
      const FwSpecies sp = species[trees[0].species];
      deform_strong_trees(FW_STRONG_TREES, trees, &sp, walk, strong_v, strong_w, strong_b, rest_elements,
                          state, amplitudes, displacements);
    } else {
      for (int g = 0; g < count; ++g) {
        const FwSpecies sp = species[trees[g].species];
        deform_strong_trees(1, &trees[g], &sp, walk, strong_v, strong_w, strong_b, rest_elements, state,
                            amplitudes, displacements);
      }
    }
  }
}
