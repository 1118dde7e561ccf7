/* The modal time step of every tree: q'' + gamma q' + omega^2 q = f per instance-mode, the force held over
 * the step (DESIGN.md, "Numerics: Trees: Integration"). Reference: trees/ForestReference.cpp
 * exact_modal_step, semi_implicit_modal_step.
 *
 * Work mapping: one instance-mode per loop iteration (FW_FLAT_FOR over the flat modes); mode_instance names
 * each flat mode's instance. Every mode is independent, and this gives a GPU the most work-items; on a CPU
 * the contiguous blocks keep one instance's record in cache for all its modes.
 *
 * State: state[2 j] = q, state[2 j + 1] = qdot of flat mode j (kg^1/2 m, kg^1/2 m/s). Per instance of scale
 * s: omega = omega_i / s, gamma = 2 zeta_i omega. */
#include "common.cl"

/* omega and gamma of flat mode j. */
FW_INLINE void tree_mode_parameters(int j, __global const int* mode_instance,
                                    __global const FwTreeInstance* instances,
                                    __global const FwSpecies* species, __global const float* omega,
                                    __global const float* zeta, float* w, float* gamma) {
  const FwTreeInstance tree = instances[mode_instance[j]];
  const int m = species[tree.species].modal_offset + (j - tree.mode_offset);
  *w = omega[m] / tree.scale;
  *gamma = 2.0f * zeta[m] * *w;
}

/* Exact solution over dt: x = q - f/omega^2 is a free damped oscillator, a = gamma/2, d = omega^2 - a^2,
 *   x(t) = e^-at [x0 C + (v0 + a x0) S],  x'(t) = e^-at [v0 C - (a v0 + omega^2 x0) S],
 * C, S = cos(w t), sin(w t)/w (d = w^2 > 0), cosh(k t), sinh(k t)/k (d = -k^2 < 0), or their Taylor series
 * in d t^2 near critical damping (error below 2e-9 for |d t^2| < 1e-2). */
__kernel void tree_modal_step_exact(const int total_modes, const float dt, __global const int* mode_instance,
                                    __global const FwTreeInstance* instances,
                                    __global const FwSpecies* species, __global const float* omega,
                                    __global const float* zeta, __global const float* forces,
                                    __global float* state) {
  FW_FLAT_FOR(j, total_modes) {
    float w, gamma;
    tree_mode_parameters((int)j, mode_instance, instances, species, omega, zeta, &w, &gamma);
    const float a = 0.5f * gamma;
    const float w2 = w * w;
    const float f = forces[j];
    const float x0 = state[2 * j] - f / w2, v0 = state[2 * j + 1];
    const float d = (w - a) * (w + a);
    const float z = d * dt * dt;
    float c, s; /* e^-at C, e^-at S */
    if (fabs(z) < 1e-2f) {
      const float decay = exp(-a * dt);
      c = decay * (1.0f - z * (0.5f - z * (1.0f / 24.0f)));
      s = decay * dt * (1.0f - z * (1.0f / 6.0f - z * (1.0f / 120.0f)));
    } else if (d > 0.0f) {
      const float wd = sqrt(d);
      const float decay = exp(-a * dt);
      float cosine;
      const float sine = sincos(wd * dt, &cosine);
      c = decay * cosine;
      s = decay * sine / wd;
    } else {
      /* Over-damped: both exponentials decay, so nothing overflows; a - k = omega^2 / (a + k). */
      const float k = sqrt(-d);
      const float slow = exp(-w2 / (a + k) * dt), fast = exp(-(a + k) * dt);
      c = 0.5f * (slow + fast);
      s = 0.5f * (slow - fast) / k;
    }
    state[2 * j] = f / w2 + x0 * c + (v0 + a * x0) * s;
    state[2 * j + 1] = v0 * c - (a * v0 + w2 * x0) * s;
  }
}

/* Diener's semi-implicit Euler: qdot += dt (f - gamma qdot - omega^2 q); q += dt qdot. Stable for
 * omega dt < 2 (less with damping). */
__kernel void tree_modal_step_semi_implicit(const int total_modes, const float dt,
                                            __global const int* mode_instance,
                                            __global const FwTreeInstance* instances,
                                            __global const FwSpecies* species, __global const float* omega,
                                            __global const float* zeta, __global const float* forces,
                                            __global float* state) {
  FW_FLAT_FOR(j, total_modes) {
    float w, gamma;
    tree_mode_parameters((int)j, mode_instance, instances, species, omega, zeta, &w, &gamma);
    const float q = state[2 * j];
    const float qdot = state[2 * j + 1] + dt * (forces[j] - gamma * state[2 * j + 1] - w * w * q);
    state[2 * j] = q + dt * qdot;
    state[2 * j + 1] = qdot;
  }
}
