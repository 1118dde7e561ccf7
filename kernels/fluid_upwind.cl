/* One Runge-Kutta stage of flux-form upwind advection of the face velocities (solver.advection: upwind5):
 * out = base + coef_dt * R(stage), R the tendency -div(U q) of each component, with the fifth-, third- or
 * first-order interpolation of fluid/UpwindStencil.hpp (the formulas and where the order drops). Reference:
 * fluid/ReferenceStages.cpp upwind_stage.
 *
 * The stage velocity comes as padded copies (kernels/fluid_ghosts.cl: FW_PAD ghost layers by the boundary
 * rules), the base component and the result unpadded. Each work-item computes FW_LANES consecutive faces of
 * one x-row in vector arithmetic (kernels/lanes.cl FW_LANE_SETUP); every load is a row of the lanes, a
 * vector load on CPUs. A face computes both its fluxes along each axis: the lower one is its lower
 * neighbour's upper one, from the same values by the same operations, so the two agree to the bit and the
 * fluxes telescope (momentum is conserved). Global range: (ceil(extent_x / FW_LANES), extent_y, extent_z)
 * of the component's faces.
 */
#include "common.cl"
#include "lanes.cl"

/* Contraction into fused multiply-adds could differ between the two places a flux is computed. */
#pragma OPENCL FP_CONTRACT OFF

/* The flux U q through one side of a face's control volume: q from the values a .. f (q_m-2 .. q_m+3 along
 * the axis, the flux point between c and d) at the order of `order` (FW_UPWIND_*), upwind-biased by U. The
 * three interpolations are each a centred part minus |U| / U times an upwind correction. */
FW_INLINE lanef upwind_flux(lanef U, lanei order, lanef a, lanef b, lanef c, lanef d, lanef e, lanef f) {
  const lanef centred5 = (37.0f * (c + d) - 8.0f * (b + e) + (a + f)) / 60.0f;
  const lanef upwind5 = (10.0f * (d - c) - 5.0f * (e - b) + (f - a)) / 60.0f;
  const lanef centred3 = (7.0f * (c + d) - (b + e)) / 12.0f;
  const lanef upwind3 = (3.0f * (d - c) - (e - b)) / 12.0f;
  const lanef centred1 = 0.5f * (c + d), upwind1 = 0.5f * (d - c);
  const lanei fifth = order == FW_UPWIND_FIFTH, third = order == FW_UPWIND_THIRD;
  const lanef centred = select(select(centred1, centred3, third), centred5, fifth);
  const lanef upwind = select(select(upwind1, upwind3, third), upwind5, fifth);
  return U * centred - fabs(U) * upwind;
}

/* The packed orders (fluid/UpwindStencil.hpp) of the lanes' faces, from face index `first` on: a vector load
 * where every lane is valid, else the lanes past the row repeat its last face (FW_LANE_SETUP). */
FW_INLINE lanei order_lanes(__global const ushort* orders, int first, int valid) {
  if (valid == FW_LANES) return convert_lanei(lane_load(0, orders + first));
  ushort lanes[FW_LANES];
  for (int l = 0; l < FW_LANES; ++l) lanes[l] = orders[first + min(l, valid - 1)];
  return convert_lanei(lane_load(0, lanes));
}

/* Upper minus lower flux of component c's faces along axis a (c a literal below, so the compiler folds the
 * component logic away). qp: component c's padded copy, at: the lanes' padded indices in it; ap: component
 * a's padded copy, at_a: the lanes' padded indices in that one. */
FW_INLINE lanef flux_difference(const FwGrid* g, int c, int a, __global const float* qp, lanei at,
                                __global const float* ap, lanei at_a, lanei packed, int valid) {
  const int s = padded_stride(g, c, a);
  const lanef q_3 = row_lanes(qp, at - 3 * s, valid), q_2 = row_lanes(qp, at - 2 * s, valid),
              q_1 = row_lanes(qp, at - s, valid), q0 = row_lanes(qp, at, valid),
              q1 = row_lanes(qp, at + s, valid), q2 = row_lanes(qp, at + 2 * s, valid),
              q3 = row_lanes(qp, at + 3 * s, valid);
  lanef U_lower, U_upper;
  if (a == c) { /* the component advects itself: U at the volume's sides is the mean of the faces there */
    U_lower = 0.5f * (q_1 + q0);
    U_upper = 0.5f * (q0 + q1);
  } else { /* component a on the sides' two faces that meet there, one back along c */
    const int sa = padded_stride(g, a, a), sc = padded_stride(g, a, c);
    U_lower = 0.5f * (row_lanes(ap, at_a - sc, valid) + row_lanes(ap, at_a, valid));
    U_upper = 0.5f * (row_lanes(ap, at_a + sa - sc, valid) + row_lanes(ap, at_a + sa, valid));
  }
  const lanei lower = (packed >> FW_UPWIND_SHIFT(a, 0)) & FW_UPWIND_BITS;
  const lanei upper = (packed >> FW_UPWIND_SHIFT(a, 1)) & FW_UPWIND_BITS;
  return upwind_flux(U_upper, upper, q_2, q_1, q0, q1, q2, q3) -
         upwind_flux(U_lower, lower, q_3, q_2, q_1, q0, q1, q2);
}

FW_INLINE void upwind_stage_lanes(const FwGrid g, const int c, const float coef_dt, __global const float* up,
                                  __global const float* vp, __global const float* wp,
                                  __global const ushort* orders, __global const float* base,
                                  __global float* out) {
  FW_LANE_SETUP(c)
  const int first = face_index(&g, c, i0, j, k);
  const lanei packed = order_lanes(orders, first, valid);
  __global const float* qp = c == 0 ? up : (c == 1 ? vp : wp);
  const lanei at = lane_padded_index(&g, c, i, j, k);
  const lanef net = flux_difference(&g, c, 0, qp, at, up, lane_padded_index(&g, 0, i, j, k), packed, valid) +
                    flux_difference(&g, c, 1, qp, at, vp, lane_padded_index(&g, 1, i, j, k), packed, valid) +
                    flux_difference(&g, c, 2, qp, at, wp, lane_padded_index(&g, 2, i, j, k), packed, valid);
  const lanef q = row_lanes(base, (lanei)(first) + (i - (lanei)(i0)), valid);
  store_lane_span(out, first, skip, valid, q - (coef_dt / g.h) * net);
}

__kernel void upwind_stage_u(const FwGrid g, const float coef_dt, __global const float* up,
                             __global const float* vp, __global const float* wp,
                             __global const ushort* orders, __global const float* base, __global float* out) {
  upwind_stage_lanes(g, 0, coef_dt, up, vp, wp, orders, base, out);
}
__kernel void upwind_stage_v(const FwGrid g, const float coef_dt, __global const float* up,
                             __global const float* vp, __global const float* wp,
                             __global const ushort* orders, __global const float* base, __global float* out) {
  upwind_stage_lanes(g, 1, coef_dt, up, vp, wp, orders, base, out);
}
__kernel void upwind_stage_w(const FwGrid g, const float coef_dt, __global const float* up,
                             __global const float* vp, __global const float* wp,
                             __global const ushort* orders, __global const float* base, __global float* out) {
  upwind_stage_lanes(g, 2, coef_dt, up, vp, wp, orders, base, out);
}
