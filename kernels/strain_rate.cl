/* The resolved strain rate of the wind grid at cell centres, shared by the subgrid models
 * (subgrid_stress.cl: Smagorinsky; subgrid_tke.cl: the subgrid energy's production): 2 S_ij S_ij with
 * S_ij = (d_j u_i + d_i u_j) / 2 from central differences of the cell-centred velocity over 2h, one-sided
 * over h at a non-periodic edge, wrapped across a periodic one (through the face indices, so that the
 * unpadded arrays serve). Reference: fluid::reference::strain_rate_squared. A kernel resolves a row's
 * StrainRows once (strain_rows, with difference_offsets along y and z) and then asks per cell. */
#include "common.cl"

/* Where a derivative along an axis of n cells looks at index x: one cell up (*plus = 1) and down
 * (*minus = 1), or the cell itself (0) at a non-periodic edge, where the difference turns one-sided; across a
 * periodic seam the face indices wrap. *inverse = 1 / (span h), 0 for a single cell along a non-periodic
 * axis. */
FW_INLINE void difference_offsets(int x, int n, int periodic, float h, int* plus, int* minus,
                                  float* inverse) {
  *plus = (x + 1 < n || periodic) ? 1 : 0;
  *minus = (x > 0 || periodic) ? 1 : 0;
  const int span = *plus + *minus;
  *inverse = span > 0 ? 1.0f / ((float)span * h) : 0.0f;
}

/* The x index of a face of component c up to two faces outside its row: wrapped on a periodic x axis
 * (one step of nx, without the integer division of a general modulo). The strain's differences never
 * leave a row along a non-periodic axis. */
FW_INLINE int wrap_face_x(const FwGrid* g, int c, int x) {
  return x < 0 ? x + g->nx : (x >= face_extent(g, c, 0) ? x - g->nx : x);
}

/* The face rows of component c that hold the two faces along c of the cells of row (jy, kz): a cell's
 * centre value is 0.5 (q[lo + x] + q[hi + x + (c == 0)]). Only periodic axes take the rows outside. */
typedef struct {
  int lo, hi;
} CentreRows;

FW_INLINE CentreRows centre_rows(const FwGrid* g, int c, int jy, int kz) {
  CentreRows r;
  float sign;
  resolve_face_row(g, c, jy, kz, &r.lo, &sign);
  resolve_face_row(g, c, jy + (c == 1), kz + (c == 2), &r.hi, &sign);
  return r;
}

/* What the strain of the cells of row (j, k) reads for component c: the cells' own rows (for the difference
 * along x), the rows of the cells up and down y and z (difference_offsets), and the inverse spans along y
 * and z. */
typedef struct {
  CentreRows own, y_up, y_down, z_up, z_down;
} StrainRows;

FW_INLINE StrainRows strain_rows(const FwGrid* g, int c, int j, int k, int py, int my, int pz, int mz) {
  StrainRows r;
  r.own = centre_rows(g, c, j, k);
  r.y_up = centre_rows(g, c, j + py, k);
  r.y_down = centre_rows(g, c, j - my, k);
  r.z_up = centre_rows(g, c, j, k + pz);
  r.z_down = centre_rows(g, c, j, k - mz);
  return r;
}

/* Difference of the centre values of component c between cells x_up of rows `up` and x_down of rows
 * `down`, times `inverse`; with wrap set, the face indices wrap along a periodic x axis. */
FW_INLINE float centre_difference(const FwGrid* g, __global const float* q, int c, int wrap, CentreRows up,
                                  int x_up, CentreRows down, int x_down, float inverse) {
  const int ci = c == 0;
  int up_lo = x_up, up_hi = x_up + ci, down_lo = x_down, down_hi = x_down + ci;
  if (wrap) {
    up_lo = wrap_face_x(g, c, up_lo);
    up_hi = wrap_face_x(g, c, up_hi);
    down_lo = wrap_face_x(g, c, down_lo);
    down_hi = wrap_face_x(g, c, down_hi);
  }
  return 0.5f * ((q[up.lo + up_lo] + q[up.hi + up_hi]) - (q[down.lo + down_lo] + q[down.hi + down_hi])) *
         inverse;
}

/* d q_c / d x_a at cell i of row (j, k) for a = x, y, z, from its StrainRows: along x between cells i + px
 * and i - mx (wrapped with wrap set), along y and z between the rows' cells i. */
FW_INLINE void velocity_gradient(const FwGrid* g, __global const float* q, int c, const StrainRows* r, int i,
                                 int wrap, int px, int mx, float ix, float iy, float iz, float* d_x,
                                 float* d_y, float* d_z) {
  *d_x = centre_difference(g, q, c, wrap, r->own, i + px, r->own, i - mx, ix);
  *d_y = centre_difference(g, q, c, 0, r->y_up, i, r->y_down, i, iy);
  *d_z = centre_difference(g, q, c, 0, r->z_up, i, r->z_down, i, iz);
}

/* 2 S_ij S_ij (1/s^2) of cell i of row (j, k) from its StrainRows: the diagonal twice, each off-diagonal
 * pair (d_ij + d_ji)^2 once. */
FW_INLINE float strain_rate_squared(const FwGrid* g, const StrainRows* ru, const StrainRows* rv,
                                    const StrainRows* rw, __global const float* u, __global const float* v,
                                    __global const float* w, int i, int wrap, int px, int mx, float ix,
                                    float iy, float iz) {
  float du_x, du_y, du_z, dv_x, dv_y, dv_z, dw_x, dw_y, dw_z;
  velocity_gradient(g, u, 0, ru, i, wrap, px, mx, ix, iy, iz, &du_x, &du_y, &du_z);
  velocity_gradient(g, v, 1, rv, i, wrap, px, mx, ix, iy, iz, &dv_x, &dv_y, &dv_z);
  velocity_gradient(g, w, 2, rw, i, wrap, px, mx, ix, iy, iz, &dw_x, &dw_y, &dw_z);
  const float sxy = du_y + dv_x, sxz = du_z + dw_x, syz = dv_z + dw_y;
  return 2.0f * (du_x * du_x + dv_y * dv_y + dw_z * dw_z) + sxy * sxy + sxz * sxz + syz * syz;
}
