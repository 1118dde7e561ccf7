/* The subgrid stress (Smagorinsky eddy viscosity and its explicit diffusion) and the log-law wall stress.
 * Numerics, units and the stability clamp: fluid/SubgridStress.hpp. Reference: fluid/ReferenceStages.cpp
 * eddy_viscosity, diffuse_eddy, wall_stress. */
#include "strain_rate.cl"

/* A cell index up to two steps outside an axis of n cells: wrapped on a periodic axis, else the edge cell
 * (the domain's boundary face belongs to the cell inside). */
FW_INLINE int wrap_or_clamp(int x, int n, int periodic) {
  if (n == 1) return 0;
  if (periodic) return x < 0 ? x + n : (x >= n ? x - n : x);
  return clamp(x, 0, n - 1);
}

/* nu of cell i of row (j, k), a function so that the interior loop (wrap 0, literal offsets) runs without
 * the x-edge logic: min((C_s h)^2 |S|, cap), 0 where the cell is not fluid. */
FW_INLINE float cell_eddy_viscosity(const FwGrid* g, const StrainRows* ru, const StrainRows* rv,
                                    const StrainRows* rw, __global const float* u, __global const float* v,
                                    __global const float* w, int fluid, float cs_h_squared, float cap, int i,
                                    int wrap, int px, int mx, float ix, float iy, float iz) {
  const float s2 = strain_rate_squared(g, ru, rv, rw, u, v, w, i, wrap, px, mx, ix, iy, iz);
  return fluid ? fmin(cs_h_squared * sqrt(s2), cap) : 0.0f;
}

/* nu = min((C_s h)^2 |S|, cap) per cell (m^2/s), 0 in solid cells; |S| = sqrt(2 S_ij S_ij) from central
 * differences of the cell-centred velocity (after the step's forces), one-sided at non-periodic edges and
 * wrapped across periodic ones: no ghost but a periodic twin is read, so the unpadded arrays serve.
 * cs_h_squared = (C_s h)^2, m^2; cap = kEddyDiffusionLimit h^2 / dt. The rows are resolved once per row;
 * along x only the two edge cells can differ, so the interior cells run with literal offsets and contiguous
 * loads. Global range: rows over the cells. */
__kernel void eddy_viscosity(const FwGrid g, const float cs_h_squared, const float cap,
                             __global const uchar* restrict mask, __global const float* restrict u,
                             __global const float* restrict v, __global const float* restrict w,
                             __global float* restrict nu) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  int py, my, pz, mz;
  float iy, iz;
  difference_offsets(j, g.ny, axis_periodic(&g, 1), g.h, &py, &my, &iy);
  difference_offsets(k, g.nz, axis_periodic(&g, 2), g.h, &pz, &mz, &iz);
  const StrainRows ru = strain_rows(&g, 0, j, k, py, my, pz, mz),
                   rv = strain_rows(&g, 1, j, k, py, my, pz, mz),
                   rw = strain_rows(&g, 2, j, k, py, my, pz, mz);
  const int periodic_x = axis_periodic(&g, 0);
  const int row_cell = cell_index(&g, 0, j, k);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(g.nx);
  /* Cells 1 .. nx-2 difference across both neighbours inside the row; the edge cells one-sided or wrapped. */
  const int first = clamp(1, begin, end), last = clamp(g.nx - 1, first, end);
  const float ix_interior = 0.5f / g.h;
  /* An edge cell: its own x offsets, the face indices wrapped. */
#define FW_EDGE_EDDY_VISCOSITY(i_)                                                                        \
  do {                                                                                                    \
    int px, mx;                                                                                           \
    float ix;                                                                                             \
    difference_offsets(i_, g.nx, periodic_x, g.h, &px, &mx, &ix);                                         \
    const int id = row_cell + (i_);                                                                       \
    nu[id] = cell_eddy_viscosity(&g, &ru, &rv, &rw, u, v, w, mask[id] & FW_MASK_FLUID, cs_h_squared, cap, \
                                 i_, 1, px, mx, ix, iy, iz);                                              \
  } while (0)
  for (int i = begin; i < first; ++i) FW_EDGE_EDDY_VISCOSITY(i);
  for (int i = first; i < last; ++i) {
    const int id = row_cell + i;
    nu[id] = cell_eddy_viscosity(&g, &ru, &rv, &rw, u, v, w, mask[id] & FW_MASK_FLUID, cs_h_squared, cap, i,
                                 0, 1, 1, ix_interior, iy, iz);
  }
  for (int i = last; i < end; ++i) FW_EDGE_EDDY_VISCOSITY(i);
#undef FW_EDGE_EDDY_VISCOSITY
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

/* A row of faces that the eddy diffusion reads as a neighbour row: the index of its face (0, j', k') and the
 * sign its values take (fetch_face's rules, resolve_face_row), or `inflow` where it lies across an inflow
 * face. */
typedef struct {
  int row, inflow;
  float sign;
} NeighbourRow;

FW_INLINE NeighbourRow neighbour_row(const FwGrid* g, int c, int jy, int kz) {
  NeighbourRow r;
  r.row = 0;
  r.inflow = resolve_face_row(g, c, jy, kz, &r.row, &r.sign);
  return r;
}

/* Face x of the diffused row itself, which may lie one face outside it: there the row's ghost by
 * fetch_face's rules along x (wrapped, mirrored, clamped or prescribed). */
FW_INLINE float row_ghost(const FwGrid* g, const FwStep* s, __global const float* profile,
                          __global const float* q, int c, int at, int x, int j, int k) {
  int xr = x;
  float sign = 1.0f;
  if (resolve_face_axis(g, c, 0, &xr, &sign)) return inflow_face_value(g, s, profile, c, x, j, k);
  return sign * q[at + xr];
}

/* What the diffusion of row (j, k) of component c reads besides its own row `at`: the cells sharing its
 * faces and those of its neighbours one row down and up y and z (lo and hi as in face_row_cells), the
 * neighbour rows of faces, whether any of them is prescribed (an inflow), and whether (and how far down, in
 * cells) the faces below are checked for a solid (the wall_slip rule). */
typedef struct {
  int at, lo, hi, lo_ym, hi_ym, lo_yp, hi_yp, lo_zm, hi_zm, lo_zp, hi_zp;
  NeighbourRow ym, yp, zm, zp;
  int any_inflow, check_below, down;
  float ghost_lo, ghost_hi; /* the row's faces x = -1 and x = extent (row_ghost) */
} EddyRows;

FW_INLINE EddyRows eddy_rows(const FwGrid* g, const FwStep* s, __global const float* profile,
                             __global const float* q, int c, int wall_slip, int j, int k) {
  EddyRows r;
  r.at = face_index(g, c, 0, j, k);
  r.ghost_lo = row_ghost(g, s, profile, q, c, r.at, -1, j, k);
  r.ghost_hi = row_ghost(g, s, profile, q, c, r.at, face_extent(g, c, 0), j, k);
  face_row_cells(g, c, j, k, &r.lo, &r.hi);
  face_row_cells(g, c, j - 1, k, &r.lo_ym, &r.hi_ym);
  face_row_cells(g, c, j + 1, k, &r.lo_yp, &r.hi_yp);
  face_row_cells(g, c, j, k - 1, &r.lo_zm, &r.hi_zm);
  face_row_cells(g, c, j, k + 1, &r.lo_zp, &r.hi_zp);
  r.ym = neighbour_row(g, c, j - 1, k);
  r.yp = neighbour_row(g, c, j + 1, k);
  r.zm = neighbour_row(g, c, j, k - 1);
  r.zp = neighbour_row(g, c, j, k + 1);
  r.any_inflow = r.ym.inflow | r.yp.inflow | r.zm.inflow | r.zp.inflow;
  r.check_below = wall_slip && c < 2 && k > 0;
  r.down = r.check_below ? g->nx * g->ny : 0;
  return r;
}

/* Face x of neighbour row n (at the face's own x, inside the row), the row seen from face (i, j, k): its
 * resolved value, or the prescribed one when it is an inflow row (`inflow` literal 0 drops that path). */
FW_INLINE float neighbour_value(const FwGrid* g, const FwStep* s, __global const float* profile,
                                __global const float* q, int c, NeighbourRow n, int inflow, int i, int jn,
                                int kn) {
  if (inflow && n.inflow) return inflow_face_value(g, s, profile, c, i, jn, kn);
  return n.sign * q[n.row + i];
}

/* One face's update: out = q + dt / (2 h^2) sum of the six (nu_face + nu_neighbour) (q_nb - q). wrap and
 * inflow are literals in the interior loop (0), so that it runs without the edge logic. */
FW_INLINE float eddy_face(const FwGrid* g, const FwStep* s, __global const float* profile, int c,
                          const EddyRows* r, __global const uchar* mask, __global const float* nu,
                          __global const float* q, int i, int j, int k, int wrap, int inflow) {
  const int periodic_x = axis_periodic(g, 0);
  const float n0 = face_nu(g, nu, c, periodic_x, wrap, r->lo, r->hi, i);
  const float nxm = face_nu(g, nu, c, periodic_x, wrap, r->lo, r->hi, i - 1),
              nxp = face_nu(g, nu, c, periodic_x, wrap, r->lo, r->hi, i + 1);
  const float nym = face_nu(g, nu, c, periodic_x, wrap, r->lo_ym, r->hi_ym, i);
  const float nyp = face_nu(g, nu, c, periodic_x, wrap, r->lo_yp, r->hi_yp, i);
  const float nzm = face_nu(g, nu, c, periodic_x, wrap, r->lo_zm, r->hi_zm, i);
  const float nzp = face_nu(g, nu, c, periodic_x, wrap, r->lo_zp, r->hi_zp, i);
  const float qc = q[r->at + i];
  /* The two cells of the face below (its own cells one layer down; the row itself when not checked, so
   * that the loads stay in bounds and the loop branch-free). */
  int x_lo = c == 0 ? i - 1 : i, x_hi = i;
  if (wrap) {
    x_lo = wrap_or_clamp(x_lo, g->nx, periodic_x);
    x_hi = wrap_or_clamp(x_hi, g->nx, periodic_x);
  }
  const int open_below =
      !r->check_below || ((mask[r->lo - r->down + x_lo] & mask[r->hi - r->down + x_hi]) & FW_MASK_FLUID);
  const float below = open_below ? neighbour_value(g, s, profile, q, c, r->zm, inflow, i, j, k - 1) : qc;
  const float west = (wrap && i == 0) ? r->ghost_lo : q[r->at + i - 1];
  const float east = (wrap && i + 1 == face_extent(g, c, 0)) ? r->ghost_hi : q[r->at + i + 1];
  const float flux = (n0 + nxm) * (west - qc) + (n0 + nxp) * (east - qc) +
                     (n0 + nym) * (neighbour_value(g, s, profile, q, c, r->ym, inflow, i, j - 1, k) - qc) +
                     (n0 + nyp) * (neighbour_value(g, s, profile, q, c, r->yp, inflow, i, j + 1, k) - qc) +
                     (n0 + nzm) * (below - qc) +
                     (n0 + nzp) * (neighbour_value(g, s, profile, q, c, r->zp, inflow, i, j, k + 1) - qc);
  return qc + 0.5f * s->dt / (g->h * g->h) * flux;
}

/* The eddy diffusion of component c in flux form, the diagonal part div(nu_t grad q) of the stress:
 * out = q + dt / h^2 * sum over the six neighbours of nu_edge (q_nb - q), where nu_edge is the mean of the
 * nu_face of the face and of its neighbour, and nu_face the mean of the two cells sharing a face. Each pair
 * of faces exchanges the same flux, so the stage conserves momentum. The neighbours outside the array are
 * fetch_face's ghosts (the constant-viscosity stage's rules), resolved once per row along y and z and at the
 * two ends of a row along x; the nu of a face outside the array is that of its wrapped or clamped cells.
 * With wall_slip set, a horizontal face whose neighbour below touches a solid cell exchanges nothing with it
 * (a zero gradient): the wall stress stage carries that momentum flux. Writes row (j, k) of component c
 * into out, which must not be q. */
FW_INLINE void diffuse_eddy_row(const FwGrid* g, const FwStep* s, __global const float* profile, const int c,
                                const int wall_slip, __global const uchar* mask, __global const float* nu,
                                __global const float* q, __global float* out, const int j, const int k) {
  const EddyRows r = eddy_rows(g, s, profile, q, c, wall_slip, j, k);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(face_extent(g, c, 0));
  /* A row next to an inflow face along y or z (rare) takes the general path throughout. */
  if (r.any_inflow) {
    for (int i = begin; i < end; ++i)
      out[r.at + i] = eddy_face(g, s, profile, c, &r, mask, nu, q, i, j, k, 1, 1);
    return;
  }
  /* Faces 2 .. nx-2 need no wrap: their neighbours' cells i-2 .. i+1 lie inside the row. */
  const int first = clamp(2, begin, end), last = clamp(g->nx - 1, first, end);
  for (int i = begin; i < first; ++i)
    out[r.at + i] = eddy_face(g, s, profile, c, &r, mask, nu, q, i, j, k, 1, 0);
  for (int i = first; i < last; ++i)
    out[r.at + i] = eddy_face(g, s, profile, c, &r, mask, nu, q, i, j, k, 0, 0);
  for (int i = last; i < end; ++i)
    out[r.at + i] = eddy_face(g, s, profile, c, &r, mask, nu, q, i, j, k, 1, 0);
}

/* One kernel a component, so that c is a literal and the selects above fold away (one kernel doing the
 * three components' rows that share cells measured 10% slower than these three). Global range: rows over
 * the component's faces. */
#define FW_DIFFUSE_EDDY_KERNEL(name, c)                                                                    \
  __kernel void name(const FwGrid g, const FwStep s, __global const float* profile, const int wall_slip,   \
                     __global const uchar* restrict mask, __global const float* restrict nu,               \
                     __global const float* restrict q, __global float* restrict out) {                     \
    FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));                    \
    diffuse_eddy_row(&g, &s, profile, c, wall_slip, mask, nu, q, out, get_global_id(1), get_global_id(2)); \
  }
FW_DIFFUSE_EDDY_KERNEL(diffuse_eddy_u, 0)
FW_DIFFUSE_EDDY_KERNEL(diffuse_eddy_v, 1)
FW_DIFFUSE_EDDY_KERNEL(diffuse_eddy_w, 2)
#undef FW_DIFFUSE_EDDY_KERNEL

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
