/* Wind load on the trees: the wind sampled at every instance's sample points and turned into modal forces
 * (DESIGN.md, "Numerics: Trees: Wind basis"). Reference: trees/ForestReference.cpp sample_wind,
 * modal_forces.
 *
 * Work mapping: one instance per loop iteration (FW_FLAT_FOR over instances). Sampling (S x 3 trilinear
 * interpolations of 8 faces each) costs more than the m dot products of length 3S that follow, so an
 * instance samples once and reuses the loads for all its modes, instead of every instance-mode sampling
 * again. On a CPU each work-item takes a contiguous block of instances, whose modes are contiguous too. */
#include "common.cl"

/* Component c of the MAC velocity at X (cell units, world = origin + h X): trilinear on the component's own
 * staggered lattice, the position clamped to that lattice (constant beyond the outermost faces). */
FW_INLINE float tree_sample_component(const FwGrid* g, __global const float* q, int c, const float X[3]) {
  int lo[3], hi[3];
  float t[3];
  for (int a = 0; a < 3; ++a) {
    const int extent = face_extent(g, c, a);
    const float x = clamp(X[a] - face_offset(c, a), 0.0f, (float)(extent - 1));
    lo[a] = min((int)x, extent - 1);
    hi[a] = min(lo[a] + 1, extent - 1);
    t[a] = x - (float)lo[a];
  }
  const float c00 =
      mix(q[face_index(g, c, lo[0], lo[1], lo[2])], q[face_index(g, c, hi[0], lo[1], lo[2])], t[0]);
  const float c10 =
      mix(q[face_index(g, c, lo[0], hi[1], lo[2])], q[face_index(g, c, hi[0], hi[1], lo[2])], t[0]);
  const float c01 =
      mix(q[face_index(g, c, lo[0], lo[1], hi[2])], q[face_index(g, c, hi[0], lo[1], hi[2])], t[0]);
  const float c11 =
      mix(q[face_index(g, c, lo[0], hi[1], hi[2])], q[face_index(g, c, hi[0], hi[1], hi[2])], t[0]);
  return mix(mix(c00, c10, t[1]), mix(c01, c11, t[1]), t[2]);
}

/* For every instance: sampled_wind (3 floats per flat sample, m/s, world frame) and
 * forces[mode_offset + i] = sum_s |v_s| v_s . (s^1/2 R p_i^s)  (N / kg^1/2). */
__kernel void tree_wind_load(const FwGrid g, const int instance_count,
                             __global const FwTreeInstance* instances, __global const FwSpecies* species,
                             __global const float* projections, __global const float* sample_points,
                             __global const float* u, __global const float* v, __global const float* w,
                             __global float* sampled_wind, __global float* forces) {
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw;
    const float root_scale = sqrt(tree.scale);
    /* s^1/2 R^T (|v| v) per sample: the load in the skeleton frame, so that p_i^s needs no rotation. */
    float load[3 * FW_MAX_TREE_SAMPLES];
    for (int s = 0; s < sp.sample_count; ++s) {
      __global const float* p = sample_points + sp.sample_point_offset + 3 * s;
      const float world[3] = {tree.position[0] + tree.scale * (cs * p[0] - sn * p[1]),
                              tree.position[1] + tree.scale * (sn * p[0] + cs * p[1]),
                              tree.position[2] + tree.scale * p[2]};
      float X[3];
      for (int a = 0; a < 3; ++a) X[a] = (world[a] - g.origin[a]) / g.h;
      const float vx = tree_sample_component(&g, u, 0, X);
      const float vy = tree_sample_component(&g, v, 1, X);
      const float vz = tree_sample_component(&g, w, 2, X);
      __global float* out = sampled_wind + 3 * (tree.sample_offset + s);
      out[0] = vx;
      out[1] = vy;
      out[2] = vz;
      const float speed = sqrt(vx * vx + vy * vy + vz * vz) * root_scale;
      load[3 * s] = speed * (cs * vx + sn * vy);
      load[3 * s + 1] = speed * (-sn * vx + cs * vy);
      load[3 * s + 2] = speed * vz;
    }
    const int row = 3 * sp.sample_count;
    for (int i = 0; i < sp.mode_count; ++i) {
      __global const float* p = projections + sp.projection_offset + i * row;
      float f = 0.0f;
      for (int r = 0; r < row; ++r) f += load[r] * p[r];
      forces[tree.mode_offset + i] = f;
    }
  }
}
