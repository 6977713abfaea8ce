/* CPU-side sample generation: deterministic, so the same command gives the same AO bytes. */
#ifndef OB_SAMPLING_H
#define OB_SAMPLING_H

#include <stdint.h>

/* PCG32 (O'Neill 2014): small, fast, statistically sound, and seedable. */
typedef struct ob_rng { uint64_t state, inc; } ob_rng;
void ob_rng_seed(ob_rng *r, uint64_t seed, uint64_t stream);
uint32_t ob_rng_next(ob_rng *r);
/* Uniform in [0, 1). */
float ob_rng_float(ob_rng *r);

/* Normal-oriented hemisphere kernel (seed 004 §3.3): `count` points inside the unit hemisphere
 * around +Z, each scaled by lerp(0.1, 1, (i/count)^2) so more samples lie near the centre, where
 * occluders matter most. Writes xyz0 quadruples (std140 vec4s). */
void ob_hemisphere_kernel(float *out_xyzw, int count, uint64_t seed);

/* 4x4 rotation noise (seed 004 §3.3): unit vectors in the tangent plane (xy, z = 0), stored as
 * RG pairs, 16 of them, row by row. */
void ob_rotation_noise_4x4(float *out_rg, uint64_t seed);

#endif
