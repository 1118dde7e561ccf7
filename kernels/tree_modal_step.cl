/* The modal time step of every tree: q'' + gamma q' + omega^2 q = f per instance-mode, the force held over
 * the step (docs/design.md, "Numerics: Trees: Integration"). Reference: trees/ForestReference.cpp
 * exact_modal_step, semi_implicit_modal_step.
 *
 * Work mapping: one instance-mode per loop iteration (FW_FLAT_FOR over the flat modes); mode_instance names
 * each flat mode's instance. Every mode is independent, and this gives a GPU the most work-items; on a CPU
 * the contiguous blocks keep one instance's record in cache for all its modes.
 *
 * State: state[2 j] = q, state[2 j + 1] = qdot of flat mode j (kg^1/2 m, kg^1/2 m/s). Per instance of scale
 * s: omega = omega_i / s, gamma = 2 zeta_i omega. */
#include "common.cl"
#include "damped_oscillator.cl"

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

/* Exact over dt for the force held constant (damped_oscillator.cl). */
__kernel void tree_modal_step_exact(const int total_modes, const float dt, __global const int* mode_instance,
                                    __global const FwTreeInstance* instances,
                                    __global const FwSpecies* species, __global const float* omega,
                                    __global const float* zeta, __global const float* forces,
                                    __global float* state) {
  FW_FLAT_FOR(j, total_modes) {
    float w, gamma;
    tree_mode_parameters((int)j, mode_instance, instances, species, omega, zeta, &w, &gamma);
    float q = state[2 * j], qdot = state[2 * j + 1];
    damped_oscillator_step(w, gamma, forces[j], dt, &q, &qdot);
    state[2 * j] = q;
    state[2 * j + 1] = qdot;
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

/* The start in equilibrium with the wind of the last load: q = f / omega^2 and qdot = 0, the static answer
 * of every mode (docs/design.md, "Numerics: Trees: Integration"). */
__kernel void tree_modal_equilibrium(const int total_modes, __global const int* mode_instance,
                                     __global const FwTreeInstance* instances,
                                     __global const FwSpecies* species, __global const float* omega,
                                     __global const float* forces, __global float* state) {
  FW_FLAT_FOR(j, total_modes) {
    const FwTreeInstance tree = instances[mode_instance[j]];
    const int m = species[tree.species].modal_offset + ((int)j - tree.mode_offset);
    const float w = omega[m] / tree.scale;
    state[2 * j] = forces[j] / (w * w);
    state[2 * j + 1] = 0.0f;
  }
}
