/* Deardorff's subgrid energy e (one float a cell, m^2/s^2) and the eddy viscosity it gives: the stages of
 * the tke subgrid model, in the order host::WindGrid runs them each step (tke_viscosity, tke_advect,
 * tke_update; tke_equilibrium once, for the start). The equations, the constants, the ghosts and why the
 * sinks are implicit: fluid/SubgridTke.hpp. Reference: fluid/SubgridTke.cpp tke_equilibrium,
 * tke_viscosity, tke_advect, tke_update. Global range of every kernel: rows over the cells. */
#include "strain_rate.cl"

/* Where a neighbour of a cell along one axis lies (fluid/SubgridTke.cpp resolve_axis). */
#define FW_TKE_INSIDE 0 /* in the grid; on a periodic axis wrapped into it */
#define FW_TKE_INFLOW 1 /* across an inflow face: e is FwTke.inflow there */
#define FW_TKE_CLOSED 2 /* across a wall or outflow face: zero gradient */

FW_INLINE int resolve_cell_axis(const FwGrid* g, int a, int* x) {
  const int n = axis_cells(g, a);
  if (*x >= 0 && *x < n) return FW_TKE_INSIDE;
  if (axis_periodic(g, a)) {
    *x = ((*x % n) + n) % n;
    return FW_TKE_INSIDE;
  }
  return g->bc[2 * a + (*x < 0 ? 0 : 1)] == FW_BC_INFLOW ? FW_TKE_INFLOW : FW_TKE_CLOSED;
}

/* 1 for a fluid cell on a wall (the fluid::wall_cells rule): its cell below is solid, or it sits on a
 * slip or no-slip ground. Its mixing length is the wall's (FwTke [1]). */
FW_INLINE int cell_on_wall(const FwGrid* g, __global const uchar* mask, int id, int k) {
  if (k == 0) return g->bc[FW_FACE_GROUND] == FW_BC_SLIP || g->bc[FW_FACE_GROUND] == FW_BC_NO_SLIP;
  return !(mask[id - g->nx * g->ny] & FW_MASK_FLUID);
}

/* Component c of the resolved velocity at the centre of cell (i, j, k): the mean of its two faces. */
FW_INLINE float centre_velocity(const FwGrid* g, __global const float* q, int c, int i, int j, int k) {
  return 0.5f *
         (q[face_index(g, c, i, j, k)] + q[face_index(g, c, i + (c == 0), j + (c == 1), k + (c == 2))]);
}

/* The strain of a row's cells: the StrainRows of the three components and the inverse spans along y and z,
 * resolved once a row. */
typedef struct {
  StrainRows u, v, w;
  float iy, iz;
} RowStrain;

FW_INLINE RowStrain row_strain(const FwGrid* g, int j, int k) {
  RowStrain r;
  int py, my, pz, mz;
  difference_offsets(j, g->ny, axis_periodic(g, 1), g->h, &py, &my, &r.iy);
  difference_offsets(k, g->nz, axis_periodic(g, 2), g->h, &pz, &mz, &r.iz);
  r.u = strain_rows(g, 0, j, k, py, my, pz, mz);
  r.v = strain_rows(g, 1, j, k, py, my, pz, mz);
  r.w = strain_rows(g, 2, j, k, py, my, pz, mz);
  return r;
}

/* |S|^2 = 2 S_ij S_ij of cell i of the row (the general path with its own x offsets: these kernels are not
 * where a step's time goes). */
FW_INLINE float row_strain_at(const FwGrid* g, const RowStrain* r, __global const float* u,
                              __global const float* v, __global const float* w, int i) {
  int px, mx;
  float ix;
  difference_offsets(i, g->nx, axis_periodic(g, 0), g->h, &px, &mx, &ix);
  return strain_rate_squared(g, &r->u, &r->v, &r->w, u, v, w, i, 1, px, mx, ix, r->iy, r->iz);
}

/* The start: e = max(floor, (C_m l / (C_eps / l)) |S|^2), the shear production's balance with the
 * dissipation (fluid::tke_shear_equilibrium), 0 in solid cells. */
__kernel void tke_equilibrium(const FwGrid g, const FwTke t, __global const uchar* restrict mask,
                              __global const float* restrict u, __global const float* restrict v,
                              __global const float* restrict w, __global float* restrict energy) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  const RowStrain r = row_strain(&g, j, k);
  const int row = cell_index(&g, 0, j, k), end = FW_ROW_END(g.nx);
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = row + i;
    float e = 0.0f;
    if (mask[id] & FW_MASK_FLUID) {
      const int wall = cell_on_wall(&g, mask, id, k);
      const float ratio = t.viscosity_length[wall] / t.dissipation_rate[wall];
      e = fmax(t.floor, ratio * row_strain_at(&g, &r, u, v, w, i));
    }
    energy[id] = e;
  }
}

/* Step 1: nu = min(C_m l sqrt(e), cap) per cell (m^2/s), 0 in solid cells; cap = kEddyDiffusionLimit h^2 /
 * dt. */
__kernel void tke_viscosity(const FwGrid g, const FwTke t, const float cap,
                            __global const uchar* restrict mask, __global const float* restrict energy,
                            __global float* restrict nu) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  const int row = cell_index(&g, 0, j, k), end = FW_ROW_END(g.nx);
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = row + i;
    const int fluid = mask[id] & FW_MASK_FLUID;
    nu[id] = fluid ? fmin(t.viscosity_length[cell_on_wall(&g, mask, id, k)] * sqrt(energy[id]), cap) : 0.0f;
  }
}

/* The two cells base and base + 1 along axis a that the advection's interpolation reads, which may lie
 * outside the grid: wrapped on a periodic axis, else the edge cell; inflow[n] = 1 where one lies across an
 * inflow face (it then reads FwTke.inflow). Resolved once per axis, not per corner. */
FW_INLINE void advect_axis(const FwGrid* g, int a, int base, int at[2], int inflow[2]) {
  for (int n = 0; n < 2; ++n) {
    at[n] = base + n;
    const int across = resolve_cell_axis(g, a, &at[n]);
    inflow[n] = across == FW_TKE_INFLOW;
    if (across != FW_TKE_INSIDE) at[n] = clamp(at[n], 0, axis_cells(g, a) - 1);
  }
}

/* Step 2: out = e at each cell centre traced back over s.dt along the cell-centred velocity (one Euler
 * step), trilinear between cell centres; a corner across an inflow face reads FwTke.inflow, a solid one
 * the departing cell's own e. 0 in solid cells. out must not be energy. */
__kernel void tke_advect(const FwGrid g, const FwStep s, const FwTke t, __global const uchar* restrict mask,
                         __global const float* restrict u, __global const float* restrict v,
                         __global const float* restrict w, __global const float* restrict energy,
                         __global float* restrict out) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  const int row = cell_index(&g, 0, j, k), end = FW_ROW_END(g.nx);
  const float steps = s.dt / g.h;  // cells travelled per m/s
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = row + i;
    if (!(mask[id] & FW_MASK_FLUID)) {
      out[id] = 0.0f;
      continue;
    }
    const float own = energy[id];
    /* The domain's positions, so that a rank's block gets a whole grid's fractions (docs/parallel.md). */
    const float at[3] = {(float)(i + g.ox) - steps * centre_velocity(&g, u, 0, i, j, k),
                         (float)(j + g.oy) - steps * centre_velocity(&g, v, 1, i, j, k),
                         (float)k - steps * centre_velocity(&g, w, 2, i, j, k)};
    int cx[2], cy[2], cz[2], ix[2], iy[2], iz[2];
    float frac[3];
    for (int a = 0; a < 3; ++a) frac[a] = at[a] - floor(at[a]);
    advect_axis(&g, 0, (int)floor(at[0]) - g.ox, cx, ix);
    advect_axis(&g, 1, (int)floor(at[1]) - g.oy, cy, iy);
    advect_axis(&g, 2, (int)floor(at[2]), cz, iz);
    float value = 0.0f;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy) {
        const int line = cell_index(&g, 0, cy[dy], cz[dz]);
        const float wyz = (dy ? frac[1] : 1.0f - frac[1]) * (dz ? frac[2] : 1.0f - frac[2]);
        for (int dx = 0; dx < 2; ++dx) {
          const int c = line + cx[dx];
          const float corner =
              (ix[dx] | iy[dy] | iz[dz]) ? t.inflow : ((mask[c] & FW_MASK_FLUID) ? energy[c] : own);
          value += (dx ? frac[0] : 1.0f - frac[0]) * wyz * corner;
        }
      }
    out[id] = value;
  }
}

/* One face's share of the diffusion of e: K_f (e_nb - e) with K_f = min(nu + nu_nb, cap) to a fluid
 * neighbour inside (`across` FW_TKE_INSIDE, index nb), min(2 nu, cap) (inflow - e) across an inflow face, 0
 * across a closed face or into a solid cell. */
FW_INLINE float face_exchange(const FwTke* t, __global const uchar* mask, __global const float* nu,
                              __global const float* advected, int across, int nb, float nu_own, float e,
                              float cap) {
  if (across == FW_TKE_INFLOW) return fmin(2.0f * nu_own, cap) * (t->inflow - e);
  if (across != FW_TKE_INSIDE || !(mask[nb] & FW_MASK_FLUID)) return 0.0f;
  return fmin(nu_own + nu[nb], cap) * (advected[nb] - e);
}

/* A row of cells beside the updated one along y or z: how it lies (FW_TKE_*) and, inside, its first cell. */
typedef struct {
  int across, row;
} NeighbourCells;

FW_INLINE NeighbourCells neighbour_cells(const FwGrid* g, int a, int j, int k) {
  int at[3] = {0, j, k};
  NeighbourCells n;
  n.across = resolve_cell_axis(g, a, &at[a]);
  n.row = n.across == FW_TKE_INSIDE ? cell_index(g, 0, at[1], at[2]) : 0;
  return n;
}

/* Steps 3 and 4 on the advected e*: energy = max(floor, (e* + dt (D + P + W)) / (1 + dt (C_eps sqrt(e*) / l
 * + s k |U|))), D = sum of face_exchange / h^2, P = nu |S|^2 from the velocity, W = wake_fraction k |U|^3;
 * k from drag_density where has_canopy (else 0: the buffer is not read). 0 in solid cells. */
__kernel void tke_update(const FwGrid g, const FwStep s, const FwTke t, const float cap, const int has_canopy,
                         __global const uchar* restrict mask, __global const float* restrict u,
                         __global const float* restrict v, __global const float* restrict w,
                         __global const float* restrict nu, __global const float* restrict drag_density,
                         __global const float* restrict advected, __global float* restrict energy) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  const RowStrain r = row_strain(&g, j, k);
  const NeighbourCells sides[4] = {neighbour_cells(&g, 1, j - 1, k), neighbour_cells(&g, 1, j + 1, k),
                                   neighbour_cells(&g, 2, j, k - 1), neighbour_cells(&g, 2, j, k + 1)};
  const int row = cell_index(&g, 0, j, k), end = FW_ROW_END(g.nx);
  const float inverse_h2 = 1.0f / (g.h * g.h);
  for (int i = FW_ROW_BEGIN; i < end; ++i) {
    const int id = row + i;
    if (!(mask[id] & FW_MASK_FLUID)) {
      energy[id] = 0.0f;
      continue;
    }
    const float e = advected[id], nu_own = nu[id];
    float flux = 0.0f;
    for (int side = -1; side <= 1; side += 2) {
      int x = i + side;
      const int across = resolve_cell_axis(&g, 0, &x);
      flux += face_exchange(&t, mask, nu, advected, across, row + x, nu_own, e, cap);
    }
    for (int n = 0; n < 4; ++n)
      flux += face_exchange(&t, mask, nu, advected, sides[n].across, sides[n].row + i, nu_own, e, cap);
    const float uc = centre_velocity(&g, u, 0, i, j, k), vc = centre_velocity(&g, v, 1, i, j, k),
                wc = centre_velocity(&g, w, 2, i, j, k);
    const float speed = sqrt(uc * uc + vc * vc + wc * wc);
    const float drag = has_canopy ? drag_density[id] : 0.0f;
    const float production =
        nu_own * row_strain_at(&g, &r, u, v, w, i) + t.wake_fraction * drag * speed * speed * speed;
    const float sink =
        t.dissipation_rate[cell_on_wall(&g, mask, id, k)] * sqrt(e) + t.canopy_sink * drag * speed;
    energy[id] = fmax(t.floor, (e + s.dt * (flux * inverse_h2 + production)) / (1.0f + s.dt * sink));
  }
}
