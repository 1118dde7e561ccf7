/* Advection of the face velocities: semi-Lagrangian RK2 with trilinear interpolation, and the correction
 * pass of clamped MacCormack. Reference: fluid/ReferenceStages.cpp advect_semi_lagrangian, advect_maccormack.
 *
 * Every input is a padded copy (kernels/fluid_ghosts.cl), so interpolation has no boundary logic. Each
 * work-item advects FW_LANES consecutive faces of one x-row at once in vector arithmetic: the coordinate and
 * weight computations run as SIMD on CPUs, and only the loads of the interpolation corners stay scalar
 * (gathers). Global range: (ceil(extent_x / FW_LANES), extent_y, extent_z) of the component's faces.
 */
#include "common.cl"
#include "lanes.cl"

/* Lower interpolation index and fraction along axis a of component c, for positions p (cell units):
 * periodic axes wrap p into [0, n) (a back-trace moves less than one period), other axes clamp to the ghost
 * layer; the same rules as fluid/ReferenceStages.cpp sample(). */
FW_INLINE void lane_coordinate(const FwGrid* g, int c, int a, lanef p, lanei* i0, lanef* fraction) {
  const float n = (float)axis_cells(g, a);
  lanef q;
  if (g->bc[2 * a] == FW_BC_PERIODIC) {
    p = select(p, p + n, p < 0.0f);
    p = select(p, p - n, p >= n);
    q = clamp(p, 0.0f, n) - face_offset(c, a);
  } else {
    q = clamp(p - face_offset(c, a), -1.0f, (float)face_extent(g, c, a));
  }
  /* q >= -1, so truncating q + 4 gives floor(q) + 4. */
  const lanei fl = convert_lanei(q + 4.0f) - 4;
  *i0 = fl;
  *fraction = q - convert_lanef(fl);
}

/* Trilinear interpolation of component c's padded copy qp at positions (X, Y, Z). */
FW_INLINE lanef sample_lanes(__global const float* qp, int c, lanef X, lanef Y, lanef Z, const FwGrid* g) {
  lanei i0, j0, k0;
  lanef fx, fy, fz;
  lane_coordinate(g, c, 0, X, &i0, &fx);
  lane_coordinate(g, c, 1, Y, &j0, &fy);
  lane_coordinate(g, c, 2, Z, &k0, &fz);
  const int sy = padded_extent(g, c, 0);
  const int sz = sy * padded_extent(g, c, 1);
  const lanei base = (i0 + FW_PAD) + sy * (j0 + FW_PAD) + sz * (k0 + FW_PAD);
  const lanef v000 = gather(qp, base), v100 = gather(qp, base + 1);
  const lanef v010 = gather(qp, base + sy), v110 = gather(qp, base + sy + 1);
  const lanef v001 = gather(qp, base + sz), v101 = gather(qp, base + sz + 1);
  const lanef v011 = gather(qp, base + sz + sy), v111 = gather(qp, base + sz + sy + 1);
  const lanef x00 = v000 + fx * (v100 - v000);
  const lanef x10 = v010 + fx * (v110 - v010);
  const lanef x01 = v001 + fx * (v101 - v001);
  const lanef x11 = v011 + fx * (v111 - v011);
  const lanef y0 = x00 + fy * (x10 - x00);
  const lanef y1 = x01 + fy * (x11 - x01);
  return y0 + fz * (y1 - y0);
}

/* Stride of component a's padded copy along axis `axis`. */
FW_INLINE int padded_stride(const FwGrid* g, int a, int axis) {
  return axis == 0 ? 1
                   : (axis == 1 ? padded_extent(g, a, 0) : padded_extent(g, a, 0) * padded_extent(g, a, 1));
}

/* Component a (a != c) at the faces `at` (padded indices of component a at the same (i,j,k)) of component c:
 * the mean of its four nearest faces, which is trilinear interpolation at that point (fractions of one half
 * on axes a and c, zero on the third). */
FW_INLINE lanef cross_component(const FwGrid* g, __global const float* ap, int a, int c, lanei at) {
  const int step_c = padded_stride(g, a, c), step_a = padded_stride(g, a, a);
  return 0.25f * ((gather(ap, at - step_c) + gather(ap, at)) +
                  (gather(ap, at - step_c + step_a) + gather(ap, at + step_a)));
}

/* The lanes of one work-item: faces i = i0 .. i0 + 7 of row (j, k), clamped to the row (tail lanes repeat the
 * last face and are not stored). Returns the padded index of component a at those faces. */
FW_INLINE lanei lane_padded_index(const FwGrid* g, int a, lanei i, int j, int k) {
  return (i + FW_PAD) + padded_extent(g, a, 0) * ((j + FW_PAD) + padded_extent(g, a, 1) * (k + FW_PAD));
}

/* Back-traced positions of faces (i, j, k) of component c through the padded velocity over dt (explicit
 * midpoint; negative dt traces forward). The first stage reads the velocity at the faces themselves. */
FW_INLINE void backtrace_lanes(const FwGrid* g, int c, lanei i, int j, int k, float dt,
                               __global const float* up, __global const float* vp, __global const float* wp,
                               lanef* X, lanef* Y, lanef* Z) {
  const lanef Px = convert_lanef(i) + face_offset(c, 0);
  const lanef Py = (lanef)((float)j + face_offset(c, 1));
  const lanef Pz = (lanef)((float)k + face_offset(c, 2));
  const float scale = dt / g->h; /* m/s -> cells */
  const lanef Vu = c == 0 ? gather(up, lane_padded_index(g, 0, i, j, k))
                          : cross_component(g, up, 0, c, lane_padded_index(g, 0, i, j, k));
  const lanef Vv = c == 1 ? gather(vp, lane_padded_index(g, 1, i, j, k))
                          : cross_component(g, vp, 1, c, lane_padded_index(g, 1, i, j, k));
  const lanef Vw = c == 2 ? gather(wp, lane_padded_index(g, 2, i, j, k))
                          : cross_component(g, wp, 2, c, lane_padded_index(g, 2, i, j, k));
  const lanef Mx = Px - 0.5f * scale * Vu, My = Py - 0.5f * scale * Vv, Mz = Pz - 0.5f * scale * Vw;
  *X = Px - scale * sample_lanes(up, 0, Mx, My, Mz, g);
  *Y = Py - scale * sample_lanes(vp, 1, Mx, My, Mz, g);
  *Z = Pz - scale * sample_lanes(wp, 2, Mx, My, Mz, g);
}

/* This work-item's faces: first index, count inside the row, and the clamped lane indices. */
#define FW_LANE_SETUP(c)                                \
  const int j = get_global_id(1), k = get_global_id(2); \
  const int ex = face_extent(&g, c, 0);                 \
  const int i0 = (int)get_global_id(0) * FW_LANES;      \
  if (i0 >= ex) return;                                 \
  const int valid = min(FW_LANES, ex - i0);             \
  const lanei i = min((lanei)(i0) + FW_LANE_OFFSETS, (lanei)(ex - 1));

/* out = qp sampled at the back-traced position of each face (c is a literal in each kernel below, so the
 * compiler folds the component logic away). */
FW_INLINE void advect_lanes(const FwGrid g, const int c, const float dt, __global const float* up,
                            __global const float* vp, __global const float* wp, __global const float* qp,
                            __global float* out) {
  FW_LANE_SETUP(c)
  lanef X, Y, Z;
  backtrace_lanes(&g, c, i, j, k, dt, up, vp, wp, &X, &Y, &Z);
  store_lanes(out, face_index(&g, c, i0, j, k), valid, sample_lanes(qp, c, X, Y, Z, &g));
}

/* out = forward + (q - back) / 2, unless that leaves the range of the eight values of q the forward step
 * interpolated between, where out = forward (no new extrema). qp is q's padded copy; out may alias back. */
FW_INLINE void maccormack_lanes(const FwGrid g, const int c, const float dt, __global const float* up,
                                __global const float* vp, __global const float* wp, __global const float* qp,
                                __global const float* forward, __global const float* back,
                                __global float* out) {
  FW_LANE_SETUP(c)
  lanef X, Y, Z;
  backtrace_lanes(&g, c, i, j, k, dt, up, vp, wp, &X, &Y, &Z);
  lanei a0, b0, c0;
  lanef fx, fy, fz;
  lane_coordinate(&g, c, 0, X, &a0, &fx);
  lane_coordinate(&g, c, 1, Y, &b0, &fy);
  lane_coordinate(&g, c, 2, Z, &c0, &fz);
  const int sy = padded_extent(&g, c, 0);
  const int sz = sy * padded_extent(&g, c, 1);
  const lanei base = (a0 + FW_PAD) + sy * (b0 + FW_PAD) + sz * (c0 + FW_PAD);
  const lanef v000 = gather(qp, base), v100 = gather(qp, base + 1);
  const lanef v010 = gather(qp, base + sy), v110 = gather(qp, base + sy + 1);
  const lanef v001 = gather(qp, base + sz), v101 = gather(qp, base + sz + 1);
  const lanef v011 = gather(qp, base + sz + sy), v111 = gather(qp, base + sz + sy + 1);
  const lanef lo = fmin(fmin(fmin(v000, v100), fmin(v010, v110)), fmin(fmin(v001, v101), fmin(v011, v111)));
  const lanef hi = fmax(fmax(fmax(v000, v100), fmax(v010, v110)), fmax(fmax(v001, v101), fmax(v011, v111)));
  const int first = face_index(&g, c, i0, j, k);
  const lanef fwd = gather(forward, (lanei)(first) + (i - (lanei)(i0)));
  const lanef bwd = gather(back, (lanei)(first) + (i - (lanei)(i0)));
  const lanef q = gather(qp, lane_padded_index(&g, c, i, j, k));
  const lanef corrected = fwd + 0.5f * (q - bwd);
  store_lanes(out, first, valid, select(corrected, fwd, (corrected < lo) | (corrected > hi)));
}

__kernel void advect_u(const FwGrid g, const float dt, __global const float* up, __global const float* vp,
                       __global const float* wp, __global const float* qp, __global float* out) {
  advect_lanes(g, 0, dt, up, vp, wp, qp, out);
}
__kernel void advect_v(const FwGrid g, const float dt, __global const float* up, __global const float* vp,
                       __global const float* wp, __global const float* qp, __global float* out) {
  advect_lanes(g, 1, dt, up, vp, wp, qp, out);
}
__kernel void advect_w(const FwGrid g, const float dt, __global const float* up, __global const float* vp,
                       __global const float* wp, __global const float* qp, __global float* out) {
  advect_lanes(g, 2, dt, up, vp, wp, qp, out);
}
__kernel void maccormack_correct_u(const FwGrid g, const float dt, __global const float* up,
                                   __global const float* vp, __global const float* wp,
                                   __global const float* qp, __global const float* forward,
                                   __global const float* back, __global float* out) {
  maccormack_lanes(g, 0, dt, up, vp, wp, qp, forward, back, out);
}
__kernel void maccormack_correct_v(const FwGrid g, const float dt, __global const float* up,
                                   __global const float* vp, __global const float* wp,
                                   __global const float* qp, __global const float* forward,
                                   __global const float* back, __global float* out) {
  maccormack_lanes(g, 1, dt, up, vp, wp, qp, forward, back, out);
}
__kernel void maccormack_correct_w(const FwGrid g, const float dt, __global const float* up,
                                   __global const float* vp, __global const float* wp,
                                   __global const float* qp, __global const float* forward,
                                   __global const float* back, __global float* out) {
  maccormack_lanes(g, 2, dt, up, vp, wp, qp, forward, back, out);
}
