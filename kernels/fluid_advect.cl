/* Advection of the face velocities: semi-Lagrangian RK2 with trilinear interpolation, and the two extra
 * passes of clamped MacCormack. Reference: fluid/ReferenceStages.cpp advect_semi_lagrangian/maccormack. */
#include "common.cl"

/* out = q (component c) sampled at the back-traced position of each face, tracing through (u, v, w) over
 * dt seconds (negative dt traces forward). Global range: rows over the component's faces. */
__kernel void advect_component(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                               const float dt, __global const float* u, __global const float* v,
                               __global const float* w, __global const float* q, __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float3 B = backtrace_face(c, i, j, k, dt, u, v, w, &g, &s, profile);
    out[face_index(&g, c, i, j, k)] = sample_face(q, c, B.x, B.y, B.z, &g, &s, profile);
  }
}

/* MacCormack correction: out = forward + (q - back) / 2, unless that leaves the range of the eight values
 * of q the forward step interpolated between, where out = forward (keeps the scheme free of new extrema). */
__kernel void maccormack_correct(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                                 __global const float* u, __global const float* v, __global const float* w,
                                 __global const float* q, __global const float* forward,
                                 __global const float* back, __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float3 B = backtrace_face(c, i, j, k, s.dt, u, v, w, &g, &s, profile);
    int i0, j0, k0;
    float fx, fy, fz;
    face_coordinate(&g, c, 0, B.x, &i0, &fx);
    face_coordinate(&g, c, 1, B.y, &j0, &fy);
    face_coordinate(&g, c, 2, B.z, &k0, &fz);
    float lo = INFINITY, hi = -INFINITY;
    for (int d = 0; d < 8; ++d) {
      const float val =
          fetch_face(q, c, i0 + (d & 1), j0 + ((d >> 1) & 1), k0 + ((d >> 2) & 1), &g, &s, profile);
      lo = fmin(lo, val);
      hi = fmax(hi, val);
    }
    const int id = face_index(&g, c, i, j, k);
    const float fwd = forward[id];
    const float corrected = fwd + 0.5f * (q[id] - back[id]);
    out[id] = (corrected < lo || corrected > hi) ? fwd : corrected;
  }
}
