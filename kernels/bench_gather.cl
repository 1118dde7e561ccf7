/* Corner-load throughput, the limit that binds advection: the loads of one trilinear interpolation of the
 * advection kernels (kernels/fluid_advect.cl: the eight corners of a cell of a padded 3D array, through the
 * same cell_corners()) at positions displaced from each lane's own cell, and nothing else. Two regimes:
 *  - scattered: a pseudo-random 0..3 cells on every axis for each lane, as in a flow sheared across a
 *    work-item's lanes; cell_corners then gathers;
 *  - windowed: one 0..3-cell displacement per work-item, its upper half of lanes one cell further along x, as
 *    the back-traces of consecutive faces in a smooth flow straddle two cells; cell_corners then takes the
 *    windowed loads.
 * Each work-item does FW_LANES consecutive x positions of one row, like advection. The host counts 8 loads
 * per position. Global range: (ceil(nx / FW_LANES), ny, nz) over an nx x ny x nz array with
 * FW_GATHER_MARGIN cells of margin on every side of q, so that no displaced corner leaves it. */
#include "common.cl"
#include "lanes.cl"

#define FW_GATHER_MARGIN 4

/* A small pseudo-random displacement (0..3 cells) from a lane's coordinates: a hash. */
FW_INLINE lanei displacement(lanei i, int j, int k, int axis) {
  const lanei h = (i * 73856093) ^ ((lanei)(j)*19349663) ^ ((lanei)(k)*83492791) ^ ((lanei)(axis)*2654435);
  return (h >> 7) & 3;
}

/* out = the sum of the eight corners at each lane's displaced cell; `windowed` picks the regime. */
__kernel void corner_loads(const int nx, const int ny, const int nz, const int windowed,
                           __global const float* q, __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int i0 = (int)get_global_id(0) * FW_LANES;
  if (i0 >= nx || j >= ny || k >= nz) return; /* past the range: whole work-groups */
  const int valid = min(FW_LANES, nx - i0);
  const lanei i = min((lanei)(i0) + FW_LANE_OFFSETS, (lanei)(nx - 1));
  const int sy = nx + 2 * FW_GATHER_MARGIN, sz = sy * (ny + 2 * FW_GATHER_MARGIN);
  const lanei item = (lanei)(i0);
  const lanei straddle = (FW_LANE_OFFSETS >= FW_LANES / 2) & 1; /* 1 in the upper half of the lanes */
  const lanei x = windowed ? i + displacement(item, j, k, 0) + straddle : i + displacement(i, j, k, 0);
  const lanei y = (lanei)(j) + displacement(windowed ? item : i, j, k, 1);
  const lanei z = (lanei)(k) + displacement(windowed ? item : i, j, k, 2);
  lanef v[8];
  cell_corners(q, x, y, z, sy, sz, v);
  const lanef sum = ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7]));
  store_lanes(out, i0 + nx * (j + ny * k), valid, sum);
}
