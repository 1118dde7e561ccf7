/* The wind at fixed points (probes), sampled every probe interval without copying the grid back.
 * Reference: trees/ForestReference.cpp sample_mac_velocity (the same clamped trilinear MAC sample the trees
 * use). Work mapping: one point per loop iteration. */
#include "common.cl"

/* positions: 3 floats per point, world frame, m; wind: 3 floats per point, m/s. */
__kernel void probe_sample(const FwGrid g, const int point_count, __global const float* positions,
                           __global const float* u, __global const float* v, __global const float* w,
                           __global float* wind) {
  FW_FLAT_FOR(n, point_count) {
    float X[3];
    for (int a = 0; a < 3; ++a) X[a] = (positions[3 * n + a] - g.origin[a]) / g.h;
    wind[3 * n] = sample_mac_component(&g, u, 0, X);
    wind[3 * n + 1] = sample_mac_component(&g, v, 1, X);
    wind[3 * n + 2] = sample_mac_component(&g, w, 2, X);
  }
}

/* Points that other ranks sampled (host/stages/PointWindOnDevice), written into their places: wind[3 slots[n]
 * + a] = values[3 n + a]. */
__kernel void probe_place(const int count, __global const int* slots, __global const float* values,
                          __global float* wind) {
  FW_FLAT_FOR(n, count) {
    for (int a = 0; a < 3; ++a) wind[3 * slots[n] + a] = values[3 * n + a];
  }
}
