/* Lanes: FW_LANES consecutive values handled by one work-item in vector arithmetic, so that the arithmetic
 * runs as SIMD on CPUs (PoCL does not vectorise loops inside a work-item). Contiguous data comes with
 * lane_load/lane_store; scattered data with gather(), whose loads stay scalar. Used by advection
 * (fluid_advect.cl) and the attached leaves (leaves.cl). */
#ifndef FW_LANES_CL
#define FW_LANES_CL

#include "common.cl"

/* The lane types and their vector built-ins for FW_LANES (kernels/shared_types.h) values. */
#if FW_LANES == 8
typedef float8 lanef;
typedef int8 lanei;
#define lane_load vload8
#define lane_store vstore8
#define convert_lanef convert_float8
#define convert_lanei convert_int8
#define convert_lanei_rte convert_int8_rte
#define FW_LANE_OFFSETS ((lanei)(0, 1, 2, 3, 4, 5, 6, 7))
/* q[at] for every lane. */
FW_INLINE lanef gather(__global const float* q, lanei at) {
  return (lanef)(q[at.s0], q[at.s1], q[at.s2], q[at.s3], q[at.s4], q[at.s5], q[at.s6], q[at.s7]);
}
#elif FW_LANES == 16
typedef float16 lanef;
typedef int16 lanei;
#define lane_load vload16
#define lane_store vstore16
#define convert_lanef convert_float16
#define convert_lanei convert_int16
#define convert_lanei_rte convert_int16_rte
#define FW_LANE_OFFSETS ((lanei)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
FW_INLINE lanef gather(__global const float* q, lanei at) {
  return (lanef)(q[at.s0], q[at.s1], q[at.s2], q[at.s3], q[at.s4], q[at.s5], q[at.s6], q[at.s7], q[at.s8],
                 q[at.s9], q[at.sa], q[at.sb], q[at.sc], q[at.sd], q[at.se], q[at.sf]);
}
#else
#error "FW_LANES must be 8 or 16"
#endif

/* out[first + l] = value lane l for the first `valid` lanes: the lanes past the end of a row or a range are
 * not stored. */
FW_INLINE void store_lanes(__global float* out, int first, int valid, lanef value) {
  if (valid == FW_LANES) {
    lane_store(value, 0, out + first);
    return;
  }
  float lanes[FW_LANES];
  lane_store(value, 0, lanes);
  for (int l = 0; l < valid; ++l) out[first + l] = lanes[l];
}

/* sin r, and cos r in *cosine, for |r| <= pi/2: Taylor series to r^11 and r^12 (error below 6e-8 at pi/2).
 * Written out, with sincos_lanes, because PoCL's vector sine and cosine were 40% of the attached leaves' step
 * (measured, docs/leaves.md "Cost"). */
FW_INLINE lanef sincos_quarter_lanes(const lanef r, lanef* cosine) {
  const lanef r2 = r * r;
  lanef s = -1.0f / 39916800.0f;
  s = s * r2 + 1.0f / 362880.0f;
  s = s * r2 - 1.0f / 5040.0f;
  s = s * r2 + 1.0f / 120.0f;
  s = s * r2 - 1.0f / 6.0f;
  lanef c = 1.0f / 479001600.0f;
  c = c * r2 - 1.0f / 3628800.0f;
  c = c * r2 + 1.0f / 40320.0f;
  c = c * r2 - 1.0f / 720.0f;
  c = c * r2 + 1.0f / 24.0f;
  c = c * r2 - 0.5f;
  *cosine = c * r2 + 1.0f;
  return (s * r2 + 1.0f) * r;
}

/* sin x, and cos x in *cosine, for any x: reduced to [-pi, pi] by whole turns (2 pi split in two, good to
 * about 1e-6 for |x| < 1e4), folded to [-pi/2, pi/2] by sin(pi - r) = sin r, cos(pi - r) = -cos r. */
FW_INLINE lanef sincos_lanes(const lanef x, lanef* cosine) {
  const lanef turns = convert_lanef(convert_lanei_rte(x * 0.159154943f));
  lanef r = (x - turns * 6.28125f) - turns * 1.93530717e-3f;
  const lanei folded = fabs(r) > 1.57079633f;
  r = select(r, copysign((lanef)(3.14159265f), r) - r, folded);
  lanef c;
  const lanef s = sincos_quarter_lanes(r, &c);
  *cosine = select(c, -c, folded);
  return s;
}

#endif
