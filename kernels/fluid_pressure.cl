/* The pressure Poisson equation A phi = b on one level of the multigrid hierarchy: smoothers, residuals,
 * grid transfers and the vector operations of conjugate gradients.
 *
 * (A phi)_c = popcount(open) phi_c - sum over open faces of phi_neighbour, with phi = 0 across outflow
 * faces and wrap-around on periodic axes (see fluid/PressureLevels.hpp). Sums (the *_columns kernels)
 * write one partial per x-y column of cells: its values added in float from k = 0 up, whatever the work
 * mapping. The host adds the columns exactly (base/ExactSum), so a sum depends on the cells' values alone,
 * not on how the grid is split into work-groups or, over MPI, into blocks (docs/parallel.md).
 * Reference: fluid/ReferenceStages.cpp apply_operator, residual, jacobi_sweep, red_black_sweep (as passes),
 * restrict_residual, prolong_add.
 */
#include "common.cl"

FW_INLINE int level_index(const FwLevel* L, int i, int j, int k) {
  return i + L->nx * (j + L->ny * k);
}

FW_INLINE int plane_cells(const FwLevel* L) {
  return L->nx * L->ny;
}

/* The parity of row (j, k) in global indices: a cell's red-black colour is (i + row_parity) % 2, i local.
 * The origin may be negative (a block's halo across a periodic wrap); & 1 is still its parity. */
FW_INLINE int row_parity(const FwLevel* L, int j, int k) {
  return (j + k + L->ox + L->oy) & 1;
}

/* Plane k of an array on the level and its z neighbours, each a pointer to nx * ny values, wrapped on a
 * periodic z axis. Where a neighbour plane does not exist the pointer repeats `here` and `faces` drops that
 * face, so the loads stay valid and branch-free (and the planes of k = 0 and nz - 1 take the vectorised
 * runs too). */
typedef struct FwPlanes {
  __global const float* below;
  __global const float* here;
  __global const float* above;
  uchar faces; /* the FW_MASK_OPEN bits the planes can serve */
} FwPlanes;

/* The planes of `values` around plane k. */
FW_INLINE FwPlanes level_planes(const FwLevel* L, __global const float* values, int k) {
  const int cells = plane_cells(L), periodic_z = L->periodic & 4;
  const int has_below = k > 0 || periodic_z, has_above = k < L->nz - 1 || periodic_z;
  FwPlanes P;
  P.here = values + k * cells;
  P.below = has_below ? values + (k > 0 ? k - 1 : L->nz - 1) * cells : P.here;
  P.above = has_above ? values + (k < L->nz - 1 ? k + 1 : 0) * cells : P.here;
  P.faces = (FW_MASK_OPEN_ALL & ~((1 << FW_FACE_GROUND) | (1 << FW_FACE_TOP))) |
            (has_below ? 1 << FW_FACE_GROUND : 0) | (has_above ? 1 << FW_FACE_TOP : 0);
  return P;
}

/* Sum of the planes' values over the open faces (mask m) of cell (i, j) of the plane, index p in the plane:
 * any cell, wrap-around in x and y where periodic. */
FW_INLINE float edge_neighbour_sum(const FwLevel* L, const FwPlanes* P, int i, int j, int p, uchar m) {
  const int sy = L->nx;
  __global const float* here = P->here;
  m &= P->faces;
  float sum = 0.0f;
  if (m & 1) sum += i > 0 ? here[p - 1] : ((L->periodic & 1) ? here[p + (L->nx - 1)] : 0.0f);
  if (m & 2) sum += i < L->nx - 1 ? here[p + 1] : ((L->periodic & 1) ? here[p - (L->nx - 1)] : 0.0f);
  if (m & 4) sum += j > 0 ? here[p - sy] : ((L->periodic & 2) ? here[p + sy * (L->ny - 1)] : 0.0f);
  if (m & 8) sum += j < L->ny - 1 ? here[p + sy] : ((L->periodic & 2) ? here[p - sy * (L->ny - 1)] : 0.0f);
  if (m & 16) sum += P->below[p];
  if (m & 32) sum += P->above[p];
  return sum;
}

/* The same sum for a cell whose four in-plane neighbours lie inside the plane: the loads are unconditional
 * and the mask only selects, so the compiler can vectorise. Same order as above. */
FW_INLINE float interior_neighbour_sum(const FwLevel* L, const FwPlanes* P, int p, uchar m) {
  const int sy = L->nx;
  __global const float* here = P->here;
  m &= P->faces;
  const float xm = here[p - 1], xp = here[p + 1], ym = here[p - sy], yp = here[p + sy], zm = P->below[p],
              zp = P->above[p];
  return ((m & 1) ? xm : 0.0f) + ((m & 2) ? xp : 0.0f) + ((m & 4) ? ym : 0.0f) + ((m & 8) ? yp : 0.0f) +
         ((m & 16) ? zm : 0.0f) + ((m & 32) ? zp : 0.0f);
}

FW_INLINE float diagonal(uchar m) {
  return (float)popcount((uint)(m & FW_MASK_OPEN_ALL));
}

/* A fluid cell with all six faces open: most cells of a level, whose update needs no mask arithmetic. */
#define FW_MASK_OPEN_FLUID (FW_MASK_FLUID | FW_MASK_OPEN_ALL)

/* How a run of cells along x is computed. Edge: any cell (wrap-around, masks). Interior: the in-plane
 * neighbours lie inside, so the loads are unconditional and the masks only select (vectorises). Open: an
 * interior run of open fluid cells whose planes serve all six faces: plain six-point sums, diagonal 6
 * (half the arithmetic of an interior run, and the passes are bound by their arithmetic under PoCL). A
 * constant at each use, so the choices below fold away. */
#define FW_RUN_EDGE 0
#define FW_RUN_INTERIOR 1
#define FW_RUN_OPEN 2

FW_INLINE float run_neighbour_sum(const FwLevel* L, const FwPlanes* P, int i, int j, int p, uchar m,
                                  int run) {
  if (run == FW_RUN_EDGE) return edge_neighbour_sum(L, P, i, j, p, m);
  if (run == FW_RUN_INTERIOR) return interior_neighbour_sum(L, P, p, m);
  const int sy = L->nx;
  return P->here[p - 1] + P->here[p + 1] + P->here[p - sy] + P->here[p + sy] + P->below[p] + P->above[p];
}

FW_INLINE float run_diagonal(uchar m, int run) {
  return run == FW_RUN_OPEN ? 6.0f : diagonal(m);
}

FW_INLINE int run_fluid(uchar m, int run) {
  return run == FW_RUN_OPEN || (m & FW_MASK_FLUID);
}

/* The runs of this work-item's cells [begin, end) of row j (mask_row: the row's masks): [begin, lo) and
 * [hi, end) edge runs, [lo, hi) interior (empty for an edge row), and whether that interior run is open. */
typedef struct FwRowRuns {
  int begin, lo, hi, end, open;
} FwRowRuns;

FW_INLINE FwRowRuns row_runs(const FwLevel* L, const FwPlanes* P, __global const uchar* mask_row, int j,
                             int begin, int end) {
  FwRowRuns R;
  const int interior_row = j > 0 && j < L->ny - 1;
  R.begin = begin;
  R.end = end;
  R.lo = interior_row ? clamp(1, begin, end) : end;
  R.hi = interior_row ? clamp(L->nx - 1, R.lo, end) : end;
  int open = P->faces == FW_MASK_OPEN_ALL;
  for (int i = R.lo; i < R.hi; ++i) open &= mask_row[i] == FW_MASK_OPEN_FLUID;
  R.open = open;
  return R;
}

/* Runs `body` (a statement of i and the constant run) for every i of the runs R, each run in its own loop
 * with its own constant, so that each loop compiles to its kind of code. */
#define FW_FOR_RUNS(R, body)                   \
  do {                                         \
    for (int i = (R).begin; i < (R).lo; ++i) { \
      const int run = FW_RUN_EDGE;             \
      body;                                    \
    }                                          \
    if ((R).open) {                            \
      for (int i = (R).lo; i < (R).hi; ++i) {  \
        const int run = FW_RUN_OPEN;           \
        body;                                  \
      }                                        \
    } else {                                   \
      for (int i = (R).lo; i < (R).hi; ++i) {  \
        const int run = FW_RUN_INTERIOR;       \
        body;                                  \
      }                                        \
    }                                          \
    for (int i = (R).hi; i < (R).end; ++i) {   \
      const int run = FW_RUN_EDGE;             \
      body;                                    \
    }                                          \
  } while (0)

/* The Jacobi value of cell (i, j) at index p of its plane: (1 - w) phi + w (b + sum phi_nb) / diag, w the
 * relaxation weight, on fluid cells, 0 elsewhere. mask and b point at the plane; branch-free. */
FW_INLINE float jacobi_value(const FwLevel* L, __global const uchar* mask, __global const float* b,
                             const FwPlanes* P, float relaxation_weight, int i, int j, int p, int run) {
  const uchar m = mask[p];
  const float d = run_diagonal(m, run);
  const float out = (1.0f - relaxation_weight) * P->here[p] +
                    relaxation_weight * (b[p] + run_neighbour_sum(L, P, i, j, p, m, run)) / d;
  return (run_fluid(m, run) && d > 0.0f) ? out : 0.0f;
}

__kernel void jacobi_sweep(const FwLevel L, __global const uchar* mask, __global const float* b,
                           __global const float* phi, __global float* phi_out,
                           const float relaxation_weight) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), plane = k * plane_cells(&L), row = j * L.nx;
  const FwPlanes P = level_planes(&L, phi, k);
  mask += plane, b += plane, phi_out += plane;
  const FwRowRuns R = row_runs(&L, &P, mask + row, j, FW_ROW_BEGIN, FW_ROW_END(L.nx));
  FW_FOR_RUNS(R, phi_out[row + i] = jacobi_value(&L, mask, b, &P, relaxation_weight, i, j, row + i, run));
}

/* Red-black Gauss-Seidel, one colour per pass and out of place: cells with (i + j + k) % 2 == colour get the
 * Gauss-Seidel value computed from the planes P (their neighbours all have the other colour, so this equals
 * the in-place update), every other cell is copied. Writing each cell once to a second buffer keeps the
 * loop free of dependences, so it streams and vectorises like a Jacobi sweep. parity: row_parity. */
/* Whether the pass of `colour` updates cell i of a row of that parity (mask m, diagonal d). */
FW_INLINE int red_black_updates(uchar m, float d, int colour, int parity, int i, int run) {
  return ((i + parity) & 1) == colour && run_fluid(m, run) && d > 0.0f;
}

FW_INLINE float red_black_value(const FwLevel* L, __global const uchar* mask, __global const float* b,
                                const FwPlanes* P, int colour, int parity, int i, int j, int p, int run) {
  const uchar m = mask[p];
  const float d = run_diagonal(m, run);
  const float updated = (b[p] + run_neighbour_sum(L, P, i, j, p, m, run)) / d;
  return red_black_updates(m, d, colour, parity, i, run) ? updated : P->here[p];
}

/* One colour pass over cells [begin, end) of row j of plane k; mask, b and out point at the plane. */
FW_INLINE void red_black_row(const FwLevel* L, __global const uchar* mask, __global const float* b,
                             const FwPlanes* P, __global float* out, int colour, int j, int k, int begin,
                             int end) {
  const int row = j * L->nx, parity = row_parity(L, j, k);
  const FwRowRuns R = row_runs(L, P, mask + row, j, begin, end);
  FW_FOR_RUNS(R, out[row + i] = red_black_value(L, mask, b, P, colour, parity, i, j, row + i, run));
}

__kernel void red_black_pass(const FwLevel L, __global const uchar* mask, __global const float* b,
                             __global const float* phi, __global float* phi_out, const int colour) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), plane = k * plane_cells(&L);
  const FwPlanes P = level_planes(&L, phi, k);
  red_black_row(&L, mask + plane, b + plane, &P, phi_out + plane, colour, j, k, FW_ROW_BEGIN,
                FW_ROW_END(L.nx));
}

/* Red-black Gauss-Seidel in place: the pass of `colour` overwrites the cells of that colour in phi. It moves
 * 13 bytes a cell where red_black_pass moves 17 (a store to a second buffer first reads its line). Every
 * neighbour of a cell has the other colour (the hierarchy keeps periodic extents even or 1, see
 * fluid/PressureLevels.hpp), so no item reads a cell another item changes, and the values equal
 * red_black_pass's.
 * Under the CPU layout the interior runs take explicit FW_COLOUR_LANES-wide vectors, since the compiler will
 * not vectorise a loop that stores values later iterations load. A chunk stores all its lanes, the other
 * colour's with the values it loaded: those cells do not change, so no item reads a changing value. Each
 * chunk's x - 1 neighbours are loaded before the previous chunk's store, because a load overlapping a store
 * in flight cannot take its data from the store buffer and stalls (about 0.1 ms a pass on 128x128x64). */
#define FW_COLOUR_LANES 16
#define FW_COLOUR_LANE_INDEX ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))

/* interior_neighbour_sum or the open run's sum for the FW_COLOUR_LANES cells from index p of the plane; m:
 * their masks, xm: their x - 1 neighbours. Same order of additions as the scalar sums. */
FW_INLINE float16 chunk_neighbour_sum(const FwLevel* L, const FwPlanes* P, int16 m, float16 xm, int p,
                                      int run) {
  const int sy = L->nx;
  __global const float* here = P->here;
  const float16 xp = vload16(0, here + p + 1), ym = vload16(0, here + p - sy), yp = vload16(0, here + p + sy),
                zm = vload16(0, P->below + p), zp = vload16(0, P->above + p);
  if (run == FW_RUN_OPEN) return xm + xp + ym + yp + zm + zp;
  const float16 none = 0.0f;
  m &= (int)P->faces;
  return select(none, xm, (m & 1) != 0) + select(none, xp, (m & 2) != 0) + select(none, ym, (m & 4) != 0) +
         select(none, yp, (m & 8) != 0) + select(none, zm, (m & 16) != 0) + select(none, zp, (m & 32) != 0);
}

/* The in-place pass over the FW_COLOUR_LANES cells from column i (index p of the plane) of an interior or
 * open run; phi points at the plane. */
FW_INLINE void red_black_chunk(const FwLevel* L, __global const uchar* mask, __global const float* b,
                               const FwPlanes* P, __global float* phi, float16 xm, int colour, int parity,
                               int i, int p, int run) {
  const int16 m = convert_int16(vload16(0, mask + p));
  const float16 d = run == FW_RUN_OPEN ? (float16)6.0f : convert_float16(popcount(m & FW_MASK_OPEN_ALL));
  const float16 updated = (vload16(0, b + p) + chunk_neighbour_sum(L, P, m, xm, p, run)) / d;
  int16 active = ((FW_COLOUR_LANE_INDEX + (i + parity)) & 1) == colour;
  if (run != FW_RUN_OPEN) active &= ((m & FW_MASK_FLUID) != 0) & (d > 0.0f);
  vstore16(select(vload16(0, phi + p), updated, active), 0, phi + p);
}

/* The in-place pass of one cell: written only where it changes (on a GPU, half the stores). */
FW_INLINE void red_black_cell(const FwLevel* L, __global const uchar* mask, __global const float* b,
                              const FwPlanes* P, __global float* phi, int colour, int parity, int i, int j,
                              int p, int run) {
  const uchar m = mask[p];
  const float d = run_diagonal(m, run);
  if (red_black_updates(m, d, colour, parity, i, run))
    phi[p] = (b[p] + run_neighbour_sum(L, P, i, j, p, m, run)) / d;
}

/* The in-place pass over cells [begin, end) of row j (first index row of the plane), all of one run. */
FW_INLINE void red_black_update_run(const FwLevel* L, __global const uchar* mask, __global const float* b,
                                    const FwPlanes* P, __global float* phi, int colour, int parity, int j,
                                    int row, int begin, int end, int run) {
  int i = begin;
  if (FW_ROW_CHUNK >= FW_COLOUR_LANES && run != FW_RUN_EDGE && end - begin >= FW_COLOUR_LANES) {
    float16 xm = vload16(0, phi + row + i - 1);
    for (; i + FW_COLOUR_LANES <= end; i += FW_COLOUR_LANES) {
      /* The next chunk's start, or this one's on the last (its load is then unused but valid). */
      const int next = min(i + FW_COLOUR_LANES, end - FW_COLOUR_LANES);
      const float16 next_xm = vload16(0, phi + row + next - 1);
      red_black_chunk(L, mask, b, P, phi, xm, colour, parity, i, row + i, run);
      xm = next_xm;
    }
  }
  for (; i < end; ++i) red_black_cell(L, mask, b, P, phi, colour, parity, i, j, row + i, run);
}

__kernel void red_black_update(const FwLevel L, __global const uchar* mask, __global const float* b,
                               __global float* phi, const int colour) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), plane = k * plane_cells(&L), row = j * L.nx;
  const int parity = row_parity(&L, j, k);
  const FwPlanes P = level_planes(&L, phi, k);
  mask += plane, b += plane, phi += plane;
  const FwRowRuns R = row_runs(&L, &P, mask + row, j, FW_ROW_BEGIN, FW_ROW_END(L.nx));
  red_black_update_run(&L, mask, b, &P, phi, colour, parity, j, row, R.begin, R.lo, FW_RUN_EDGE);
  if (R.open)
    red_black_update_run(&L, mask, b, &P, phi, colour, parity, j, row, R.lo, R.hi, FW_RUN_OPEN);
  else
    red_black_update_run(&L, mask, b, &P, phi, colour, parity, j, row, R.lo, R.hi, FW_RUN_INTERIOR);
  red_black_update_run(&L, mask, b, &P, phi, colour, parity, j, row, R.hi, R.end, FW_RUN_EDGE);
}

/* `sweeps` red-black sweeps of a small level in one launch by one work-group: each sweep the pass of colour
 * `first` (phi -> scratch), then the other (scratch -> phi), the same passes and values as red_black_pass
 * launched 2 * sweeps times. Passes before first_pass are skipped: first_pass = 1 continues a smoothing
 * whose first pass (into scratch) was written by smoothing_start or restrict_residual. The group's items
 * share out the rows, a barrier between passes. On small levels the launches, not the cells, cost the time
 * (about 0.1 ms each under PoCL). Global range: one group, of any size. */
__kernel void red_black_sweeps(const FwLevel L, __global const uchar* mask, __global const float* b,
                               __global float* phi, __global float* scratch, const int sweeps,
                               const int first, const int first_pass) {
  const int rows = L.ny * L.nz;
  const int item = get_local_id(0), items = get_local_size(0);
  for (int pass = first_pass; pass < 2 * sweeps; ++pass) {
    const int colour = (pass & 1) ? 1 - first : first;
    __global const float* from = (pass & 1) ? scratch : phi;
    __global float* to = (pass & 1) ? phi : scratch;
    for (int row = item; row < rows; row += items) {
      const int j = row % L.ny, k = row / L.ny, plane = k * plane_cells(&L);
      const FwPlanes P = level_planes(&L, from, k);
      red_black_row(&L, mask + plane, b + plane, &P, to + plane, colour, j, k, 0, L.nx);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
  }
}

/* (A d) of cell (i, j) at index p of its plane, 0 off the fluid. */
FW_INLINE float operator_value(const FwLevel* L, __global const uchar* mask, const FwPlanes* D, int i, int j,
                               int p, int run) {
  const uchar m = mask[p];
  const float out = run_diagonal(m, run) * D->here[p] - run_neighbour_sum(L, D, i, j, p, m, run);
  return run_fluid(m, run) ? out : 0.0f;
}

/* r = b - A phi of cell (i, j) at index p of its plane, 0 off the fluid. */
FW_INLINE float residual_value(const FwLevel* L, __global const uchar* mask, __global const float* b,
                               const FwPlanes* P, int i, int j, int p, int run) {
  return run_fluid(mask[p], run) ? b[p] - operator_value(L, mask, P, i, j, p, run) : 0.0f;
}

/* r = b - A phi (rows). */
__kernel void residual(const FwLevel L, __global const uchar* mask, __global const float* b,
                       __global const float* phi, __global float* r) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), plane = k * plane_cells(&L), row = j * L.nx;
  const FwPlanes P = level_planes(&L, phi, k);
  mask += plane, b += plane, r += plane;
  const FwRowRuns R = row_runs(&L, &P, mask + row, j, FW_ROW_BEGIN, FW_ROW_END(L.nx));
  FW_FOR_RUNS(R, r[row + i] = residual_value(&L, mask, b, &P, i, j, row + i, run));
}

/* The column sums' start: this item's cells [begin, end) of column row j zeroed (columns: nx * ny values, the
 * column of cell (i, j) at i + nx j). Each column kernel then adds plane k = 0, 1, ... in order. */
FW_INLINE __global float* zeroed_columns(const FwLevel* L, __global float* columns, int j, int begin,
                                         int end) {
  columns += j * L->nx;
  for (int i = begin; i < end; ++i) columns[i] = 0.0f;
  return columns;
}

/* q = A d (rows); CG then takes the column sums of d q (dot_product_columns): apart, both stream at full
 * speed, where one kernel over whole columns ran at half. */
__kernel void apply_operator(const FwLevel L, __global const uchar* mask, __global const float* d,
                             __global float* q) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), plane = k * plane_cells(&L), row = j * L.nx;
  const FwPlanes D = level_planes(&L, d, k);
  mask += plane, q += plane;
  const FwRowRuns R = row_runs(&L, &D, mask + row, j, FW_ROW_BEGIN, FW_ROW_END(L.nx));
  FW_FOR_RUNS(R, q[row + i] = operator_value(&L, mask, &D, i, j, row + i, run));
}

/* The first smoothing pass from a zero guess, which needs no neighbours: w b / diag (w the relaxation weight)
 * on the fluid cells the pass updates, 0 elsewhere. colour: the colour a red-black pass updates (w = 1), or
 * FW_SMOOTH_ALL_CELLS for a damped Jacobi sweep; cell_colour = (i + j + k) % 2. The same value as
 * red_black_value or jacobi_value with phi = 0. */
FW_INLINE float smoothing_start_value(uchar m, float b, float relaxation_weight, int colour,
                                      int cell_colour) {
  const float d = diagonal(m);
  const int active =
      (colour == FW_SMOOTH_ALL_CELLS || cell_colour == colour) && (m & FW_MASK_FLUID) && d > 0.0f;
  return active ? relaxation_weight * b / d : 0.0f;
}

/* out = the first smoothing pass of A phi = b from phi = 0 (a fill and a pass in one, reading no
 * neighbours). */
__kernel void smoothing_start(const FwLevel L, __global const uchar* mask, __global const float* b,
                              __global float* out, const float relaxation_weight, const int colour) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2), row = level_index(&L, 0, j, k);
  const int parity = row_parity(&L, j, k);
  mask += row, b += row, out += row;
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(L.nx); ++i)
    out[i] = smoothing_start_value(mask[i], b[i], relaxation_weight, colour, (i + parity) & 1);
}

/* Coarse right-hand side: scale * mean of the fine residual r (from the residual kernel) over each coarse
 * cell's children, and the coarse level's first smoothing pass from a zero guess (as smoothing_start, into
 * coarse_start). The coarse operator has unit couplings at spacing 2h, so scale = 4 is the rediscretised
 * equation (see PressureSolver).
 * A coarse cell with one child along an axis (an odd fine extent) reads that child twice, so every cell
 * sums eight values and the mean is sum / 8 without counting. Pairs along x are read with stride 2, which
 * vectorises. Rows over the coarse level.
 * On a rank's block (docs/parallel.md) the children of coarse cell (I, J) are the fine cells from (2 I + sx,
 * 2 J + sy), s = 2 C.o - F.o, the pairing of global indices. A coarse cell whose children lie outside the
 * fine cells is a halo cell: it is skipped, and its values come with the halo. */
/* Coarse cell I of the row (coarse_mask, coarse_b and coarse_start point at it): its right-hand side
 * (restricted, off the fluid 0) and its first smoothing pass from a zero guess. */
FW_INLINE void store_coarse_cell(__global const uchar* coarse_mask, __global float* coarse_b,
                                 __global float* coarse_start, int I, float restricted,
                                 float relaxation_weight, int colour, int parity) {
  const uchar m = coarse_mask[I];
  const float bc = (m & FW_MASK_FLUID) ? restricted : 0.0f;
  coarse_b[I] = bc;
  coarse_start[I] = smoothing_start_value(m, bc, relaxation_weight, colour, (I + parity) & 1);
}

__kernel void restrict_residual(const FwLevel F, const FwLevel C, __global const uchar* coarse_mask,
                                __global const float* r, __global float* coarse_b,
                                __global float* coarse_start, const float scale,
                                const float relaxation_weight, const int colour) {
  FW_ROWS_GUARD(C.nx, C.ny, C.nz); /* rows over the coarse level */
  const int sx = 2 * C.ox - F.ox, sy = 2 * C.oy - F.oy;
  const int J = get_global_id(1), K = get_global_id(2), j = 2 * J + sy, k = 2 * K, plane = plane_cells(&F);
  if (j < 0 || j >= F.ny) return; /* a halo row */
  /* The four fine rows of the coarse row: (j, k), (j + 1, k), (j, k + 1), (j + 1, k + 1). */
  __global const float* r00 = r + level_index(&F, 0, j, k);
  __global const float* r10 = j + 1 < F.ny ? r00 + F.nx : r00;
  __global const float* r01 = k + 1 < F.nz ? r00 + plane : r00;
  __global const float* r11 = k + 1 < F.nz ? r10 + plane : r10;
  const int row = level_index(&C, 0, J, K), parity = row_parity(&C, J, K);
  coarse_mask += row, coarse_b += row, coarse_start += row;
  const float weight = 0.125f * scale;
  /* I in [first, pairs): both children inside; I == pairs with an odd count left: one child. */
  const int first = sx < 0 ? (1 - sx) / 2 : 0, pairs = (F.nx - sx) / 2;
  const int begin = max(FW_ROW_BEGIN, first), end = FW_ROW_END(C.nx);
  for (int I = begin; I < min(end, pairs); ++I) {
    const int i = 2 * I + sx;
    const float sum =
        (r00[i] + r00[i + 1]) + (r10[i] + r10[i + 1]) + (r01[i] + r01[i + 1]) + (r11[i] + r11[i + 1]);
    store_coarse_cell(coarse_mask, coarse_b, coarse_start, I, weight * sum, relaxation_weight, colour,
                      parity);
  }
  const int single = pairs; /* its one child is the row's last cell */
  if ((F.nx - sx) % 2 != 0 && single >= begin && single < end) {
    const int i = 2 * single + sx;
    const float sum = 2.0f * ((r00[i] + r10[i]) + (r01[i] + r11[i]));
    store_coarse_cell(coarse_mask, coarse_b, coarse_start, single, weight * sum, relaxation_weight, colour,
                      parity);
  }
}

/* phi += the interpolated coarse correction e on every fluid cell: e_P + slope * sum over the axes of
 * (e_N - e_P), P the parent, N its neighbour on the child's side along the axis. slope = 1/4 is linear
 * interpolation (a child sits a quarter of the coarse spacing from P towards N), slope = 0 piecewise
 * constant. Across an open coarse face N wraps on a periodic axis and is 0 beyond the domain (an outflow's
 * ghost); across a closed face N = P. Linear interpolation makes stand-alone V-cycles converge with the
 * rediscretised coarse equation (orders 2 + 1 of interpolation and restriction exceed the operator's 2;
 * piecewise constant, 1 + 1, diverged); CG takes piecewise constant, the transpose of the averaging
 * restriction, which keeps its preconditioner symmetric.
 * Rows over the fine level: a fine row's y and z sides are the same for all its cells, so each row reads
 * three coarse rows. */
typedef struct FwCoarseRows {
  __global const float* parent; /* e on coarse row (J, K) */
  __global const float* side_y; /* e on the row beside it on the fine row's y side, wrapped */
  __global const float* side_z; /* ... and z side */
  float weight_y, weight_z;     /* 0 where that side lies beyond the domain (the ghost's 0), else 1 */
  float slope;                  /* 1/4: linear interpolation, 0: piecewise constant */
  uchar face_y, face_z;         /* the coarse faces towards side_y and side_z */
} FwCoarseRows;

/* The coarse row beside row `at` of an axis of n coarse rows (stride apart) on `side` (1: above), wrapped
 * where periodic; *weight = 0 and the row itself where it lies beyond the domain. */
FW_INLINE __global const float* side_row(__global const float* row, int at, int n, int stride, int side,
                                         int periodic, float* weight) {
  const int to = side ? at + 1 : at - 1;
  *weight = 1.0f;
  if (to >= 0 && to < n) return row + (to - at) * stride;
  if (periodic) return row + ((to + n) % n - at) * stride;
  *weight = 0.0f;
  return row;
}

/* The coarse rows of fine row (j, k), j shifted by sy = 2 C.oy - F.oy (the pairing of global indices, see
 * restrict_residual): J = (j - sy) / 2 rounded down, which may lie outside the coarse cells for a halo row.
 */
FW_INLINE FwCoarseRows coarse_rows(const FwLevel* C, __global const float* e, int j, int sy, int k,
                                   float slope) {
  const int J = (j - sy) >> 1, K = k / 2, side_y = (j - sy) & 1, side_z = k & 1;
  FwCoarseRows R;
  R.slope = slope;
  R.parent = e + level_index(C, 0, J, K);
  R.side_y = side_row(R.parent, J, C->ny, C->nx, side_y, C->periodic & 2, &R.weight_y);
  R.side_z = side_row(R.parent, K, C->nz, plane_cells(C), side_z, C->periodic & 4, &R.weight_z);
  R.face_y = 1 << (FW_FACE_SOUTH + side_y);
  R.face_z = 1 << (FW_FACE_GROUND + side_z);
  return R;
}

/* The interpolated correction of the child on x side `side_x` of coarse cell I (mask m), given its x
 * neighbour's value e_x. */
FW_INLINE float linear_correction(const FwCoarseRows* R, uchar m, int I, int side_x, float e_x) {
  const float p = R->parent[I];
  const float dx = (m & (1 << (FW_FACE_WEST + side_x))) ? e_x - p : 0.0f;
  const float dy = (m & R->face_y) ? R->weight_y * R->side_y[I] - p : 0.0f;
  const float dz = (m & R->face_z) ? R->weight_z * R->side_z[I] - p : 0.0f;
  return p + R->slope * ((dx + dy) + dz);
}

/* Fine cell i of the row, any position: its x neighbour wrapped or beyond the domain. Its parent is coarse
 * cell (i - sx) / 2, sx = 2 C.ox - F.ox; a halo cell whose parent lies outside the coarse cells is skipped.
 */
FW_INLINE void prolong_edge_cell(const FwLevel* C, const FwCoarseRows* R, __global const uchar* coarse_mask,
                                 __global const uchar* fine_mask, __global float* phi, int i, int sx) {
  const int I = (i - sx) >> 1, side_x = (i - sx) & 1, to = side_x ? I + 1 : I - 1;
  if (I < 0 || I >= C->nx) return;
  const float e_x = (to >= 0 && to < C->nx) ? R->parent[to]
                    : (C->periodic & 1)     ? R->parent[(to + C->nx) % C->nx]
                                            : 0.0f;
  if (fine_mask[i] & FW_MASK_FLUID) phi[i] += linear_correction(R, coarse_mask[I], I, side_x, e_x);
}

__kernel void prolong_add(const FwLevel F, const FwLevel C, __global const uchar* fine_mask,
                          __global const uchar* coarse_mask, __global const float* coarse_e,
                          __global float* phi, const float slope) {
  FW_ROWS_GUARD(F.nx, F.ny, F.nz); /* rows over the fine level */
  const int sx = 2 * C.ox - F.ox, sy = 2 * C.oy - F.oy;
  const int j = get_global_id(1), k = get_global_id(2), row = level_index(&F, 0, j, k);
  const int J = (j - sy) >> 1;
  if (J < 0 || J >= C.ny) return; /* a halo row whose parents lie outside the coarse cells */
  fine_mask += row, phi += row;
  coarse_mask += level_index(&C, 0, J, k / 2);
  const FwCoarseRows R = coarse_rows(&C, coarse_e, j, sy, k, slope);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(F.nx);
  /* Interior pairs (2I + sx, 2I + sx + 1), wholly in [begin, end) with both x neighbours inside the coarse
   * row: one parent load for both children, stride-2 stores (vectorises); every other cell one by one. */
  const int pair_lo = max((begin - sx + 1) >> 1, 1), pair_hi = max(pair_lo, min((end - sx) >> 1, C.nx - 1));
  const int head_end = min(end, 2 * pair_lo + sx), tail_begin = max(head_end, 2 * pair_hi + sx);
  for (int i = begin; i < head_end; ++i) prolong_edge_cell(&C, &R, coarse_mask, fine_mask, phi, i, sx);
  for (int I = pair_lo; I < pair_hi; ++I) {
    const uchar m = coarse_mask[I];
    const float lo = linear_correction(&R, m, I, 0, R.parent[I - 1]);
    const float hi = linear_correction(&R, m, I, 1, R.parent[I + 1]);
    const int i = 2 * I + sx;
    phi[i] += (fine_mask[i] & FW_MASK_FLUID) ? lo : 0.0f;
    phi[i + 1] += (fine_mask[i + 1] & FW_MASK_FLUID) ? hi : 0.0f;
  }
  for (int i = tail_begin; i < end; ++i) prolong_edge_cell(&C, &R, coarse_mask, fine_mask, phi, i, sx);
}

/* x += alpha d; r -= alpha q; columns = the column sums of r^2. */
__kernel void cg_update_columns(const FwLevel L, const float alpha, __global const float* restrict d,
                                __global const float* restrict q, __global float* restrict x,
                                __global float* restrict r, __global float* restrict columns) {
  FW_ROWS_GUARD(L.nx, L.ny, 1); /* one item a column of the level: (nx, ny, 1) */
  const int j = get_global_id(1), begin = FW_ROW_BEGIN, end = FW_ROW_END(L.nx);
  __global float* column = zeroed_columns(&L, columns, j, begin, end);
  for (int k = 0; k < L.nz; ++k) {
    const int row = level_index(&L, 0, j, k);
    for (int i = begin; i < end; ++i) {
      x[row + i] += alpha * d[row + i];
      const float res = r[row + i] - alpha * q[row + i];
      r[row + i] = res;
      column[i] += res * res;
    }
  }
}

/* d = z + beta d. */
__kernel void cg_direction(const FwLevel L, const float beta, __global const float* z, __global float* d) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(L.nx); ++i) {
    const int id = level_index(&L, i, j, k);
    d[id] = z[id] + beta * d[id];
  }
}

/* columns = the column sums of a b. */
__kernel void dot_product_columns(const FwLevel L, __global const float* a, __global const float* b,
                                  __global float* restrict columns) {
  FW_ROWS_GUARD(L.nx, L.ny, 1); /* one item a column of the level: (nx, ny, 1) */
  const int j = get_global_id(1), begin = FW_ROW_BEGIN, end = FW_ROW_END(L.nx);
  __global float* column = zeroed_columns(&L, columns, j, begin, end);
  for (int k = 0; k < L.nz; ++k) {
    const int row = level_index(&L, 0, j, k);
    for (int i = begin; i < end; ++i) column[i] += a[row + i] * b[row + i];
  }
}

/* x += value on fluid cells (removes the mean of b when A is singular). */
__kernel void add_on_fluid(const FwLevel L, __global const uchar* mask, const float value,
                           __global float* x) {
  FW_ROWS_GUARD(L.nx, L.ny, L.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(L.nx); ++i) {
    const int id = level_index(&L, i, j, k);
    if (mask[id] & FW_MASK_FLUID) x[id] += value;
  }
}

/* columns = the column sums of x over fluid cells. */
__kernel void sum_on_fluid_columns(const FwLevel L, __global const uchar* restrict mask,
                                   __global const float* restrict x, __global float* restrict columns) {
  FW_ROWS_GUARD(L.nx, L.ny, 1); /* one item a column of the level: (nx, ny, 1) */
  const int j = get_global_id(1), begin = FW_ROW_BEGIN, end = FW_ROW_END(L.nx);
  __global float* column = zeroed_columns(&L, columns, j, begin, end);
  for (int k = 0; k < L.nz; ++k) {
    const int row = level_index(&L, 0, j, k);
    for (int i = begin; i < end; ++i) column[i] += (mask[row + i] & FW_MASK_FLUID) ? x[row + i] : 0.0f;
  }
}
