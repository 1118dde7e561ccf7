/* What the element trees' kernels share (kernels/tree_branches.cl, kernels/tree_loads.cl): 3 x 3 matrices,
 * an entry's joint stiffness and rest element (FwBranch, trees/BranchElements.hpp), and the joints'
 * rotations as unit quaternions (trees/BranchPose.hpp). */
#ifndef FW_BRANCH_COMMON_CL
#define FW_BRANCH_COMMON_CL

#include "common.cl"

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

/* q p, quaternions as (w, x, y, z). */
FW_INLINE float4 quaternion_mul(const float4 q, const float4 p) {
  const float3 qv = q.yzw, pv = p.yzw;
  const float3 v = q.x * pv + p.x * qv + cross(qv, pv);
  return (float4)(q.x * p.x - dot(qv, pv), v.x, v.y, v.z);
}

/* The largest joint angle, rad, whose half-angle cosine and sinc quaternion_exp takes from their series:
 * at half-angles up to pi/4 the first term left out, x^12 / 12!, is 1e-10, far below a float's digits. */
#define FW_SERIES_MAX_ANGLE 1.5707963f

/* Exp(theta): the unit quaternion of the rotation by |theta| about theta, (cos(a/2), sin(a/2)/a theta).
 * Joints turn by far less than a right angle, so their half-angle functions come from Taylor series in
 * (a/2)^2 = theta.theta / 4: a few FMAs and no square root, where a scalar sin and cos cost tens of ns on
 * a CPU device. Larger angles take the library's functions. */
FW_INLINE float4 quaternion_exp(const float3 theta) {
  const float angle_squared = dot(theta, theta);
  float c, sinc;
  if (angle_squared < FW_SERIES_MAX_ANGLE * FW_SERIES_MAX_ANGLE) {
    const float x2 = 0.25f * angle_squared;
    c = 1.0f + x2 * (-1.0f / 2 +
                     x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
    sinc = 0.5f * (1.0f + x2 * (-1.0f / 6 +
                                x2 * (1.0f / 120 +
                                      x2 * (-1.0f / 5040 + x2 * (1.0f / 362880 + x2 * (-1.0f / 39916800))))));
  } else {
    const float angle = sqrt(angle_squared);
    c = cos(0.5f * angle);
    sinc = sin(0.5f * angle) / angle;
  }
  const float3 v = sinc * theta;
  return (float4)(c, v.x, v.y, v.z);
}

#endif
