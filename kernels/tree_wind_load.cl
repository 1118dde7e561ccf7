/* Wind load on the trees: the wind sampled at every instance's sample points and turned into modal forces
 * (docs/design.md, "Numerics: Trees: Wind basis"). Reference: trees/ForestReference.cpp sample_wind,
 * modal_forces.
 *
 * Three kernels: tree_sample_positions once, when the forest is uploaded (the sample points' world
 * positions as floats); then every step probe_sample (kernels/probe_sample.cl) over those positions, and
 * tree_wind_forces. Over MPI ranks the samples that lie in another rank's block come from that rank between
 * the two (host/stages/PointWindAcrossRanks), which is why sampling and forces are apart.
 *
 * Work mapping: one instance per loop iteration (FW_FLAT_FOR over instances). An instance's m dot products of
 * length 3S reuse one pass over its sampled wind. On a CPU each work-item takes a contiguous block of
 * instances, whose modes are contiguous too. */
#include "common.cl"

/* For every instance: sample_world (3 floats per flat sample, m, world frame) = x + s R p_s. */
__kernel void tree_sample_positions(const int instance_count, __global const FwTreeInstance* instances,
                                    __global const FwSpecies* species, __global const float* sample_points,
                                    __global float* sample_world) {
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw;
    for (int s = 0; s < sp.sample_count; ++s) {
      __global const float* p = sample_points + sp.sample_point_offset + 3 * s;
      __global float* out = sample_world + 3 * (tree.sample_offset + s);
      out[0] = tree.position[0] + tree.scale * (cs * p[0] - sn * p[1]);
      out[1] = tree.position[1] + tree.scale * (sn * p[0] + cs * p[1]);
      out[2] = tree.position[2] + tree.scale * p[2];
    }
  }
}

/* For every instance, from its sampled wind (3 floats per flat sample, m/s, world frame):
 * forces[mode_offset + i] = sum_s f(|v_s|) |v_s| v_s . (s^1/2 R p_i^s)  (N / kg^1/2), f the drag law's factor
 * (the same as the air's canopy drag). */
__kernel void tree_wind_forces(const FwDragLaw law, const int instance_count,
                               __global const FwTreeInstance* instances, __global const FwSpecies* species,
                               __global const float* projections, __global const float* sampled_wind,
                               __global float* forces) {
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw;
    const float root_scale = sqrt(tree.scale);
    /* s^1/2 R^T (|v| v) per sample: the load in the skeleton frame, so that p_i^s needs no rotation. */
    float load[3 * FW_MAX_TREE_SAMPLES];
    for (int s = 0; s < sp.sample_count; ++s) {
      __global const float* v = sampled_wind + 3 * (tree.sample_offset + s);
      const float vx = v[0], vy = v[1], vz = v[2];
      const float world_speed = sqrt(vx * vx + vy * vy + vz * vz);
      const float speed = world_speed * drag_law_factor(law, world_speed) * root_scale;
      load[3 * s] = speed * (cs * vx + sn * vy);
      load[3 * s + 1] = speed * (-sn * vx + cs * vy);
      load[3 * s + 2] = speed * vz;
    }
    const int row = 3 * sp.sample_count;
    for (int i = 0; i < sp.mode_count; ++i) {
      __global const float* p = projections + sp.projection_offset + i * row;
      float f = 0.0f;
      for (int r = 0; r < row; ++r) f += load[r] * p[r];
      forces[tree.mode_offset + i] = f;
    }
  }
}

/* Unresolved turbulence (trees/UnresolvedTurbulence.hpp; reference: trees/ForestReference.cpp
 * unresolved_modal_forces, advance_travelled). Run right after tree_wind_forces, only when the forcing is on,
 * so that the resolved forces stay bit for bit what they are without it.
 *
 * table: N points (N a power of two), 6 floats each: the unit-intensity series (l, t1, t2) and its running
 * integral C (m). offsets: per flat sample, an integer in [0, N). travel: per instance 3 floats, in series
 * points: the travelled distance split into whole points (an integer-valued float below N <= 2^24, exact)
 * and the fraction in [0, 1), so that the read keeps its sub-point precision however far a tree has
 * travelled; and the last step's distance, the read window. */

#define FW_SERIES_STRIDE 6

/* C(whole + t) of component c (t in [0, 1)): C at the point plus the linear piece's integral. */
FW_INLINE float unresolved_integral(__global const float* table, int point, int next, float t, int c,
                                    float spacing) {
  const float a = table[FW_SERIES_STRIDE * point + c], b = table[FW_SERIES_STRIDE * next + c];
  return table[FW_SERIES_STRIDE * point + 3 + c] + spacing * t * (a + 0.5f * (b - a) * t);
}

/* Tree k's forces[mode_offset + i] += sum_s intensity |v_s|^2 (2 xi_l e_par + xi_t1 e_h + xi_t2 e_v) .
 * (s^1/2 R p_i^s), the linearised drag |v| v' + v (v . v') / |v| of the fluctuation
 * v' = intensity |v_s| (xi_l e_par + xi_t1 e_h + xi_t2 e_v), xi the series' mean over the window
 * [x - W, x], x = whole + offset_s + fraction, W = clamp(last step, 1, N) points. */
__kernel void tree_unresolved_load(const int instance_count, __global const FwTreeInstance* instances,
                                   __global const FwSpecies* species, __global const float* projections,
                                   __global const float* sampled_wind, __global const float* table,
                                   const int series_length, const float spacing, __global const int* offsets,
                                   __global const float* travel, const float intensity,
                                   __global float* forces) {
  /* Horizontal part of e_par below this: a vertical wind, e_h = x (as the reference). */
  const float vertical_wind = 1e-9f;
  const int mask = series_length - 1;
  FW_FLAT_FOR(k, instance_count) {
    const FwTreeInstance tree = instances[k];
    const FwSpecies sp = species[tree.species];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw;
    const float root_scale = sqrt(tree.scale);
    const int whole = (int)travel[3 * k];
    const float fraction = travel[3 * k + 1];
    const float window = clamp(travel[3 * k + 2], 1.0f, (float)series_length);
    /* The window's start, (whole + back) + back_fraction, back <= -1. */
    const float start = fraction - window;
    const float back = floor(start);
    const float back_fraction = start - back;
    const float to_mean = 1.0f / (window * spacing);
    float load[3 * FW_MAX_TREE_SAMPLES];
    for (int s = 0; s < sp.sample_count; ++s) {
      __global const float* vs = sampled_wind + 3 * (tree.sample_offset + s);
      const float vx = vs[0], vy = vs[1], vz = vs[2];
      const float speed = sqrt(vx * vx + vy * vy + vz * vz);
      float dx = 0.0f, dy = 0.0f, dz = 0.0f;
      if (speed > 0.0f) {
        const int hi = (whole + offsets[tree.sample_offset + s]) & mask;
        const int lo = (hi + (int)back) & mask;
        float xi[3];
        for (int c = 0; c < 3; ++c)
          xi[c] = (unresolved_integral(table, hi, (hi + 1) & mask, fraction, c, spacing) -
                   unresolved_integral(table, lo, (lo + 1) & mask, back_fraction, c, spacing)) *
                  to_mean;
        const float px = vx / speed, py = vy / speed, pz = vz / speed;
        float hx = -py, hy = px;
        const float horizontal = sqrt(hx * hx + hy * hy);
        if (horizontal > vertical_wind) {
          hx /= horizontal;
          hy /= horizontal;
        } else {
          hx = 1.0f;
          hy = 0.0f;
        }
        /* e_v = e_par x e_h, e_h = (hx, hy, 0). */
        const float ex = -pz * hy, ey = pz * hx, ez = px * hy - py * hx;
        const float a = intensity * speed * speed * root_scale;
        dx = a * (2.0f * xi[0] * px + xi[1] * hx + xi[2] * ex);
        dy = a * (2.0f * xi[0] * py + xi[1] * hy + xi[2] * ey);
        dz = a * (2.0f * xi[0] * pz + xi[2] * ez);
      }
      /* Into the skeleton frame (R^T), where p_i^s lives. */
      load[3 * s] = cs * dx + sn * dy;
      load[3 * s + 1] = -sn * dx + cs * dy;
      load[3 * s + 2] = dz;
    }
    const int row = 3 * sp.sample_count;
    for (int i = 0; i < sp.mode_count; ++i) {
      __global const float* p = projections + sp.projection_offset + i * row;
      float f = 0.0f;
      for (int r = 0; r < row; ++r) f += load[r] * p[r];
      forces[tree.mode_offset + i] += f;
    }
  }
}

/* After the modal step: every instance's last step = |v| dt / dx series points, v its first sample's wind
 * (from the last wind load), and its travel advanced by it, the whole points wrapped with the period. */
__kernel void tree_unresolved_advance(const int instance_count, __global const FwTreeInstance* instances,
                                      __global const float* sampled_wind, const int series_length,
                                      const float spacing, const float dt, __global float* travel) {
  FW_FLAT_FOR(k, instance_count) {
    __global const float* v = sampled_wind + 3 * instances[k].sample_offset;
    const float points = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * dt / spacing;
    const float advanced = travel[3 * k + 1] + points;
    const float step = floor(advanced);
    /* Masking keeps the index in range whatever the float held (a blown-up wind is caught by the run). */
    travel[3 * k] = (float)(((int)travel[3 * k] + (int)step) & (series_length - 1));
    travel[3 * k + 1] = advanced - step;
    travel[3 * k + 2] = points;
  }
}
