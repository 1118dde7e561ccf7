/* The element tree models (trees/TreeDynamics.hpp): Oliapuram's articulated rigid branches and Ota's
 * cantilever springs, on every tree whose species one of them moves. References: trees/RigidBranches.cpp,
 * trees/SpringBranches.cpp, trees/BranchPose.cpp; the table: trees/BranchElements.hpp (FwBranch).
 *
 * Work mapping: one tree per loop iteration (FW_FLAT_FOR over the element trees) where a tree is walked in
 * its table's order, parents before children, or back up it: an element needs its children's results (the
 * rigid bodies' recursion up) or its parent's (the pose down), so one work-item keeps a tree's entries in
 * order. The springs' angles are independent: FW_LANES entries of one tree per iteration, in vector
 * arithmetic (kernels/lanes.cl). A rigid tree's recursion keeps FW_RIGID_SCRATCH_FLOATS per entry, and the
 * pose FW_POSE_FLOATS, in `scratch`, a slice of `scratch_stride` floats per work-item that gets a tree (the
 * host sizes it for its largest tree; the items past the trees, in a range rounded up to whole work-groups,
 * have none and touch none).
 *
 * Flat arrays, per element tree t at trees[t].entry_offset: the wind sampled at each entry's element centre
 * (3 floats, world frame), the joint state (FW_JOINT_FLOATS: angle, rate). Instance k of scale s: lengths s,
 * masses s^3, inertias s^5, joint stiffness s^3, drag per metre s, spring constants s
 * (trees/BranchElements.hpp). */
#include "branch_common.cl"
#include "lanes.cl"

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

/* Three vectors' components, lane by lane. */
typedef struct {
  lanef x, y, z;
} LaneVec3;

FW_INLINE LaneVec3 lane_cross(const LaneVec3 a, const LaneVec3 b) {
  LaneVec3 c;
  c.x = a.y * b.z - a.z * b.y;
  c.y = a.z * b.x - a.x * b.z;
  c.z = a.x * b.y - a.y * b.x;
  return c;
}

/* Springs (trees/SpringBranches.hpp): every entry's joint angle from its own load at time t; no rate. The
 * elements are independent: one block of FW_LANES consecutive entries of one spring tree per loop iteration
 * (`blocks`: its index into `trees` and its first entry), lane by lane, the lanes past the tree's last entry
 * repeating it and storing nothing. The root's entry has no element and keeps a zero angle. */
__kernel void spring_angles(const int block_count, __global const int* blocks,
                            __global const FwBranchTree* trees, __global const FwTreeInstance* instances,
                            __global const FwSpecies* species, __global const FwBranchSpecies* models,
                            __global const FwBranch* branches, const FwDragLaw law,
                            __global const float* wind, const float time, __global float* joints) {
  const float turn = 2.0f * M_PI_F / (float)(1u << FW_PHASE_BITS);
  FW_FLAT_FOR(k, block_count) {
    const int2 block = vload2(k, blocks);
    const FwBranchTree bt = trees[block.x];
    const FwTreeInstance tree = instances[bt.instance];
    const FwBranchSpecies model = models[tree.species];
    const FwSpecies sp = species[tree.species];
    const int n = sp.node_count, table = sp.skeleton_offset;
    const int first = block.y, valid = min(FW_LANES, n - first);

    /* The lanes' elements and winds. */
    float rx[FW_LANES], ry[FW_LANES], rz[FW_LANES], length[FW_LANES], wood_drag[FW_LANES],
        foliage_drag[FW_LANES], spring[FW_LANES], wx[FW_LANES], wy[FW_LANES], wz[FW_LANES], phase[FW_LANES];
    for (int l = 0; l < FW_LANES; ++l) {
      const int j = first + min(l, valid - 1);
      const FwBranch e = branches[table + j];
      rx[l] = e.rest[0];
      ry[l] = e.rest[1];
      rz[l] = e.rest[2];
      /* The root's entry has no element: a unit length keeps its lane finite. */
      length[l] = j > 0 ? e.length : 1.0f;
      wood_drag[l] = e.branch_drag;
      foliage_drag[l] = e.leaf_drag;
      spring[l] = e.spring;
      __global const float* w = wind + 3 * (bt.entry_offset + j);
      wx[l] = w[0];
      wy[l] = w[1];
      wz[l] = w[2];
      phase[l] = turn * (float)fw_phase_bits((fw_uint)bt.id, (fw_uint)j);
    }
    const lanef L = lane_load(0, length);
    LaneVec3 axis;
    axis.x = lane_load(0, rx) / L;
    axis.y = lane_load(0, ry) / L;
    axis.z = lane_load(0, rz) / L;

    /* The drag (element_load, lane by lane): the wind in the skeleton frame, s^2 L (b P v + l v) |v| f(|v|).
     */
    const float cs = tree.cos_yaw, sn = tree.sin_yaw, s = tree.scale;
    const lanef gx = lane_load(0, wx), gy = lane_load(0, wy);
    LaneVec3 v;
    v.x = cs * gx + sn * gy;
    v.y = -sn * gx + cs * gy;
    v.z = lane_load(0, wz);
    const lanef speed = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    const lanef along_v = model.normal_drag ? axis.x * v.x + axis.y * v.y + axis.z * v.z : (lanef)(0.0f);
    const lanef factor =
        law.exponent == 0.0f
            ? (lanef)(1.0f)
            : powr(fmax(speed, law.lowest_speed) * law.inverse_reference_speed, law.exponent);
    const lanef magnitude = s * s * L * speed * factor, b = lane_load(0, wood_drag),
                foliage = lane_load(0, foliage_drag);
    LaneVec3 F;
    F.x = magnitude * (b * (v.x - along_v * axis.x) + foliage * v.x);
    F.y = magnitude * (b * (v.y - along_v * axis.y) + foliage * v.y);
    F.z = magnitude * (b * (v.z - along_v * axis.z) + foliage * v.z);

    /* The bend: the load across the element over s k, over s L, and its angle with the sine on top. */
    const lanef along_F = F.x * axis.x + F.y * axis.y + F.z * axis.z;
    LaneVec3 normal;
    normal.x = F.x - along_F * axis.x;
    normal.y = F.y - along_F * axis.y;
    normal.z = F.z - along_F * axis.z;
    const lanef load = sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
    const lanef bend = load / (s * lane_load(0, spring)) / (s * L);
    const lanef steady = fmin(atan_lanes(bend), model.max_angle);
    const lanef amplitude = model.sway_amplitude * steady / model.max_angle;
    lanef unused_cosine;
    const lanef sine = sincos_lanes(model.sway_omega * time + lane_load(0, phase), &unused_cosine);
    const lanef swayed = bend * (1.0f + amplitude * sine);
    const lanef theta = clamp(atan_lanes(swayed), -model.max_angle, model.max_angle);
    /* theta about axis x the load's direction; zero without a load, and at the root. */
    const lanei bent = load > 0.0f && first + FW_LANE_OFFSETS > 0;
    const lanef per_load = select((lanef)(0.0f), theta / load, bent);
    const LaneVec3 turn_axis = lane_cross(axis, normal);
    float ax[FW_LANES], ay[FW_LANES], az[FW_LANES];
    lane_store(per_load * turn_axis.x, 0, ax);
    lane_store(per_load * turn_axis.y, 0, ay);
    lane_store(per_load * turn_axis.z, 0, az);
    for (int l = 0; l < valid; ++l) {
      __global float* joint = joints + FW_JOINT_FLOATS * (bt.entry_offset + first + l);
      vstore3((float3)(ax[l], ay[l], az[l]), 0, joint);
      vstore3((float3)(0.0f), 1, joint);
    }
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

/* The pose (trees/BranchPose.hpp): every entry's orientation Q = Q_parent Exp(theta) from the root down, and
 * its node's displacement u = u_parent + R (Q - I) s rest (world frame), written into the forest's
 * displacements. (Q - I) r = 2 w (v x r) + 2 v x (v x r) for the unit quaternion (w, v) of Q keeps its
 * digits at small angles. The orientations live only while their tree is posed: in this work-item's slice of
 * `scratch` (FW_POSE_FLOATS an entry, `scratch_stride` floats an item), which its next tree reuses while the
 * slice is still in cache. */
__kernel void branch_deform(const int tree_count, __global const FwBranchTree* trees,
                            __global const FwTreeInstance* instances, __global const FwSpecies* species,
                            __global const FwBranch* branches, __global const float* joints,
                            __global float* scratch, const int scratch_stride,
                            __global float* displacements) {
  __global float* orientation = scratch + get_global_id(0) * (size_t)scratch_stride;
  FW_FLAT_FOR(t, tree_count) {
    const FwBranchTree bt = trees[t];
    const FwTreeInstance tree = instances[bt.instance];
    const FwSpecies sp = species[tree.species];
    const float s = tree.scale, cs = tree.cos_yaw, sn = tree.sin_yaw;
    __global float* u = displacements + 3 * (size_t)tree.node_offset;
    vstore4((float4)(1.0f, 0.0f, 0.0f, 0.0f), 0, orientation);
    vstore3((float3)(0.0f), branches[sp.skeleton_offset].node, u);
    for (int j = 1; j < sp.node_count; ++j) {
      const FwBranch e = branches[sp.skeleton_offset + j];
      const float3 theta = vload3(0, joints + FW_JOINT_FLOATS * (bt.entry_offset + j));
      const float4 q = quaternion_mul(vload4(e.parent_entry, orientation), quaternion_exp(theta));
      vstore4(q, j, orientation);
      const float3 r = s * branch_rest(&e);
      const float3 vr = cross(q.yzw, r);
      const float3 change = 2.0f * q.x * vr + 2.0f * cross(q.yzw, vr);
      const float3 world = (float3)(cs * change.x - sn * change.y, sn * change.x + cs * change.y, change.z);
      vstore3(vload3(e.parent_node, u) + world, e.node, u);
    }
  }
}
