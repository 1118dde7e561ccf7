/* Arithmetic peak of the device: independent chains of float8 fused multiply-adds, the compute roofline that
 * the deformation kernel (u = Phi q, one FMA per node, mode and axis) is compared against. Eight independent
 * accumulators per work-item keep every FMA pipeline busy; the result is written so nothing is optimised out.
 */
#include "common.cl"

__kernel void fma_peak(__global float* out, const int iterations) {
  const float seed = (float)get_global_id(0) * 1e-9f;
  const float8 m = (float8)(0.999999f);
  const float8 c = (float8)(1e-7f);
  float8 a0 = (float8)(seed), a1 = a0 + 0.1f, a2 = a0 + 0.2f, a3 = a0 + 0.3f;
  float8 a4 = a0 + 0.4f, a5 = a0 + 0.5f, a6 = a0 + 0.6f, a7 = a0 + 0.7f;
  for (int i = 0; i < iterations; ++i) {
    a0 = fma(a0, m, c);
    a1 = fma(a1, m, c);
    a2 = fma(a2, m, c);
    a3 = fma(a3, m, c);
    a4 = fma(a4, m, c);
    a5 = fma(a5, m, c);
    a6 = fma(a6, m, c);
    a7 = fma(a7, m, c);
  }
  const float8 sum = ((a0 + a1) + (a2 + a3)) + ((a4 + a5) + (a6 + a7));
  out[get_global_id(0)] = sum.s0 + sum.s1 + sum.s2 + sum.s3 + sum.s4 + sum.s5 + sum.s6 + sum.s7;
}
