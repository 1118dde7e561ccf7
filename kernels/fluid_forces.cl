/* External forces on the face velocities: uniform body force, travelling gusts, vorticity confinement and
 * explicit viscous diffusion. Reference: fluid/ReferenceStages.cpp add_body_force, add_gusts,
 * vorticity, add_vorticity_confinement, diffuse. */
#include "common.cl"

/* q (component c) += dt * (body acceleration + sum of gust accelerations at t + dt/2). */
__kernel void apply_forces(const FwGrid g, const FwStep s, const int c, const float body_acceleration,
                           __global const FwGust* gusts, const int gust_count, __global float* q) {
  FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  const float tm = s.time + 0.5f * s.dt;
  const float y = g.origin[1] + g.h * (j + g.oy + face_offset(c, 1));
  const float z = g.origin[2] + g.h * (k + face_offset(c, 2));
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float x = g.origin[0] + g.h * (i + g.ox + face_offset(c, 0));
    float add = s.dt * body_acceleration;
    for (int n = 0; n < gust_count; ++n) {
      const FwGust G = gusts[n];
      const float tau = tm - G.start;
      if (!(tau > 0.0f && tau < G.duration)) continue;
      const float dx = x - (G.center[0] + G.travel[0] * tau);
      const float dy = y - (G.center[1] + G.travel[1] * tau);
      const float dz = z - (G.center[2] + G.travel[2] * tau);
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float rate = G.peak_speed * (M_PI_F / G.duration) * sin(2.0f * M_PI_F * tau / G.duration) *
                         exp(-r2 / (G.radius * G.radius));
      add += s.dt * rate * G.direction[c];
    }
    q[face_index(&g, c, i, j, k)] += add;
  }
}

/* The first and last cell of the domain along axis a, in this grid's indices. The vorticity and the
 * confinement turn one-sided at the domain's edges, periodic or not; a rank's block on a cut periodic axis
 * holds the domain's edge inside its cells (its halo lies across the seam), so it clamps there as a whole
 * grid does. */
FW_INLINE int domain_first(const FwGrid* g, int a) {
  return a < 2 && g->wrap[a] > 0 ? max(0, -(a == 0 ? g->ox : g->oy)) : 0;
}
FW_INLINE int domain_last(const FwGrid* g, int a) {
  const int last = axis_cells(g, a) - 1;
  return a < 2 && g->wrap[a] > 0 ? min(last, g->wrap[a] - 1 - (a == 0 ? g->ox : g->oy)) : last;
}

/* Cell-centred velocity component c. */
FW_INLINE float centre_velocity(const FwGrid* g, __global const float* q, int c, int i, int j, int k) {
  int hi[3] = {i, j, k};
  hi[c] += 1;
  return 0.5f * (q[face_index(g, c, i, j, k)] + q[face_index(g, c, hi[0], hi[1], hi[2])]);
}

/* d(component c)/d(axis a) at a cell: central difference, one-sided at the domain's edge. */
FW_INLINE float centre_derivative(const FwGrid* g, __global const float* q, int c, int a, int i, int j,
                                  int k) {
  int p[3] = {i, j, k}, m[3] = {i, j, k};
  p[a] = min(p[a] + 1, domain_last(g, a));
  m[a] = max(m[a] - 1, domain_first(g, a));
  const int span = p[a] - m[a];
  if (span == 0) return 0.0f;
  return (centre_velocity(g, q, c, p[0], p[1], p[2]) - centre_velocity(g, q, c, m[0], m[1], m[2])) /
         (span * g->h);
}

/* vorticity: 4 floats a cell (wx, wy, wz, |w|), 1/s. */
__kernel void vorticity(const FwGrid g, __global const float* u, __global const float* v,
                        __global const float* w, __global float* vorticity) {
  FW_ROWS_GUARD(g.nx, g.ny, g.nz);
  const int j = get_global_id(1), k = get_global_id(2);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(g.nx); ++i) {
    const float wx = centre_derivative(&g, w, 2, 1, i, j, k) - centre_derivative(&g, v, 1, 2, i, j, k);
    const float wy = centre_derivative(&g, u, 0, 2, i, j, k) - centre_derivative(&g, w, 2, 0, i, j, k);
    const float wz = centre_derivative(&g, v, 1, 0, i, j, k) - centre_derivative(&g, u, 0, 1, i, j, k);
    const int id = 4 * cell_index(&g, i, j, k);
    vorticity[id] = wx;
    vorticity[id + 1] = wy;
    vorticity[id + 2] = wz;
    vorticity[id + 3] = sqrt(wx * wx + wy * wy + wz * wz);
  }
}

/* Component c of the confinement force epsilon h (N x vorticity) at a cell. */
FW_INLINE float confinement_force(const FwGrid* g, __global const float* vorticity, float epsilon, int c,
                                  int i, int j, int k) {
  float eta[3];
  const int at[3] = {i, j, k};
  for (int a = 0; a < 3; ++a) {
    int p[3] = {i, j, k}, m[3] = {i, j, k};
    p[a] = min(at[a] + 1, domain_last(g, a));
    m[a] = max(at[a] - 1, domain_first(g, a));
    const int span = p[a] - m[a];
    eta[a] = span ? (vorticity[4 * cell_index(g, p[0], p[1], p[2]) + 3] -
                     vorticity[4 * cell_index(g, m[0], m[1], m[2]) + 3]) /
                        (span * g->h)
                  : 0.0f;
  }
  const float len = sqrt(eta[0] * eta[0] + eta[1] * eta[1] + eta[2] * eta[2]) + 1e-20f;
  const float N[3] = {eta[0] / len, eta[1] / len, eta[2] / len};
  const int id = 4 * cell_index(g, i, j, k);
  const float W[3] = {vorticity[id], vorticity[id + 1], vorticity[id + 2]};
  const float scale = epsilon * g->h;
  if (c == 0) return scale * (N[1] * W[2] - N[2] * W[1]);
  if (c == 1) return scale * (N[2] * W[0] - N[0] * W[2]);
  return scale * (N[0] * W[1] - N[1] * W[0]);
}

/* q (component c) += dt * confinement force averaged from the two cells beside the face. */
__kernel void vorticity_confinement(const FwGrid g, const FwStep s, const int c, const float epsilon,
                                    __global const float* vorticity, __global float* q) {
  FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  const int first = domain_first(&g, c), last = domain_last(&g, c);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    int lo[3] = {i, j, k}, hi[3] = {i, j, k};
    lo[c] = max(lo[c] - 1, first);
    hi[c] = min(hi[c], last);
    const float f = 0.5f * (confinement_force(&g, vorticity, epsilon, c, lo[0], lo[1], lo[2]) +
                            confinement_force(&g, vorticity, epsilon, c, hi[0], hi[1], hi[2]));
    q[face_index(&g, c, i, j, k)] += s.dt * f;
  }
}

/* out = q + nu dt / h^2 * (sum of the six neighbours - 6 q), neighbours through fetch_face's ghost rules. */
__kernel void diffuse(const FwGrid g, const FwStep s, __global const float* profile, const int c,
                      const float nu_dt_over_h2, __global const float* q, __global float* out) {
  FW_ROWS_GUARD(face_extent(&g, c, 0), face_extent(&g, c, 1), face_extent(&g, c, 2));
  const int j = get_global_id(1), k = get_global_id(2);
  const int ex = face_extent(&g, c, 0);
  for (int i = FW_ROW_BEGIN; i < FW_ROW_END(ex); ++i) {
    const float centre = q[face_index(&g, c, i, j, k)];
    const float lap =
        fetch_face(q, c, i - 1, j, k, &g, &s, profile) + fetch_face(q, c, i + 1, j, k, &g, &s, profile) +
        fetch_face(q, c, i, j - 1, k, &g, &s, profile) + fetch_face(q, c, i, j + 1, k, &g, &s, profile) +
        fetch_face(q, c, i, j, k - 1, &g, &s, profile) + fetch_face(q, c, i, j, k + 1, &g, &s, profile) -
        6.0f * centre;
    out[face_index(&g, c, i, j, k)] = centre + nu_dt_over_h2 * lap;
  }
}

/* Implicit canopy drag, F = -k f(|u|) |u| u with k = Cd a the drag density (1/m, one float a cell) and f
 * the drag law's factor (fluid/DragLaw.hpp: (max(|u|, floor) / U_ref)^exponent, 1 for exponent 0):
 * out = q / (1 + dt k_face f |u|_face), which never reverses or amplifies the flow for any dt.
 * k_face is the mean of the two cells beside the face (at a domain face that does not wrap, the one inside);
 * |u|_face takes the face's own component and the other two averaged from the four faces of those two cells.
 * Reads the old u, v, w and writes component c to `out`, on the faces first .. first + count - 1 of
 * component c only: the host passes the box of faces next to a cell of non-zero drag (a forest covers a
 * small part of the domain; a box at a periodic seam holds the faces on both sides of it), and copies them
 * back with copy_face_box. Global range: (ceil(count.x / FW_ROW_CHUNK), count.y,
 * count.z). Reference: fluid/ReferenceStages.cpp canopy_drag. */
FW_INLINE void canopy_drag_box(const FwGrid* g, const float dt, const int c, const int4 first,
                               const int4 count, const FwDragLaw law, __global const float* drag,
                               __global const float* u, __global const float* v, __global const float* w,
                               __global float* out) {
  FW_ROWS_GUARD(count.x, count.y, count.z);
  const int j = first.y + (int)get_global_id(1), k = first.z + (int)get_global_id(2);
  const int n = axis_cells(g, c);
  /* The face's own component q and the other two, a (axis d1) and b (axis d2). */
  const int d1 = c == 0 ? 1 : 0, d2 = c == 2 ? 1 : 2;
  __global const float* q = c == 0 ? u : (c == 1 ? v : w);
  __global const float* a = d1 == 0 ? u : v;
  __global const float* b = d2 == 1 ? v : w;
  for (int r = FW_ROW_BEGIN; r < FW_ROW_END(count.x); ++r) {
    const int i = first.x + r;
    int lo[3] = {i, j, k}, hi[3] = {i, j, k};
    /* At the domain's edge the one cell inside, but across a periodic seam the cell on the other side: the
     * seam's face is the domain's face 0 and its face n at once, and a block cut there reads it from its
     * halo. */
    const int wrap = axis_periodic(g, c);
    lo[c] = lo[c] > 0 ? lo[c] - 1 : (wrap ? n - 1 : 0);
    hi[c] = hi[c] < n ? hi[c] : (wrap ? 0 : n - 1);
    const float kf =
        0.5f * (drag[cell_index(g, lo[0], lo[1], lo[2])] + drag[cell_index(g, hi[0], hi[1], hi[2])]);
    const int face = face_index(g, c, i, j, k);
    const float qf = q[face];
    if (kf == 0.0f) { /* gaps between the trees: a plain copy */
      out[face] = qf;
      continue;
    }
    /* The next faces up along d1 and d2 of both cells. */
    int lo1[3] = {lo[0], lo[1], lo[2]}, hi1[3] = {hi[0], hi[1], hi[2]};
    int lo2[3] = {lo[0], lo[1], lo[2]}, hi2[3] = {hi[0], hi[1], hi[2]};
    lo1[d1] += 1;
    hi1[d1] += 1;
    lo2[d2] += 1;
    hi2[d2] += 1;
    const float ma =
        0.25f * (a[face_index(g, d1, lo[0], lo[1], lo[2])] + a[face_index(g, d1, lo1[0], lo1[1], lo1[2])] +
                 a[face_index(g, d1, hi[0], hi[1], hi[2])] + a[face_index(g, d1, hi1[0], hi1[1], hi1[2])]);
    const float mb =
        0.25f * (b[face_index(g, d2, lo[0], lo[1], lo[2])] + b[face_index(g, d2, lo2[0], lo2[1], lo2[2])] +
                 b[face_index(g, d2, hi[0], hi[1], hi[2])] + b[face_index(g, d2, hi2[0], hi2[1], hi2[2])]);
    const float speed = sqrt(qf * qf + ma * ma + mb * mb);
    out[face] = qf / (1.0f + dt * kf * drag_law_factor(law, speed) * speed);
  }
}

/* One kernel a component, so that c is a literal and the index arrays above fold into registers. */
__kernel void canopy_drag_u(const FwGrid g, const FwStep s, const int4 first, const int4 count,
                            const FwDragLaw law, __global const float* drag, __global const float* u,
                            __global const float* v, __global const float* w, __global float* out) {
  canopy_drag_box(&g, s.dt, 0, first, count, law, drag, u, v, w, out);
}
__kernel void canopy_drag_v(const FwGrid g, const FwStep s, const int4 first, const int4 count,
                            const FwDragLaw law, __global const float* drag, __global const float* u,
                            __global const float* v, __global const float* w, __global float* out) {
  canopy_drag_box(&g, s.dt, 1, first, count, law, drag, u, v, w, out);
}
__kernel void canopy_drag_w(const FwGrid g, const FwStep s, const int4 first, const int4 count,
                            const FwDragLaw law, __global const float* drag, __global const float* u,
                            __global const float* v, __global const float* w, __global float* out) {
  canopy_drag_box(&g, s.dt, 2, first, count, law, drag, u, v, w, out);
}

/* to = from on the faces first .. first + count - 1 of component c; the range as for canopy_drag_*. */
__kernel void copy_face_box(const FwGrid g, const int c, const int4 first, const int4 count,
                            __global const float* from, __global float* to) {
  FW_ROWS_GUARD(count.x, count.y, count.z);
  const int j = first.y + (int)get_global_id(1), k = first.z + (int)get_global_id(2);
  const int row = face_index(&g, c, first.x, j, k);
  for (int r = FW_ROW_BEGIN; r < FW_ROW_END(count.x); ++r) to[row + r] = from[row + r];
}
