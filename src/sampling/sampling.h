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

/* Radical inverse Phi_b(i) (SSDO thesis eq. 3.5-3.6): the base-b digits of i mirrored about the
 * radix point. Exact for every i < 2^32 in double precision for bases 2..16. */
double ob_radical_inverse(uint32_t i, uint32_t base);

/* Unit directions around +Z from two numbers in [0,1) (SSDO thesis §5.3):
 * cosine-weighted, p = cos(theta)/pi (eq. 5.2), and uniform in solid angle, p = 1/(2 pi) (eq. 5.3). */
void ob_direction_cosine(double r1, double r2, float out[3]);
void ob_direction_uniform(double r1, double r2, float out[3]);

/* Where a kernel's numbers come from: a seeded PCG32, or the Halton sequence with bases 2 and 5
 * for the direction and 3 for the length (SSDO thesis §5.3). Halton counts that are multiples of 10
 * split the hemisphere evenly (the period of bases 2 x 5, SSDO thesis §4.1); 30 adds the length's
 * base 3. */
typedef enum ob_sampling { OB_SAMPLING_RANDOM = 0, OB_SAMPLING_HALTON = 1 } ob_sampling;
typedef enum ob_direction_pdf { OB_DIRECTIONS_UNIFORM = 0, OB_DIRECTIONS_COSINE = 1 } ob_direction_pdf;

/* Normal-oriented hemisphere kernel (Puri 2024 §3.3): `count` points inside the unit hemisphere
 * around +Z, more of them near the centre, where occluders matter most: point i has length
 * r3 * lerp(0.1, 1, (i/count)^2) (at least 0.1) for random numbers, lerp(0.1, 1, r3^2) for Halton
 * (independent of the count, so prefixes are kernels too). Writes xyz0 quadruples (std140 vec4s). */
void ob_hemisphere_kernel(float *out_xyzw, int count, ob_sampling sampling, ob_direction_pdf pdf, uint64_t seed);

/* Crytek's kernel (Puri 2024 §2.2): the same lengths, directions uniform over the whole sphere. */
void ob_sphere_kernel(float *out_xyzw, int count, ob_sampling sampling, uint64_t seed);

/* 4x4 rotation noise (Puri 2024 §3.3): unit vectors in the tangent plane (xy, z = 0), stored as
 * RG pairs, 16 of them, row by row. */
void ob_rotation_noise_4x4(float *out_rg, uint64_t seed);

#endif
