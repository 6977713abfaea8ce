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

void ob_hemisphere_kernel(float *out, int count, uint64_t seed)
{
    ob_rng rng;
    ob_rng_seed(&rng, seed, 1u);
    for (int i = 0; i < count; ++i) {
        /* Rejection-free: a random direction in the hemisphere (z in (0,1]) and a random length,
         * then the accelerating scale. z is kept away from 0 so no sample lies in the tangent
         * plane, where depth precision alone would decide occlusion. */
        float x = 0.0f, y = 0.0f, z = 0.0f, len2 = 0.0f;
        do {
            x = ob_rng_float(&rng) * 2.0f - 1.0f;
            y = ob_rng_float(&rng) * 2.0f - 1.0f;
            z = 0.05f + 0.95f * ob_rng_float(&rng);
            len2 = x * x + y * y + z * z;
        } while (len2 > 1.0f || len2 < 1e-4f);
        float inv = 1.0f / sqrtf(len2);
        float len = ob_rng_float(&rng);
        float t = (float)i / (float)count;
        float scale = 0.1f + 0.9f * t * t; /* lerp(0.1, 1, t^2) */
        float k = inv * len * scale;
        /* Keep at least a tenth of the radius so the innermost samples still probe something. */
        if (len * scale < 0.1f) k = inv * 0.1f;
        out[4 * i + 0] = x * k;
        out[4 * i + 1] = y * k;
        out[4 * i + 2] = z * k;
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
