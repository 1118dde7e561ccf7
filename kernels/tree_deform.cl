/* Skeleton deformation for output frames: u_node = s^-3/2 R sum_i phi_node_i q_i per instance node, world
 * frame, m (Diener 2008, eq. 10). Reference: trees/ForestReference.cpp displacements.
 *
 * Work mapping: one block of 8 consecutive flat nodes per loop iteration (FW_FLAT_FOR over the blocks). Node
 * shapes are stored mode-major (trees/Forest.hpp), so for one mode the x y z of 8 consecutive nodes are 24
 * contiguous floats: three vload8 and three float8 multiply-adds with the same q_i. Eight nodes in flight
 * keep the FMA pipelines busy where one node's three sums would wait on each other's latency. A block whose
 * nodes belong to two instances (at most one per instance boundary) takes the per-node path. */
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
          x += phi[i * row] * qi;
          y += phi[i * row + 1] * qi;
          z += phi[i * row + 2] * qi;
        }
        store_displacement(displacements, (size_t)n, &tree, x, y, z);
      }
    }
  }
}
