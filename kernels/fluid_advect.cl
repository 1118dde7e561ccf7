/* Advection of the face velocities: semi-Lagrangian RK2 with trilinear interpolation, and the correction
 * pass of clamped MacCormack. Every input is a padded copy (kernels/fluid_ghosts.cl), so the inner loop has
 * no boundary logic. Reference: fluid/ReferenceStages.cpp advect_semi_lagrangian, advect_maccormack. */
#include "common.cl"

/* One face of component c: qp sampled at the face's back-traced position. */
FW_INLINE float advect_face(const FwGrid* g, const int c, const float dt, int i, int j, int k,
                            __global const float* up, __global const float* vp, __global const float* wp,
                            __global const float* qp) {
  const float3 B = backtrace_padded(c, i, j, k, dt, up, vp, wp, g);
  return sample_padded(qp, c, B.x, B.y, B.z, g);
}

/* MacCormack's value at one face: forward + (q - back) / 2, unless that leaves the range of the eight
 * values of q the forward step interpolated between, where it is the forward value (no new extrema). */
FW_INLINE float maccormack_face(const FwGrid* g, const int c, const float dt, int i, int j, int k,
                                __global const float* up, __global const float* vp, __global const float* wp,
                                __global const float* qp, float fwd, float back) {
  const float3 B = backtrace_padded(c, i, j, k, dt, up, vp, wp, g);
  int i0, j0, k0;
  float fx, fy, fz;
  face_coordinate(g, c, 0, B.x, &i0, &fx);
  face_coordinate(g, c, 1, B.y, &j0, &fy);
  face_coordinate(g, c, 2, B.z, &k0, &fz);
  const int sy = padded_extent(g, c, 0);
  const int sz = sy * padded_extent(g, c, 1);
  const int base = (i0 + FW_PAD) + sy * (j0 + FW_PAD) + sz * (k0 + FW_PAD);
  const float lo =
      fmin(fmin(fmin(qp[base], qp[base + 1]), fmin(qp[base + sy], qp[base + sy + 1])),
           fmin(fmin(qp[base + sz], qp[base + sz + 1]), fmin(qp[base + sz + sy], qp[base + sz + sy + 1])));
  const float hi =
      fmax(fmax(fmax(qp[base], qp[base + 1]), fmax(qp[base + sy], qp[base + sy + 1])),
           fmax(fmax(qp[base + sz], qp[base + sz + 1]), fmax(qp[base + sz + sy], qp[base + sz + sy + 1])));
  const float corrected = fwd + 0.5f * (qp[padded_index(g, c, i, j, k)] - back);
  return (corrected < lo || corrected > hi) ? fwd : corrected;
}

/* The kernels below exist once per component so that c is a constant the compiler folds away. With one
 * face per work-item (FW_ROW_CHUNK == 1, the host's choice for this file) the body is straight-line code,
 * which PoCL vectorises across work-items. Global range: rows over the component's faces. */
#if FW_ROW_CHUNK == 1
#define FW_FOR_FACE(i, extent)         \
  const int i = (int)get_global_id(0); \
  if (i < (extent))
#else
#define FW_FOR_FACE(i, extent) for (int i = FW_ROW_BEGIN; i < FW_ROW_END(extent); ++i)
#endif

/* out = qp sampled at the back-traced position of each face, tracing through the padded velocity
 * (up, vp, wp) over dt seconds (negative dt traces forward). */
#define FW_ADVECT_KERNEL(name, c)                                                                        \
  __kernel void name(const FwGrid g, const float dt, __global const float* up, __global const float* vp, \
                     __global const float* wp, __global const float* qp, __global float* out) {          \
    const int j = get_global_id(1), k = get_global_id(2);                                                \
    FW_FOR_FACE(i, face_extent(&g, c, 0)) {                                                              \
      out[face_index(&g, c, i, j, k)] = advect_face(&g, c, dt, i, j, k, up, vp, wp, qp);                 \
    }                                                                                                    \
  }

/* out = MacCormack's corrected value; qp is q's padded copy, out may alias back. */
#define FW_MACCORMACK_KERNEL(name, c)                                                                    \
  __kernel void name(const FwGrid g, const float dt, __global const float* up, __global const float* vp, \
                     __global const float* wp, __global const float* qp, __global const float* forward,  \
                     __global const float* back, __global float* out) {                                  \
    const int j = get_global_id(1), k = get_global_id(2);                                                \
    FW_FOR_FACE(i, face_extent(&g, c, 0)) {                                                              \
      const int id = face_index(&g, c, i, j, k);                                                         \
      out[id] = maccormack_face(&g, c, dt, i, j, k, up, vp, wp, qp, forward[id], back[id]);              \
    }                                                                                                    \
  }

FW_ADVECT_KERNEL(advect_u, 0)
FW_ADVECT_KERNEL(advect_v, 1)
FW_ADVECT_KERNEL(advect_w, 2)
FW_MACCORMACK_KERNEL(maccormack_correct_u, 0)
FW_MACCORMACK_KERNEL(maccormack_correct_v, 1)
FW_MACCORMACK_KERNEL(maccormack_correct_w, 2)
