/* Prescribed face velocities. Reference: fluid/ReferenceStages.cpp enforce_boundaries. */
#include "common.cl"

/* Faces open in the pressure mask are left to the projection. Every other face gets its prescribed value:
 * the ambient profile (and the inflow turbulence) on inflow faces beside a fluid cell, 0 on walls and on
 * faces touching a solid. The high face of a periodic axis repeats the low one (computed from the low face's
 * inputs, not its output, so no work-item reads what another writes). */
/* The prescribed value of one face with the general rules, or its current value if it is open. */
FW_INLINE float boundary_face(const FwGrid* g, const FwStep* s, int c, __global const uchar* mask,
                              __global const float* q, __global const float* inflow, int i, int j, int k) {
  const int own = own_index(c, i, j, k);
  const int n = axis_cells(g, c);
  const int periodic = g->bc[2 * c] == FW_BC_PERIODIC;
  if (periodic && own == n) {
    /* The low twin: same (i,j,k) with the own index 0. */
    const int li = c == 0 ? 0 : i, lj = c == 1 ? 0 : j, lk = c == 2 ? 0 : k;
    return face_open(g, mask, c, li, lj, lk) ? q[face_index(g, c, li, lj, lk)] : 0.0f;
  }
  if (face_open(g, mask, c, i, j, k)) return q[face_index(g, c, i, j, k)];
  if ((own == 0 || own == n) && !periodic) {
    const int face = 2 * c + (own == 0 ? 0 : 1);
    const int fluid = mask[face_cell(g, c, i, j, k)] & FW_MASK_FLUID;
    if (g->bc[face] == FW_BC_INFLOW && fluid) return inflow_face_value(g, s, inflow, c, i, j, k);
  }
  return 0.0f;
}

__kernel void enforce_boundaries(const FwGrid g, const FwStep s, __global const float* inflow, const int c,
                                 __global const uchar* mask, __global float* q) {
  FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(face_extent(&g, c, 0));
  const int sc = cell_stride(&g, c), bit = 2 * c + 1;
  int lo, hi;
  interior_face_span(&g, c, j, k, begin, end, &lo, &hi);
  for (int i = begin; i < lo; ++i)
    q[face_index(&g, c, i, j, k)] = boundary_face(&g, &s, c, mask, q, inflow, i, j, k);
  for (int i = lo; i < hi; ++i) { /* interior: closed faces touch a solid and carry its zero velocity */
    const int id = face_index(&g, c, i, j, k);
    q[id] = ((mask[cell_index(&g, i, j, k) - sc] >> bit) & 1) ? q[id] : 0.0f;
  }
  for (int i = hi; i < end; ++i)
    q[face_index(&g, c, i, j, k)] = boundary_face(&g, &s, c, mask, q, inflow, i, j, k);
}
