/* Advection of the face velocities: semi-Lagrangian RK2 with trilinear interpolation, and the correction
 * pass of clamped MacCormack. Every input is a padded copy (kernels/fluid_ghosts.cl), so the inner loop has
 * no boundary logic. Reference: fluid/ReferenceStages.cpp advect_semi_lagrangian, advect_maccormack. */
#include "common.cl"

/* out = qp (component c) sampled at the back-traced position of each face, tracing through the padded
 * velocity (up, vp, wp) over dt seconds (negative dt traces forward). Rows over the component's faces. */
__kernel void advect_component(const FwGrid g, const int c, const float dt, __global const float* up,
                               __global const float* vp, __global const float* wp, __global const float* qp,
                               __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float3 B = backtrace_padded(c, i, j, k, dt, up, vp, wp, &g);
    out[face_index(&g, c, i, j, k)] = sample_padded(qp, c, B.x, B.y, B.z, &g);
  }
}

/* MacCormack correction: out = forward + (q - back) / 2, unless that leaves the range of the eight values
 * of q the forward step interpolated between, where out = forward (keeps the scheme free of new extrema).
 * qp is q's padded copy; out may alias back. */
__kernel void maccormack_correct(const FwGrid g, const int c, const float dt, __global const float* up,
                                 __global const float* vp, __global const float* wp, __global const float* qp,
                                 __global const float* forward, __global const float* back, __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  const int sy = padded_extent(&g, c, 0);
  const int sz = sy * padded_extent(&g, c, 1);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float3 B = backtrace_padded(c, i, j, k, dt, up, vp, wp, &g);
    int i0, j0, k0;
    float fx, fy, fz;
    face_coordinate(&g, c, 0, B.x, &i0, &fx);
    face_coordinate(&g, c, 1, B.y, &j0, &fy);
    face_coordinate(&g, c, 2, B.z, &k0, &fz);
    const int base = (i0 + FW_PAD) + sy * (j0 + FW_PAD) + sz * (k0 + FW_PAD);
    const float lo = fmin(fmin(fmin(qp[base], qp[base + 1]), fmin(qp[base + sy], qp[base + sy + 1])),
                          fmin(fmin(qp[base + sz], qp[base + sz + 1]), fmin(qp[base + sz + sy], qp[base + sz + sy + 1])));
    const float hi = fmax(fmax(fmax(qp[base], qp[base + 1]), fmax(qp[base + sy], qp[base + sy + 1])),
                          fmax(fmax(qp[base + sz], qp[base + sz + 1]), fmax(qp[base + sz + sy], qp[base + sz + sy + 1])));
    const int id = face_index(&g, c, i, j, k);
    const float fwd = forward[id];
    const float corrected = fwd + 0.5f * (qp[padded_index(&g, c, i, j, k)] - back[id]);
    out[id] = (corrected < lo || corrected > hi) ? fwd : corrected;
  }
}
