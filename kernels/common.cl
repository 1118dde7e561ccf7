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
#define FW_INLINE static inline __attribute__((always_inline))

#ifndef FW_ROW_CHUNK
#define FW_ROW_CHUNK 1
#endif

/* First and one-past-last x index of this work-item's run. */
#define FW_ROW_BEGIN ((int)get_global_id(0) * FW_ROW_CHUNK)
#define FW_ROW_END(extent_x) min(FW_ROW_BEGIN + FW_ROW_CHUNK, (extent_x))

/* The host rounds every range up to whole work-groups (host/runtime/ComputeContext.hpp), so a kernel over
 * an array of extent_x * extent_y * extent_z values first sends the items past it home: past the rows (y)
 * or planes (z), or with a run that starts past the row's end (x). Not in a reduction, whose items must all
 * reach the group's barriers (FW_REDUCTION_ROW_END). */
#define FW_ROWS_GUARD(extent_x, extent_y, extent_z)                        \
  if (FW_ROW_BEGIN >= (extent_x) || (int)get_global_id(1) >= (extent_y) || \
      (int)get_global_id(2) >= (extent_z))                                 \
  return

/* Maxima leave one partial per work-group (host/runtime/ComputeContext.hpp): the host launches them on a
 * range padded to whole groups of FW_GROUP_X x FW_GROUP_Y x 1 items, a power of two in all. Items past the
 * array do no work but must reach the group's reduction: a reduction kernel never returns early. (Sums
 * leave column sums instead, which the host adds exactly: fluid_pressure.cl.) */
#ifndef FW_GROUP_X
#define FW_GROUP_X 1
#endif
#ifndef FW_GROUP_Y
#define FW_GROUP_Y 1
#endif
#define FW_GROUP_ITEMS (FW_GROUP_X * FW_GROUP_Y)

/* The local memory a group reduction needs; declared at kernel scope, as OpenCL C 1.2 asks. */
#define FW_GROUP_SCRATCH __local float fw_group_scratch[FW_GROUP_ITEMS]

/* Index of this work-group among all groups: where its partial goes. */
FW_INLINE int group_index(void) {
  return (int)get_group_id(0) +
         (int)get_num_groups(0) * ((int)get_group_id(1) + (int)get_num_groups(1) * (int)get_group_id(2));
}

/* One past the last x index of this item's run in a reduction kernel: its run (FW_ROW_END), or an empty one
 * when its row j lies past the array's extent_y rows (the range's y is padded to whole groups). */
#define FW_REDUCTION_ROW_END(extent_x, extent_y) \
  ((int)get_global_id(1) < (extent_y) ? FW_ROW_END(extent_x) : FW_ROW_BEGIN)

/* Writes to partial[group] the maximum of every item's value (NaN wins, so a blow-up is seen), as a tree. */
FW_INLINE void write_group_max(float value, __local float* scratch, __global float* partial) {
  const int l = (int)get_local_id(0) + (int)get_local_size(0) * (int)get_local_id(1);
  scratch[l] = value;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = FW_GROUP_ITEMS / 2; stride > 0; stride >>= 1) {
    if (l < stride) {
      const float a = scratch[l], b = scratch[l + stride];
      scratch[l] = (b > a || isnan(b)) && !isnan(a) ? b : a;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0) partial[group_index()] = scratch[0];
}
#define FW_GROUP_MAX(value, partial) write_group_max((value), fw_group_scratch, (partial))

FW_INLINE int axis_cells(const FwGrid* g, int a) {
  return a == 0 ? g->nx : (a == 1 ? g->ny : g->nz);
}

/* 1 where axis a wraps: its cell n - 1 and cell 0 are neighbours across the seam. */
FW_INLINE int axis_periodic(const FwGrid* g, int a) {
  return g->bc[2 * a] == FW_BC_PERIODIC;
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

/* The inflow profile factor at height index k (clamped to the array). */
FW_INLINE float inflow_shape(const FwGrid* g, __global const float* inflow, int k) {
  return inflow[clamp(k, 0, g->nz - 1)];
}

/* Where the prescribed shell (kernels/shared_types.h) starts in `inflow`: after the profile and the box. */
FW_INLINE int inflow_shell_start(const FwGrid* g, const FwStep* s) {
  return g->nz + 3 * s->turbulence_cells[0] * s->turbulence_cells[1] * s->turbulence_cells[2];
}

/* The shell index of face index (i, j, k) of component c in the blocks of domain face f, or -1 where they do
 * not hold it. */
FW_INLINE int inflow_shell_index(const FwGrid* g, int f, int c, int i, int j, int k) {
  const int a = f / 2, b1 = a == 0 ? 1 : 0, b2 = a == 2 ? 1 : 2;
  const int at[3] = {i, j, k};
  const int layer = (f & 1) ? at[a] - (face_extent(g, c, a) - 1) : at[a] + FW_PAD;
  const int t1 = at[b1] + FW_PAD, t2 = at[b2] + FW_PAD;
  const int span1 = fw_shell_span(axis_cells(g, b1)), span2 = fw_shell_span(axis_cells(g, b2));
  if (layer < 0 || layer >= FW_SHELL_LAYERS || t1 < 0 || t1 >= span1 || t2 < 0 || t2 >= span2) return -1;
  return fw_shell_face_offset(g->nx, g->ny, g->nz, f) + c * fw_shell_block(g->nx, g->ny, g->nz, a) + t1 +
         span1 * (t2 + span2 * layer);
}

/* The prescribed value of component c at face index (i, j, k) (an inflow face of the normal component, or a
 * ghost beyond an inflow face): the ambient profile at height index k, plus, with the turbulence on, its
 * sample at the face, read from the shell of the first inflow face (in x, y, z order) that holds the face
 * (kernels/inflow_shell.cl fills it once per step). Every face a kernel asks for lies within FW_PAD of the
 * array, which the shell holds; one it does not hold comes back NaN, so that the blow-up check names it.
 * Mirrors fluid::InflowState::value(). */
FW_INLINE float inflow_face_value(const FwGrid* g, const FwStep* s, __global const float* inflow, int c,
                                  int i, int j, int k) {
  if (s->turbulence_sigma == 0.0f) return s->ambient[c] * inflow_shape(g, inflow, k);
  for (int f = 0; f < 6; ++f) {
    if (g->bc[f] != FW_BC_INFLOW) continue;
    const int at = inflow_shell_index(g, f, c, i, j, k);
    if (at >= 0) return inflow[inflow_shell_start(g, s) + at];
  }
  return NAN;
}

/* Resolves the index *x of component c along axis a, which may lie outside the array, by the boundary
 * rules of fetch_face: wrapped on a periodic axis, mirrored with a flipped *sign at a no-slip wall for a
 * tangential component, else clamped to the edge value. Returns 1, leaving *x alone, where that side of the
 * axis is an inflow (the value is then the prescribed one). */
FW_INLINE int resolve_face_axis(const FwGrid* g, int c, int a, int* x, float* sign) {
  const int ext = face_extent(g, c, a);
  if (*x >= 0 && *x < ext) return 0;
  const int low = *x < 0;
  const int bc = g->bc[2 * a + (low ? 0 : 1)];
  const int n = axis_cells(g, a);
  if (bc == FW_BC_PERIODIC) {
    *x = ((*x % n) + n) % n;
    return 0;
  }
  if (bc == FW_BC_INFLOW) return 1;
  if (bc == FW_BC_NO_SLIP && a != c) {
    *x = low ? (-1 - *x) : (2 * ext - 1 - *x);
    *sign = -*sign;
  }
  *x = clamp(*x, 0, ext - 1);
  return 0;
}

/* The index of face (0, jy, kz) of component c, the y and z indices resolved by fetch_face's rules: in the
 * array, or wrapped on a periodic axis (*sign = -1 where a no-slip wall mirrors the row, else 1). Returns 1
 * where the row lies across an inflow face (its values are then prescribed, inflow_face_value). */
FW_INLINE int resolve_face_row(const FwGrid* g, int c, int jy, int kz, int* row, float* sign) {
  *sign = 1.0f;
  if (resolve_face_axis(g, c, 1, &jy, sign) || resolve_face_axis(g, c, 2, &kz, sign)) return 1;
  *row = face_index(g, c, 0, jy, kz);
  return 0;
}

/* Value of component c at face index (i,j,k), which may lie outside the array. Periodic axes wrap; an inflow
 * face gives the ambient profile (and the inflow turbulence); a no-slip wall mirrors tangential components
 * with a flipped sign (zero at the wall); other walls and outflow repeat the edge value. The axes resolve
 * in order x, y, z. `profile` is the inflow buffer of inflow_face_value. Mirrors
 * fluid/ReferenceStages.cpp fetch(). */
FW_INLINE float fetch_face(__global const float* q, int c, int i, int j, int k, const FwGrid* g,
                           const FwStep* s, __global const float* profile) {
  int idx[3] = {i, j, k};
  float sign = 1.0f;
  for (int a = 0; a < 3; ++a)
    if (resolve_face_axis(g, c, a, &idx[a], &sign)) return inflow_face_value(g, s, profile, c, i, j, k);
  return sign * q[face_index(g, c, idx[0], idx[1], idx[2])];
}

/* Component c of the MAC velocity at X (cell units of the domain, world = origin + h X), for point samples
 * (trees, probes, leaves): trilinear on the component's own staggered lattice, the position clamped to the
 * domain's lattice (constant beyond its outermost faces). On a rank's block the corners and fractions are the
 * whole grid's, and only the corners' indices come back into the block's arrays (by ox, oy), so a block
 * holding a point's corners in its cells or halo samples the bits one process would. */
FW_INLINE float sample_mac_component(const FwGrid* g, __global const float* q, int c, const float X[3]) {
  int lo[3], hi[3];
  float t[3];
  for (int a = 0; a < 3; ++a) {
    const int extent = (a < 2 ? g->domain[a] : g->nz) + (c == a ? 1 : 0);
    const int offset = a == 0 ? g->ox : (a == 1 ? g->oy : 0);
    const float x = clamp(X[a] - face_offset(c, a), 0.0f, (float)(extent - 1));
    const int first = min((int)x, extent - 1);
    t[a] = x - (float)first;
    lo[a] = first - offset;
    hi[a] = min(first + 1, extent - 1) - offset;
  }
  const float c00 =
      mix(q[face_index(g, c, lo[0], lo[1], lo[2])], q[face_index(g, c, hi[0], lo[1], lo[2])], t[0]);
  const float c10 =
      mix(q[face_index(g, c, lo[0], hi[1], lo[2])], q[face_index(g, c, hi[0], hi[1], lo[2])], t[0]);
  const float c01 =
      mix(q[face_index(g, c, lo[0], lo[1], hi[2])], q[face_index(g, c, hi[0], lo[1], hi[2])], t[0]);
  const float c11 =
      mix(q[face_index(g, c, lo[0], hi[1], hi[2])], q[face_index(g, c, hi[0], hi[1], hi[2])], t[0]);
  return mix(mix(c00, c10, t[1]), mix(c01, c11, t[1]), t[2]);
}

/* The drag law's factor C_D(|u|) / C_D0 at `speed` (m/s): 1 for the constant coefficient. */
FW_INLINE float drag_law_factor(const FwDragLaw law, float speed) {
  return law.exponent == 0.0f
             ? 1.0f
             : powr(fmax(speed, law.lowest_speed) * law.inverse_reference_speed, law.exponent);
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

/* Splits this work-item's run [begin, end) of face row (j, k) of component c into edge faces and a run
 * [lo, hi) of interior faces: faces with a fluid-or-solid cell on both sides inside the domain, so that
 * the face is owned by the cell below it along c and needs no boundary logic. */
FW_INLINE void interior_face_span(const FwGrid* g, int c, int j, int k, int begin, int end, int* lo,
                                  int* hi) {
  int first = 0, last = end; /* interior range of i for this row, before clipping to [begin, end) */
  if (c == 0) {
    first = 1;
    last = g->nx; /* faces 1 .. nx-1 */
  } else if ((c == 1 && (j == 0 || j == g->ny)) || (c == 2 && (k == 0 || k == g->nz))) {
    first = last = end; /* a boundary row: everything goes the general way */
  }
  *lo = clamp(first, begin, end);
  *hi = clamp(last, *lo, end);
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

/* Padded copies of a velocity component carry FW_PAD (kernels/shared_types.h) ghost layers on every side,
 * filled by fetch_face's rules (kernels/fluid_ghosts.cl), so that interpolation needs no boundary logic in
 * its inner loop. */

FW_INLINE int padded_extent(const FwGrid* g, int c, int a) {
  return face_extent(g, c, a) + 2 * FW_PAD;
}

FW_INLINE int padded_index(const FwGrid* g, int c, int i, int j, int k) {
  return (i + FW_PAD) + padded_extent(g, c, 0) * ((j + FW_PAD) + padded_extent(g, c, 1) * (k + FW_PAD));
}
