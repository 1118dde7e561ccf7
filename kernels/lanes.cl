/* Lanes: FW_LANES consecutive values handled by one work-item in vector arithmetic, so that the arithmetic
 * runs as SIMD on CPUs (PoCL does not vectorise loops inside a work-item). Contiguous data comes with
 * lane_load/lane_store; scattered data with gather(), whose loads stay scalar. Used by advection
 * (fluid_advect.cl) and the attached leaves (leaves.cl). */
#ifndef FW_LANES_CL
#define FW_LANES_CL

#include "common.cl"

/* The smallest and the largest of eight ints, by halves. */
FW_INLINE int min_of_eight(int8 v) {
  const int4 a = min(v.lo, v.hi);
  const int2 b = min(a.lo, a.hi);
  return min(b.x, b.y);
}
FW_INLINE int max_of_eight(int8 v) {
  const int4 a = max(v.lo, v.hi);
  const int2 b = max(a.lo, a.hi);
  return max(b.x, b.y);
}

/* The lane types and their vector built-ins for FW_LANES (kernels/shared_types.h) values. */
/* The sum of eight longs and the largest of eight floats, by halves. */
FW_INLINE long sum_of_eight(long8 v) {
  const long4 a = v.lo + v.hi;
  const long2 b = a.lo + a.hi;
  return b.x + b.y;
}
FW_INLINE float max_of_eight_floats(float8 v) {
  const float4 a = fmax(v.lo, v.hi);
  const float2 b = fmax(a.lo, a.hi);
  return fmax(b.x, b.y);
}

#if FW_LANES == 8
typedef float8 lanef;
typedef int8 lanei;
typedef long8 lanel;
#define convert_lanel convert_long8
#define lane_load_bytes vload8
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
/* The smallest and the largest lane. */
FW_INLINE int lane_min(lanei v) {
  return min_of_eight(v);
}
FW_INLINE int lane_max(lanei v) {
  return max_of_eight(v);
}
/* The sum of the lanes; the largest lane. */
FW_INLINE long lane_sum_long(lanel v) {
  return sum_of_eight(v);
}
FW_INLINE float lane_max_float(lanef v) {
  return max_of_eight_floats(v);
}
#elif FW_LANES == 16
typedef float16 lanef;
typedef int16 lanei;
typedef long16 lanel;
#define convert_lanel convert_long16
#define lane_load_bytes vload16
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
FW_INLINE int lane_min(lanei v) {
  return min_of_eight(min(v.lo, v.hi));
}
FW_INLINE long lane_sum_long(lanel v) {
  return sum_of_eight(v.lo + v.hi);
}
FW_INLINE float lane_max_float(lanef v) {
  return max_of_eight_floats(fmax(v.lo, v.hi));
}
FW_INLINE int lane_max(lanei v) {
  return max_of_eight(max(v.lo, v.hi));
}
#else
#error "FW_LANES must be 8 or 16"
#endif

/* Windowed loads: lanes whose indices nearly follow the lanes, at[l] = l + shift[l] with every shift within
 * FW_WINDOW_SHIFTS of the smallest, as the back-traced corners of consecutive faces in a smooth flow are.
 * Such a gather is FW_WINDOW_SHIFTS contiguous vector loads, one per shift, blended lane by lane: on a CPU a
 * few vector instructions instead of FW_LANES scalar loads, and the same values. A window reads up to
 * FW_WINDOW_SLACK (kernels/shared_types.h) values past the highest index a lane asks for, so buffers read
 * this way are that much longer, and up to FW_WINDOW_SHIFTS - 1 before the lowest. */
#if FW_WINDOW_SHIFTS != 3
#error "LaneWindow blends three shifts"
#endif
typedef struct {
  int first;       /* the smallest shift */
  lanei at_second; /* lanes whose shift is first + 1 (all bits set), ... */
  lanei at_third;  /* ... and first + 2 */
} LaneWindow;

/* Whether the indices `at` fit one window; if so, *w describes it. */
FW_INLINE int lane_window(lanei at, LaneWindow* w) {
  const lanei shift = at - FW_LANE_OFFSETS;
  w->first = lane_min(shift);
  w->at_second = shift == w->first + 1;
  w->at_third = shift == w->first + 2;
  return lane_max(shift) - w->first < FW_WINDOW_SHIFTS;
}

/* q[at + offset] in *low and q[at + offset + 1] in *high for every lane of window w: the two x-neighbours
 * of a row of interpolation corners share their loads. */
FW_INLINE void window_pair(__global const float* q, const LaneWindow* w, int offset, lanef* low,
                           lanef* high) {
  __global const float* p = q + w->first + offset;
  const lanef s0 = lane_load(0, p), s1 = lane_load(0, p + 1), s2 = lane_load(0, p + 2),
              s3 = lane_load(0, p + 3);
  *low = select(select(s0, s1, w->at_second), s2, w->at_third);
  *high = select(select(s1, s2, w->at_second), s3, w->at_third);
}

/* q[at] for the lanes of one run, at[l] = at[0] + l for its `valid` lanes and clamped past them: one vector
 * load where every lane is valid, else a gather. */
FW_INLINE lanef row_lanes(__global const float* q, lanei at, int valid) {
  return valid == FW_LANES ? lane_load(0, q + at.s0) : gather(q, at);
}

/* The x-pair of window_pair at row offset `at`, and, where `stepping`, at `at + step` for the lanes in
 * `stepped`. The flags are scalars: OpenCL's any() on the lane masks made PoCL's code twice as slow. */
FW_INLINE void stepped_pair(__global const float* q, const LaneWindow* w, int at, int step, int stepping,
                            lanei stepped, lanef* low, lanef* high) {
  window_pair(q, w, at, low, high);
  if (!stepping) return;
  lanef low_next, high_next;
  window_pair(q, w, at + step, &low_next, &high_next);
  *low = select(*low, low_next, stepped);
  *high = select(*high, high_next, stepped);
}

/* The x-pair at row offset `at`, plus sy for the lanes in y_stepped and plus sz for those in z_stepped. */
FW_INLINE void row_pair(__global const float* q, const LaneWindow* w, int at, int sy, int sz, int y_spread,
                        lanei y_stepped, int z_spread, lanei z_stepped, lanef* low, lanef* high) {
  stepped_pair(q, w, at, sy, y_spread, y_stepped, low, high);
  if (!z_spread) return;
  lanef low_next, high_next;
  stepped_pair(q, w, at + sz, sy, y_spread, y_stepped, &low_next, &high_next);
  *low = select(*low, low_next, z_stepped);
  *high = select(*high, high_next, z_stepped);
}

/* The eight corners v[a + 2b + 4c] = q[x + a + sy (y + b) + sz (z + c)] of every lane's cell (x, y, z) of a
 * 3D array (x stride 1, y stride sy, z stride sz). Windowed loads where the lanes' cells lie along one row,
 * or straddle two neighbouring rows in y or z, as the back-traced cells of a smooth or turbulent flow do (a
 * back-trace crosses a row boundary across a work-item wherever a cross-stream velocity changes sign);
 * gathers elsewhere. */
FW_INLINE void cell_corners(__global const float* q, lanei x, lanei y, lanei z, int sy, int sz, lanef v[8]) {
  LaneWindow w;
  const int y_low = lane_min(y), z_low = lane_min(z);
  const int y_spread = lane_max(y) - y_low, z_spread = lane_max(z) - z_low;
  if (lane_window(x, &w) && y_spread <= 1 && z_spread <= 1) {
    const lanei y_stepped = y != y_low, z_stepped = z != z_low;
    const int at = sy * y_low + sz * z_low;
    row_pair(q, &w, at, sy, sz, y_spread, y_stepped, z_spread, z_stepped, &v[0], &v[1]);
    row_pair(q, &w, at + sy, sy, sz, y_spread, y_stepped, z_spread, z_stepped, &v[2], &v[3]);
    row_pair(q, &w, at + sz, sy, sz, y_spread, y_stepped, z_spread, z_stepped, &v[4], &v[5]);
    row_pair(q, &w, at + sz + sy, sy, sz, y_spread, y_stepped, z_spread, z_stepped, &v[6], &v[7]);
    return;
  }
  const lanei base = x + sy * y + sz * z;
  /* Written out: PoCL leaves a loop over the corners rolled, which doubles the cost of the kernel. */
  v[0] = gather(q, base);
  v[1] = gather(q, base + 1);
  v[2] = gather(q, base + sy);
  v[3] = gather(q, base + sy + 1);
  v[4] = gather(q, base + sz);
  v[5] = gather(q, base + sz + 1);
  v[6] = gather(q, base + sz + sy);
  v[7] = gather(q, base + sz + sy + 1);
}

/* Trilinear blend of the corners v (cell_corners' order) at fractions (fx, fy, fz). */
FW_INLINE lanef trilinear(const lanef v[8], lanef fx, lanef fy, lanef fz) {
  const lanef x00 = v[0] + fx * (v[1] - v[0]);
  const lanef x10 = v[2] + fx * (v[3] - v[2]);
  const lanef x01 = v[4] + fx * (v[5] - v[4]);
  const lanef x11 = v[6] + fx * (v[7] - v[6]);
  const lanef y0 = x00 + fy * (x10 - x00);
  const lanef y1 = x01 + fy * (x11 - x01);
  return y0 + fz * (y1 - y0);
}

/* out[first + l] = value lane l for the lanes begin <= l < end. */
FW_INLINE void store_lane_span(__global float* out, int first, int begin, int end, lanef value) {
  if (begin == 0 && end == FW_LANES) {
    lane_store(value, 0, out + first);
    return;
  }
  float lanes[FW_LANES];
  lane_store(value, 0, lanes);
  for (int l = begin; l < end; ++l) out[first + l] = lanes[l];
}

/* out[first + l] = value lane l for the first `valid` lanes: the lanes past the end of a row or a range are
 * not stored. */
FW_INLINE void store_lanes(__global float* out, int first, int valid, lanef value) {
  store_lane_span(out, first, 0, valid, value);
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

/* atan x for any x (NaN to NaN): halved twice, by atan x = pi/2 - atan(1/x) above 1 and atan t = pi/4 +
 * atan((t - 1)/(t + 1)) above tan(pi/8), then its Taylor series to u^17 (|u| <= tan(pi/8): the first term
 * left out, u^19/19, is 3e-9). Written out for the same reason as the sine: PoCL's arctangent and sine
 * were 85% of the springs' angle kernel (docs/tree-models.md "Cost"). */
FW_INLINE lanef atan_lanes(const lanef x) {
  const lanef a = fabs(x);
  const lanei above_one = a > 1.0f;
  const lanef t = select(a, 1.0f / a, above_one);
  const lanei above_eighth = t > 0.41421356f; /* tan(pi/8) */
  const lanef u = select(t, (t - 1.0f) / (t + 1.0f), above_eighth);
  const lanef u2 = u * u;
  lanef p = 1.0f / 17.0f;
  p = p * u2 - 1.0f / 15.0f;
  p = p * u2 + 1.0f / 13.0f;
  p = p * u2 - 1.0f / 11.0f;
  p = p * u2 + 1.0f / 9.0f;
  p = p * u2 - 1.0f / 7.0f;
  p = p * u2 + 1.0f / 5.0f;
  p = p * u2 - 1.0f / 3.0f;
  lanef r = (p * u2 + 1.0f) * u;
  r = select(r, 0.78539816f + r, above_eighth);
  r = select(r, 1.57079633f - r, above_one);
  return copysign(r, x);
}

/* Face rows: the lane kernels over a velocity component (advection) give each work-item FW_LANES faces of
 * one x-row. */

/* Stride of component a's padded copy along axis `axis`. */
FW_INLINE int padded_stride(const FwGrid* g, int a, int axis) {
  return axis == 0 ? 1
                   : (axis == 1 ? padded_extent(g, a, 0) : padded_extent(g, a, 0) * padded_extent(g, a, 1));
}

/* The padded index of component a at the lanes' faces i of row (j, k) (FW_LANE_SETUP's lanes: consecutive,
 * or in a row shorter than FW_LANES clamped to its last face). */
FW_INLINE lanei lane_padded_index(const FwGrid* g, int a, lanei i, int j, int k) {
  return (i + FW_PAD) + padded_extent(g, a, 0) * ((j + FW_PAD) + padded_extent(g, a, 1) * (k + FW_PAD));
}

/* This work-item's faces: FW_LANES consecutive faces of row (j, k) from i0, of which it stores the lanes
 * `skip` .. `valid` - 1. The last item of a row that does not fill its lanes moves back to end at the row's
 * end, redoing faces of the item before it without storing them: its lanes then stay contiguous, for vector
 * and windowed loads. Rows shorter than FW_LANES clamp the lanes past the row to its last face. Items past
 * the rows or planes (the range is rounded up to whole work-groups) return at once. */
#define FW_LANE_SETUP(c)                                                                   \
  const int j = get_global_id(1), k = get_global_id(2);                                    \
  const int ex = face_extent(&g, c, 0);                                                    \
  const int own_first = (int)get_global_id(0) * FW_LANES;                                  \
  if (own_first >= ex || j >= face_extent(&g, c, 1) || k >= face_extent(&g, c, 2)) return; \
  const int i0 = max(0, min(own_first, ex - FW_LANES));                                    \
  const int skip = own_first - i0;                                                         \
  const int valid = min(FW_LANES, ex - i0);                                                \
  const lanei i = min((lanei)(i0) + FW_LANE_OFFSETS, (lanei)(ex - 1));

#endif
