/* The element tree models (trees/TreeDynamics.hpp): Oliapuram's articulated rigid branches and Ota's
 * cantilever springs, on every tree whose species one of them moves. References: trees/RigidBranches.cpp,
 * trees/SpringBranches.cpp, trees/BranchPose.cpp; the table: trees/BranchElements.hpp (FwBranch).
 *
 * Work mapping: one tree per loop iteration (FW_FLAT_FOR over the element trees) where a tree is walked in
 * its table's order, parents before children, or back up it: an element needs its children's results (the
 * rigid bodies' recursion up) or its parent's (the pose down), so one work-item keeps a tree's entries in
 * order. The springs' angles are independent: one entry per iteration. A
 * rigid tree's recursion keeps FW_RIGID_SCRATCH_FLOATS per entry in `scratch`, a slice of `scratch_stride`
 * floats per work-item (the host sizes it for its largest tree).
 *
 * Flat arrays, per element tree t at trees[t].entry_offset: the wind sampled at each entry's element centre
 * (3 floats, world frame), the joint state (FW_JOINT_FLOATS: angle, rate), the orientation (a quaternion,
 * 4 floats: w, x, y, z). Instance k of scale s: lengths s, masses s^3, inertias s^5, joint stiffness s^3,
 * drag per metre s, spring constants s (trees/BranchElements.hpp). */
#include "common.cl"
#include "lanes.cl"

/* A 3 x 3 matrix by rows. */
typedef struct {
  float3 r0, r1, r2;
} Mat3;

FW_INLINE Mat3 mat_rows(const float3 r0, const float3 r1, const float3 r2) {
  Mat3 m;
  m.r0 = r0;
  m.r1 = r1;
  m.r2 = r2;
  return m;
}

FW_INLINE float3 mat_vec(const Mat3 m, const float3 v) {
  return (float3)(dot(m.r0, v), dot(m.r1, v), dot(m.r2, v));
}

FW_INLINE Mat3 mat_transpose(const Mat3 m) {
  Mat3 t;
  t.r0 = (float3)(m.r0.x, m.r1.x, m.r2.x);
  t.r1 = (float3)(m.r0.y, m.r1.y, m.r2.y);
  t.r2 = (float3)(m.r0.z, m.r1.z, m.r2.z);
  return t;
}

FW_INLINE Mat3 mat_mul(const Mat3 a, const Mat3 b) {
  const Mat3 bt = mat_transpose(b);
  return mat_rows(mat_vec(bt, a.r0), mat_vec(bt, a.r1), mat_vec(bt, a.r2));
}

FW_INLINE Mat3 mat_add(const Mat3 a, const Mat3 b) {
  Mat3 c;
  c.r0 = a.r0 + b.r0;
  c.r1 = a.r1 + b.r1;
  c.r2 = a.r2 + b.r2;
  return c;
}

FW_INLINE Mat3 mat_sub(const Mat3 a, const Mat3 b) {
  Mat3 c;
  c.r0 = a.r0 - b.r0;
  c.r1 = a.r1 - b.r1;
  c.r2 = a.r2 - b.r2;
  return c;
}

FW_INLINE Mat3 mat_scale(const float s, const Mat3 a) {
  Mat3 c;
  c.r0 = s * a.r0;
  c.r1 = s * a.r1;
  c.r2 = s * a.r2;
  return c;
}

/* [r]: [r] v = r x v. */
FW_INLINE Mat3 mat_skew(const float3 r) {
  Mat3 m;
  m.r0 = (float3)(0.0f, -r.z, r.y);
  m.r1 = (float3)(r.z, 0.0f, -r.x);
  m.r2 = (float3)(-r.y, r.x, 0.0f);
  return m;
}

FW_INLINE Mat3 mat_diagonal(const float d) {
  Mat3 m;
  m.r0 = (float3)(d, 0.0f, 0.0f);
  m.r1 = (float3)(0.0f, d, 0.0f);
  m.r2 = (float3)(0.0f, 0.0f, d);
  return m;
}

/* The inverse by the adjugate; the joint terms inverted here are symmetric positive definite. */
FW_INLINE Mat3 mat_inverse(const Mat3 m) {
  const float3 c0 = cross(m.r1, m.r2), c1 = cross(m.r2, m.r0), c2 = cross(m.r0, m.r1);
  const float inverse_det = 1.0f / dot(m.r0, c0);
  return mat_scale(inverse_det, mat_transpose(mat_rows(c0, c1, c2)));
}

FW_INLINE Mat3 mat_load(__global const float* p) {
  return mat_rows(vload3(0, p), vload3(1, p), vload3(2, p));
}

FW_INLINE void mat_store(const Mat3 m, __global float* p) {
  vstore3(m.r0, 0, p);
  vstore3(m.r1, 1, p);
  vstore3(m.r2, 2, p);
}

/* K_e from its six stored values (xx yy zz xy xz yz). */
FW_INLINE Mat3 joint_stiffness(const FwBranch* e) {
  const float* k = e->stiffness;
  return mat_rows((float3)(k[0], k[3], k[4]), (float3)(k[3], k[1], k[5]), (float3)(k[4], k[5], k[2]));
}

FW_INLINE float3 branch_rest(const FwBranch* e) {
  return (float3)(e->rest[0], e->rest[1], e->rest[2]);
}

/* The drag on entry j's element of tree `tree` (N, skeleton frame, at scale s) from the wind sampled at its
 * centre (world frame): s^2 L (b P v + l v) |v| f(|v|), f the drag law's factor. */
FW_INLINE float3 element_load(const FwBranch* e, const FwTreeInstance* tree, const FwDragLaw law,
                              __global const float* wind, const int normal_drag) {
  const float3 w = vload3(0, wind);
  const float cs = tree->cos_yaw, sn = tree->sin_yaw;
  const float3 v = (float3)(cs * w.x + sn * w.y, -sn * w.x + cs * w.y, w.z);
  const float speed = length(v);
  float3 wood = v;
  if (normal_drag) {
    const float3 axis = branch_rest(e) / e->length;
    wood -= dot(axis, v) * axis;
  }
  const float s = tree->scale;
  return (s * s * e->length * speed * drag_law_factor(law, speed)) *
         (e->branch_drag * wood + e->leaf_drag * v);
}

/* Once, when the forest is uploaded: every entry's element centre in the world frame, x + s R c (the root's
 * entry: the root), where its wind is sampled. */
__kernel void branch_sample_positions(const int tree_count, __global const FwBranchTree* trees,
                                      __global const FwTreeInstance* instances,
                                      __global const FwSpecies* species, __global const FwBranch* branches,
                                      __global float* sample_world) {
  FW_FLAT_FOR(t, tree_count) {
    const FwBranchTree bt = trees[t];
    const FwTreeInstance tree = instances[bt.instance];
    const FwSpecies sp = species[tree.species];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw;
    for (int j = 0; j < sp.node_count; ++j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      const float3 c = (float3)(e.centre[0], e.centre[1], e.centre[2]);
      const float3 world = (float3)(tree.position[0], tree.position[1], tree.position[2]) +
                           tree.scale * (float3)(cs * c.x - sn * c.y, sn * c.x + cs * c.y, c.z);
      vstore3(world, bt.entry_offset + j, sample_world);
    }
  }
}

/* Springs (trees/SpringBranches.hpp): every entry's joint angle from its own load at time t; no rate. One
 * entry per loop iteration (FW_FLAT_FOR over the flat entries of every element tree): the elements are
 * independent, and their atan and sin vectorise across work-items. entry_tree names each flat entry's tree
 * (an index into `trees`); entries of trees of another model are left alone. */
__kernel void spring_angles(const int entry_count, __global const int* entry_tree,
                            __global const FwBranchTree* trees, __global const FwTreeInstance* instances,
                            __global const FwSpecies* species, __global const FwBranchSpecies* models,
                            __global const FwBranch* branches, const FwDragLaw law,
                            __global const float* wind, const float time, __global float* joints) {
  const float turn = 2.0f * M_PI_F / (float)(1u << FW_PHASE_BITS);
  FW_FLAT_FOR(flat, entry_count) {
    const FwBranchTree bt = trees[entry_tree[flat]];
    const FwTreeInstance tree = instances[bt.instance];
    const FwBranchSpecies model = models[tree.species];
    if (model.model != FW_DYNAMICS_SPRINGS) continue;
    const int j = (int)flat - bt.entry_offset;
    float3 angle = (float3)(0.0f);
    if (j > 0) {
      const FwBranch e = branches[species[tree.species].skeleton_offset + j];
      const float s = tree.scale;
      const float3 F = element_load(&e, &tree, law, wind + 3 * flat, model.normal_drag);
      const float3 axis = branch_rest(&e) / e.length;
      const float3 normal = F - dot(F, axis) * axis;
      const float load = length(normal);
      if (load > 0.0f) {
        const float bend = load / (s * e.spring) / (s * e.length);
        const float steady = fmin(atan(bend), model.max_angle);
        const float amplitude = model.sway_amplitude * steady / model.max_angle;
        const float phase = turn * (float)fw_phase_bits((fw_uint)bt.id, (fw_uint)j);
        const float swayed = bend * (1.0f + amplitude * sin(model.sway_omega * time + phase));
        const float theta = clamp(atan(swayed), -model.max_angle, model.max_angle);
        angle = theta * cross(axis, normal / load);
      }
    }
    __global float* joint = joints + FW_JOINT_FLOATS * flat;
    vstore3(angle, 0, joint);
    vstore3((float3)(0.0f), 1, joint);
  }
}

/* Scratch slot of an entry during the recursion up: accumulated A, B, M (9 floats each) and the bias force's
 * moment and force (3 each); rewritten once the entry is done with A, B, D^-1 (9 each) and u (3). */
#define SLOT_A 0
#define SLOT_B 9
#define SLOT_M 18
#define SLOT_N 27
#define SLOT_F 30
#define SLOT_D_INVERSE 18
#define SLOT_U 27

/* Rigid bodies (trees/RigidBranches.hpp): one implicit (theta-method) step of every joint, the
 * articulated-body recursion up the tree, then the accelerations down it. */
__kernel void rigid_branches_step(const int tree_count, __global const FwBranchTree* trees,
                                  __global const FwTreeInstance* instances, __global const FwSpecies* species,
                                  __global const FwBranchSpecies* models, __global const FwBranch* branches,
                                  const FwDragLaw law, __global const float* wind, const float dt,
                                  __global float* joints, __global float* scratch, const int scratch_stride) {
  __global float* work = scratch + get_global_id(0) * (size_t)scratch_stride;
  FW_FLAT_FOR(t, tree_count) {
    const FwBranchTree bt = trees[t];
    const FwTreeInstance tree = instances[bt.instance];
    const FwSpecies sp = species[tree.species];
    const int n = sp.node_count;
    const float s = tree.scale, s3 = s * s * s, s5 = s3 * s * s;
    /* C = beta K at scale s: beta = 2 zeta / (omega_1 / s). */
    const FwBranchSpecies model = models[tree.species];
    const float beta = model.damping * s;
    const float w = FW_RIGID_IMPLICIT_WEIGHT;
    const float joint_term = w * dt * beta + w * w * dt * dt;
    for (int i = 0; i < FW_RIGID_SCRATCH_FLOATS * n; ++i) work[i] = 0.0f;

    for (int j = n - 1; j >= 1; --j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      __global float* slot = work + FW_RIGID_SCRATCH_FLOATS * j;
      const float3 rest = s * branch_rest(&e);
      const float3 axis = branch_rest(&e) / e.length;
      const float mass = s3 * e.mass;
      /* The rod about its joint: inertia about its centre c = rest / 2, moved to the joint. */
      const Mat3 along = mat_rows(axis.x * axis, axis.y * axis, axis.z * axis);
      const Mat3 centre_inertia =
          mat_add(mat_scale(s5 * e.mass * e.length * e.length / 12.0f, mat_sub(mat_diagonal(1.0f), along)),
                  mat_scale(s5 * e.axial_inertia, along));
      const Mat3 c = mat_skew(0.5f * rest);
      const Mat3 A =
          mat_add(mat_load(slot + SLOT_A), mat_sub(centre_inertia, mat_scale(mass, mat_mul(c, c))));
      const Mat3 B = mat_add(mat_load(slot + SLOT_B), mat_scale(mass, c));
      const Mat3 M = mat_add(mat_load(slot + SLOT_M), mat_diagonal(mass));
      const float3 F = element_load(&e, &tree, law, wind + 3 * (bt.entry_offset + j), model.normal_drag);
      const float3 pn = vload3(0, slot + SLOT_N) - cross(0.5f * rest, F);
      const float3 pf = vload3(0, slot + SLOT_F) - F;

      __global const float* joint = joints + FW_JOINT_FLOATS * (bt.entry_offset + j);
      const float3 theta = vload3(0, joint), rate = vload3(1, joint);
      const Mat3 K = mat_scale(s3, joint_stiffness(&e));
      const float3 torque = -mat_vec(K, theta + w * dt * rate) - beta * mat_vec(K, rate);
      const Mat3 D_inverse = mat_inverse(mat_add(A, mat_scale(joint_term, K)));
      const float3 u = torque - pn;

      if (e.parent_entry > 0) {
        const Mat3 AD = mat_mul(A, D_inverse);
        const Mat3 BtD = mat_mul(mat_transpose(B), D_inverse);
        const Mat3 Aa = mat_sub(A, mat_mul(AD, A));
        const Mat3 Ba = mat_sub(B, mat_mul(AD, B));
        const Mat3 Ma = mat_sub(M, mat_mul(BtD, B));
        const float3 na = pn + mat_vec(AD, u), fa = pf + mat_vec(BtD, u);
        /* Moved to the parent's joint, r = this joint - the parent's: trees/RigidBranches.cpp shift_into. */
        const FwBranch parent = branches[sp.skeleton_offset + e.parent_entry];
        const float3 r = s * branch_rest(&parent);
        const Mat3 R = mat_skew(r);
        __global float* up = work + FW_RIGID_SCRATCH_FLOATS * e.parent_entry;
        const Mat3 shifted_A = mat_add(mat_sub(Aa, mat_mul(Ba, R)),
                                       mat_sub(mat_mul(R, mat_transpose(Ba)), mat_mul(mat_mul(R, Ma), R)));
        mat_store(mat_add(mat_load(up + SLOT_A), shifted_A), up + SLOT_A);
        mat_store(mat_add(mat_load(up + SLOT_B), mat_add(Ba, mat_mul(R, Ma))), up + SLOT_B);
        mat_store(mat_add(mat_load(up + SLOT_M), Ma), up + SLOT_M);
        vstore3(vload3(0, up + SLOT_N) + na + cross(r, fa), 0, up + SLOT_N);
        vstore3(vload3(0, up + SLOT_F) + fa, 0, up + SLOT_F);
      }
      mat_store(A, slot + SLOT_A);
      mat_store(B, slot + SLOT_B);
      mat_store(D_inverse, slot + SLOT_D_INVERSE);
      vstore3(u, 0, slot + SLOT_U);
    }

    /* Down: the joint's angular acceleration from its parent's; the parent's accelerations (angular, and
     * linear at its joint) replace its A's first two rows, which nothing reads any more. */
    for (int j = 1; j < n; ++j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      __global float* slot = work + FW_RIGID_SCRATCH_FLOATS * j;
      float3 alpha = (float3)(0.0f), a = (float3)(0.0f);
      if (e.parent_entry > 0) {
        __global const float* up = work + FW_RIGID_SCRATCH_FLOATS * e.parent_entry;
        const FwBranch parent = branches[sp.skeleton_offset + e.parent_entry];
        alpha = vload3(0, up + SLOT_A);
        a = vload3(1, up + SLOT_A) + cross(alpha, s * branch_rest(&parent));
      }
      const Mat3 A = mat_load(slot + SLOT_A), B = mat_load(slot + SLOT_B);
      const float3 acceleration = mat_vec(mat_load(slot + SLOT_D_INVERSE),
                                          vload3(0, slot + SLOT_U) - mat_vec(A, alpha) - mat_vec(B, a));
      vstore3(alpha + acceleration, 0, slot + SLOT_A);
      vstore3(a, 1, slot + SLOT_A);
      __global float* joint = joints + FW_JOINT_FLOATS * (bt.entry_offset + j);
      const float3 rate = vload3(1, joint), new_rate = rate + dt * acceleration;
      vstore3(vload3(0, joint) + dt * ((1.0f - w) * rate + w * new_rate), 0, joint);
      vstore3(new_rate, 1, joint);
    }
  }
}

/* Rigid bodies at rest in the sampled wind (trees/RigidBranches.cpp equilibrium): theta = K^-1 M, M the
 * moment about the joint of everything beyond it, and no rate. The scratch holds each entry's moment and
 * force (SLOT_N, SLOT_F). */
__kernel void rigid_branches_equilibrium(const int tree_count, __global const FwBranchTree* trees,
                                         __global const FwTreeInstance* instances,
                                         __global const FwSpecies* species,
                                         __global const FwBranchSpecies* models,
                                         __global const FwBranch* branches, const FwDragLaw law,
                                         __global const float* wind, __global float* joints,
                                         __global float* scratch, const int scratch_stride) {
  __global float* work = scratch + get_global_id(0) * (size_t)scratch_stride;
  FW_FLAT_FOR(t, tree_count) {
    const FwBranchTree bt = trees[t];
    const FwTreeInstance tree = instances[bt.instance];
    const FwSpecies sp = species[tree.species];
    const int n = sp.node_count;
    const float s = tree.scale;
    for (int j = 0; j < n; ++j) {
      vstore3((float3)(0.0f), 0, work + FW_RIGID_SCRATCH_FLOATS * j + SLOT_N);
      vstore3((float3)(0.0f), 0, work + FW_RIGID_SCRATCH_FLOATS * j + SLOT_F);
    }
    vstore3((float3)(0.0f), 0, joints + FW_JOINT_FLOATS * bt.entry_offset);
    vstore3((float3)(0.0f), 1, joints + FW_JOINT_FLOATS * bt.entry_offset);
    for (int j = n - 1; j >= 1; --j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      __global float* slot = work + FW_RIGID_SCRATCH_FLOATS * j;
      const float3 F =
          element_load(&e, &tree, law, wind + 3 * (bt.entry_offset + j), models[tree.species].normal_drag);
      const float3 moment = vload3(0, slot + SLOT_N) + cross(0.5f * s * branch_rest(&e), F);
      const float3 force = vload3(0, slot + SLOT_F) + F;
      if (e.parent_entry > 0) {
        const FwBranch parent = branches[sp.skeleton_offset + e.parent_entry];
        __global float* up = work + FW_RIGID_SCRATCH_FLOATS * e.parent_entry;
        vstore3(vload3(0, up + SLOT_N) + moment + cross(s * branch_rest(&parent), force), 0, up + SLOT_N);
        vstore3(vload3(0, up + SLOT_F) + force, 0, up + SLOT_F);
      }
      __global float* joint = joints + FW_JOINT_FLOATS * (bt.entry_offset + j);
      const Mat3 K = mat_scale(s * s * s, joint_stiffness(&e));
      vstore3(mat_vec(mat_inverse(K), moment), 0, joint);
      vstore3((float3)(0.0f), 1, joint);
    }
  }
}

/* The pose, FW_LANES trees of one species at a time, one per lane: their walks are the same, so every step
 * of it is vector arithmetic across the trees (PoCL does not vectorise a loop inside a work-item). */

/* Three vectors' components, lane by lane. */
typedef struct {
  lanef x, y, z;
} LaneVec3;

/* Unit quaternions (w, v), lane by lane. */
typedef struct {
  lanef w;
  LaneVec3 v;
} LaneQuat;

FW_INLINE LaneVec3 lane_cross(const LaneVec3 a, const LaneVec3 b) {
  LaneVec3 c;
  c.x = a.y * b.z - a.z * b.y;
  c.y = a.z * b.x - a.x * b.z;
  c.z = a.x * b.y - a.y * b.x;
  return c;
}

/* q p. */
FW_INLINE LaneQuat lane_quaternion_mul(const LaneQuat q, const LaneQuat p) {
  const LaneVec3 c = lane_cross(q.v, p.v);
  LaneQuat r;
  r.w = q.w * p.w - (q.v.x * p.v.x + q.v.y * p.v.y + q.v.z * p.v.z);
  r.v.x = q.w * p.v.x + p.w * q.v.x + c.x;
  r.v.y = q.w * p.v.y + p.w * q.v.y + c.y;
  r.v.z = q.w * p.v.z + p.w * q.v.z + c.z;
  return r;
}

/* The largest joint angle, rad, whose half-angle cosine and sine lane_quaternion_exp take from their series
 * (sincos_quarter_lanes, good to 6e-8 up to a half-angle of pi/2). */
#define FW_SERIES_MAX_ANGLE 3.14159265f

/* Exp(theta): the unit quaternion of the rotation by a = |theta| about theta, (cos(a/2), sin(a/2)/a theta).
 * Joints turn by far less than a half turn, so every lane takes the series, whose sine over a needs no
 * division near 0; a lane beyond it takes sincos_lanes' reduction. */
FW_INLINE LaneQuat lane_quaternion_exp(const LaneVec3 theta) {
  const lanef angle = sqrt(theta.x * theta.x + theta.y * theta.y + theta.z * theta.z);
  lanef c;
  const lanef s = sincos_quarter_lanes(0.5f * angle, &c);
  /* sin(a/2)/a, whose limit at a = 0 is 1/2. */
  lanef sinc = select(s / angle, (lanef)(0.5f), angle == 0.0f);
  const lanei beyond = angle > FW_SERIES_MAX_ANGLE;
  if (any(beyond)) {
    lanef far_c;
    const lanef far_s = sincos_lanes(0.5f * angle, &far_c);
    c = select(c, far_c, beyond);
    sinc = select(sinc, far_s / angle, beyond);
  }
  LaneQuat q;
  q.w = c;
  q.v.x = sinc * theta.x;
  q.v.y = sinc * theta.y;
  q.v.z = sinc * theta.z;
  return q;
}

/* Floats of a pose slot per entry (kernels/shared_types.h FW_POSE_SCRATCH_FLOATS): the lanes' orientation
 * (w, x, y, z) and displacement (x, y, z, world frame), a lanef each. */
FW_INLINE void pose_store(__global float* slot, const LaneQuat q, const LaneVec3 u) {
  lane_store(q.w, 0, slot);
  lane_store(q.v.x, 1, slot);
  lane_store(q.v.y, 2, slot);
  lane_store(q.v.z, 3, slot);
  lane_store(u.x, 4, slot);
  lane_store(u.y, 5, slot);
  lane_store(u.z, 6, slot);
}

FW_INLINE LaneQuat pose_orientation(__global const float* slot) {
  LaneQuat q;
  q.w = lane_load(0, slot);
  q.v.x = lane_load(1, slot);
  q.v.y = lane_load(2, slot);
  q.v.z = lane_load(3, slot);
  return q;
}

FW_INLINE LaneVec3 pose_displacement(__global const float* slot) {
  LaneVec3 u;
  u.x = lane_load(4, slot);
  u.y = lane_load(5, slot);
  u.z = lane_load(6, slot);
  return u;
}

/* The pose (trees/BranchPose.hpp): every entry's orientation Q = Q_parent Exp(theta) from the root down, and
 * its node's displacement u = u_parent + R (Q - I) s rest (world frame), written into the forest's
 * displacements. (Q - I) r = 2 w (v x r) + 2 v x (v x r) for the unit quaternion (w, v) of Q keeps its
 * digits at small angles.
 *
 * Work mapping: one group of `groups` per loop iteration, FW_LANES element trees of one species (their
 * indices into `trees`, -1 past a group's last tree, whose lanes repeat its first and store nothing). Every
 * lane does the same operations whatever its neighbours, so a tree's frame has the same bits alone or in any
 * group. The lanes' orientations and displacements live only while their group is posed, in this
 * work-item's slice of `scratch` (FW_POSE_SCRATCH_FLOATS an entry, `scratch_stride` floats an item), which
 * its next group reuses while the slice is still in cache. */
__kernel void branch_deform(const int group_count, __global const int* groups,
                            __global const FwBranchTree* trees, __global const FwTreeInstance* instances,
                            __global const FwSpecies* species, __global const FwBranch* branches,
                            __global const float* joints, __global float* scratch, const int scratch_stride,
                            __global float* displacements) {
  __global float* work = scratch + get_global_id(0) * (size_t)scratch_stride;
  FW_FLAT_FOR(group, group_count) {
    __global const int* members = groups + FW_LANES * group;
    int first_joint[FW_LANES], first_node[FW_LANES];
    float scale[FW_LANES], cos_yaw[FW_LANES], sin_yaw[FW_LANES];
    int count = 0;
    for (int g = 0; g < FW_LANES; ++g) {
      const int member = members[g];
      if (member >= 0) count = g + 1;
      const FwBranchTree bt = trees[member >= 0 ? member : members[0]];
      const FwTreeInstance tree = instances[bt.instance];
      first_joint[g] = FW_JOINT_FLOATS * bt.entry_offset;
      first_node[g] = 3 * tree.node_offset;
      scale[g] = tree.scale;
      cos_yaw[g] = tree.cos_yaw;
      sin_yaw[g] = tree.sin_yaw;
    }
    const FwSpecies sp = species[instances[trees[members[0]].instance].species];
    const lanef s = lane_load(0, scale), cs = lane_load(0, cos_yaw), sn = lane_load(0, sin_yaw);
    const lanei joint_at = lane_load(0, first_joint);

    LaneQuat q;
    q.w = (lanef)(1.0f);
    q.v.x = q.v.y = q.v.z = (lanef)(0.0f);
    LaneVec3 u = q.v;
    pose_store(work, q, u);
    const int root = branches[sp.skeleton_offset].node;
    for (int g = 0; g < count; ++g) vstore3((float3)(0.0f), 0, displacements + first_node[g] + 3 * root);

    for (int j = 1; j < sp.node_count; ++j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      __global const float* parent = work + FW_POSE_SCRATCH_FLOATS * e.parent_entry;
      LaneVec3 theta;
      const lanei at = joint_at + FW_JOINT_FLOATS * j;
      theta.x = gather(joints, at);
      theta.y = gather(joints, at + 1);
      theta.z = gather(joints, at + 2);
      q = lane_quaternion_mul(pose_orientation(parent), lane_quaternion_exp(theta));
      LaneVec3 r;
      r.x = s * e.rest[0];
      r.y = s * e.rest[1];
      r.z = s * e.rest[2];
      const LaneVec3 vr = lane_cross(q.v, r), vvr = lane_cross(q.v, vr);
      const lanef cx = 2.0f * (q.w * vr.x + vvr.x), cy = 2.0f * (q.w * vr.y + vvr.y),
                  cz = 2.0f * (q.w * vr.z + vvr.z);
      u = pose_displacement(parent);
      u.x += cs * cx - sn * cy;
      u.y += sn * cx + cs * cy;
      u.z += cz;
      pose_store(work + FW_POSE_SCRATCH_FLOATS * j, q, u);
      float ux[FW_LANES], uy[FW_LANES], uz[FW_LANES];
      lane_store(u.x, 0, ux);
      lane_store(u.y, 0, uy);
      lane_store(u.z, 0, uz);
      for (int g = 0; g < count; ++g)
        vstore3((float3)(ux[g], uy[g], uz[g]), 0, displacements + first_node[g] + 3 * e.node);
    }
  }
}
