/* Ghost layers: a padded copy of one velocity component, FW_PAD extra layers on every side, filled by the
 * boundary rules of fetch_face (periodic wrap, inflow profile, no-slip mirror, edge repeat).
 *
 * A padded row (j, k) resolves its y and z indices once (resolve_face_row, in fetch_face's order), so that
 * the part of the row inside the array along x is a plain signed copy of one source row, which streams with
 * vector loads; only the FW_PAD ghosts at either end of a row resolve x per value. This gives exactly
 * fetch_face's value everywhere. Global range: rows over the padded array. */
#include "common.cl"

/* The value at ghost x index i (outside the row) of a row whose y and z resolved to `source` and
 * `row_sign`. */
FW_INLINE float x_ghost_value(const FwGrid* g, const FwStep* s, __global const float* profile, int c, int i,
                              int j, int k, __global const float* source, float row_sign) {
  int x = i;
  float sign = row_sign;
  if (resolve_face_axis(g, c, 0, &x, &sign)) return inflow_face_value(g, s, profile, c, i, j, k);
  return sign * source[x];
}

__kernel void pad_component(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                            __global const float* q, __global float* padded) {
  FW_ROWS_GUARD(padded_extent(&g, c, 0), padded_extent(&g, c, 1), padded_extent(&g, c, 2));
  const int j = (int)get_global_id(1) - FW_PAD, k = (int)get_global_id(2) - FW_PAD;
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(padded_extent(&g, c, 0));
  __global float* row = padded + padded_index(&g, c, -FW_PAD, j, k);
  int source_row = 0;
  float row_sign;
  if (resolve_face_row(&g, c, j, k, &source_row, &row_sign)) {
    for (int ip = begin; ip < end; ++ip) row[ip] = inflow_face_value(&g, &s, profile, c, ip - FW_PAD, j, k);
    return;
  }
  __global const float* source = q + source_row;
  const int copy_lo = clamp(FW_PAD, begin, end),
            copy_hi = clamp(FW_PAD + face_extent(&g, c, 0), copy_lo, end);
  for (int ip = begin; ip < copy_lo; ++ip)
    row[ip] = x_ghost_value(&g, &s, profile, c, ip - FW_PAD, j, k, source, row_sign);
  for (int ip = copy_lo; ip < copy_hi; ++ip) row[ip] = row_sign * source[ip - FW_PAD];
  for (int ip = copy_hi; ip < end; ++ip)
    row[ip] = x_ghost_value(&g, &s, profile, c, ip - FW_PAD, j, k, source, row_sign);
}
