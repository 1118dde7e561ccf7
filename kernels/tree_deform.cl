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
 * The strong-wind correction (trees/StrongWindCorrection.hpp) is Diener's fitted quadratic correction (per
 * node, parallel: tree_deform_strong), followed by a projection that restores each element's rest length
 * exactly (sequential along each tree, output frames only: tree_restore_lengths, enqueued right after it).
 *
 * tree_deform_strong: Diener's part (2008, section 5.2),
 * u_node = s R sum_i (q~_i v_node_i + q~_i^2 w_node_i), q~_i = atan(b_i s^-5/2 q_i) / b_i: v and w are fitted
 * on the species at scale 1, whose modal coordinate is s^-5/2 times the instance's and whose displacement
 * is 1/s of it. Same work mapping; v and w share the layout (and FwSpecies.shape_offset) of the node shapes,
 * b the per-mode offset of omega. q~ is computed once per instance-mode beforehand (tree_strong_amplitudes,
 * into a buffer laid out as the modal forces), so that the arctan is paid once per mode, not per node.
 *
 * tree_restore_lengths: the projection, in place on Diener's displacements. Parents before children, each
 * node goes to its parent's corrected position plus the rest length times the unit vector of Diener's
 * element (node minus parent); the root stays. A node depends on all its ancestors, hence one instance per
 * loop iteration (FW_FLAT_FOR over the instances) walking the species' packed walk (trees/Forest.hpp,
 * ForestPacking::walk and rest_elements, from FwSpecies.skeleton_offset).
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

/* q~ = atan(b q) / b, and q for b = 0 (a mode fitted without any reparametrisation). */
FW_INLINE float strong_wind_amplitude(const float q, const float b) {
  return b > 0.0f ? atan(b * q) / b : q;
}

/* s R (x, y, z): the species' corrected displacement turned and grown into the instance's. */
FW_INLINE void store_grown_displacement(__global float* displacements, const size_t n,
                                        const FwTreeInstance* tree, const float x, const float y,
                                        const float z) {
  const float s = tree->scale, cs = tree->cos_yaw, sn = tree->sin_yaw;
  displacements[3 * n] = s * (cs * x - sn * y);
  displacements[3 * n + 1] = s * (sn * x + cs * y);
  displacements[3 * n + 2] = s * z;
}

/* q~_j = atan(b s^-5/2 q_j) / b of every instance-mode j: the species' reparametrised coordinate, read by
 * tree_deform_strong. One instance-mode per iteration. */
__kernel void tree_strong_amplitudes(const int total_modes, __global const int* mode_instance,
                                     __global const FwTreeInstance* instances,
                                     __global const FwSpecies* species, __global const float* strong_b,
                                     __global const float* state, __global float* amplitudes) {
  FW_FLAT_FOR(j, total_modes) {
    const FwTreeInstance tree = instances[mode_instance[j]];
    const int i = (int)j - tree.mode_offset;
    /* s^-5/2: the species' modal coordinate of the instance's. */
    const float to_species = 1.0f / (tree.scale * tree.scale * sqrt(tree.scale));
    amplitudes[j] =
        strong_wind_amplitude(to_species * state[2 * j], strong_b[species[tree.species].modal_offset + i]);
  }
}

__kernel void tree_deform_strong(const int total_nodes, __global const int* node_instance,
                                 __global const FwTreeInstance* instances, __global const FwSpecies* species,
                                 __global const float* strong_v, __global const float* strong_w,
                                 __global const float* amplitudes, __global float* displacements) {
  const int blocks = (total_nodes + 7) / 8;
  FW_FLAT_FOR(b, blocks) {
    const int first = 8 * (int)b;
    const int count = min(8, total_nodes - first);
    const int k = node_instance[first];
    if (count == 8 && node_instance[first + 7] == k) {
      const FwTreeInstance tree = instances[k];
      const FwSpecies sp = species[tree.species];
      const int m = sp.mode_count, row = 3 * sp.node_count;
      const int offset = sp.shape_offset + 3 * (first - tree.node_offset);
      __global const float* v = strong_v + offset;
      __global const float* w = strong_w + offset;
      __global const float* t = amplitudes + tree.mode_offset;
      float8 a0 = (float8)(0.0f), a1 = (float8)(0.0f), a2 = (float8)(0.0f);
      for (int i = 0; i < m; ++i) {
        const float8 ti = (float8)(t[i]), t2 = ti * ti;
        __global const float* pv = v + i * row;
        __global const float* pw = w + i * row;
        a0 = fma(vload8(0, pv), ti, fma(vload8(0, pw), t2, a0));
        a1 = fma(vload8(1, pv), ti, fma(vload8(1, pw), t2, a1));
        a2 = fma(vload8(2, pv), ti, fma(vload8(2, pw), t2, a2));
      }
      float sum[24];
      vstore8(a0, 0, sum);
      vstore8(a1, 1, sum);
      vstore8(a2, 2, sum);
      for (int j = 0; j < 8; ++j) {
        store_grown_displacement(displacements, (size_t)(first + j), &tree, sum[3 * j], sum[3 * j + 1],
                                 sum[3 * j + 2]);
      }
    } else {
      for (int n = first; n < first + count; ++n) {
        const FwTreeInstance tree = instances[node_instance[n]];
        const FwSpecies sp = species[tree.species];
        const int m = sp.mode_count, row = 3 * sp.node_count;
        const int offset = sp.shape_offset + 3 * (n - tree.node_offset);
        __global const float* t = amplitudes + tree.mode_offset;
        float x = 0.0f, y = 0.0f, z = 0.0f;
        for (int i = 0; i < m; ++i) {
          const float ti = t[i], t2 = ti * ti;
          const int at = offset + i * row;
          x = fma(strong_v[at], ti, fma(strong_w[at], t2, x));
          y = fma(strong_v[at + 1], ti, fma(strong_w[at + 1], t2, y));
          z = fma(strong_v[at + 2], ti, fma(strong_w[at + 2], t2, z));
        }
        store_grown_displacement(displacements, (size_t)n, &tree, x, y, z);
      }
    }
  }
}

/* trees/Skeleton.hpp kMinElementLength, m: an element whose Diener image is shorter has no direction of its
 * own and keeps its rest direction, as in the reference walk. */
#define FW_MIN_ELEMENT_LENGTH 1e-9f

/* In the world frame, as displacements: with x_n = position + s R p_n the rest positions and u_n Diener's
 * displacements, x'_c = x'_p + L unit(x_c + u_c - x_p - u_p), L = s |p_c - p_p|, and u'_c = x'_c - x_c. The
 * same written as u'_c = u'_p + (L unit(r + delta) - r), r = x_c - x_p = s R (p_c - p_p), delta = u_c - u_p,
 * never forms a world position, so that trees far from the origin lose no digits to it (float spacing at
 * 500 m is 3e-5 m). L unit(r + delta) - r = (L / |d|) delta - (2 r.delta + delta.delta) / (|d| (L + |d|)) r,
 * d = r + delta, avoids the cancellation of two nearly equal vectors at small delta, and with L = |r| as
 * rounded here a tree at rest stays exactly at rest (the reference walk: StrongWindCorrection.cpp).
 * In place, two sweeps: children before parents, each node's e_c = L unit(r + delta) - r replaces u_c while
 * its parent still holds Diener's u_p (the parent comes later in that order); then parents before children,
 * u'_c = u'_p + e_c. */
__kernel void tree_restore_lengths(const int instance_count, __global const FwTreeInstance* instances,
                                   __global const FwSpecies* species, __global const int* walk,
                                   __global const float* rest_elements, __global float* displacements) {
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const int n = sp.node_count;
    __global const int* steps = walk + 2 * sp.skeleton_offset;
    __global const float* rest = rest_elements + 3 * sp.skeleton_offset;
    __global float* u = displacements + 3 * (size_t)tree.node_offset;
    const float s = tree.scale, cs = tree.cos_yaw, sn = tree.sin_yaw;
    /* x'_root = x_root (Diener's root rows are zero already; the reference ignores them). */
    vstore3((float3)(0.0f), steps[0], u);
    for (int j = n - 1; j >= 1; --j) {
      const int2 step = vload2(j, steps); /* (node, parent) */
      const float3 e = vload3(j, rest);   /* p_c - p_p, skeleton frame */
      const float3 r = s * (float3)(cs * e.x - sn * e.y, sn * e.x + cs * e.y, e.z);
      const float3 delta = vload3(step.x, u) - vload3(step.y, u);
      const float rest_length = length(r), d_length = length(r + delta);
      /* An element whose Diener image has collapsed keeps its rest direction: no change. */
      float3 change = (float3)(0.0f);
      if (d_length >= FW_MIN_ELEMENT_LENGTH)
        change = (rest_length / d_length) * delta -
                 ((2.0f * dot(r, delta) + dot(delta, delta)) / (d_length * (rest_length + d_length))) * r;
      vstore3(change, step.x, u);
    }
    for (int j = 1; j < n; ++j) {
      const int2 step = vload2(j, steps);
      vstore3(vload3(step.y, u) + vload3(step.x, u), step.x, u);
    }
  }
}
