/* The pressure Poisson equation A phi = b on one level of the multigrid hierarchy: smoothers, residuals,
 * grid transfers and the vector operations of conjugate gradients.
 *
 * (A phi)_c = popcount(open) phi_c - sum over open faces of phi_neighbour, with phi = 0 across outflow
 * faces and wrap-around on periodic axes (see fluid/PressureLevels.hpp). Reductions write one partial
 * value per work-group (common.cl); the host adds them in double precision, in a fixed order
 * (deterministic).
 * Reference: fluid/ReferenceStages.cpp apply_operator, residual, jacobi_sweep, red_black_sweep (as passes),
 * restrict_residual, prolong_add.
 */
#include "common.cl"

FW_INLINE int level_index(const FwLevel* L, int i, int j, int k) {
  return i + L->nx * (j + L->ny * k);
}

/* Sum of phi over the open faces of cell (i,j,k) (index id, mask m). */
FW_INLINE float open_neighbour_sum(const FwLevel* L, __global const float* phi, int i, int j, int k, int id,
                                   uchar m) {
  const int sy = L->nx, sz = L->nx * L->ny;
  float sum = 0.0f;
  if (m & 1) sum += i > 0 ? phi[id - 1] : ((L->periodic & 1) ? phi[id + (L->nx - 1)] : 0.0f);
  if (m & 2) sum += i < L->nx - 1 ? phi[id + 1] : ((L->periodic & 1) ? phi[id - (L->nx - 1)] : 0.0f);
  if (m & 4) sum += j > 0 ? phi[id - sy] : ((L->periodic & 2) ? phi[id + sy * (L->ny - 1)] : 0.0f);
  if (m & 8) sum += j < L->ny - 1 ? phi[id + sy] : ((L->periodic & 2) ? phi[id - sy * (L->ny - 1)] : 0.0f);
  if (m & 16) sum += k > 0 ? phi[id - sz] : ((L->periodic & 4) ? phi[id + sz * (L->nz - 1)] : 0.0f);
  if (m & 32) sum += k < L->nz - 1 ? phi[id + sz] : ((L->periodic & 4) ? phi[id - sz * (L->nz - 1)] : 0.0f);
  return sum;
}

/* Sum over open faces for a cell whose six neighbours all lie inside the level: the loads are
 * unconditional and the mask only selects, so the compiler can vectorise. Same order as above. */
FW_INLINE float interior_neighbour_sum(const FwLevel* L, __global const float* phi, int id, uchar m) {
  const int sy = L->nx, sz = L->nx * L->ny;
  const float xm = phi[id - 1], xp = phi[id + 1], ym = phi[id - sy], yp = phi[id + sy], zm = phi[id - sz],
              zp = phi[id + sz];
  return ((m & 1) ? xm : 0.0f) + ((m & 2) ? xp : 0.0f) + ((m & 4) ? ym : 0.0f) + ((m & 8) ? yp : 0.0f) +
         ((m & 16) ? zm : 0.0f) + ((m & 32) ? zp : 0.0f);
}

/* Either sum, by where the cell is. */
FW_INLINE float neighbour_sum(const FwLevel* L, __global const float* phi, int i, int j, int k, int id,
                              uchar m) {
  if (i > 0 && i < L->nx - 1 && j > 0 && j < L->ny - 1 && k > 0 && k < L->nz - 1)
    return interior_neighbour_sum(L, phi, id, m);
  return open_neighbour_sum(L, phi, i, j, k, id, m);
}

/* Splits this work-item's run of row (j, k) into [begin, lo) and [hi, end), whose cells may touch the
 * level's edge, and [lo, hi), whose cells have all six neighbours inside (empty for an edge row). */
FW_INLINE void interior_span(const FwLevel* L, int j, int k, int begin, int end, int* lo, int* hi) {
  const int interior_row = j > 0 && j < L->ny - 1 && k > 0 && k < L->nz - 1;
  *lo = interior_row ? clamp(1, begin, end) : end;
  *hi = interior_row ? clamp(L->nx - 1, *lo, end) : end;
}

FW_INLINE float diagonal(uchar m) {
  return (float)popcount((uint)(m & FW_MASK_OPEN_ALL));
}

/* phi_out = (1 - omega) phi + omega (b + sum phi_nb) / diag. */
/* Jacobi update of one cell with the general (edge-aware) neighbour sum. */
FW_INLINE float jacobi_cell(const FwLevel* L, __global const uchar* mask, __global const float* b,
                            __global const float* phi, float omega, int i, int j, int k) {
  const int id = level_index(L, i, j, k);
  const uchar m = mask[id];
  const float d = diagonal(m);
  if (!(m & FW_MASK_FLUID) || d == 0.0f) return 0.0f;
  return (1.0f - omega) * phi[id] + omega * (b[id] + open_neighbour_sum(L, phi, i, j, k, id, m)) / d;
}

__kernel void jacobi_sweep(const FwLevel L, __global const uchar* mask, __global const float* b,
                           __global const float* phi, __global float* phi_out, const float omega) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(L.nx);
  int lo, hi;
  interior_span(&L, j, k, begin, end, &lo, &hi);
  for (int i = begin; i < lo; ++i)
    phi_out[level_index(&L, i, j, k)] = jacobi_cell(&L, mask, b, phi, omega, i, j, k);
  /* Interior run: branch-free (selects only), so it vectorises. */
  for (int i = lo; i < hi; ++i) {
    const int id = level_index(&L, i, j, k);
    const uchar m = mask[id];
    const float d = diagonal(m);
    const float out = (1.0f - omega) * phi[id] + omega * (b[id] + interior_neighbour_sum(&L, phi, id, m)) / d;
    phi_out[id] = ((m & FW_MASK_FLUID) && d > 0.0f) ? out : 0.0f;
  }
  for (int i = hi; i < end; ++i)
    phi_out[level_index(&L, i, j, k)] = jacobi_cell(&L, mask, b, phi, omega, i, j, k);
}

/* One colour of red-black Gauss-Seidel, out of place: cells with (i + j + k) % 2 == colour get the
 * Gauss-Seidel value computed from phi (their neighbours all have the other colour, so this equals the
 * in-place update), every other cell is copied. Writing each cell once to a second buffer keeps the loop
 * free of dependences, so it streams and vectorises like a Jacobi sweep. */
FW_INLINE float red_black_cell(const FwLevel* L, __global const uchar* mask, __global const float* b,
                               __global const float* phi, int colour, int i, int j, int k) {
  const int id = level_index(L, i, j, k);
  const uchar m = mask[id];
  const float d = diagonal(m);
  if (((i + j + k) & 1) != colour || !(m & FW_MASK_FLUID) || d == 0.0f) return phi[id];
  return (b[id] + open_neighbour_sum(L, phi, i, j, k, id, m)) / d;
}

__kernel void red_black_pass(const FwLevel L, __global const uchar* mask, __global const float* b,
                             __global const float* phi, __global float* phi_out, const int colour) {
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_ROW_END(L.nx);
  int lo, hi;
  interior_span(&L, j, k, begin, end, &lo, &hi);
  for (int i = begin; i < lo; ++i)
    phi_out[level_index(&L, i, j, k)] = red_black_cell(&L, mask, b, phi, colour, i, j, k);
  for (int i = lo; i < hi; ++i) { /* interior: branch-free */
    const int id = level_index(&L, i, j, k);
    const uchar m = mask[id];
    const float d = diagonal(m);
    const float updated = (b[id] + interior_neighbour_sum(&L, phi, id, m)) / d;
    const int active = ((i + j + k) & 1) == colour && (m & FW_MASK_FLUID) && d > 0.0f;
    phi_out[id] = active ? updated : phi[id];
  }
  for (int i = hi; i < end; ++i)
    phi_out[level_index(&L, i, j, k)] = red_black_cell(&L, mask, b, phi, colour, i, j, k);
}

/* `sweeps` red-black sweeps of a small level in one launch by one work-group: each sweep the pass of colour
 * `first` (phi -> scratch), then the other (scratch -> phi), the same passes and values as red_black_pass
 * launched 2 * sweeps times. The group's items share out the rows, a barrier between passes. On small
 * levels the launches, not the cells, cost the time (about 0.1 ms each under PoCL). Global range: one
 * group, of any size. */
__kernel void red_black_sweeps(const FwLevel L, __global const uchar* mask, __global const float* b,
                               __global float* phi, __global float* scratch, const int sweeps,
                               const int first) {
  const int rows = L.ny * L.nz;
  const int item = get_local_id(0), items = get_local_size(0);
  for (int pass = 0; pass < 2 * sweeps; ++pass) {
    const int colour = (pass & 1) ? 1 - first : first;
    __global const float* from = (pass & 1) ? scratch : phi;
    __global float* to = (pass & 1) ? phi : scratch;
    for (int row = item; row < rows; row += items) {
      const int j = row % L.ny, k = row / L.ny;
      for (int i = 0; i < L.nx; ++i)
        to[level_index(&L, i, j, k)] = red_black_cell(&L, mask, b, from, colour, i, j, k);
    }
    barrier(CLK_GLOBAL_MEM_FENCE);
  }
}

/* Residual of one cell with the general (edge-aware) neighbour sum. */
FW_INLINE float residual_cell(const FwLevel* L, __global const uchar* mask, __global const float* b,
                              __global const float* phi, int i, int j, int k) {
  const int id = level_index(L, i, j, k);
  const uchar m = mask[id];
  if (!(m & FW_MASK_FLUID)) return 0.0f;
  return b[id] - (diagonal(m) * phi[id] - open_neighbour_sum(L, phi, i, j, k, id, m));
}

/* r = b - A phi; partial[group] = sum of r^2 over the group's cells. */
__kernel void residual(const FwLevel L, __global const uchar* mask, __global const float* b,
                       __global const float* phi, __global float* r, __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_REDUCTION_ROW_END(L.nx, L.ny);
  int lo, hi;
  interior_span(&L, j, k, begin, end, &lo, &hi);
  float sum = 0.0f;
  for (int i = begin; i < lo; ++i) {
    const float res = residual_cell(&L, mask, b, phi, i, j, k);
    r[level_index(&L, i, j, k)] = res;
    sum += res * res;
  }
  for (int i = lo; i < hi; ++i) { /* branch-free interior run */
    const int id = level_index(&L, i, j, k);
    const uchar m = mask[id];
    const float res = b[id] - (diagonal(m) * phi[id] - interior_neighbour_sum(&L, phi, id, m));
    const float kept = (m & FW_MASK_FLUID) ? res : 0.0f;
    r[id] = kept;
    sum += kept * kept;
  }
  for (int i = hi; i < end; ++i) {
    const float res = residual_cell(&L, mask, b, phi, i, j, k);
    r[level_index(&L, i, j, k)] = res;
    sum += res * res;
  }
  FW_GROUP_SUM(sum, partial);
}

/* (A d) of one cell with the general neighbour sum. */
FW_INLINE float operator_cell(const FwLevel* L, __global const uchar* mask, __global const float* d, int i,
                              int j, int k) {
  const int id = level_index(L, i, j, k);
  const uchar m = mask[id];
  if (!(m & FW_MASK_FLUID)) return 0.0f;
  return diagonal(m) * d[id] - open_neighbour_sum(L, d, i, j, k, id, m);
}

/* q = A d; partial[group] = sum of d q. */
__kernel void apply_operator_dot(const FwLevel L, __global const uchar* mask, __global const float* d,
                                 __global float* q, __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int begin = FW_ROW_BEGIN, end = FW_REDUCTION_ROW_END(L.nx, L.ny);
  int lo, hi;
  interior_span(&L, j, k, begin, end, &lo, &hi);
  float sum = 0.0f;
  for (int i = begin; i < lo; ++i) {
    const int id = level_index(&L, i, j, k);
    const float out = operator_cell(&L, mask, d, i, j, k);
    q[id] = out;
    sum += d[id] * out;
  }
  for (int i = lo; i < hi; ++i) { /* branch-free interior run */
    const int id = level_index(&L, i, j, k);
    const uchar m = mask[id];
    const float out = (m & FW_MASK_FLUID) ? diagonal(m) * d[id] - interior_neighbour_sum(&L, d, id, m) : 0.0f;
    q[id] = out;
    sum += d[id] * out;
  }
  for (int i = hi; i < end; ++i) {
    const int id = level_index(&L, i, j, k);
    const float out = operator_cell(&L, mask, d, i, j, k);
    q[id] = out;
    sum += d[id] * out;
  }
  FW_GROUP_SUM(sum, partial);
}

/* Coarse right-hand side: scale * mean of the fine residual r (from the residual kernel) over each coarse
 * cell's children; the coarse solution starts at 0. The coarse operator has unit couplings at spacing 2h,
 * so scale = 4 is the rediscretised equation and scale = 2 the Galerkin one (see PressureSolver).
 * Rows over the coarse level. */
__kernel void restrict_residual(const FwLevel F, const FwLevel C, __global const uchar* coarse_mask,
                                __global const float* r, __global float* coarse_b, __global float* coarse_phi,
                                const float scale) {
  const int J = get_global_id(1), K = get_global_id(2);
  for (int I = FW_ROW_BEGIN; I < FW_ROW_END(C.nx); ++I) {
    float sum = 0.0f;
    int children = 0;
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          const int i = 2 * I + di, j = 2 * J + dj, k = 2 * K + dk;
          if (i >= F.nx || j >= F.ny || k >= F.nz) continue;
          ++children;
          sum += r[level_index(&F, i, j, k)];
        }
    const int cid = level_index(&C, I, J, K);
    coarse_b[cid] = (coarse_mask[cid] & FW_MASK_FLUID) ? scale * sum / (float)children : 0.0f;
    coarse_phi[cid] = 0.0f;
  }
}

/* phi += e_coarse on every fluid cell (piecewise-constant prolongation). Rows over the fine level. */
__kernel void prolong_add(const FwLevel F, const FwLevel C, __global const uchar* fine_mask,
                          __global const float* coarse_e, __global float* phi) {
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(F.nx); ++i) {
    const int id = level_index(&F, i, j, k);
    if (fine_mask[id] & FW_MASK_FLUID) phi[id] += coarse_e[level_index(&C, i / 2, j / 2, k / 2)];
  }
}

/* x += alpha d; r -= alpha q; partial[group] = sum of r^2. */
__kernel void cg_update(const FwLevel L, const float alpha, __global const float* d, __global const float* q,
                        __global float* x, __global float* r, __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int end = FW_REDUCTION_ROW_END(L.nx, L.ny);
  float sum = 0.0f;
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = level_index(&L, i, j, k);
    x[id] += alpha * d[id];
    const float res = r[id] - alpha * q[id];
    r[id] = res;
    sum += res * res;
  }
  FW_GROUP_SUM(sum, partial);
}

/* d = z + beta d. */
__kernel void cg_direction(const FwLevel L, const float beta, __global const float* z, __global float* d) {
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(L.nx); ++i) {
    const int id = level_index(&L, i, j, k);
    d[id] = z[id] + beta * d[id];
  }
}

/* partial[group] = sum of a b. */
__kernel void dot_product(const FwLevel L, __global const float* a, __global const float* b,
                          __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int end = FW_REDUCTION_ROW_END(L.nx, L.ny);
  float sum = 0.0f;
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = level_index(&L, i, j, k);
    sum += a[id] * b[id];
  }
  FW_GROUP_SUM(sum, partial);
}

/* x += value on fluid cells (removes the mean of b when A is singular). */
__kernel void add_on_fluid(const FwLevel L, __global const uchar* mask, const float value,
                           __global float* x) {
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(L.nx); ++i) {
    const int id = level_index(&L, i, j, k);
    if (mask[id] & FW_MASK_FLUID) x[id] += value;
  }
}

/* partial[group] = sum of x over fluid cells. */
__kernel void sum_on_fluid(const FwLevel L, __global const uchar* mask, __global const float* x,
                           __global float* partial) {
  FW_GROUP_SCRATCH;
  const int j = get_global_id(1), k = get_global_id(2);
  const int end = FW_REDUCTION_ROW_END(L.nx, L.ny);
  float sum = 0.0f;
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = level_index(&L, i, j, k);
    if (mask[id] & FW_MASK_FLUID) sum += x[id];
  }
  FW_GROUP_SUM(sum, partial);
}
