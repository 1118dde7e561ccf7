/* Ghost layers: a padded copy of one velocity component, FW_PAD extra layers on every side, filled by the
 * boundary rules of fetch_face (periodic wrap, inflow profile, no-slip mirror, edge repeat).
 * Global range: rows over the padded array. */
#include "common.cl"

__kernel void pad_component(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                            __global const float* q, __global float* padded) {
  const int px = padded_extent(&g, c, 0);
  const int j = (int)get_global_id(1) - FW_PAD, k = (int)get_global_id(2) - FW_PAD;
  const int ex = face_extent(&g, c, 0), ey = face_extent(&g, c, 1), ez = face_extent(&g, c, 2);
  const int inside_jk = j >= 0 && j < ey && k >= 0 && k < ez;
  for (int ip = FW_ROW_BEGIN; ip < FW_ROW_END(px); ++ip) {
    const int i = ip - FW_PAD;
    const float value = (inside_jk && i >= 0 && i < ex) ? q[face_index(&g, c, i, j, k)]
                                                        : fetch_face(q, c, i, j, k, &g, &s, profile);
    padded[padded_index(&g, c, i, j, k)] = value;
  }
}
