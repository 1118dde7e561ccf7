/* STREAM triad, the memory-bandwidth roofline the benchmarks compare against: a = b + s c. */
#include "common.cl"

__kernel void stream_triad(const ulong n, __global float* a, __global const float* b, __global const float* c,
                           const float s) {
  FW_FLAT_FOR(i, n) {
    a[i] = b[i] + s * c[i];
  }
}
