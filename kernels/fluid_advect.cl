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
 * layer; the same rules as fluid/ReferenceStages.cpp sample(). Positions are the domain's: on a rank's block
 * (whose periodic axes are never cut ones) they include its offset, so that the fraction is the float a whole
 * grid computes, and only the index comes back into the block's arrays (docs/parallel.md). */
FW_INLINE void lane_coordinate(const FwGrid* g, int c, int a, lanef p, lanei* i0, lanef* fraction) {
  const int offset = a == 0 ? g->ox : (a == 1 ? g->oy : 0);
  const int wrap = a < 2 ? g->wrap[a] : 0;
  lanef q;
  lanei unwrap = (lanei)(0);
  if (g->bc[2 * a] == FW_BC_PERIODIC || wrap > 0) {
    /* Wrapped by the domain's period (a block on a cut periodic axis too: the float p + n rounds otherwise
     * than p), and the index then taken back beside the cells where the padded copy still holds it: a face n
     * of the staggered axis is read as its twin face 0 (they differ between boundary passes), as a block,
     * which holds only one of the two, must read it. A back-trace of more than the ghost layers stays
     * wrapped. */
    const int period = wrap > 0 ? wrap : axis_cells(g, a);
    const float n = (float)period;
    const lanei below = p < 0.0f, above = p >= n;
    p = select(p, p + n, below);
    p = select(p, p - n, above);
    unwrap = select(unwrap, (lanei)(-period), below);
    unwrap = select(unwrap, (lanei)(period), above);
    q = clamp(p, 0.0f, n) - face_offset(c, a);
  } else {
    q = clamp(p - face_offset(c, a), (float)(offset - 1), (float)(offset + face_extent(g, c, a)));
  }
  const lanef fl = floor(q);
  const lanei wrapped = convert_lanei(fl) - offset, back = wrapped + unwrap;
  const lanei inside = back >= -FW_PAD && back + 1 < face_extent(g, c, a) + FW_PAD;
  *i0 = select(wrapped, back, inside);
  *fraction = q - fl;
}

/* The eight interpolation corners of component c's padded copy qp around positions (X, Y, Z) (cell_corners'
 * order), and the fractions within their cells. */
FW_INLINE void interpolation_corners(const FwGrid* g, __global const float* qp, int c, lanef X, lanef Y,
                                     lanef Z, lanef v[8], lanef* fx, lanef* fy, lanef* fz) {
  lanei i0, j0, k0;
  lane_coordinate(g, c, 0, X, &i0, fx);
  lane_coordinate(g, c, 1, Y, &j0, fy);
  lane_coordinate(g, c, 2, Z, &k0, fz);
  const int sy = padded_extent(g, c, 0);
  cell_corners(qp, i0 + FW_PAD, j0 + FW_PAD, k0 + FW_PAD, sy, sy * padded_extent(g, c, 1), v);
}

/* Trilinear interpolation of component c's padded copy qp at positions (X, Y, Z). */
FW_INLINE lanef sample_lanes(__global const float* qp, int c, lanef X, lanef Y, lanef Z, const FwGrid* g) {
  lanef fx, fy, fz, v[8];
  interpolation_corners(g, qp, c, X, Y, Z, v, &fx, &fy, &fz);
  return trilinear(v, fx, fy, fz);
}

/* Component a (a != c) at the faces `at` (padded indices of component a at the same (i,j,k)) of component c:
 * the mean of its four nearest faces, which is trilinear interpolation at that point (fractions of one half
 * on axes a and c, zero on the third). */
FW_INLINE lanef cross_component(const FwGrid* g, __global const float* ap, int a, int c, lanei at,
                                int valid) {
  const int step_c = padded_stride(g, a, c), step_a = padded_stride(g, a, a);
  return 0.25f * ((row_lanes(ap, at - step_c, valid) + row_lanes(ap, at, valid)) +
                  (row_lanes(ap, at - step_c + step_a, valid) + row_lanes(ap, at + step_a, valid)));
}

/* Back-traced positions of faces (i, j, k) of component c through the padded velocity over dt (explicit
 * midpoint; negative dt traces forward). The first stage reads the velocity at the faces themselves. */
FW_INLINE void backtrace_lanes(const FwGrid* g, int c, lanei i, int valid, int j, int k, float dt,
                               __global const float* up, __global const float* vp, __global const float* wp,
                               lanef* X, lanef* Y, lanef* Z) {
  /* The domain's positions (lane_coordinate). */
  const lanef Px = convert_lanef(i + g->ox) + face_offset(c, 0);
  const lanef Py = (lanef)((float)(j + g->oy) + face_offset(c, 1));
  const lanef Pz = (lanef)((float)k + face_offset(c, 2));
  const float scale = dt / g->h; /* m/s -> cells */
  const lanei at_u = lane_padded_index(g, 0, i, j, k), at_v = lane_padded_index(g, 1, i, j, k),
              at_w = lane_padded_index(g, 2, i, j, k);
  const lanef Vu = c == 0 ? row_lanes(up, at_u, valid) : cross_component(g, up, 0, c, at_u, valid);
  const lanef Vv = c == 1 ? row_lanes(vp, at_v, valid) : cross_component(g, vp, 1, c, at_v, valid);
  const lanef Vw = c == 2 ? row_lanes(wp, at_w, valid) : cross_component(g, wp, 2, c, at_w, valid);
  const lanef Mx = Px - 0.5f * scale * Vu, My = Py - 0.5f * scale * Vv, Mz = Pz - 0.5f * scale * Vw;
  *X = Px - scale * sample_lanes(up, 0, Mx, My, Mz, g);
  *Y = Py - scale * sample_lanes(vp, 1, Mx, My, Mz, g);
  *Z = Pz - scale * sample_lanes(wp, 2, Mx, My, Mz, g);
}

/* out = qp sampled at the back-traced position of each face (c is a literal in each kernel below, so the
 * compiler folds the component logic away). */
FW_INLINE void advect_lanes(const FwGrid g, const int c, const float dt, __global const float* up,
                            __global const float* vp, __global const float* wp, __global const float* qp,
                            __global float* out) {
  FW_LANE_SETUP(c)
  lanef X, Y, Z;
  backtrace_lanes(&g, c, i, valid, j, k, dt, up, vp, wp, &X, &Y, &Z);
  store_lane_span(out, face_index(&g, c, i0, j, k), skip, valid, sample_lanes(qp, c, X, Y, Z, &g));
}

/* out = forward + (q - back) / 2, unless that leaves the range of the eight values of q the forward step
 * interpolated between, where out = forward (no new extrema). qp is q's padded copy; out may alias back (a
 * face's lane reads back only at that face, and only the item that stores the face keeps its lane). */
FW_INLINE void maccormack_lanes(const FwGrid g, const int c, const float dt, __global const float* up,
                                __global const float* vp, __global const float* wp, __global const float* qp,
                                __global const float* forward, __global const float* back,
                                __global float* out) {
  FW_LANE_SETUP(c)
  lanef X, Y, Z;
  backtrace_lanes(&g, c, i, valid, j, k, dt, up, vp, wp, &X, &Y, &Z);
  lanef fx, fy, fz, v[8];
  interpolation_corners(&g, qp, c, X, Y, Z, v, &fx, &fy, &fz);
  const lanef lo = fmin(fmin(fmin(v[0], v[1]), fmin(v[2], v[3])), fmin(fmin(v[4], v[5]), fmin(v[6], v[7])));
  const lanef hi = fmax(fmax(fmax(v[0], v[1]), fmax(v[2], v[3])), fmax(fmax(v[4], v[5]), fmax(v[6], v[7])));
  const int first = face_index(&g, c, i0, j, k);
  const lanei at = (lanei)(first) + (i - (lanei)(i0));
  const lanef fwd = row_lanes(forward, at, valid);
  const lanef bwd = row_lanes(back, at, valid);
  const lanef q = row_lanes(qp, lane_padded_index(&g, c, i, j, k), valid);
  const lanef corrected = fwd + 0.5f * (q - bwd);
  store_lane_span(out, first, skip, valid, select(corrected, fwd, (corrected < lo) | (corrected > hi)));
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
