/* Leaves on the device (docs/leaves.md): flutter of attached leaves, shedding, flight in the resolved wind,
 * landing and exits; and on output frames every leaf's blade, the attached ones at their deformed anchors.
 * Reference: trees/LeafReference.cpp. Host: host/stages/LeafStages.
 *
 * Before a step, the host samples the wind at every site (the centre of a cell that holds the rest centre of
 * at least one leaf: host/stages/PointWindOnDevice). Attached leaves read their site's wind: one load a leaf
 * instead of 24. A step then runs two kernels:
 *  - leaves_flying_step: one leaf at a time, over blocks of FW_LANES flat leaves (FW_FLAT_FOR); blocks
 *    without a flying leaf are skipped with one vector compare. It runs before the attached leaves, so that
 *    a leaf shed in a step flies from the next one on.
 *  - leaves_attached_step: blocks of FW_LANES consecutive leaves of one instance in vector arithmetic
 *    (kernels/lanes.cl), a run of blocks per work-item (block_run). leaves_frame has the same mapping.
 *
 * Flat leaf j = first_leaf[k] + i is leaf i of instance k, rest leaf leaf_offset + i of its species (the rest
 * table: FW_REST_* in shared_types.h). Per flat leaf, every array padded by FW_LANES values: state (uchar,
 * FW_LEAF_*); theta and theta_rate (attached, pseudo-branch: rad, rad/s); position, velocity and normal
 * (4 floats: the blade centre, m; m/s; unit), kept for leaves that are no longer attached, from the step
 * that shed them on; flight (4 floats: the world tumble axis and the blade's side, m) and flight_drag (1/m),
 * set when a leaf is shed, so that a flying leaf needs nothing of its tree. Counters (FW_LEAF_COUNT_*) are
 * atomics: the totals do not depend on the order of the leaves.
 *
 * Over MPI ranks a rank steps the leaves of its own trees, and the flying and landed leaves in its block's
 * own columns: after each step leaves_leaving lists those outside them, and the host sends them on. Their
 * flight samples and tests cells in the domain's indices, so a leaf moves by the bits one process gives it.
 */
#include "common.cl"
#include "lanes.cl"

#define FW_AIR_DENSITY 1.2f          /* kg/m^3, trees/LeafSettings.hpp kAirDensity */
#define FW_LEAF_NORMAL_FORCE 1.2f    /* C_n, kLeafNormalForceCoefficient */
#define FW_GRAVITY 9.81f             /* m/s^2, kGravity */
#define FW_LEAF_TUMBLE_STROUHAL 0.1f /* kLeafTumbleStrouhal */
#define FW_PI 3.14159265358979f
#define FW_MAX_FLUTTER_ANGLE (0.5f * FW_PI) /* theta is clamped to [-pi/2, pi/2] */
#define FW_MAX_SUB_STEP_CELLS 0.5f          /* a flying leaf moves at most half a cell per sub-step */

/* ---- One leaf at a time: flying leaves --------------------------------------------------------------- */

/* R(yaw) d: a skeleton-frame direction in the world. */
FW_INLINE float3 turn(const FwTreeInstance* tree, const float3 d) {
  return (float3)(tree->cos_yaw * d.x - tree->sin_yaw * d.y, tree->sin_yaw * d.x + tree->cos_yaw * d.y, d.z);
}

/* v turned by angle about the unit axis (Rodrigues). The native sine and cosine: their error (a few 1e-7 on
 * PoCL, within the reference test's tolerances) is far below the model's. */
FW_INLINE float3 rotate_about(const float3 v, const float3 axis, const float angle) {
  const float c = native_cos(angle), s = native_sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}

/* The MAC wind at world position p, m/s (sample_mac_component: trilinear, clamped to the lattice). */
FW_INLINE float3 wind_at(const FwGrid* g, __global const float* u, __global const float* v,
                         __global const float* w, const float3 p) {
  const float X[3] = {(p.x - g->origin[0]) / g->h, (p.y - g->origin[1]) / g->h, (p.z - g->origin[2]) / g->h};
  return (float3)(sample_mac_component(g, u, 0, X), sample_mac_component(g, v, 1, X),
                  sample_mac_component(g, w, 2, X));
}

/* Below the ground or in a solid cell (world position x). Outside the domain's sides nothing is solid (exits
 * come first). On a rank's block cut across a periodic axis, the halo beyond the domain's face holds the
 * cells of the axis' other end: a leaf that wrapped there mid-step finds them one period away. A cell in the
 * domain beyond a rank's block and its halo counts a FW_LEAF_COUNT_PAST_HALO and reads as free. Reference:
 * LeafReference.cpp Terrain::blocked. */
FW_INLINE int blocked(const FwGrid* g, __global const uchar* mask, const float3 x, __global int* counters) {
  if (x.z < g->origin[2]) return 1;
  const int n[3] = {g->domain[0], g->domain[1], g->nz}, offset[3] = {g->ox, g->oy, 0};
  const int extent[3] = {g->nx, g->ny, g->nz};
  const float p[3] = {x.x, x.y, x.z};
  int cell[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = (int)floor((p[a] - g->origin[a]) / g->h);
    if (cell[a] < 0 || cell[a] >= n[a]) return 0;
  }
  for (int a = 0; a < 3; ++a) {
    cell[a] -= offset[a];
    const int period = a < 2 ? g->wrap[a] : 0;
    if (period > 0 && cell[a] < 0) cell[a] += period;
    if (period > 0 && cell[a] >= extent[a]) cell[a] -= period;
    if (cell[a] < 0 || cell[a] >= extent[a]) {
      atomic_inc(&counters[FW_LEAF_COUNT_PAST_HALO]);
      return 0;
    }
  }
  return !(mask[cell_index(g, cell[0], cell[1], cell[2])] & FW_MASK_FLUID);
}

/* z of the top face of the layer that holds x: the ground for a point below it. */
FW_INLINE float top_face(const FwGrid* g, const float3 x) {
  const int k = max(-1, (int)floor((x.z - g->origin[2]) / g->h));
  return g->origin[2] + (float)(k + 1) * g->h;
}

/* Wraps q (and p with it) through the domain's periodic x and y sides; 0 when q left through any other side
 * or the top (the ground is no side: below it is blocked). A rank's block cut across a periodic axis has slip
 * sides, and its `wrap` says the domain's axis is periodic: it wraps the leaf as one process does, and the
 * host then sends it to the rank that holds it. */
FW_INLINE int inside_or_wrapped(const FwGrid* g, float3* p, float3* q) {
  const int n[2] = {g->domain[0], g->domain[1]};
  for (int a = 0; a < 2; ++a) {
    const float lo = g->origin[a], span = (float)n[a] * g->h;
    float qa = a == 0 ? q->x : q->y;
    if (qa >= lo && qa < lo + span) continue;
    if (g->bc[2 * a] != FW_BC_PERIODIC && g->wrap[a] == 0) return 0;
    float shift = -span * floor((qa - lo) / span);
    if (qa + shift >= lo + span) shift -= span; /* rounding just below lo */
    if (a == 0) {
      q->x += shift;
      p->x += shift;
    } else {
      q->y += shift;
      p->y += shift;
    }
  }
  return q->z < g->origin[2] + (float)g->nz * g->h;
}

FW_INLINE void land(const int j, const float3 x, __global uchar* state, __global float4* position,
                    __global float4* velocity, __global int* counters) {
  state[j] = FW_LEAF_LANDED;
  position[j] = (float4)(x, 0.0f);
  velocity[j] = (float4)(0.0f);
  atomic_inc(&counters[FW_LEAF_COUNT_LANDED]);
}

/* One step of flying leaf j: implicit drag and gravity, then the move in sub-steps of at most half a cell
 * that find solids and sides (reference: LeafReference.cpp fly and move). `side`: the blade's side, m;
 * `tumble_axis`: world frame. */
FW_INLINE void step_flying(const FwGrid* g, const FwStep* s, const float flight_drag, const float side,
                           const float3 tumble_axis, __global const uchar* mask, __global const float* u,
                           __global const float* v, __global const float* w, const int j,
                           __global uchar* state, __global float4* position, __global float4* velocity,
                           __global float4* normal, __global int* counters) {
  float3 x = position[j].xyz;
  const float3 v0 = velocity[j].xyz;
  const float3 wind = wind_at(g, u, v, w, x);
  const float k = flight_drag;
  const float relative = length(wind - v0);
  const float dt = s->dt;
  float3 vel =
      (v0 + dt * ((float3)(0.0f, 0.0f, -FW_GRAVITY) + k * relative * wind)) / (1.0f + dt * k * relative);
  /* Tumbling: the blade turns about its horizontal axis at Omega = 2 pi St |u - v| / l (visual only). */
  const float tumble = 2.0f * FW_PI * FW_LEAF_TUMBLE_STROUHAL * relative / side * dt;
  normal[j] = (float4)(normalize(rotate_about(normal[j].xyz, tumble_axis, tumble)), 0.0f);

  float3 travel = dt * vel;
  const int pieces = max(1, (int)ceil(length(travel) / (FW_MAX_SUB_STEP_CELLS * g->h)));
  for (int piece = 0; piece < pieces; ++piece) {
    float3 p = x, q = x + travel / (float)pieces;
    if (!inside_or_wrapped(g, &p, &q)) {
      state[j] = FW_LEAF_EXITED;
      position[j] = (float4)(q, 0.0f);
      velocity[j] = (float4)(0.0f);
      atomic_inc(&counters[FW_LEAF_COUNT_EXITED]);
      return;
    }
    if (!blocked(g, mask, q, counters)) {
      x = q;
      continue;
    }
    /* Solid below: the sub-step started above the blocking cell's top face, and the point on it is free. */
    const float3 on_top = (float3)(q.x, q.y, top_face(g, q));
    if (p.z >= on_top.z && !blocked(g, mask, on_top, counters)) {
      land(j, on_top, state, position, velocity, counters);
      return;
    }
    /* A wall from the side: stay at the wall at the sub-step's new height, fall on without horizontal speed.
     */
    vel.x = vel.y = 0.0f;
    travel.x = travel.y = 0.0f;
    const float3 down = (float3)(p.x, p.y, q.z);
    if (!blocked(g, mask, down, counters)) {
      x = down;
      continue;
    }
    land(j, (float3)(p.x, p.y, top_face(g, down)), state, position, velocity, counters);
    return;
  }
  position[j] = (float4)(x, 0.0f);
  velocity[j] = (float4)(vel, 0.0f);
}

/* One step of every flying leaf over s.dt. */
__kernel void leaves_flying_step(const FwGrid g, const FwStep s, const int leaf_count,
                                 __global const uchar* mask, __global const float* u, __global const float* v,
                                 __global const float* w, __global const float4* flight,
                                 __global const float* flight_drag, __global uchar* state,
                                 __global float4* position, __global float4* velocity,
                                 __global float4* normal, __global int* counters) {
  /* FW_LANES states at a time: most leaves are attached or landed, and a block without a flying leaf costs
   * one vector compare. The state array is padded by FW_LANES. */
  FW_FLAT_FOR(block, (leaf_count + FW_LANES - 1) / FW_LANES) {
    const int j0 = (int)block * FW_LANES;
    if (!any(convert_lanei(lane_load(0, state + j0) == (uchar)(FW_LEAF_FLYING)))) continue;
    for (int j = j0; j < min(j0 + FW_LANES, leaf_count); ++j) {
      if (state[j] != FW_LEAF_FLYING) continue;
      const float4 f = flight[j];
      step_flying(&g, &s, flight_drag[j], f.w, f.xyz, mask, u, v, w, j, state, position, velocity, normal,
                  counters);
    }
  }
}

/* Over ranks, after a step: the flying and landed leaves whose cell column lies outside the block's own cells
 * (own_lo <= i < own_hi along x, y, the domain's indices), their slots appended to `leaving` (in no order:
 * the host sorts them) and counted in FW_LEAF_COUNT_LEAVING. */
__kernel void leaves_leaving(const FwGrid g, const int leaf_count, const int own_lo_x, const int own_hi_x,
                             const int own_lo_y, const int own_hi_y, __global const uchar* state,
                             __global const float4* position, __global int* leaving, __global int* counters) {
  FW_FLAT_FOR(block, (leaf_count + FW_LANES - 1) / FW_LANES) {
    const int j0 = (int)block * FW_LANES;
    const lanei st = convert_lanei(lane_load(0, state + j0));
    if (!any((st == (lanei)(FW_LEAF_FLYING)) | (st == (lanei)(FW_LEAF_LANDED)))) continue;
    for (int j = j0; j < min(j0 + FW_LANES, leaf_count); ++j) {
      if (state[j] != FW_LEAF_FLYING && state[j] != FW_LEAF_LANDED) continue;
      const float4 p = position[j];
      const int i = (int)floor((p.x - g.origin[0]) / g.h), k = (int)floor((p.y - g.origin[1]) / g.h);
      if (i >= own_lo_x && i < own_hi_x && k >= own_lo_y && k < own_hi_y) continue;
      leaving[atomic_inc(&counters[FW_LEAF_COUNT_LEAVING])] = j;
    }
  }
}

/* Over ranks: the leaves in `slots` packed for the host (FW_LEAF_PACKED_FLOATS each, shared_types.h), and
 * their slots emptied (FW_LEAF_MOVED; the host restores a leaf it keeps). */
__kernel void leaves_pack(const int count, __global const int* slots, __global uchar* state,
                          __global const float4* position, __global const float4* velocity,
                          __global const float4* normal, __global const float4* flight,
                          __global const float* flight_drag, __global float4* packed) {
  FW_FLAT_FOR(n, count) {
    const int j = slots[n];
    packed[4 * n] = (float4)(position[j].xyz, (float)state[j]);
    packed[4 * n + 1] = (float4)(velocity[j].xyz, flight_drag[j]);
    packed[4 * n + 2] = normal[j];
    packed[4 * n + 3] = flight[j];
    state[j] = FW_LEAF_MOVED;
  }
}

/* Over ranks: the leaves that other ranks sent (packed as leaves_pack packs them) into `slots`: freed slots
 * of leaves that moved on, or new ones past the last. */
__kernel void leaves_unpack(const int count, __global const int* slots, __global const float4* packed,
                            __global uchar* state, __global float4* position, __global float4* velocity,
                            __global float4* normal, __global float4* flight, __global float* flight_drag) {
  FW_FLAT_FOR(n, count) {
    const int j = slots[n];
    const float4 where = packed[4 * n], motion = packed[4 * n + 1];
    position[j] = (float4)(where.xyz, 0.0f);
    state[j] = (uchar)where.w;
    velocity[j] = (float4)(motion.xyz, 0.0f);
    flight_drag[j] = motion.w;
    normal[j] = packed[4 * n + 2];
    flight[j] = packed[4 * n + 3];
  }
}

/* Field `field` (one row) of rest leaf r. */
FW_INLINE float rest_value(__global const float* rest, const int stride, const int field, const int r) {
  return rest[field * stride + r];
}

/* ---- FW_LANES leaves at a time: attached leaves ------------------------------------------------------ */

/* A 3-vector per lane. */
typedef struct {
  lanef x, y, z;
} lane3;

FW_INLINE lane3 lane3_of(const lanef x, const lanef y, const lanef z) {
  lane3 r = {x, y, z};
  return r;
}
FW_INLINE lane3 add3(const lane3 a, const lane3 b) {
  return lane3_of(a.x + b.x, a.y + b.y, a.z + b.z);
}
FW_INLINE lane3 scale3(const lanef s, const lane3 a) {
  return lane3_of(s * a.x, s * a.y, s * a.z);
}
FW_INLINE lanef dot3(const lane3 a, const lane3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
FW_INLINE lane3 cross3(const lane3 a, const lane3 b) {
  return lane3_of(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* v turned about the unit axis by the angle whose cosine and sine are c and s (Rodrigues). */
FW_INLINE lane3 rotate_lanes(const lane3 v, const lane3 axis, const lanef c, const lanef s) {
  return add3(add3(scale3(c, v), scale3(s, cross3(axis, v))), scale3(dot3(axis, v) * (1.0f - c), axis));
}
/* The lanes of a 3-vector in private arrays, for the per-lane scalar work of rare events and frames. */
typedef struct {
  float x[FW_LANES], y[FW_LANES], z[FW_LANES];
} LaneArrays;

FW_INLINE LaneArrays split3(const lane3 v) {
  LaneArrays a;
  lane_store(v.x, 0, a.x);
  lane_store(v.y, 0, a.y);
  lane_store(v.z, 0, a.z);
  return a;
}
FW_INLINE float3 lane_value(const LaneArrays* a, const int l) {
  return (float3)(a->x[l], a->y[l], a->z[l]);
}

/* R(yaw) d and R(yaw)^T d: between an instance's skeleton frame and the world. */
FW_INLINE lane3 to_world(const FwTreeInstance* tree, const lane3 d) {
  return lane3_of(tree->cos_yaw * d.x - tree->sin_yaw * d.y, tree->sin_yaw * d.x + tree->cos_yaw * d.y, d.z);
}
FW_INLINE lane3 to_skeleton(const FwTreeInstance* tree, const lane3 d) {
  return lane3_of(tree->cos_yaw * d.x + tree->sin_yaw * d.y, -tree->sin_yaw * d.x + tree->cos_yaw * d.y, d.z);
}

/* The rest geometry of rest leaves r0 .. r0 + FW_LANES - 1 (skeleton frame). Fields a kernel does not use are
 * never loaded: the compiler drops dead loads. */
typedef struct {
  lane3 anchor, petiole, hinge, normal, swing;
  lanef hinge_normal, kappa, along, strength;
  lanef phase[3], frequency[3];
} RestLanes;

FW_INLINE lanef rest_row(__global const float* rest, const int stride, const int field, const int r0) {
  return lane_load(0, rest + field * stride + r0);
}
FW_INLINE lane3 rest_vector(__global const float* rest, const int stride, const int field, const int r0) {
  return lane3_of(rest_row(rest, stride, field, r0), rest_row(rest, stride, field + 1, r0),
                  rest_row(rest, stride, field + 2, r0));
}
FW_INLINE RestLanes rest_lanes(__global const float* rest, const int stride, const int r0) {
  RestLanes r;
  r.anchor = rest_vector(rest, stride, FW_REST_ANCHOR, r0);
  r.petiole = rest_vector(rest, stride, FW_REST_PETIOLE, r0);
  r.hinge = rest_vector(rest, stride, FW_REST_HINGE, r0);
  r.normal = rest_vector(rest, stride, FW_REST_NORMAL, r0);
  r.swing = rest_vector(rest, stride, FW_REST_SWING, r0);
  r.hinge_normal = rest_row(rest, stride, FW_REST_HINGE_NORMAL, r0);
  r.kappa = rest_row(rest, stride, FW_REST_KAPPA, r0);
  r.along = rest_row(rest, stride, FW_REST_ALONG, r0);
  r.strength = rest_row(rest, stride, FW_REST_STRENGTH, r0);
  for (int a = 0; a < 3; ++a) {
    r.phase[a] = rest_row(rest, stride, FW_REST_PHASE + a, r0);
    r.frequency[a] = rest_row(rest, stride, FW_REST_FREQUENCY + a, r0);
  }
  return r;
}

/* The wind of the lanes' sites (leaf_site_wind), in the instance's skeleton frame. */
FW_INLINE lane3 site_wind_lanes(const FwTreeInstance* tree, __global const float* site_wind,
                                const lanei site) {
  const lanei at = 3 * site;
  return to_skeleton(tree,
                     lane3_of(gather(site_wind, at), gather(site_wind + 1, at), gather(site_wind + 2, at)));
}

/* The blade's normal at pseudo-branch angle theta (cosine c, sine s): the rest normal turned about the
 * hinge, n0 c + (h x n0) s + h (h . n0)(1 - c). */
FW_INLINE lane3 normal_at(const RestLanes* r, const lanef c, const lanef s) {
  return add3(add3(scale3(c, r->normal), scale3(s, r->swing)),
              scale3((1.0f - c) * r->hinge_normal, r->hinge));
}

/* The blade of attached leaves, skeleton frame: the direction of its centre from the anchor (petiole) and
 * its normal. Pseudo-branch: both turned by theta about the hinge. Stochastic (`t`: time, s; `speed`: the
 * wind's, m/s): Rot = R_z(theta_H) R_hinge(theta_V) R_petiole(theta_R) with theta_R = the roll plus
 * roll_coupling theta_H, amplitudes scaled by min(1, speed / U_ref) (reference: flutter_stochastic). */
FW_INLINE void blade_lanes(const FwLeafSpecies* sp, const RestLanes* r, const lanef theta, const float t,
                           const lanef speed, lane3* petiole, lane3* normal) {
  if (sp->model == FW_FLUTTER_STOCHASTIC) {
    const lanef g = fmin((lanef)(1.0f), speed / sp->reference_speed);
    lanef angle[3];
    lanef unused;
    for (int a = 0; a < 3; ++a)
      angle[a] =
          sp->amplitude[a] * g * sincos_lanes(2.0f * FW_PI * r->frequency[a] * t + r->phase[a], &unused);
    const lanef roll = angle[2] + sp->roll_coupling * angle[0];
    const lanef zero = (lanef)(0.0f), one = (lanef)(1.0f);
    const lane3 up = lane3_of(zero, zero, one);
    lanef ch, cv, cr;
    const lanef sh = sincos_lanes(angle[0], &ch), sv = sincos_lanes(angle[1], &cv),
                sr = sincos_lanes(roll, &cr);
    *petiole = rotate_lanes(rotate_lanes(r->petiole, r->hinge, cv, sv), up, ch, sh);
    *normal =
        rotate_lanes(rotate_lanes(rotate_lanes(r->normal, r->petiole, cr, sr), r->hinge, cv, sv), up, ch, sh);
    return;
  }
  lanef c;
  const lanef s = sincos_quarter_lanes(theta, &c); /* |theta| <= FW_MAX_FLUTTER_ANGLE = pi/2 */
  /* The petiole is normal to the hinge: p0 c + (h x p0) s. */
  *petiole = add3(scale3(c, r->petiole), scale3(s, cross3(r->hinge, r->petiole)));
  *normal = normal_at(r, c, s);
}

/* One step of x'' + gamma x' + w2 x = f over dt, f held: the two-stage Radau IIA method (order 3, L-stable).
 * For this linear system it is exactly y1 = R(M) y0 with R(z) = (1 + z/3) / (1 - 2z/3 + z^2/6), the (1,2)
 * Pade approximant of e^z, M = [[0, 1], [-p, -g]] (p = w2 dt^2, g = gamma dt) on y = (x - f/w2, dt x'): a
 * 2 x 2 solve, no exponential, sine or square root. Its numerical damping is below 1e-3 of critical at
 * w dt = 0.4, and it damps motions far faster than the step (w dt >> 1) instead of ringing. Reference:
 * trees/LeafReference.cpp radau_oscillator_step. */
FW_INLINE void radau_oscillator_lanes(const lanef w2, const lanef gamma, const lanef f, const float dt,
                                      lanef* x, lanef* v) {
  const lanef p = w2 * (dt * dt), g = gamma * dt;
  const lanef x_rest = f / w2;
  const lanef y0 = *x - x_rest, y1 = dt * (*v);
  const lanef b0 = y0 + y1 * (1.0f / 3.0f), b1 = y1 - (p * y0 + g * y1) * (1.0f / 3.0f); /* N y */
  const lanef d00 = 1.0f - p * (1.0f / 6.0f), d01 = -(2.0f / 3.0f + g * (1.0f / 6.0f));
  const lanef d10 = -p * d01, d11 = 1.0f + g * (2.0f / 3.0f) + (g * g - p) * (1.0f / 6.0f); /* D */
  const lanef per_det = 1.0f / (d00 * d11 - d01 * d10); /* det D > 0: the roots of D are 2 +- i sqrt 2 */
  *x = x_rest + (d11 * b0 - d01 * b1) * per_det;
  *v = (d00 * b1 - d10 * b0) * (per_det * (1.0f / dt));
}

/* Oliapuram's pseudo-branch over dt, FW_LANES leaves of an instance of scale `scale` in the skeleton-frame
 * wind u, their blades' normals n at the step's start. The torque is linearised about the step's start: the
 * air's damping D and stabilising stiffness K join the oscillator, so that any dt is stable (docs/leaves.md;
 * reference flutter_pseudo_branch). */
FW_INLINE void flutter_pseudo_branch_lanes(const FwLeafSpecies* sp, const float scale, const RestLanes* r,
                                           const lane3 u, const lane3 n, const float dt, lanef* theta,
                                           lanef* rate) {
  const float lever = sp->lever * scale, area = sp->area * scale * scale;
  const float side = sp->side * scale, mass = sp->mass * scale * scale;
  const float per_inertia =
      1.0f / (mass * (lever * lever + side * side / 12.0f)); /* multiplies: no divides */
  const float q = 0.5f * FW_AIR_DENSITY * FW_LEAF_NORMAL_FORCE * area;
  const lanef un = dot3(u, n) - lever * (*rate) * r->kappa;
  const lanef tau0 = lever * r->kappa * q * fabs(un) * un;
  const lanef damping = 2.0f * q * fabs(un) * lever * lever * r->kappa * r->kappa;
  const lanef stiffness = fmax(-2.0f * lever * r->kappa * q * fabs(un) * dot3(u, cross3(r->hinge, n)), 0.0f);
  const lanef held = (tau0 + damping * (*rate) + stiffness * (*theta)) * per_inertia;
  const float omega = sp->omega;
  radau_oscillator_lanes(omega * omega + stiffness * per_inertia,
                         2.0f * sp->damping_ratio * omega + damping * per_inertia, held, dt, theta, rate);
  /* The stop: the blade rests against it. */
  const lanei stopped = fabs(*theta) > FW_MAX_FLUTTER_ANGLE;
  *theta = select(*theta, copysign((lanef)(FW_MAX_FLUTTER_ANGLE), *theta), stopped);
  *rate = select(*rate, (lanef)(0.0f), stopped);
}

/* Leaf blocks: FW_LANES consecutive leaves of one instance, instance k's blocks first_block[k] ..
 * first_block[k + 1] - 1 (instance_count + 1 values). Each work-item takes a contiguous run of blocks (CPUs:
 * a few runs per core; GPUs: about one block each) and walks the instances it spans, so that an instance's
 * parameters are loaded and broadcast to the lanes once per run, not once per block. */
FW_INLINE int instance_of_block(__global const int* first_block, const int instance_count, const int b) {
  int lo = 0, hi = instance_count - 1; /* the last k with first_block[k] <= b */
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (first_block[mid] <= b)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

/* This work-item's run of blocks: [*begin, *end). */
FW_INLINE void block_run(const int block_count, int* begin, int* end) {
  const int items = (int)get_global_size(0);
  const int per = (block_count + items - 1) / items;
  *begin = min(block_count, (int)get_global_id(0) * per);
  *end = min(block_count, *begin + per);
}

/* A block's leaves: leaves i0 .. i0 + valid - 1 of its instance, flat leaf j0 and rest leaf r0 of the first;
 * `attached`: the lanes that hold an attached leaf. */
#define FW_LEAF_BLOCK_SETUP                                  \
  const int valid = min(FW_LANES, sp->leaf_count - i0);      \
  const int j0 = first_leaf + i0, r0 = sp->leaf_offset + i0; \
  const lanei in_range = FW_LANE_OFFSETS < (lanei)(valid);   \
  const lanei attached = convert_lanei(lane_load(0, state + j0) == (uchar)(FW_LEAF_ATTACHED)) & in_range;

/* The loop of a lane kernel over this work-item's blocks: BLOCK(tree, sp, first_leaf, i0) for each. */
#define FW_FOR_LEAF_BLOCKS(BLOCK)                                                            \
  int b, end;                                                                                \
  block_run(block_count, &b, &end);                                                          \
  if (b >= end) return;                                                                      \
  for (int k = instance_of_block(first_block, instance_count, b); b < end; ++k) {            \
    const FwTreeInstance tree = instances[k];                                                \
    const FwLeafSpecies sp = leaf_species[tree.species];                                     \
    const int last = min(end, first_block[k + 1]);                                           \
    for (; b < last; ++b) BLOCK(&tree, &sp, first_leaf[k], (b - first_block[k]) * FW_LANES); \
  }

/* The blade centres of the lanes, world frame: the anchor plus the lever along the petiole. */
FW_INLINE lane3 blade_centres(const FwTreeInstance* tree, const FwLeafSpecies* sp, const RestLanes* r,
                              const lane3 petiole) {
  const lane3 root =
      lane3_of((lanef)(tree->position[0]), (lanef)(tree->position[1]), (lanef)(tree->position[2]));
  return add3(root, scale3((lanef)(tree->scale),
                           to_world(tree, add3(r->anchor, scale3((lanef)(sp->lever), petiole)))));
}

/* One step of the attached leaves over s.dt, ending at s.time + s.dt, and their shedding: a leaf is shed when
 * the step's wind's normal force on its blade, in the pose it has at the step's start, exceeds its petiole's
 * strength; it flies from the next step on, from that pose, at rest. */
FW_INLINE void attached_block(const FwTreeInstance* tree, const FwLeafSpecies* sp, const int first_leaf,
                              const int i0, const FwStep* s, __global const float* rest,
                              const int rest_stride, __global const int* leaf_site,
                              __global const float* site_wind, __global uchar* state, __global float* theta,
                              __global float* theta_rate, __global float4* position,
                              __global float4* velocity, __global float4* normal, __global float4* flight,
                              __global float* flight_drag, __global int* counters) {
  FW_LEAF_BLOCK_SETUP
  if (!any(attached)) return;
  const RestLanes r = rest_lanes(rest, rest_stride, r0);
  const lane3 u = site_wind_lanes(tree, site_wind, lane_load(0, leaf_site + j0));
  const lanef speed = sqrt(dot3(u, u));
  lanef angle = lane_load(0, theta + j0), rate = lane_load(0, theta_rate + j0);
  /* The blades at the step's start: the pose the last step left (the pseudo-branch's angle; the stochastic
   * angles at the step's start, in this step's wind). */
  lane3 petiole, n;
  blade_lanes(sp, &r, angle, s->time, speed, &petiole, &n);
  const float q = 0.5f * FW_AIR_DENSITY * FW_LEAF_NORMAL_FORCE * sp->area * tree->scale * tree->scale;
  const lanei shed = attached & (q * fabs(dot3(u, n)) * speed > r.strength);
  if (sp->model == FW_FLUTTER_PSEUDO_BRANCH)
    flutter_pseudo_branch_lanes(sp, tree->scale, &r, u, n, s->dt, &angle, &rate);
  /* Lanes of leaves no longer attached store values nobody reads. */
  store_lanes(theta, j0, valid, angle);
  store_lanes(theta_rate, j0, valid, rate);
  if (!any(shed)) return;
  /* Rare: scalar stores of the shed lanes. */
  const LaneArrays centre = split3(blade_centres(tree, sp, &r, petiole)), nw = split3(to_world(tree, n));
  int flag[FW_LANES];
  lane_store(shed, 0, flag);
  for (int l = 0; l < FW_LANES; ++l) {
    if (!flag[l]) continue;
    const int j = j0 + l;
    const int rl = r0 + l;
    const float3 axis = (float3)(rest_value(rest, rest_stride, FW_REST_TUMBLE_AXIS, rl),
                                 rest_value(rest, rest_stride, FW_REST_TUMBLE_AXIS + 1, rl),
                                 rest_value(rest, rest_stride, FW_REST_TUMBLE_AXIS + 2, rl));
    state[j] = FW_LEAF_FLYING;
    position[j] = (float4)(lane_value(&centre, l), 0.0f);
    normal[j] = (float4)(lane_value(&nw, l), 0.0f);
    velocity[j] = (float4)(0.0f);
    flight[j] = (float4)(turn(tree, axis), sp->side * tree->scale);
    flight_drag[j] = sp->flight_drag;
    atomic_inc(&counters[FW_LEAF_COUNT_SHED]);
  }
}

#define FW_ATTACHED_BLOCK(tree, sp, first_leaf, i0)                                                   \
  attached_block(tree, sp, first_leaf, i0, &s, rest, rest_stride, leaf_site, site_wind, state, theta, \
                 theta_rate, position, velocity, normal, flight, flight_drag, counters)

__kernel void leaves_attached_step(
    const FwStep s, const int block_count, const int instance_count, __global const int* first_block,
    __global const int* first_leaf, __global const FwTreeInstance* instances,
    __global const FwLeafSpecies* leaf_species, __global const float* rest, const int rest_stride,
    __global const int* leaf_site, __global const float* site_wind, __global uchar* state,
    __global float* theta, __global float* theta_rate, __global float4* position, __global float4* velocity,
    __global float4* normal, __global float4* flight, __global float* flight_drag,
    __global int* counters){FW_FOR_LEAF_BLOCKS(FW_ATTACHED_BLOCK)}

/* Every leaf's blade at time t (the last step's end): the attached ones from their angles (and the wind of
 * that step, for the stochastic amplitudes), at their anchors moved by their element's displacement
 * interpolated between its two nodes when `displaced` (`displacements`: 3 floats per flat node, world frame,
 * from the trees' deformation of the same frame); the others where they are. rest_nodes: each rest leaf's
 * element nodes (2 ints, species-local). Same work mapping as leaves_attached_step. */
FW_INLINE void frame_block(const FwTreeInstance* tree, const FwLeafSpecies* sp, const int first_leaf,
                           const int i0, const float t, __global const float* rest, const int rest_stride,
                           __global const int* rest_nodes, __global const int* leaf_site,
                           __global const float* site_wind, const int displaced,
                           __global const float* displacements, __global const uchar* state,
                           __global const float* theta, __global const float4* position,
                           __global const float4* normal, __global float4* frame_position,
                           __global float4* frame_normal) {
  FW_LEAF_BLOCK_SETUP
  const RestLanes r = rest_lanes(rest, rest_stride, r0);
  const lane3 u = site_wind_lanes(tree, site_wind, lane_load(0, leaf_site + j0));
  lane3 petiole, n;
  blade_lanes(sp, &r, lane_load(0, theta + j0), t, sqrt(dot3(u, u)), &petiole, &n);
  const LaneArrays centre = split3(blade_centres(tree, sp, &r, petiole)), nw = split3(to_world(tree, n));
  float along[FW_LANES];
  int flag[FW_LANES];
  lane_store(r.along, 0, along);
  lane_store(attached, 0, flag);
  for (int l = 0; l < valid; ++l) {
    const int j = j0 + l;
    if (!flag[l]) {
      frame_position[j] = position[j];
      frame_normal[j] = normal[j];
      continue;
    }
    float3 x = lane_value(&centre, l);
    if (displaced) {
      const int a = tree->node_offset + rest_nodes[2 * (r0 + l)];
      const int b = tree->node_offset + rest_nodes[2 * (r0 + l) + 1];
      const float3 da = (float3)(displacements[3 * a], displacements[3 * a + 1], displacements[3 * a + 2]);
      const float3 db = (float3)(displacements[3 * b], displacements[3 * b + 1], displacements[3 * b + 2]);
      x += mix(da, db, along[l]);
    }
    frame_position[j] = (float4)(x, 0.0f);
    frame_normal[j] = (float4)(lane_value(&nw, l), 0.0f);
  }
}

#define FW_FRAME_BLOCK(tree, sp, first_leaf, i0)                                                           \
  frame_block(tree, sp, first_leaf, i0, t, rest, rest_stride, rest_nodes, leaf_site, site_wind, displaced, \
              displacements, state, theta, position, normal, frame_position, frame_normal)

__kernel void leaves_frame(const float t, const int block_count, const int instance_count,
                           __global const int* first_block, __global const int* first_leaf,
                           __global const FwTreeInstance* instances,
                           __global const FwLeafSpecies* leaf_species, __global const float* rest,
                           const int rest_stride, __global const int* rest_nodes,
                           __global const int* leaf_site, __global const float* site_wind,
                           const int displaced, __global const float* displacements,
                           __global const uchar* state, __global const float* theta,
                           __global const float4* position, __global const float4* normal,
                           __global float4* frame_position, __global float4* frame_normal) {
  FW_FOR_LEAF_BLOCKS(FW_FRAME_BLOCK)
}
