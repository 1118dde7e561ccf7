/* The subgrid stress (Smagorinsky eddy viscosity and its explicit diffusion) and the log-law wall stress.
 * Numerics, units and the stability clamp: fluid/SubgridStress.hpp. Reference: fluid/ReferenceStages.cpp
 * eddy_viscosity, diffuse_eddy, wall_stress. */
#include "common.cl"

FW_INLINE int axis_periodic(const FwGrid* g, int a) {
  return g->bc[2 * a] == FW_BC_PERIODIC;
}

/* A cell index up to two steps outside an axis of n cells: wrapped on a periodic axis, else the edge cell
 * (the domain's boundary face belongs to the cell inside). */
FW_INLINE int wrap_or_clamp(int x, int n, int periodic) {
  if (n == 1) return 0;
  if (periodic) return x < 0 ? x + n : (x >= n ? x - n : x);
  return clamp(x, 0, n - 1);
}

/* Where a derivative along an axis of n cells looks at index x: one cell up (*plus = 1) and down
 * (*minus = 1), or the cell itself (0) at a non-periodic edge, where the difference turns one-sided; across a
 * periodic seam the padded copy's ghosts hold the wrapped values. *inverse = 1 / (span h), 0 for a single
 * cell along a non-periodic axis. */
FW_INLINE void difference_offsets(int x, int n, int periodic, float h, int* plus, int* minus,
                                  float* inverse) {
  *plus = (x + 1 < n || periodic) ? 1 : 0;
  *minus = (x > 0 || periodic) ? 1 : 0;
  const int span = *plus + *minus;
  *inverse = span > 0 ? 1.0f / ((float)span * h) : 0.0f;
}

/* Difference of the cell-centred values of a padded component between the cells `up` and `down` padded
 * indices away from the cell at `at`, times `inverse`; `own` is the component's stride along its own axis
 * (a cell's centre value is the mean of its two faces along it). */
FW_INLINE float centre_difference(__global const float* pq, int at, int own, int up, int down,
                                  float inverse) {
  const int p = at + up, m = at - down;
  return 0.5f * ((pq[p] + pq[p + own]) - (pq[m] + pq[m + own])) * inverse;
}

/* The padded strides along y and z of u, v and w, and the padded index of each component's face (0, j, k). */
typedef struct {
  int yu, zu, yv, zv, yw, zw;
  int row_u, row_v, row_w;
} PaddedRows;

FW_INLINE PaddedRows padded_rows(const FwGrid* g, int j, int k) {
  PaddedRows r;
  r.yu = padded_extent(g, 0, 0);
  r.zu = r.yu * padded_extent(g, 0, 1);
  r.yv = padded_extent(g, 1, 0);
  r.zv = r.yv * padded_extent(g, 1, 1);
  r.yw = padded_extent(g, 2, 0);
  r.zw = r.yw * padded_extent(g, 2, 1);
  r.row_u = padded_index(g, 0, 0, j, k);
  r.row_v = padded_index(g, 1, 0, j, k);
  r.row_w = padded_index(g, 2, 0, j, k);
  return r;
}

/* 2 S_ij S_ij at cell i of a row, from central differences of the cell-centred padded velocity; the
 * offsets and inverse spans along each axis come from difference_offsets. */
FW_INLINE float strain_rate_squared(const PaddedRows* r, __global const float* pu, __global const float* pv,
                                    __global const float* pw, int i, int px, int mx, float ix, int py, int my,
                                    float iy, int pz, int mz, float iz) {
  const int au = r->row_u + i, av = r->row_v + i, aw = r->row_w + i;
  /* dc_a = d u_c / d x_a */
  const float du_x = centre_difference(pu, au, 1, px, mx, ix);
  const float du_y = centre_difference(pu, au, 1, py * r->yu, my * r->yu, iy);
  const float du_z = centre_difference(pu, au, 1, pz * r->zu, mz * r->zu, iz);
  const float dv_x = centre_difference(pv, av, r->yv, px, mx, ix);
  const float dv_y = centre_difference(pv, av, r->yv, py * r->yv, my * r->yv, iy);
  const float dv_z = centre_difference(pv, av, r->yv, pz * r->zv, mz * r->zv, iz);
  const float dw_x = centre_difference(pw, aw, r->zw, px, mx, ix);
  const float dw_y = centre_difference(pw, aw, r->zw, py * r->yw, my * r->yw, iy);
  const float dw_z = centre_difference(pw, aw, r->zw, pz * r->zw, mz * r->zw, iz);
  /* 2 S_ij S_ij: the diagonal twice, each off-diagonal pair (d_ij + d_ji)^2 once. */
  const float sxy = du_y + dv_x, sxz = du_z + dw_x, syz = dv_z + dw_y;
  return 2.0f * (du_x * du_x + dv_y * dv_y + dw_z * dw_z) + sxy * sxy + sxz * sxz + syz * syz;
}

/* nu of cell (i, j, k) with the offsets of difference_offsets on every axis: the general path, for the edge
 * cells of a row. */
FW_INLINE void edge_eddy_viscosity(const FwGrid* g, const PaddedRows* rows, __global const uchar* mask,
                                   __global const float* pu, __global const float* pv,
                                   __global const float* pw, __global float* nu, float cs_h_squared,
                                   float cap, int i, int j, int k) {
  int px, mx, py, my, pz, mz;
  float ix, iy, iz;
  difference_offsets(i, g->nx, axis_periodic(g, 0), g->h, &px, &mx, &ix);
  difference_offsets(j, g->ny, axis_periodic(g, 1), g->h, &py, &my, &iy);
  difference_offsets(k, g->nz, axis_periodic(g, 2), g->h, &pz, &mz, &iz);
  const float s2 = strain_rate_squared(rows, pu, pv, pw, i, px, mx, ix, py, my, iy, pz, mz, iz);
  const int id = cell_index(g, i, j, k);
  nu[id] = (mask[id] & FW_MASK_FLUID) ? fmin(cs_h_squared * sqrt(s2), cap) : 0.0f;
}

/* nu = min((C_s h)^2 |S|, cap) per cell (m^2/s), 0 in solid cells; |S| = sqrt(2 S_ij S_ij) from central
 * differences of the cell-centred padded velocity (kernels/fluid_ghosts.cl pad_component, after the step's
 * forces), one-sided at non-periodic edges. cs_h_squared = (C_s h)^2, m^2; cap = kEddyDiffusionLimit h^2 /
 * dt. The y and z offsets are fixed for a row; along x only the two edge cells can differ, so the interior
 * cells run with literal offsets and contiguous loads. Global range: rows over the cells. */
__kernel void eddy_viscosity(const FwGrid g, const float cs_h_squared, const float cap,
                             __global const uchar* mask, __global const float* pu, __global const float* pv,
                             __global const float* pw, __global float* nu) {
  const int j = get_global_id(1), k = get_global_id(2);
  int py, my, pz, mz;
  float iy, iz;
  difference_offsets(j, g.ny, axis_periodic(&g, 1), g.h, &py, &my, &iy);
  difference_offsets(k, g.nz, axis_periodic(&g, 2), g.h, &pz, &mz, &iz);
  const int periodic_x = axis_periodic(&g, 0);
  const PaddedRows rows = padded_rows(&g, j, k);
  const int row_cell = cell_index(&g, 0, j, k);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(g.nx);
  /* Cells 1 .. nx-2 difference across both neighbours (as every cell does along a periodic axis). */
  const int first = clamp(periodic_x ? 0 : 1, begin, end);
  const int last = clamp(periodic_x ? g.nx : g.nx - 1, first, end);
  const float ix_interior = 0.5f / g.h;
  for (int i = begin; i < first; ++i)
    edge_eddy_viscosity(&g, &rows, mask, pu, pv, pw, nu, cs_h_squared, cap, i, j, k);
  for (int i = first; i < last; ++i) {
    const float s2 = strain_rate_squared(&rows, pu, pv, pw, i, 1, 1, ix_interior, py, my, iy, pz, mz, iz);
    const int id = row_cell + i;
    nu[id] = (mask[id] & FW_MASK_FLUID) ? fmin(cs_h_squared * sqrt(s2), cap) : 0.0f;
  }
  for (int i = last; i < end; ++i)
    edge_eddy_viscosity(&g, &rows, mask, pu, pv, pw, nu, cs_h_squared, cap, i, j, k);
}

/* The cells sharing the faces of row (j, k) of component c (which may lie one row outside the array), as
 * the indices of the cells (0, j', k') of their rows; the x index is added per face (face_nu). */
FW_INLINE void face_row_cells(const FwGrid* g, int c, int j, int k, int* row_lo, int* row_hi) {
  int lo[3] = {0, j, k}, hi[3] = {0, j, k};
  if (c > 0) lo[c] -= 1;
  for (int a = 1; a < 3; ++a) {
    const int n = axis_cells(g, a), periodic = axis_periodic(g, a);
    lo[a] = wrap_or_clamp(lo[a], n, periodic);
    hi[a] = wrap_or_clamp(hi[a], n, periodic);
  }
  *row_lo = cell_index(g, 0, lo[1], lo[2]);
  *row_hi = cell_index(g, 0, hi[1], hi[2]);
}

/* nu_face of face i (which may lie one face outside the array) of a row of component c: the mean of the two
 * cells sharing it. `wrap` = 0 where i - 2 .. i + 1 are all inside the row, which skips the wrap and lets
 * the interior run vectorise. */
FW_INLINE float face_nu(const FwGrid* g, __global const float* nu, int c, int periodic_x, int wrap,
                        int row_lo, int row_hi, int i) {
  int lo = c == 0 ? i - 1 : i, hi = i;
  if (wrap) {
    lo = wrap_or_clamp(lo, g->nx, periodic_x);
    hi = wrap_or_clamp(hi, g->nx, periodic_x);
  }
  return 0.5f * (nu[row_lo + lo] + nu[row_hi + hi]);
}

/* One face's update inside diffuse_eddy_rows, a macro so that each of its loops gets the wrap it needs as a
 * literal and the interior loop carries no wrap at all. */
#define FW_EDDY_FACE(wrap_)                                                                               \
  do {                                                                                                    \
    const float n0 = face_nu(g, nu, c, periodic_x, wrap_, lo, hi, i);                                     \
    const float nxm = face_nu(g, nu, c, periodic_x, wrap_, lo, hi, i - 1),                                \
                nxp = face_nu(g, nu, c, periodic_x, wrap_, lo, hi, i + 1);                                \
    const float nym = face_nu(g, nu, c, periodic_x, wrap_, lo_ym, hi_ym, i);                              \
    const float nyp = face_nu(g, nu, c, periodic_x, wrap_, lo_yp, hi_yp, i);                              \
    const float nzm = face_nu(g, nu, c, periodic_x, wrap_, lo_zm, hi_zm, i);                              \
    const float nzp = face_nu(g, nu, c, periodic_x, wrap_, lo_zp, hi_zp, i);                              \
    const int at = row_at + i;                                                                            \
    const float q = pq[at];                                                                               \
    /* The two cells of the face below (its own cells one layer down; the row itself when not checked, so \
     * that the loads stay in bounds and the loop branch-free). */                                        \
    int x_lo = c == 0 ? i - 1 : i, x_hi = i;                                                              \
    if (wrap_) {                                                                                          \
      x_lo = wrap_or_clamp(x_lo, g->nx, periodic_x);                                                      \
      x_hi = wrap_or_clamp(x_hi, g->nx, periodic_x);                                                      \
    }                                                                                                     \
    const int open_below =                                                                                \
        !check_below || ((mask[lo - down + x_lo] & mask[hi - down + x_hi]) & FW_MASK_FLUID);              \
    const float below = open_below ? pq[at - sz] : q;                                                     \
    const float flux = (n0 + nxm) * (pq[at - 1] - q) + (n0 + nxp) * (pq[at + 1] - q) +                    \
                       (n0 + nym) * (pq[at - sy] - q) + (n0 + nyp) * (pq[at + sy] - q) +                  \
                       (n0 + nzm) * (below - q) + (n0 + nzp) * (pq[at + sz] - q);                         \
    out[row_out + i] = q + half_dt_over_h2 * flux;                                                        \
  } while (0)

/* The eddy diffusion of component c in flux form, the diagonal part div(nu_t grad q) of the stress:
 * out = q + dt / h^2 * sum over the six neighbours of nu_edge (q_nb - q), where nu_edge is the mean of the
 * nu_face of the face and of its neighbour, and nu_face the mean of the two cells sharing a face. Each pair
 * of faces exchanges the same flux, so the stage conserves momentum. Neighbours come from the padded copy of
 * q (the ghosts are the constant-viscosity stage's fetch_face rules); the nu of a face outside the array is
 * that of its wrapped or clamped cells. With wall_slip set, a horizontal face whose neighbour below touches
 * a solid cell exchanges nothing with it (a zero gradient): the wall stress stage carries that momentum
 * flux. Writes every face of component c; out may be the unpadded component itself. Global range: rows over
 * its faces. */
FW_INLINE void diffuse_eddy_rows(const FwGrid* g, const float dt, const int c, const int wall_slip,
                                 __global const uchar* mask, __global const float* nu,
                                 __global const float* pq, __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(g, c, 0), periodic_x = axis_periodic(g, 0);
  const int sy = padded_extent(g, c, 0), sz = sy * padded_extent(g, c, 1);
  const int layer = g->nx * g->ny;
  const float half_dt_over_h2 = 0.5f * dt / (g->h * g->h);
  const int check_below = wall_slip && c < 2 && k > 0;
  const int down = check_below ? layer : 0;
  int lo, hi, lo_ym, hi_ym, lo_yp, hi_yp, lo_zm, hi_zm, lo_zp, hi_zp;
  face_row_cells(g, c, j, k, &lo, &hi);
  face_row_cells(g, c, j - 1, k, &lo_ym, &hi_ym);
  face_row_cells(g, c, j + 1, k, &lo_yp, &hi_yp);
  face_row_cells(g, c, j, k - 1, &lo_zm, &hi_zm);
  face_row_cells(g, c, j, k + 1, &lo_zp, &hi_zp);
  const int row_at = padded_index(g, c, 0, j, k), row_out = face_index(g, c, 0, j, k);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(ex);
  /* Faces 2 .. nx-2 need no wrap: their neighbours' cells i-2 .. i+1 lie inside the row. */
  const int first = clamp(2, begin, end), last = clamp(g->nx - 1, first, end);
  for (int i = begin; i < first; ++i) FW_EDDY_FACE(1);
  for (int i = first; i < last; ++i) FW_EDDY_FACE(0);
  for (int i = last; i < end; ++i) FW_EDDY_FACE(1);
}

/* One kernel a component, so that c is a literal and the selects above fold away. */
__kernel void diffuse_eddy_u(const FwGrid g, const FwStep s, const int wall_slip, __global const uchar* mask,
                             __global const float* nu, __global const float* pq, __global float* out) {
  diffuse_eddy_rows(&g, s.dt, 0, wall_slip, mask, nu, pq, out);
}
__kernel void diffuse_eddy_v(const FwGrid g, const FwStep s, const int wall_slip, __global const uchar* mask,
                             __global const float* nu, __global const float* pq, __global float* out) {
  diffuse_eddy_rows(&g, s.dt, 1, wall_slip, mask, nu, pq, out);
}
__kernel void diffuse_eddy_w(const FwGrid g, const FwStep s, const int wall_slip, __global const uchar* mask,
                             __global const float* nu, __global const float* pq, __global float* out) {
  diffuse_eddy_rows(&g, s.dt, 2, wall_slip, mask, nu, pq, out);
}

/* Implicit log-law wall stress on the listed u and v faces (host/stages/WallFaces.hpp: entries below
 * u_count are u faces, the rest v faces; 5 indices an entry, the face and the four faces of the other
 * horizontal component):
 * stressed[n] = q / (1 + dt (C_w / h) weight |U|), |U| = sqrt(q^2 + b^2) the horizontal speed, b the mean
 * of the four faces, all from the old u and v. drag_per_length = C_w / h, 1/m. Out of place, so that each
 * component's |U| sees the other one before the stress; wall_stress_store then writes the faces back.
 * Mirrors fluid/ReferenceStages.cpp wall_stress. Flat over the entries. */
__kernel void wall_stress_faces(const FwStep s, const int count, const int u_count,
                                const float drag_per_length, __global const int* faces,
                                __global const float* weights, __global const float* u,
                                __global const float* v, __global float* stressed) {
  FW_FLAT_FOR(n, count) {
    const int is_v = (int)n >= u_count;
    __global const float* q = is_v ? v : u;
    __global const float* b = is_v ? u : v;
    __global const int* entry = faces + 5 * n;
    const float qf = q[entry[0]];
    const float mb = 0.25f * (b[entry[1]] + b[entry[2]] + b[entry[3]] + b[entry[4]]);
    stressed[n] = qf / (1.0f + s.dt * drag_per_length * weights[n] * sqrt(qf * qf + mb * mb));
  }
}

/* The listed faces take their stressed values. Flat over the entries. */
__kernel void wall_stress_store(const int count, const int u_count, __global const int* faces,
                                __global const float* stressed, __global float* u, __global float* v) {
  FW_FLAT_FOR(n, count) {
    __global float* q = (int)n >= u_count ? v : u;
    q[faces[5 * n]] = stressed[n];
  }
}
