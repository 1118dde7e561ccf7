/* The two ends of the pressure projection: the Poisson right-hand side from the velocity divergence, and
 * the subtraction of the pressure gradient. Reference: fluid/ReferenceStages.cpp divergence_rhs,
 * subtract_gradient, max_divergence. */
#include "common.cl"

FW_INLINE float net_outflow(const FwGrid* g, __global const float* u, __global const float* v,
                            __global const float* w, int i, int j, int k) {
  return (u[face_index(g, 0, i + 1, j, k)] - u[face_index(g, 0, i, j, k)]) +
         (v[face_index(g, 1, i, j + 1, k)] - v[face_index(g, 1, i, j, k)]) +
         (w[face_index(g, 2, i, j, k + 1)] - w[face_index(g, 2, i, j, k)]);
}

/* b = -h * net outflow (= -h^2 div u), m^2/s, in fluid cells; 0 elsewhere. */
__kernel void divergence_rhs(const FwGrid g, __global const uchar* mask, __global const float* u,
                             __global const float* v, __global const float* w, __global float* b) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(g.nx); ++i) {
    const int id = cell_index(&g, i, j, k);
    b[id] = (mask[id] & FW_MASK_FLUID) ? -g.h * net_outflow(&g, u, v, w, i, j, k) : 0.0f;
  }
}

/* partial[group] = max over the work-group's fluid cells of |div u|, 1/s. */
__kernel void max_divergence(const FwGrid g, __global const uchar* mask, __global const float* u,
                             __global const float* v, __global const float* w, __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int end = FW_REDUCTION_ROW_END(g.nx, g.ny);
  float m = 0.0f;
  for (int i = FW_ROW_BEGIN; i < end; ++i)
    if (mask[cell_index(&g, i, j, k)] & FW_MASK_FLUID)
      m = fmax(m, fabs(net_outflow(&g, u, v, w, i, j, k)) / g.h);
  FW_GROUP_MAX(m, partial);
}

/* q (component c) -= (phi_high - phi_low) / h on faces open in the mask. Outside the domain phi is the
 * outflow ghost's 0, or wraps on a periodic axis. */
/* Gradient correction of one face with the general (boundary-aware) rules. */
FW_INLINE float gradient_face(const FwGrid* g, int c, __global const uchar* mask, __global const float* phi,
                              int i, int j, int k) {
  if (!face_open(g, mask, c, i, j, k)) return 0.0f;
  const int n = axis_cells(g, c);
  const int sc = cell_stride(g, c);
  const int periodic = g->bc[2 * c] == FW_BC_PERIODIC;
  const int own = own_index(c, i, j, k);
  const int cell = face_cell(g, c, i, j, k);
  float phi_lo, phi_hi;
  if (own == 0) {
    phi_hi = phi[cell];
    phi_lo = periodic ? phi[cell + (n - 1) * sc] : 0.0f;
  } else if (own == n) {
    phi_lo = phi[cell];
    phi_hi = periodic ? phi[cell - (n - 1) * sc] : 0.0f;
  } else {
    phi_hi = phi[cell];
    phi_lo = phi[cell - sc];
  }
  return (phi_hi - phi_lo) / g->h;
}

__kernel void subtract_gradient(const FwGrid g, const int c, __global const uchar* mask,
                                __global const float* phi, __global float* q) {
  FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(face_extent(&g, c, 0));
  const int sc = cell_stride(&g, c), bit = 2 * c + 1;
  int lo, hi;
  interior_face_span(&g, c, j, k, begin, end, &lo, &hi);
  for (int i = begin; i < lo; ++i) q[face_index(&g, c, i, j, k)] -= gradient_face(&g, c, mask, phi, i, j, k);
  for (int i = lo; i < hi; ++i) { /* interior: branch-free, vectorises */
    const int cell = cell_index(&g, i, j, k);
    const float step = (phi[cell] - phi[cell - sc]) / g.h;
    q[face_index(&g, c, i, j, k)] -= ((mask[cell - sc] >> bit) & 1) ? step : 0.0f;
  }
  for (int i = hi; i < end; ++i) q[face_index(&g, c, i, j, k)] -= gradient_face(&g, c, mask, phi, i, j, k);
}

/* partial[group] = max |q| over the work-group's runs of an extent_x * extent_y * nz array (NaN propagates).
 */
__kernel void max_abs(const int extent_x, const int extent_y, __global const float* q,
                      __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int end = FW_REDUCTION_ROW_END(extent_x, extent_y);
  float m = 0.0f;
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const float a = fabs(q[i + extent_x * (j + extent_y * k)]);
    m = (a > m || isnan(a)) ? a : m;
  }
  FW_GROUP_MAX(m, partial);
}
