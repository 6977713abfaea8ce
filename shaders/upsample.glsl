#version 450 core
/* Joint bilateral upsampling (Kopf et al. 2007; SSDO thesis §3.5 eq. 3.12, §5.3):
 *
 *   S_p = 1/k_p sum_{q in 3x3 around p's AO position} S_q c(|p_lo - q|) g(I_p, I_q)
 *
 * with the full-resolution depth and normal as the guide I: g = exp(-(dd/(d sigma_d))^2) x
 * max(0, n_p . n_q)^8, and c a tent over the AO grid. A 3x3 kernel, not separated, as SSDO
 * thesis §5.3 does to keep edges sharp. AO sample q sits at full-resolution pixel k q + o.
 *
 * Two programs with the same arithmetic in the same order (tests/test_filters.c: the same bits):
 *   - plain: one invocation per full-resolution pixel, 3 fetches per AO sample of its 3x3 (27 a
 *     pixel), the baseline;
 *   - OB_UPSAMPLE_BLOCK = k (2 or 4, the grid's factor): one invocation per k x k block of full
 *     pixels, which reads the 4x4 AO samples around the block once into registers (48 fetches for
 *     k^2 pixels: 12 a pixel at k = 2, 3 at k = 4) and takes each pixel's 3x3 from them. The
 *     block's pixels lie within (k - 1) / k < 1 AO sample of each other, so their nearest samples
 *     are one of two neighbours per axis, and the 3x3 windows of all of them fit in 4x4. On
 *     llvmpipe a fetch costs about as much as the weights' arithmetic, and the plain program made
 *     the upsampler dearer than the AO pass at 1/4 scale (docs/filters.md, "Subsampling").
 * Either program also takes OB_UPSAMPLE_PAIR: a second RGBA16F value (vbgi's and ssdo's bounce,
 * gtao's bent normals; 0 on the sky) upsampled in the same dispatch with the same weights, which
 * depend only on the geometry: one pass computes them once for both (the same bits as two). */
#include "resample_params.h"

/* Compiled a second time with OB_FILTER_RGB for SSDO's RGBA16F modulation factor and bounce:
 * the same weights on every channel, the sky's value from rs.upsample_sky_value (1 for M, 0 for
 * the bounce). */
#ifdef OB_FILTER_RGB
#define OB_UP_FORMAT rgba16f
#define OB_UP_T vec4
#define OB_UP_FETCH(tex, q) texelFetch(tex, q, 0)
#define OB_UP_SKY OB_UP_T(rs.upsample_sky_value)
#define OB_UP_RESULT(v) (v)
#else
#define OB_UP_FORMAT r32f
#define OB_UP_T float
#define OB_UP_FETCH(tex, q) texelFetch(tex, q, 0).r
#define OB_UP_SKY OB_UP_T(1.0)
#define OB_UP_RESULT(v) clamp(v, 0.0, 1.0) /* AO: a weighted mean in [0, 1] but for rounding (filter_params.h) */
#endif

layout(local_size_x = OB_RESAMPLE_GROUP_X, local_size_y = OB_RESAMPLE_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D full_depth;
layout(binding = OB_UNIT_NORMAL) uniform sampler2D full_normal;
layout(binding = OB_UNIT_UPSAMPLE_LOW_DEPTH) uniform sampler2D low_depth;
layout(binding = OB_UNIT_UPSAMPLE_LOW_NORMAL) uniform sampler2D low_normal;
layout(binding = OB_UNIT_UPSAMPLE_LOW_AO) uniform sampler2D low_ao;
layout(binding = OB_IMAGE_UNIT_OUT, OB_UP_FORMAT) uniform writeonly image2D ao_out;
#ifdef OB_UPSAMPLE_PAIR
layout(binding = OB_UNIT_UPSAMPLE_LOW_SECOND) uniform sampler2D low_second; /* RGBA16F */
layout(binding = OB_IMAGE_UNIT_UPSAMPLE_SECOND, rgba16f) uniform writeonly image2D second_out;
#define SECOND_FETCH(q) texelFetch(low_second, q, 0)
#else
#define SECOND_FETCH(q) vec4(0.0) /* nothing reads it: the compiler drops its arithmetic */
#endif

/* The value(s) of an upsampled pixel: the main one and the pair's second, with the weights' sum
 * and the fallback (the sample nearest in depth). */
struct upsampled {
    OB_UP_T sum, best_value;
    vec4 sum2, best2;
    float weight, best;
};
upsampled nothing_yet() { return upsampled(OB_UP_T(0.0), OB_UP_SKY, vec4(0.0), vec4(0.0), 0.0, 1e30); }

/* Writes pixel pix's value(s); sky pixels take OB_UP_SKY and 0. */
void store(ivec2 pix, upsampled u)
{
    imageStore(ao_out, pix, vec4(OB_UP_RESULT(u.weight > 1e-4 ? u.sum / u.weight : u.best_value)));
#ifdef OB_UPSAMPLE_PAIR
    imageStore(second_out, pix, u.weight > 1e-4 ? u.sum2 / u.weight : u.best2);
#endif
}

void store_sky(ivec2 pix)
{
    imageStore(ao_out, pix, vec4(OB_UP_SKY));
#ifdef OB_UPSAMPLE_PAIR
    imageStore(second_out, pix, vec4(0.0));
#endif
}

/* The tent over the AO grid along one axis: sample coordinate q, pixel's grid coordinate u. */
float tent(int q, float u) { return max(0.0, 1.0 - abs(float(q) - u) / 1.5); }

/* An AO sample: its depth, normal, value and the pair's second value. */
struct ao_sample {
    float depth;
    vec3 normal;
    OB_UP_T value;
    vec4 second;
};

ao_sample fetch_sample(ivec2 q)
{
    return ao_sample(texelFetch(low_depth, q, 0).r, texelFetch(low_normal, q, 0).xyz, OB_UP_FETCH(low_ao, q),
                     SECOND_FETCH(q));
}

/* One AO sample s of pixel p's 3x3 with tent weight c, p with depth d and normal n: adds its
 * weight c g (eq. 3.12) and keeps the sample nearest in depth. The sky (depth <= 0) has no AO to
 * give. Both programs call it in the same order with the same operands, so they agree bit for
 * bit. */
void accumulate(float c, ao_sample s, float d, vec3 n, inout upsampled u)
{
    if (s.depth <= 0.0) return;
    float rel = abs(s.depth - d) / d;
    /* cos^8 by squaring: pow() is several times dearer on llvmpipe. */
    float cn = max(0.0, dot(n, s.normal));
    cn *= cn;
    cn *= cn;
    float g = exp(-(rel / rs.upsample_depth_sigma) * (rel / rs.upsample_depth_sigma)) * cn * cn;
    u.sum += s.value * c * g;
    u.sum2 += s.second * c * g;
    u.weight += c * g;
    /* Fallback when no neighbour is similar enough (a thin feature the AO grid missed): the
     * neighbour nearest in depth, so foreground never takes background AO. */
    if (rel < u.best) {
        u.best = rel;
        u.best_value = s.value;
        u.best2 = s.second;
    }
}

/* p's position on the AO grid (sample q lies at full pixel k q + o) and its nearest sample. */
vec2 grid_position(ivec2 pix) { return (vec2(pix) - float(rs.ao_o)) / float(rs.ao_k); }
ivec2 nearest_sample(vec2 u) { return clamp(ivec2(round(u)), ivec2(0), rs.ao_size - 1); }

#ifndef OB_UPSAMPLE_BLOCK
void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, rs.full_size))) return;
    float d = texelFetch(full_depth, pix, 0).r;
    if (d <= 0.0) {
        store_sky(pix);
        return;
    }
    vec3 n = texelFetch(full_normal, pix, 0).xyz;
    vec2 u = grid_position(pix);
    ivec2 centre = nearest_sample(u);
    upsampled value = nothing_yet();
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(centre + ivec2(x, y), ivec2(0), rs.ao_size - 1);
            accumulate(tent(q.x, u.x) * tent(q.y, u.y), fetch_sample(q), d, n, value);
        }
    }
    store(pix, value);
}
#else
const int K = OB_UPSAMPLE_BLOCK; /* full pixels per AO sample and axis: rs.ao_k */

void main()
{
    ivec2 first = ivec2(gl_GlobalInvocationID.xy) * K; /* the block's first full pixel */
    if (any(greaterThanEqual(first, rs.full_size))) return;
    /* The block's pixels' nearest samples are `low` or low + 1 per axis (nearest_sample is
     * monotonic, and the block spans (K - 1) / K of a sample), so their 3x3 windows lie in the 4x4
     * from low - 1. Each entry is the clamped sample the plain program reads there. Arrays indexed
     * by constants only, so they stay in registers. */
    ivec2 low = nearest_sample(grid_position(first));
    ao_sample around[16];
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) around[4 * b + a] = fetch_sample(clamp(low - 1 + ivec2(a, b), ivec2(0), rs.ao_size - 1));
    /* Row by row: a row's pixels share their grid y, so the three rows of `around` their windows use
     * are chosen once per row (next.y) and the tent's y factors once; per pixel only the column
     * (next.x) is chosen, one select per value of each of its 9 samples. */
    for (int j = 0; j < K; ++j) {
        int py = first.y + j;
        if (py >= rs.full_size.y) break;
        float uy = grid_position(ivec2(0, py)).y;
        int cy = nearest_sample(vec2(0.0, uy)).y;
        bool next_y = cy > low.y;
        vec3 tent_y;
        for (int y = 0; y < 3; ++y) tent_y[y] = tent(clamp(cy + y - 1, 0, rs.ao_size.y - 1), uy);
        ao_sample rows[12];
        for (int r = 0; r < 3; ++r)
            for (int a = 0; a < 4; ++a) rows[4 * r + a] = next_y ? around[4 * (r + 1) + a] : around[4 * r + a];
        for (int i = 0; i < K; ++i) {
            ivec2 pix = ivec2(first.x + i, py);
            if (pix.x >= rs.full_size.x) break;
            float d = texelFetch(full_depth, pix, 0).r;
            if (d <= 0.0) {
                store_sky(pix);
                continue;
            }
            vec3 n = texelFetch(full_normal, pix, 0).xyz;
            float ux = grid_position(pix).x;
            int cx = nearest_sample(vec2(ux, 0.0)).x;
            bool next_x = cx > low.x; /* this pixel's window starts one sample further on */
            vec3 tent_x;
            for (int x = 0; x < 3; ++x) tent_x[x] = tent(clamp(cx + x - 1, 0, rs.ao_size.x - 1), ux);
            upsampled value = nothing_yet();
            for (int y = 0; y < 3; ++y) {
                for (int x = 0; x < 3; ++x)
                    accumulate(tent_x[x] * tent_y[y], next_x ? rows[4 * y + x + 1] : rows[4 * y + x], d, n, value);
            }
            store(pix, value);
        }
    }
}
#endif
