/* The wind's plane statistics (host/stages/PlaneStatistics.hpp, docs/statistics.md): for each row (j, k) of
 * the block's own cells, the sum over its fluid cells of every FW_TERM_* (kernels/shared_types.h) as a
 * 64-bit integer, each cell's term cut toward 0 to a 32-bit multiple of 2^-s_t (scale[t] = 2^s_t: OpenCL's
 * plain conversion, one instruction, where PoCL's rounding conversion made the pass 40% slower), and the
 * row's largest |term| (not of the products of u, v and w, which the host bounds by their factors'). Integers
 * add exactly in any order, so the host's sums over rows and ranks are the same however the grid is cut: the
 * file's values over ranks are one process's. The host picks each s_t so that no cell's term passes
 * 2^FW_PLANE_CELL_BITS, and checks it against the maxima: the chunks' 32-bit lanes then take
 * FW_PLANE_FLUSH_CHUNKS cells each before they are widened. Cell centres, strain and domain-edge rules as
 * fluid::plane_profiles (the CPU reference) and kernels/strain_rate.cl: over ranks the halo holds the
 * neighbours' cells, so a cut reads what one process reads.
 *
 * A row runs in FW_LANES-cell chunks of vector arithmetic (kernels/lanes.cl; PoCL does not vectorise a loop
 * inside a work-item), and its edge cells (whose strain wraps or turns one-sided) and its tail cell by cell.
 * Where a chunk starts depends on the block, so both ways must give a cell the same floats: contraction into
 * FMAs is off, and both spell each term alike.
 *
 * Global range: (1, own_rows, nz) from (0, first_row, 0); the own cells first_x .. end_x - 1 of each row.
 * Out: FW_PLANE_TERMS values a row, row (j - first_row) + own_rows k. */
#pragma OPENCL FP_CONTRACT OFF
#include "lanes.cl"
#include "strain_rate.cl"

/* What a row's cells read: the strain's rows of each component, the inverse spans along y and z. */
typedef struct {
  StrainRows ru, rv, rw;
  float iy, iz;
  int row_cell; /* the index of cell (0, j, k) */
} StatisticsRow;

/* The fields and what the run has of them. */
typedef struct {
  __global const uchar* mask;
  __global const float *u, *v, *w, *nu, *energy, *lad;
  int has_eddy_viscosity, has_energy, has_lad;
} StatisticsFields;

/* Adds a cell's term t to the row's partial, and |t| to its maximum. */
FW_INLINE void add_term(long* sum, float* largest, float t, float scale) {
  *sum += (long)convert_int(t * scale);
  *largest = fmax(*largest, fabs(t));
}

/* Adds a product's term t to the row's partial alone: the host bounds it by its factors' maxima (a float
 * product grows with its factors' magnitudes). */
FW_INLINE void add_product(long* sum, float t, float scale) {
  *sum += (long)convert_int(t * scale);
}

/* Adds the terms of fluid cell i; px, mx, ix: its x differences (difference_offsets), wrapped when `wrap`. */
FW_INLINE void cell_terms(const FwGrid* g, const StatisticsRow* r, const StatisticsFields* f, const float* s,
                          int i, int wrap, int px, int mx, float ix, long* sum, float* most) {
  const int id = r->row_cell + i;
  if (!(f->mask[id] & FW_MASK_FLUID)) return;
  sum[FW_TERM_CELLS] += 1;
  const float uc = 0.5f * (f->u[r->ru.own.lo + i] + f->u[r->ru.own.hi + i + 1]);
  const float vc = 0.5f * (f->v[r->rv.own.lo + i] + f->v[r->rv.own.hi + i]);
  const float wc = 0.5f * (f->w[r->rw.own.lo + i] + f->w[r->rw.own.hi + i]);
  add_term(&sum[FW_TERM_U], &most[FW_TERM_U], uc, s[FW_TERM_U]);
  add_term(&sum[FW_TERM_V], &most[FW_TERM_V], vc, s[FW_TERM_V]);
  add_term(&sum[FW_TERM_W], &most[FW_TERM_W], wc, s[FW_TERM_W]);
  add_product(&sum[FW_TERM_UU], uc * uc, s[FW_TERM_UU]);
  add_product(&sum[FW_TERM_VV], vc * vc, s[FW_TERM_VV]);
  add_product(&sum[FW_TERM_WW], wc * wc, s[FW_TERM_WW]);
  add_product(&sum[FW_TERM_UUU], uc * uc * uc, s[FW_TERM_UUU]);
  add_product(&sum[FW_TERM_WWW], wc * wc * wc, s[FW_TERM_WWW]);
  add_product(&sum[FW_TERM_UW], uc * wc, s[FW_TERM_UW]);
  add_product(&sum[FW_TERM_VW], vc * wc, s[FW_TERM_VW]);
  most[FW_TERM_SPEED] = fmax(most[FW_TERM_SPEED], uc * uc + vc * vc + wc * wc);
  if (f->has_eddy_viscosity) {
    /* -2 nu_t S_xz = -nu_t (du/dz + dw/dx), -2 nu_t S_yz = -nu_t (dv/dz + dw/dy) */
    const float du_z = centre_difference(g, f->u, 0, 0, r->ru.z_up, i, r->ru.z_down, i, r->iz);
    const float dv_z = centre_difference(g, f->v, 1, 0, r->rv.z_up, i, r->rv.z_down, i, r->iz);
    const float dw_x = centre_difference(g, f->w, 2, wrap, r->rw.own, i + px, r->rw.own, i - mx, ix);
    const float dw_y = centre_difference(g, f->w, 2, 0, r->rw.y_up, i, r->rw.y_down, i, r->iy);
    add_term(&sum[FW_TERM_U_DIFF], &most[FW_TERM_U_DIFF], -f->nu[id] * (du_z + dw_x), s[FW_TERM_U_DIFF]);
    add_term(&sum[FW_TERM_V_DIFF], &most[FW_TERM_V_DIFF], -f->nu[id] * (dv_z + dw_y), s[FW_TERM_V_DIFF]);
  }
  if (f->has_energy) add_term(&sum[FW_TERM_E], &most[FW_TERM_E], f->energy[id], s[FW_TERM_E]);
  if (f->has_lad) add_term(&sum[FW_TERM_LAD], &most[FW_TERM_LAD], f->lad[id], s[FW_TERM_LAD]);
}

/* add_term and add_product for FW_LANES cells into 32-bit lanes (the caller widens them every
 * FW_PLANE_FLUSH_CHUNKS); t is 0 in the lanes outside the fluid. */
FW_INLINE void add_lane_term(lanei* sum, lanef* largest, lanef t, float scale) {
  *sum += convert_lanei(t * scale);
  *largest = fmax(*largest, fabs(t));
}
FW_INLINE void add_lane_product(lanei* sum, lanef t, float scale) {
  *sum += convert_lanei(t * scale);
}

/* The centre value of component c at cells x .. x + FW_LANES - 1 of `rows` (ci: 1 for u, whose high face is
 * one further along x). */
FW_INLINE lanef lane_centres(__global const float* q, CentreRows rows, int x, int ci) {
  return 0.5f * (lane_load(0, q + rows.lo + x) + lane_load(0, q + rows.hi + x + ci));
}

/* centre_difference between the same cells of two rows, for FW_LANES cells from x. */
FW_INLINE lanef lane_difference(__global const float* q, int ci, CentreRows up, int x_up, CentreRows down,
                                int x_down, float inverse) {
  return 0.5f *
         ((lane_load(0, q + up.lo + x_up) + lane_load(0, q + up.hi + x_up + ci)) -
          (lane_load(0, q + down.lo + x_down) + lane_load(0, q + down.hi + x_down + ci))) *
         inverse;
}

/* cell_terms for the FW_LANES cells from x, none of them at an edge of the row. */
FW_INLINE void lane_terms(const StatisticsRow* r, const StatisticsFields* f, const float* s, int x, float ix,
                          lanei* sum, lanef* most) {
  const lanei on = convert_lanei(lane_load_bytes(0, f->mask + r->row_cell + x) & (uchar)FW_MASK_FLUID) != 0;
  sum[FW_TERM_CELLS] -= on; /* true lanes are -1 */
  /* Outside the fluid the centred values are 0, and so is every product of them. */
  const lanef zero = (lanef)(0.0f);
  const lanef uc = select(zero, lane_centres(f->u, r->ru.own, x, 1), on);
  const lanef vc = select(zero, lane_centres(f->v, r->rv.own, x, 0), on);
  const lanef wc = select(zero, lane_centres(f->w, r->rw.own, x, 0), on);
  add_lane_term(&sum[FW_TERM_U], &most[FW_TERM_U], uc, s[FW_TERM_U]);
  add_lane_term(&sum[FW_TERM_V], &most[FW_TERM_V], vc, s[FW_TERM_V]);
  add_lane_term(&sum[FW_TERM_W], &most[FW_TERM_W], wc, s[FW_TERM_W]);
  add_lane_product(&sum[FW_TERM_UU], uc * uc, s[FW_TERM_UU]);
  add_lane_product(&sum[FW_TERM_VV], vc * vc, s[FW_TERM_VV]);
  add_lane_product(&sum[FW_TERM_WW], wc * wc, s[FW_TERM_WW]);
  add_lane_product(&sum[FW_TERM_UUU], uc * uc * uc, s[FW_TERM_UUU]);
  add_lane_product(&sum[FW_TERM_WWW], wc * wc * wc, s[FW_TERM_WWW]);
  add_lane_product(&sum[FW_TERM_UW], uc * wc, s[FW_TERM_UW]);
  add_lane_product(&sum[FW_TERM_VW], vc * wc, s[FW_TERM_VW]);
  most[FW_TERM_SPEED] = fmax(most[FW_TERM_SPEED], uc * uc + vc * vc + wc * wc);
  if (f->has_eddy_viscosity) {
    const lanef du_z = lane_difference(f->u, 1, r->ru.z_up, x, r->ru.z_down, x, r->iz);
    const lanef dv_z = lane_difference(f->v, 0, r->rv.z_up, x, r->rv.z_down, x, r->iz);
    const lanef dw_x = lane_difference(f->w, 0, r->rw.own, x + 1, r->rw.own, x - 1, ix);
    const lanef dw_y = lane_difference(f->w, 0, r->rw.y_up, x, r->rw.y_down, x, r->iy);
    const lanef nu = lane_load(0, f->nu + r->row_cell + x);
    add_lane_term(&sum[FW_TERM_U_DIFF], &most[FW_TERM_U_DIFF], select(zero, -nu * (du_z + dw_x), on),
                  s[FW_TERM_U_DIFF]);
    add_lane_term(&sum[FW_TERM_V_DIFF], &most[FW_TERM_V_DIFF], select(zero, -nu * (dv_z + dw_y), on),
                  s[FW_TERM_V_DIFF]);
  }
  if (f->has_energy)
    add_lane_term(&sum[FW_TERM_E], &most[FW_TERM_E],
                  select(zero, lane_load(0, f->energy + r->row_cell + x), on), s[FW_TERM_E]);
  if (f->has_lad)
    add_lane_term(&sum[FW_TERM_LAD], &most[FW_TERM_LAD],
                  select(zero, lane_load(0, f->lad + r->row_cell + x), on), s[FW_TERM_LAD]);
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
  StatisticsRow r;
  int py, my, pz, mz;
  difference_offsets(j, g.ny, axis_periodic(&g, 1), g.h, &py, &my, &r.iy);
  difference_offsets(k, g.nz, axis_periodic(&g, 2), g.h, &pz, &mz, &r.iz);
  r.ru = strain_rows(&g, 0, j, k, py, my, pz, mz);
  r.rv = strain_rows(&g, 1, j, k, py, my, pz, mz);
  r.rw = strain_rows(&g, 2, j, k, py, my, pz, mz);
  r.row_cell = cell_index(&g, 0, j, k);
  const StatisticsFields f = {mask, u, v, w, nu, energy, lad, has_eddy_viscosity, has_energy, has_lad};
  float s[FW_PLANE_TERMS];
  long sum[FW_PLANE_TERMS];
  float most[FW_PLANE_TERMS];
  lanel lane_sum[FW_PLANE_TERMS];
  lanei lane_part[FW_PLANE_TERMS]; /* the chunks since the last widening */
  lanef lane_most[FW_PLANE_TERMS];
  for (int t = 0; t < FW_PLANE_TERMS; ++t) {
    s[t] = scale[t];
    sum[t] = 0;
    most[t] = 0.0f;
    lane_sum[t] = (lanel)(0);
    lane_part[t] = (lanei)(0);
    lane_most[t] = (lanef)(0.0f);
  }
  /* The chunks: cells whose x differences are central and stay inside the row (1 .. nx - 2) where the
   * strain is summed, else any own cell. */
  const int periodic_x = axis_periodic(&g, 0);
  const int lowest = has_eddy_viscosity ? max(first_x, 1) : first_x;
  const int highest = has_eddy_viscosity ? min(end_x, g.nx - 1) : end_x;
  const int chunks = max(0, (highest - lowest) / FW_LANES);
  const float ix_central = 1.0f / ((float)2 * g.h); /* difference_offsets' inverse span for 2 cells */
  for (int n = 0; n < chunks; ++n) {
    lane_terms(&r, &f, s, lowest + n * FW_LANES, ix_central, lane_part, lane_most);
    if ((n + 1) % FW_PLANE_FLUSH_CHUNKS == 0 || n + 1 == chunks)
      for (int t = 0; t < FW_PLANE_TERMS; ++t) {
        lane_sum[t] += convert_lanel(lane_part[t]);
        lane_part[t] = (lanei)(0);
      }
  }
  const int chunked_end = lowest + chunks * FW_LANES;
  for (int i = first_x; i < end_x; ++i) {
    if (i >= lowest && i < chunked_end) continue;
    int px, mx;
    float ix;
    difference_offsets(i, g.nx, periodic_x, g.h, &px, &mx, &ix);
    cell_terms(&g, &r, &f, s, i, periodic_x, px, mx, ix, sum, most);
  }
  const int out = FW_PLANE_TERMS * ((j - first_row) + own_rows * k);
  for (int t = 0; t < FW_PLANE_TERMS; ++t) {
    sums[out + t] = sum[t] + lane_sum_long(lane_sum[t]);
    largest[out + t] = fmax(most[t], lane_max_float(lane_most[t]));
  }
  largest[out + FW_TERM_SPEED] = sqrt(largest[out + FW_TERM_SPEED]);
}
