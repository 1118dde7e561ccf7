/* Prescribed face velocities. Reference: fluid/ReferenceStages.cpp enforce_boundaries. */
#include "common.cl"

/* Faces open in the pressure mask are left to the projection. Every other face gets its prescribed value:
 * the ambient profile on inflow faces beside a fluid cell, 0 on walls and on faces touching a solid.
 * The high face of a periodic axis repeats the low one (computed from the low face's inputs, not its
 * output, so no work-item reads what another writes). */
__kernel void enforce_boundaries(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                                 __global const uchar* mask, __global float* q) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  const int n = axis_cells(&g, c);
  const int periodic = g.bc[2 * c] == FW_BC_PERIODIC;
  const float inflow_value = s.ambient[c] * profile[min(k, g.nz - 1)];
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const int own = own_index(c, i, j, k);
    const int id = face_index(&g, c, i, j, k);
    if (periodic && own == n) {
      /* The low twin: same (i,j,k) with the own index 0. */
      const int li = c == 0 ? 0 : i, lj = c == 1 ? 0 : j, lk = c == 2 ? 0 : k;
      q[id] = face_open(&g, mask, c, li, lj, lk) ? q[face_index(&g, c, li, lj, lk)] : 0.0f;
      continue;
    }
    if (face_open(&g, mask, c, i, j, k)) continue;
    float value = 0.0f;
    if ((own == 0 || own == n) && !periodic) {
      const int face = 2 * c + (own == 0 ? 0 : 1);
      const int fluid = mask[face_cell(&g, c, i, j, k)] & FW_MASK_FLUID;
      if (g.bc[face] == FW_BC_INFLOW && fluid) value = inflow_value;
    }
    q[id] = value;
  }
}
