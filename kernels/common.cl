/* Indexing, work-item mapping and interpolation shared by every fluid kernel.
 *
 * Work mapping: a kernel over an array of extent_x * ny * nz values runs on a global range
 * (ceil(extent_x / FW_ROW_CHUNK), ny, nz); each work-item walks FW_ROW_CHUNK consecutive values along x.
 * The host sets FW_ROW_CHUNK to a whole row on CPUs (streams memory best under PoCL) and to 1 on GPUs.
 *
 * Positions are in cell units: world = origin + h * X. Component c of the velocity sits on faces whose own
 * coordinate is an integer and whose other two coordinates are half-integers.
 */
#include "shared_types.h"

/* Helpers must inline: PoCL otherwise keeps large ones as calls, which blocks vectorisation. */
#define FW_INLINE inline __attribute__((always_inline))

#ifndef FW_ROW_CHUNK
#define FW_ROW_CHUNK 1
#endif

/* First and one-past-last x index of this work-item's run. */
#define FW_ROW_BEGIN ((int)get_global_id(0) * FW_ROW_CHUNK)
#define FW_ROW_END(extent_x) min(FW_ROW_BEGIN + FW_ROW_CHUNK, (extent_x))

/* Index of this work-item among all work-items, for per-item partial sums. */
FW_INLINE int row_item_index(void) {
  return (int)get_global_id(0) +
         (int)get_global_size(0) * ((int)get_global_id(1) + (int)get_global_size(1) * (int)get_global_id(2));
}

FW_INLINE int axis_cells(const FwGrid* g, int a) {
  return a == 0 ? g->nx : (a == 1 ? g->ny : g->nz);
}

FW_INLINE int face_extent(const FwGrid* g, int c, int a) {
  return axis_cells(g, a) + (c == a ? 1 : 0);
}

FW_INLINE int face_index(const FwGrid* g, int c, int i, int j, int k) {
  const int ex = g->nx + (c == 0 ? 1 : 0);
  const int ey = g->ny + (c == 1 ? 1 : 0);
  return i + ex * (j + ey * k);
}

FW_INLINE int cell_index(const FwGrid* g, int i, int j, int k) {
  return i + g->nx * (j + g->ny * k);
}

FW_INLINE float face_offset(int c, int a) {
  return c == a ? 0.0f : 0.5f;
}

/* Value of component c at face index (i,j,k), which may lie outside the array. Periodic axes wrap; an inflow
 * face gives the ambient profile; a no-slip wall mirrors tangential components with a flipped sign (zero at
 * the wall); other walls and outflow repeat the edge value. Mirrors fluid/ReferenceStages.cpp fetch(). */
FW_INLINE float fetch_face(__global const float* q, int c, int i, int j, int k, const FwGrid* g,
                           const FwStep* s, __global const float* profile) {
  int idx[3] = {i, j, k};
  float sign = 1.0f;
  for (int a = 0; a < 3; ++a) {
    const int ext = face_extent(g, c, a);
    if (idx[a] >= 0 && idx[a] < ext) continue;
    const int low = idx[a] < 0;
    const int bc = g->bc[2 * a + (low ? 0 : 1)];
    const int n = axis_cells(g, a);
    if (bc == FW_BC_PERIODIC) {
      idx[a] = ((idx[a] % n) + n) % n;
      continue;
    }
    if (bc == FW_BC_INFLOW) return s->ambient[c] * profile[clamp(idx[2], 0, g->nz - 1)];
    if (bc == FW_BC_NO_SLIP && a != c) {
      idx[a] = low ? (-1 - idx[a]) : (2 * ext - 1 - idx[a]);
      sign = -sign;
    }
    idx[a] = clamp(idx[a], 0, ext - 1);
  }
  return sign * q[face_index(g, c, idx[0], idx[1], idx[2])];
}

/* Grid coordinate of position p along axis a for component c: lower corner index and fraction. */
FW_INLINE void face_coordinate(const FwGrid* g, int c, int a, float p, int* i0, float* fraction) {
  const int n = axis_cells(g, a);
  const int periodic = g->bc[2 * a] == FW_BC_PERIODIC;
  if (periodic) {
    /* Back-traces move less than one period: a compare beats floor and a division here. */
    if (p < 0.0f) p += n;
    if (p >= n) p -= n;
    p = clamp(p, 0.0f, (float)n);
  }
  float q = p - face_offset(c, a);
  if (!periodic) q = clamp(q, -1.0f, (float)face_extent(g, c, a));
  /* q >= -1 here, so truncation of q + 4 is floor(q) + 4 (truncation vectorises, floor is a call). */
  const int fl = (int)(q + 4.0f) - 4;
  *i0 = fl;
  *fraction = q - (float)fl;
}

/* Trilinear interpolation of component c at (X, Y, Z) in cell units. */
FW_INLINE float sample_face(__global const float* q, int c, float X, float Y, float Z, const FwGrid* g,
                            const FwStep* s, __global const float* profile) {
  int i0, j0, k0;
  float fx, fy, fz;
  face_coordinate(g, c, 0, X, &i0, &fx);
  face_coordinate(g, c, 1, Y, &j0, &fy);
  face_coordinate(g, c, 2, Z, &k0, &fz);
  const int ex = face_extent(g, c, 0), ey = face_extent(g, c, 1), ez = face_extent(g, c, 2);
  float v000, v100, v010, v110, v001, v101, v011, v111;
  if (i0 >= 0 && j0 >= 0 && k0 >= 0 && i0 + 1 < ex && j0 + 1 < ey && k0 + 1 < ez) {
    /* Interior: all eight corners are stored values. */
    const int base = i0 + ex * (j0 + ey * k0);
    const int sy = ex, sz = ex * ey;
    v000 = q[base];
    v100 = q[base + 1];
    v010 = q[base + sy];
    v110 = q[base + sy + 1];
    v001 = q[base + sz];
    v101 = q[base + sz + 1];
    v011 = q[base + sz + sy];
    v111 = q[base + sz + sy + 1];
  } else {
    v000 = fetch_face(q, c, i0, j0, k0, g, s, profile);
    v100 = fetch_face(q, c, i0 + 1, j0, k0, g, s, profile);
    v010 = fetch_face(q, c, i0, j0 + 1, k0, g, s, profile);
    v110 = fetch_face(q, c, i0 + 1, j0 + 1, k0, g, s, profile);
    v001 = fetch_face(q, c, i0, j0, k0 + 1, g, s, profile);
    v101 = fetch_face(q, c, i0 + 1, j0, k0 + 1, g, s, profile);
    v011 = fetch_face(q, c, i0, j0 + 1, k0 + 1, g, s, profile);
    v111 = fetch_face(q, c, i0 + 1, j0 + 1, k0 + 1, g, s, profile);
  }
  const float x00 = v000 + fx * (v100 - v000);
  const float x10 = v010 + fx * (v110 - v010);
  const float x01 = v001 + fx * (v101 - v001);
  const float x11 = v011 + fx * (v111 - v011);
  const float y0 = x00 + fy * (x10 - x00);
  const float y1 = x01 + fy * (x11 - x01);
  return y0 + fz * (y1 - y0);
}

/* Back-traced position of face (i,j,k) of component c through (u, v, w) over dt (explicit midpoint).
 * dt may be negative (forward trace, used by MacCormack). */
FW_INLINE float3 backtrace_face(int c, int i, int j, int k, float dt, __global const float* u,
                                __global const float* v, __global const float* w, const FwGrid* g,
                                const FwStep* s, __global const float* profile) {
  const float3 P = (float3)(i + face_offset(c, 0), j + face_offset(c, 1), k + face_offset(c, 2));
  const float scale = dt / g->h; /* m/s -> cells */
  float3 V = (float3)(sample_face(u, 0, P.x, P.y, P.z, g, s, profile),
                      sample_face(v, 1, P.x, P.y, P.z, g, s, profile),
                      sample_face(w, 2, P.x, P.y, P.z, g, s, profile));
  const float3 M = P - 0.5f * scale * V;
  V = (float3)(sample_face(u, 0, M.x, M.y, M.z, g, s, profile),
               sample_face(v, 1, M.x, M.y, M.z, g, s, profile),
               sample_face(w, 2, M.x, M.y, M.z, g, s, profile));
  return P - scale * V;
}

/* Index along its own axis of face (i,j,k) of component c. */
FW_INLINE int own_index(int c, int i, int j, int k) {
  return c == 0 ? i : (c == 1 ? j : k);
}

/* Stride of the cell array along axis c. */
FW_INLINE int cell_stride(const FwGrid* g, int c) {
  return c == 0 ? 1 : (c == 1 ? g->nx : g->nx * g->ny);
}

/* Index of the cell at face (i,j,k) of component c, clamped into the grid along c: the cell above the face,
 * or for the domain's high boundary face the cell below it. */
FW_INLINE int face_cell(const FwGrid* g, int c, int i, int j, int k) {
  return cell_index(g, min(i, g->nx - 1), min(j, g->ny - 1), min(k, g->nz - 1));
}

/* Is face (i,j,k) of component c open in the pressure mask? The cell on the low side owns the face through
 * its high bit; the domain's low boundary face belongs to cell 0 through its low bit. */
FW_INLINE int face_open(const FwGrid* g, __global const uchar* mask, int c, int i, int j, int k) {
  const int own = own_index(c, i, j, k);
  const int n = axis_cells(g, c);
  if (own == 0) return (mask[face_cell(g, c, i, j, k)] >> (2 * c)) & 1;
  const int owner = own == n ? face_cell(g, c, i, j, k) : face_cell(g, c, i, j, k) - cell_stride(g, c);
  return (mask[owner] >> (2 * c + 1)) & 1;
}

/* Flat loops over n values: contiguous blocks per work-item on CPUs, a grid-stride loop on GPUs. */
#if FW_CPU_LAYOUT
#define FW_FLAT_FOR(idx, n)                                         \
  const size_t fw_items_ = get_global_size(0);                      \
  const size_t fw_per_ = ((size_t)(n) + fw_items_ - 1) / fw_items_; \
  const size_t fw_begin_ = get_global_id(0) * fw_per_;              \
  const size_t fw_end_ = min((size_t)(n), fw_begin_ + fw_per_);     \
  for (size_t idx = fw_begin_; idx < fw_end_; ++idx)
#else
#define FW_FLAT_FOR(idx, n) for (size_t idx = get_global_id(0); idx < (size_t)(n); idx += get_global_size(0))
#endif

/* Padded copies of a velocity component carry FW_PAD ghost layers on every side, filled by fetch_face's
 * rules (kernels/fluid_ghosts.cl), so that interpolation needs no boundary logic in its inner loop. */
#define FW_PAD 2

FW_INLINE int padded_extent(const FwGrid* g, int c, int a) {
  return face_extent(g, c, a) + 2 * FW_PAD;
}

FW_INLINE int padded_index(const FwGrid* g, int c, int i, int j, int k) {
  return (i + FW_PAD) + padded_extent(g, c, 0) * ((j + FW_PAD) + padded_extent(g, c, 1) * (k + FW_PAD));
}
