/* One exact step of a damped oscillator x'' + gamma x' + omega^2 x = f with f held over the step: the trees'
 * modes (tree_modal_step.cl). Reference:
 * trees/ForestReference.cpp exact_modal_step.
 *
 * y = x - f/omega^2 is a free damped oscillator, a = gamma/2, d = omega^2 - a^2,
 *   y(t) = e^-at [y0 C + (v0 + a y0) S],  y'(t) = e^-at [v0 C - (a v0 + omega^2 y0) S],
 * C, S = cos(w t), sin(w t)/w (d = w^2 > 0), cosh(k t), sinh(k t)/k (d = -k^2 < 0), or their Taylor series
 * in d t^2 near critical damping (error below 2e-9 for |d t^2| < 1e-2). */
#ifndef FW_DAMPED_OSCILLATOR_CL
#define FW_DAMPED_OSCILLATOR_CL

inline __attribute__((always_inline)) void damped_oscillator_step(const float w, const float gamma,
                                                                  const float f, const float dt, float* x,
                                                                  float* v) {
  const float a = 0.5f * gamma;
  const float w2 = w * w;
  const float x0 = *x - f / w2, v0 = *v;
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
  *x = f / w2 + x0 * c + (v0 + a * x0) * s;
  *v = v0 * c - (a * v0 + w2 * x0) * s;
}

#endif
