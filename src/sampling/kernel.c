#include <math.h>

#include "sampling/sampling.h"

void ob_rng_seed(ob_rng *r, uint64_t seed, uint64_t stream)
{
    r->state = 0u;
    r->inc = (stream << 1u) | 1u;
    (void)ob_rng_next(r);
    r->state += seed;
    (void)ob_rng_next(r);
}

uint32_t ob_rng_next(ob_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

float ob_rng_float(ob_rng *r)
{
    /* 24 bits: every value exactly representable, strictly below 1. */
    return (float)(ob_rng_next(r) >> 8) * (1.0f / 16777216.0f);
}

/* The three numbers behind kernel point i: direction (r1, r2) and length r3. */
static void kernel_numbers(ob_sampling sampling, ob_rng *rng, int i, double r[3])
{
    if (sampling == OB_SAMPLING_HALTON) {
        /* Index from 1: Phi(0) = 0 in every base would put the first point on the pole at the
         * centre. r1 (azimuth) from base 5, r2 (elevation) from base 2, as in SSDO thesis §5.3. */
        uint32_t k = (uint32_t)i + 1u;
        r[0] = ob_radical_inverse(k, 5);
        r[1] = ob_radical_inverse(k, 2);
        r[2] = ob_radical_inverse(k, 3);
    } else {
        r[0] = ob_rng_float(rng);
        r[1] = ob_rng_float(rng);
        r[2] = ob_rng_float(rng);
    }
}

/* Random (the seed's kernel): lerp(0.1, 1, (i/count)^2) x r3, kept at least 0.1 so the innermost
 * points still probe. Halton: lerp(0.1, 1, r3^2), which concentrates toward the centre as much
 * without depending on the count, so every prefix of 10, 20, 30 points (the Halton period,
 * SSDO thesis §4.1) is itself a well-spread kernel: what adaptive sample counts need. */
static float kernel_length(ob_sampling sampling, int i, int count, double r3)
{
    if (sampling == OB_SAMPLING_HALTON) return 0.1f + 0.9f * (float)(r3 * r3);
    float t = (float)i / (float)count;
    float len = (float)r3 * (0.1f + 0.9f * t * t);
    return len < 0.1f ? 0.1f : len;
}

void ob_hemisphere_kernel(float *out, int count, ob_sampling sampling, ob_direction_pdf pdf, uint64_t seed)
{
    ob_rng rng;
    ob_rng_seed(&rng, seed, 1u);
    for (int i = 0; i < count; ++i) {
        double r[3];
        kernel_numbers(sampling, &rng, i, r);
        float d[3];
        if (pdf == OB_DIRECTIONS_COSINE) ob_direction_cosine(r[0], r[1], d);
        else ob_direction_uniform(r[0], r[1], d);
        float len = kernel_length(sampling, i, count, r[2]);
        for (int c = 0; c < 3; ++c) out[4 * i + c] = d[c] * len;
        out[4 * i + 3] = 0.0f;
    }
}

void ob_sphere_kernel(float *out, int count, ob_sampling sampling, uint64_t seed)
{
    ob_rng rng;
    ob_rng_seed(&rng, seed, 3u);
    for (int i = 0; i < count; ++i) {
        double r[3];
        kernel_numbers(sampling, &rng, i, r);
        /* Uniform over the sphere: eq. 5.3 with z = 2 r2 - 1 covers both hemispheres. */
        float d[3];
        ob_direction_uniform(r[0], 2.0 * r[1] - 1.0, d);
        float len = kernel_length(sampling, i, count, r[2]);
        for (int c = 0; c < 3; ++c) out[4 * i + c] = d[c] * len;
        out[4 * i + 3] = 0.0f;
    }
}

void ob_rotation_noise_4x4(float *out_rg, uint64_t seed)
{
    /* Stratified angles (one per 1/16 of the circle) in a shuffled order: a purely random 4x4 set
     * can leave whole sectors unused, which shows as directional streaks after the 4x4 blur. */
    int order[16];
    for (int i = 0; i < 16; ++i) order[i] = i;
    ob_rng rng;
    ob_rng_seed(&rng, seed, 2u);
    for (int i = 15; i > 0; --i) { /* Fisher-Yates */
        int j = (int)(ob_rng_next(&rng) % (uint32_t)(i + 1));
        int tmp = order[i];
        order[i] = order[j];
        order[j] = tmp;
    }
    for (int i = 0; i < 16; ++i) {
        float a = ((float)order[i] + ob_rng_float(&rng)) * (6.28318530718f / 16.0f);
        out_rg[2 * i + 0] = cosf(a);
        out_rg[2 * i + 1] = sinf(a);
    }
}
