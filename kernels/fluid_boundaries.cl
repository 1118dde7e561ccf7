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
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    int idx[3] = {i, j, k};
    const int id = face_index(&g, c, i, j, k);
    if (periodic && idx[c] == n) {
      idx[c] = 0;
      const int low_open = face_open(&g, mask, c, idx[0], idx[1], idx[2]);
      q[id] = low_open ? q[face_index(&g, c, idx[0], idx[1], idx[2])] : 0.0f;
      continue;
    }
    if (face_open(&g, mask, c, i, j, k)) continue;
    float value = 0.0f;
    if ((idx[c] == 0 || idx[c] == n) && !periodic) {
      const int face = 2 * c + (idx[c] == 0 ? 0 : 1);
      int cell[3] = {i, j, k};
      cell[c] = idx[c] == 0 ? 0 : n - 1;
      const int fluid = mask[cell_index(&g, cell[0], cell[1], cell[2])] & FW_MASK_FLUID;
      if (g.bc[face] == FW_BC_INFLOW && fluid) value = s.ambient[c] * profile[clamp(k, 0, g.nz - 1)];
    }
    q[id] = value;
  }
}
