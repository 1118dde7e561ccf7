/* The prescribed inflow shell (layout: kernels/shared_types.h): the inflow's value at every face the kernels
 * may ask of an inflow face, sampled once per step while the inflow turbulence is on, so that the kernels
 * read one float (kernels/common.cl inflow_face_value) instead of interpolating the box. The samples run in
 * lanes along the box's contiguous axis: a scalar sample cost about 100 ns of a core (measured), most of it
 * the dependent chain of its index arithmetic. Mirrors fluid::InflowState::value() and
 * fluid/TurbulenceBox.cpp sample(). */
#include "lanes.cl"

/* Along one box axis of n points at world positions `world` (lanes): the lower point index, the upper one
 * (wrapped: the box is periodic) and the weight of the upper one. */
FW_INLINE void box_axis_lanes(lanef world, float offset, float inverse_spacing, int n, lanei* lo, lanei* hi,
                              lanef* t) {
  const lanef p = (world - offset) * inverse_spacing;
  const lanef wrapped = p - (float)n * floor(p * (1.0f / (float)n)); /* [0, n], n only by rounding */
  const lanef f = floor(wrapped);
  *t = wrapped - f;
  *lo = clamp(convert_lanei(f), 0, n - 1);
  *hi = select(*lo + 1, (lanei)(0), *lo + 1 == (lanei)(n));
}

/* Component c of the box at world positions (x, y, z) (lanes), m/s per unit sigma: trilinear and periodic
 * on every axis. The box follows the profile in `inflow`, 3 floats a point, x slowest. */
FW_INLINE lanef box_sample_lanes(const FwGrid* g, const FwStep* s, __global const float* inflow, int c,
                                 lanef x, lanef y, lanef z) {
  __global const float* box = inflow + g->nz + c;
  const float inverse_spacing = 1.0f / s->turbulence_spacing;
  lanei lx, hx, ly, hy, lz, hz;
  lanef tx, ty, tz;
  box_axis_lanes(x, s->turbulence_offset[0], inverse_spacing, s->turbulence_cells[0], &lx, &hx, &tx);
  box_axis_lanes(y, s->turbulence_offset[1], inverse_spacing, s->turbulence_cells[1], &ly, &hy, &ty);
  box_axis_lanes(z, s->turbulence_offset[2], inverse_spacing, s->turbulence_cells[2], &lz, &hz, &tz);
  const int sy = 3 * s->turbulence_cells[2], sx = sy * s->turbulence_cells[1];
  const lanei x0 = sx * lx, x1 = sx * hx, y0 = sy * ly, y1 = sy * hy, z0 = 3 * lz, z1 = 3 * hz;
  const lanef c00 = mix(gather(box, x0 + y0 + z0), gather(box, x1 + y0 + z0), tx);
  const lanef c10 = mix(gather(box, x0 + y1 + z0), gather(box, x1 + y1 + z0), tx);
  const lanef c01 = mix(gather(box, x0 + y0 + z1), gather(box, x1 + y0 + z1), tx);
  const lanef c11 = mix(gather(box, x0 + y1 + z1), gather(box, x1 + y1 + z1), tx);
  return mix(mix(c00, c10, ty), mix(c01, c11, ty), tz);
}

/* The shell's block of component c on domain face f (normal to axis a; b1 < b2 the other two axes): one
 * work-item a line of the block along b2, in lanes. A face's value: the ambient profile at its height index
 * plus sigma times the box at its world position, the sigma tapered to 0 where the mean wind is (below
 * z0 + d of a log law, in a canopy's displacement layer). Global range: (span1 * FW_SHELL_LAYERS, 3). */
__kernel void fill_inflow_shell(const FwGrid g, const FwStep s, const int f, __global float* inflow) {
  const int a = f / 2, b1 = a == 0 ? 1 : 0, b2 = a == 2 ? 1 : 2;
  const int span1 = fw_shell_span(axis_cells(&g, b1)), span2 = fw_shell_span(axis_cells(&g, b2));
  const int line = get_global_id(0), c = get_global_id(1);
  if (line >= span1 * FW_SHELL_LAYERS || c >= 3) return; /* past the range: whole work-groups */
  const int t1 = line % span1, layer = line / span1;
  __global float* out = inflow + inflow_shell_start(&g, &s) + fw_shell_face_offset(g.nx, g.ny, g.nz, f) +
                        c * fw_shell_block(g.nx, g.ny, g.nz, a) + t1 + span1 * span2 * layer;
  /* Face indices: fixed along a and b1, the lanes along b2. */
  lanei at[3];
  at[a] = (lanei)((f & 1) ? face_extent(&g, c, a) - 1 + layer : layer - FW_PAD);
  at[b1] = (lanei)(t1 - FW_PAD);
  for (int t2 = 0; t2 < span2; t2 += FW_LANES) {
    at[b2] = (lanei)(t2 - FW_PAD) + FW_LANE_OFFSETS;
    lanef world[3];
    const int offset[3] = {g.ox, g.oy, 0}; /* a rank's block: the domain's index of its cell 0 */
    for (int d = 0; d < 3; ++d)
      world[d] = g.origin[d] + g.h * (convert_lanef(at[d] + offset[d]) + face_offset(c, d));
    const lanef shape = gather(inflow, clamp(at[2], 0, g.nz - 1));
    const lanef taper = clamp(shape / FW_TURBULENCE_FULL_SHAPE, 0.0f, 1.0f);
    const lanef value =
        s.ambient[c] * shape +
        s.turbulence_sigma * taper * box_sample_lanes(&g, &s, inflow, c, world[0], world[1], world[2]);
    float lanes[FW_LANES];
    lane_store(value, 0, lanes);
    for (int l = 0; l < min(FW_LANES, span2 - t2); ++l) out[span1 * (t2 + l)] = lanes[l];
  }
}
