/* Leaves on the device (docs/leaves.md): flutter of attached leaves, shedding, flight in the resolved wind,
 * landing and exits; and on output frames the attached leaves at their deformed anchors.
 * Reference: trees/LeafReference.cpp. Host: host/stages/LeafStages.
 *
 * Work mapping: one leaf per loop iteration (FW_FLAT_FOR over the flat leaves). Flat leaf j belongs to
 * instance leaf_instance[j] and is species leaf j - first_leaf[instance] of its species.
 *
 * State per flat leaf: state (uchar, FW_LEAF_*), position (4 floats: blade centre, m; w unused), velocity (4
 * floats: flying m/s; attached: theta, theta', -, -), normal (4 floats, unit). Counters (FW_LEAF_COUNT_*) are
 * atomics: the totals do not depend on the order of the leaves. */
#include "common.cl"
#include "damped_oscillator.cl"

#define FW_AIR_DENSITY 1.2f          /* kg/m^3, trees/LeafSettings.hpp kAirDensity */
#define FW_LEAF_NORMAL_FORCE 1.2f    /* C_n, kLeafNormalForceCoefficient */
#define FW_GRAVITY 9.81f             /* m/s^2, kGravity */
#define FW_LEAF_TUMBLE_STROUHAL 0.1f /* kLeafTumbleStrouhal */
#define FW_PI 3.14159265358979f
#define FW_MAX_FLUTTER_ANGLE (0.5f * FW_PI) /* theta is clamped to [-pi/2, pi/2] */
#define FW_MAX_SUB_STEP_CELLS 0.5f          /* a flying leaf moves at most half a cell per sub-step */

/* A leaf's instance, its species' leaf parameters and its rest leaf. */
typedef struct {
  FwTreeInstance tree;
  FwLeafSpecies sp;
  FwRestLeaf rest;
} LeafContext;

FW_INLINE LeafContext leaf_context(const int j, __global const int* leaf_instance,
                                   __global const int* first_leaf, __global const FwTreeInstance* instances,
                                   __global const FwLeafSpecies* leaf_species,
                                   __global const FwRestLeaf* rest_leaves) {
  LeafContext ctx;
  const int k = leaf_instance[j];
  ctx.tree = instances[k];
  ctx.sp = leaf_species[ctx.tree.species];
  ctx.rest = rest_leaves[ctx.sp.leaf_offset + (j - first_leaf[k])];
  return ctx;
}

/* R(yaw) d: a skeleton-frame direction in the world. */
FW_INLINE float3 turn(const FwTreeInstance* tree, const float d[3]) {
  return (float3)(tree->cos_yaw * d[0] - tree->sin_yaw * d[1], tree->sin_yaw * d[0] + tree->cos_yaw * d[1],
                  d[2]);
}

/* position + s R p: a skeleton-frame point in the world. */
FW_INLINE float3 place(const FwTreeInstance* tree, const float p[3]) {
  return (float3)(tree->position[0], tree->position[1], tree->position[2]) + tree->scale * turn(tree, p);
}

/* v turned about the unit axis by the angle whose cosine and sine are c and s (Rodrigues). */
FW_INLINE float3 rotate_cs(const float3 v, const float3 axis, const float c, const float s) {
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0f - c));
}

/* v turned by angle about the unit axis. The native sine and cosine: their error (a few 1e-7 on PoCL, within
 * the reference test's 1e-4 m) is far below the model's, and the accurate ones were most of a leaf's step. */
FW_INLINE float3 rotate_about(const float3 v, const float3 axis, const float angle) {
  return rotate_cs(v, axis, native_cos(angle), native_sin(angle));
}

/* The MAC wind at world position p, m/s (sample_mac_component: trilinear, clamped to the lattice). */
FW_INLINE float3 wind_at(const FwGrid* g, __global const float* u, __global const float* v,
                         __global const float* w, const float3 p) {
  const float X[3] = {(p.x - g->origin[0]) / g->h, (p.y - g->origin[1]) / g->h, (p.z - g->origin[2]) / g->h};
  return (float3)(sample_mac_component(g, u, 0, X), sample_mac_component(g, v, 1, X),
                  sample_mac_component(g, w, 2, X));
}

/* The blade of an attached leaf at angle theta (pseudo-branch) or at time t (stochastic): its centre's
 * direction from the anchor and its normal, world frame. `wind_speed` scales the stochastic amplitudes. */
FW_INLINE void attached_blade(const LeafContext* ctx, const float theta, const float t,
                              const float wind_speed, float3* petiole, float3* normal) {
  const float3 p0 = turn(&ctx->tree, ctx->rest.petiole), n0 = turn(&ctx->tree, ctx->rest.normal);
  const float3 hinge = turn(&ctx->tree, ctx->rest.hinge);
  if (ctx->sp.model == FW_FLUTTER_STOCHASTIC) {
    /* R_z(theta_H) R_hinge(theta_V) R_petiole(theta_R) about the rest axes: the roll first (reference). */
    const float g = fmin(1.0f, wind_speed / ctx->sp.reference_speed);
    float angle[3];
    for (int a = 0; a < 3; ++a)
      angle[a] = ctx->sp.amplitude[a] * g *
                 native_sin(2.0f * FW_PI * ctx->rest.frequency[a] * t + ctx->rest.phase[a]);
    const float roll = angle[2] + ctx->sp.roll_coupling * angle[0];
    const float3 up = (float3)(0.0f, 0.0f, 1.0f);
    *petiole = rotate_about(rotate_about(p0, hinge, angle[1]), up, angle[0]);
    *normal = rotate_about(rotate_about(rotate_about(n0, p0, roll), hinge, angle[1]), up, angle[0]);
    return;
  }
  const float c = native_cos(theta), sn = native_sin(theta);
  *petiole = rotate_cs(p0, hinge, c, sn);
  *normal = rotate_cs(n0, hinge, c, sn);
}

/* One step of the attached leaves, and their shedding. */
FW_INLINE void step_attached(const FwGrid* g, const FwStep* s, const LeafContext* ctx,
                             __global const float* u, __global const float* v, __global const float* w,
                             const int j, __global uchar* state, __global float4* position,
                             __global float4* velocity, __global float4* normal, __global int* counters) {
  const float scale = ctx->tree.scale;
  const float lever = ctx->sp.lever * scale, area = ctx->sp.area * scale * scale;
  const float3 anchor = place(&ctx->tree, ctx->rest.anchor);
  const float3 rest_centre = anchor + lever * turn(&ctx->tree, ctx->rest.petiole);
  const float3 wind = wind_at(g, u, v, w, rest_centre);
  float4 motion = velocity[j]; /* theta, theta' */
  const float t = s->time + s->dt;
  if (ctx->sp.model == FW_FLUTTER_PSEUDO_BRANCH) {
    /* The torque linearised about the step's start: the air's damping D and stabilising stiffness K join
     * the oscillator, so that any dt is stable (docs/leaves.md; reference flutter_pseudo_branch). */
    /* The blade's normal at the step's start is the one the last step stored; kappa = (hinge x p) . n is
     * the same at every theta (p and n turn together about the hinge), so the rest pose gives it. */
    const float3 n = normal[j].xyz;
    const float3 hinge = turn(&ctx->tree, ctx->rest.hinge);
    const float kappa =
        dot(cross(hinge, turn(&ctx->tree, ctx->rest.petiole)), turn(&ctx->tree, ctx->rest.normal));
    const float q = 0.5f * FW_AIR_DENSITY * FW_LEAF_NORMAL_FORCE * area;
    const float un = dot(wind, n) - lever * motion.y * kappa;
    const float tau0 = lever * kappa * q * fabs(un) * un;
    const float damping = 2.0f * q * fabs(un) * lever * lever * kappa * kappa;
    const float stiffness = fmax(0.0f, -2.0f * lever * kappa * q * fabs(un) * dot(wind, cross(hinge, n)));
    const float side = ctx->sp.side * scale, mass = ctx->sp.mass * scale * scale;
    const float inertia = mass * (lever * lever + side * side / 12.0f);
    const float omega = ctx->sp.omega;
    const float held = (tau0 + damping * motion.y + stiffness * motion.x) / inertia;
    float theta = motion.x, rate = motion.y;
    damped_oscillator_step(sqrt(omega * omega + stiffness / inertia),
                           2.0f * ctx->sp.damping_ratio * omega + damping / inertia, held, s->dt, &theta,
                           &rate);
    if (fabs(theta) > FW_MAX_FLUTTER_ANGLE) { /* the stop: the blade rests against it */
      theta = copysign(FW_MAX_FLUTTER_ANGLE, theta);
      rate = 0.0f;
    }
    motion.x = theta;
    motion.y = rate;
  }
  float3 p, n;
  attached_blade(ctx, motion.x, t, length(wind), &p, &n);
  const float3 centre = anchor + lever * p;
  const float load = 0.5f * FW_AIR_DENSITY * FW_LEAF_NORMAL_FORCE * area * fabs(dot(wind, n)) * length(wind);
  position[j] = (float4)(centre, 0.0f);
  normal[j] = (float4)(n, 0.0f);
  if (load > ctx->rest.strength) {
    state[j] = FW_LEAF_FLYING;
    velocity[j] = (float4)(0.0f);
    atomic_inc(&counters[FW_LEAF_COUNT_SHED]);
  } else {
    velocity[j] = motion;
  }
}

/* Below the ground or in a solid cell (world position x). Outside the grid's sides nothing is solid (exits
 * come first). Reference: LeafReference.cpp Terrain::blocked. */
FW_INLINE int blocked(const FwGrid* g, __global const uchar* mask, const float3 x) {
  if (x.z < g->origin[2]) return 1;
  const int n[3] = {g->nx, g->ny, g->nz};
  const float p[3] = {x.x, x.y, x.z};
  int cell[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = (int)floor((p[a] - g->origin[a]) / g->h);
    if (cell[a] < 0 || cell[a] >= n[a]) return 0;
  }
  return !(mask[cell_index(g, cell[0], cell[1], cell[2])] & FW_MASK_FLUID);
}

/* z of the top face of the layer that holds x: the ground for a point below it. */
FW_INLINE float top_face(const FwGrid* g, const float3 x) {
  const int k = max(-1, (int)floor((x.z - g->origin[2]) / g->h));
  return g->origin[2] + (float)(k + 1) * g->h;
}

/* Wraps q (and p with it) through periodic x and y sides; 0 when q left through any other side or the top
 * (the ground is no side: below it is blocked). */
FW_INLINE int inside_or_wrapped(const FwGrid* g, float3* p, float3* q) {
  const int n[2] = {g->nx, g->ny};
  for (int a = 0; a < 2; ++a) {
    const float lo = g->origin[a], span = (float)n[a] * g->h;
    float qa = a == 0 ? q->x : q->y;
    if (qa >= lo && qa < lo + span) continue;
    if (g->bc[2 * a] != FW_BC_PERIODIC) return 0;
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

/* One step of a flying leaf: implicit drag and gravity, then the move in sub-steps of at most half a cell
 * that find solids and sides (reference: LeafReference.cpp fly and move). */
FW_INLINE void step_flying(const FwGrid* g, const FwStep* s, const LeafContext* ctx,
                           __global const uchar* mask, __global const float* u, __global const float* v,
                           __global const float* w, const int j, __global uchar* state,
                           __global float4* position, __global float4* velocity, __global float4* normal,
                           __global int* counters) {
  float3 x = position[j].xyz;
  const float3 v0 = velocity[j].xyz;
  const float3 wind = wind_at(g, u, v, w, x);
  const float k = ctx->sp.flight_drag;
  const float relative = length(wind - v0);
  const float dt = s->dt;
  float3 vel =
      (v0 + dt * ((float3)(0.0f, 0.0f, -FW_GRAVITY) + k * relative * wind)) / (1.0f + dt * k * relative);
  /* Tumbling: the blade turns about its horizontal axis at Omega = 2 pi St |u - v| / l (visual only). */
  const float side = ctx->sp.side * ctx->tree.scale;
  const float3 axis = turn(&ctx->tree, ctx->rest.tumble_axis);
  const float tumble = 2.0f * FW_PI * FW_LEAF_TUMBLE_STROUHAL * relative / side * dt;
  normal[j] = (float4)(normalize(rotate_about(normal[j].xyz, axis, tumble)), 0.0f);

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
    if (!blocked(g, mask, q)) {
      x = q;
      continue;
    }
    /* Solid below: the sub-step started above the blocking cell's top face, and the point on it is free. */
    const float3 on_top = (float3)(q.x, q.y, top_face(g, q));
    if (p.z >= on_top.z && !blocked(g, mask, on_top)) {
      land(j, on_top, state, position, velocity, counters);
      return;
    }
    /* A wall from the side: stay at the wall at the sub-step's new height, fall on without horizontal speed.
     */
    vel.x = vel.y = 0.0f;
    travel.x = travel.y = 0.0f;
    const float3 down = (float3)(p.x, p.y, q.z);
    if (!blocked(g, mask, down)) {
      x = down;
      continue;
    }
    land(j, (float3)(p.x, p.y, top_face(g, down)), state, position, velocity, counters);
    return;
  }
  position[j] = (float4)(x, 0.0f);
  velocity[j] = (float4)(vel, 0.0f);
}

/* One step of every leaf over s.dt, ending at s.time + s.dt. */
__kernel void leaves_step(const FwGrid g, const FwStep s, const int leaf_count,
                          __global const int* leaf_instance, __global const int* first_leaf,
                          __global const FwTreeInstance* instances,
                          __global const FwLeafSpecies* leaf_species, __global const FwRestLeaf* rest_leaves,
                          __global const uchar* mask, __global const float* u, __global const float* v,
                          __global const float* w, __global uchar* state, __global float4* position,
                          __global float4* velocity, __global float4* normal, __global int* counters) {
  FW_FLAT_FOR(n, leaf_count) {
    const int j = (int)n;
    const uchar now = state[j];
    if (now == FW_LEAF_LANDED || now == FW_LEAF_EXITED) continue;
    const LeafContext ctx = leaf_context(j, leaf_instance, first_leaf, instances, leaf_species, rest_leaves);
    if (now == FW_LEAF_ATTACHED)
      step_attached(&g, &s, &ctx, u, v, w, j, state, position, velocity, normal, counters);
    else
      step_flying(&g, &s, &ctx, mask, u, v, w, j, state, position, velocity, normal, counters);
  }
}

/* Output frames: every attached leaf's blade centre at its deformed anchor, the anchor moved by the
 * displacement of its element interpolated between the element's two nodes (`displacements`: 3 floats per
 * flat node, world frame, from the trees' deformation of the same frame). */
__kernel void leaves_frame(const int leaf_count, __global const int* leaf_instance,
                           __global const int* first_leaf, __global const FwTreeInstance* instances,
                           __global const FwLeafSpecies* leaf_species, __global const FwRestLeaf* rest_leaves,
                           __global const float* displacements, __global const uchar* state,
                           __global const float4* position, __global float4* frame_position) {
  FW_FLAT_FOR(n, leaf_count) {
    const int j = (int)n;
    if (state[j] != FW_LEAF_ATTACHED) {
      frame_position[j] = position[j];
      continue;
    }
    const LeafContext ctx = leaf_context(j, leaf_instance, first_leaf, instances, leaf_species, rest_leaves);
    const int a = ctx.tree.node_offset + ctx.rest.parent_node, b = ctx.tree.node_offset + ctx.rest.child_node;
    const float t = ctx.rest.along;
    const float3 da = (float3)(displacements[3 * a], displacements[3 * a + 1], displacements[3 * a + 2]);
    const float3 db = (float3)(displacements[3 * b], displacements[3 * b + 1], displacements[3 * b + 2]);
    frame_position[j] = position[j] + (float4)(mix(da, db, t), 0.0f);
  }
}
