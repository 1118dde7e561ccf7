/* The wind's plane statistics (host/stages/PlaneStatistics.hpp, docs/statistics.md): for each row (j, k) of
 * the block's own cells, the sum over its fluid cells of every FW_TERM_* (kernels/shared_types.h) as a
 * 64-bit integer, each cell's term rounded to a multiple of 2^-s_t (scale[t] = 2^s_t), and the row's largest
 * |term|. Integers add exactly in any order, so the host's sums over rows and ranks are the same however
 * the grid is cut: the file's values over ranks are one process's. The host picks each s_t so that no sum
 * can overflow, and checks it against the maxima. Cell centres, strain and domain-edge rules as
 * fluid::plane_profiles (the CPU reference) and kernels/strain_rate.cl: over ranks the halo holds the
 * neighbours' cells, so a cut reads what one process reads. Global range: (1, own_rows, nz) from
 * (0, first_row, 0); the own cells first_x .. end_x - 1 of each row. Out: FW_PLANE_TERMS values a row, row
 * (j - first_row) + own_rows k. */
#include "strain_rate.cl"

/* Adds a cell's term t to the row's partial and maximum. */
FW_INLINE void add_term(long* sum, float* largest, float t, float scale) {
  *sum += convert_long_rte(t * scale);
  *largest = fmax(*largest, fabs(t));
}

__kernel void plane_statistics(const FwGrid g, const int first_x, const int end_x, const int first_row,
                               const int own_rows, const int has_eddy_viscosity, const int has_energy,
                               const int has_lad, __global const float* restrict scale,
                               __global const uchar* restrict mask, __global const float* restrict u,
                               __global const float* restrict v, __global const float* restrict w,
                               __global const float* restrict nu, __global const float* restrict energy,
                               __global const float* restrict lad, __global long* restrict sums,
                               __global float* restrict largest) {
  const int j = get_global_id(1), k = get_global_id(2);
  if (get_global_id(0) != 0 || j >= first_row + own_rows || k >= g.nz) return;
  int py, my, pz, mz;
  float iy, iz;
  difference_offsets(j, g.ny, axis_periodic(&g, 1), g.h, &py, &my, &iy);
  difference_offsets(k, g.nz, axis_periodic(&g, 2), g.h, &pz, &mz, &iz);
  const StrainRows ru = strain_rows(&g, 0, j, k, py, my, pz, mz),
                   rv = strain_rows(&g, 1, j, k, py, my, pz, mz),
                   rw = strain_rows(&g, 2, j, k, py, my, pz, mz);
  const int periodic_x = axis_periodic(&g, 0);
  float s[FW_PLANE_TERMS];
  for (int t = 0; t < FW_PLANE_TERMS; ++t) s[t] = scale[t];
  long sum[FW_PLANE_TERMS];
  float most[FW_PLANE_TERMS];
  for (int t = 0; t < FW_PLANE_TERMS; ++t) {
    sum[t] = 0;
    most[t] = 0.0f;
  }
  const int row_cell = cell_index(&g, 0, j, k);
  for (int i = first_x; i < end_x; ++i) {
    const int id = row_cell + i;
    if (!(mask[id] & FW_MASK_FLUID)) continue;
    sum[FW_TERM_CELLS] += 1;
    const float uc = 0.5f * (u[ru.own.lo + i] + u[ru.own.hi + i + 1]);
    const float vc = 0.5f * (v[rv.own.lo + i] + v[rv.own.hi + i]);
    const float wc = 0.5f * (w[rw.own.lo + i] + w[rw.own.hi + i]);
    add_term(&sum[FW_TERM_U], &most[FW_TERM_U], uc, s[FW_TERM_U]);
    add_term(&sum[FW_TERM_V], &most[FW_TERM_V], vc, s[FW_TERM_V]);
    add_term(&sum[FW_TERM_W], &most[FW_TERM_W], wc, s[FW_TERM_W]);
    add_term(&sum[FW_TERM_UU], &most[FW_TERM_UU], uc * uc, s[FW_TERM_UU]);
    add_term(&sum[FW_TERM_VV], &most[FW_TERM_VV], vc * vc, s[FW_TERM_VV]);
    add_term(&sum[FW_TERM_WW], &most[FW_TERM_WW], wc * wc, s[FW_TERM_WW]);
    add_term(&sum[FW_TERM_UUU], &most[FW_TERM_UUU], uc * uc * uc, s[FW_TERM_UUU]);
    add_term(&sum[FW_TERM_WWW], &most[FW_TERM_WWW], wc * wc * wc, s[FW_TERM_WWW]);
    add_term(&sum[FW_TERM_UW], &most[FW_TERM_UW], uc * wc, s[FW_TERM_UW]);
    add_term(&sum[FW_TERM_VW], &most[FW_TERM_VW], vc * wc, s[FW_TERM_VW]);
    if (has_eddy_viscosity) {
      int px, mx;
      float ix;
      difference_offsets(i, g.nx, periodic_x, g.h, &px, &mx, &ix);
      float du_x, du_y, du_z, dv_x, dv_y, dv_z, dw_x, dw_y, dw_z;
      velocity_gradient(&g, u, 0, &ru, i, periodic_x, px, mx, ix, iy, iz, &du_x, &du_y, &du_z);
      velocity_gradient(&g, v, 1, &rv, i, periodic_x, px, mx, ix, iy, iz, &dv_x, &dv_y, &dv_z);
      velocity_gradient(&g, w, 2, &rw, i, periodic_x, px, mx, ix, iy, iz, &dw_x, &dw_y, &dw_z);
      /* -2 nu_t S_xz = -nu_t (du/dz + dw/dx) */
      add_term(&sum[FW_TERM_U_DIFF], &most[FW_TERM_U_DIFF], -nu[id] * (du_z + dw_x), s[FW_TERM_U_DIFF]);
      add_term(&sum[FW_TERM_V_DIFF], &most[FW_TERM_V_DIFF], -nu[id] * (dv_z + dw_y), s[FW_TERM_V_DIFF]);
    }
    if (has_energy) add_term(&sum[FW_TERM_E], &most[FW_TERM_E], energy[id], s[FW_TERM_E]);
    if (has_lad) add_term(&sum[FW_TERM_LAD], &most[FW_TERM_LAD], lad[id], s[FW_TERM_LAD]);
    most[FW_TERM_SPEED] = fmax(most[FW_TERM_SPEED], uc * uc + vc * vc + wc * wc);
  }
  const int out = FW_PLANE_TERMS * ((j - first_row) + own_rows * k);
  most[FW_TERM_SPEED] = sqrt(most[FW_TERM_SPEED]);
  for (int t = 0; t < FW_PLANE_TERMS; ++t) {
    sums[out + t] = sum[t];
    largest[out + t] = most[t];
  }
}
