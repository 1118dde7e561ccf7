/* Gather throughput, the limit that binds advection: the same loads as one trilinear interpolation of the
 * advection kernels (kernels/fluid_advect.cl: eight corners of a cell of a padded 3D array, through
 * gather()), at positions displaced from each lane's own cell by a pseudo-random 0..3 cells on every axis, as
 * a back-trace moves. Each work-item does FW_LANES consecutive x positions of one row, like advection. The
 * host counts 8 loads per position. Global range: (ceil(nx / FW_LANES), ny, nz) over an nx x ny x nz array
 * with FW_GATHER_MARGIN cells of margin on every side of q, so that no displaced corner leaves it. */
#include "common.cl"
#include "lanes.cl"

#define FW_GATHER_MARGIN 4

/* A small pseudo-random displacement (0..3 cells) from a lane's coordinates: a hash, so that neighbouring
 * lanes land in different cells as back-traces of a sheared flow do. */
FW_INLINE lanei displacement(lanei i, int j, int k, int axis) {
  const lanei h = (i * 73856093) ^ ((lanei)(j)*19349663) ^ ((lanei)(k)*83492791) ^ ((lanei)(axis)*2654435);
  return (h >> 7) & 3;
}

__kernel void gather_corners(const int nx, const int ny, const int nz, __global const float* q,
                             __global float* out) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int i0 = (int)get_global_id(0) * FW_LANES;
  if (i0 >= nx) return;
  const int valid = min(FW_LANES, nx - i0);
  const lanei i = min((lanei)(i0) + FW_LANE_OFFSETS, (lanei)(nx - 1));
  const int sy = nx + 2 * FW_GATHER_MARGIN, sz = sy * (ny + 2 * FW_GATHER_MARGIN);
  const lanei x = i + displacement(i, j, k, 0), y = j + displacement(i, j, k, 1),
              z = k + displacement(i, j, k, 2);
  const lanei base = x + sy * y + sz * z;
  const lanef sum =
      ((gather(q, base) + gather(q, base + 1)) + (gather(q, base + sy) + gather(q, base + sy + 1))) +
      ((gather(q, base + sz) + gather(q, base + sz + 1)) +
       (gather(q, base + sz + sy) + gather(q, base + sz + sy + 1)));
  store_lanes(out, i0 + nx * (j + ny * k), valid, sum);
}
