#version 450 core
/* Joint bilateral upsampling (Kopf et al. 2007; seed 003 §3.5 eq. 3.12, §5.3):
 *
 *   S_p = 1/k_p sum_{q in 3x3 around p's AO position} S_q c(|p_lo - q|) g(I_p, I_q)
 *
 * with the full-resolution depth and normal as the guide I: g = exp(-(dd/(d sigma_d))^2) x
 * max(0, n_p . n_q)^8, and c a tent over the AO grid. A 3x3 kernel, not separated, as seed
 * 003 §5.3 does to keep edges sharp. AO sample q sits at full-resolution pixel k q + o. */
#include "resample_params.h"

/* Compiled a second time with OB_FILTER_RGB for SSDO's RGBA16F modulation factor and bounce:
 * the same weights on every channel, the sky's value from rs.upsample_sky_value (1 for M, 0 for
 * the bounce). */
#ifdef OB_FILTER_RGB
#define OB_UP_FORMAT rgba16f
#define OB_UP_T vec4
#define OB_UP_FETCH(tex, q) texelFetch(tex, q, 0)
#define OB_UP_SKY OB_UP_T(rs.upsample_sky_value)
#else
#define OB_UP_FORMAT r32f
#define OB_UP_T float
#define OB_UP_FETCH(tex, q) texelFetch(tex, q, 0).r
#define OB_UP_SKY OB_UP_T(1.0)
#endif

layout(local_size_x = OB_RESAMPLE_GROUP_X, local_size_y = OB_RESAMPLE_GROUP_Y) in;

layout(binding = 0) uniform sampler2D full_depth;
layout(binding = 1) uniform sampler2D full_normal;
layout(binding = 2) uniform sampler2D low_depth;
layout(binding = 3) uniform sampler2D low_normal;
layout(binding = 4) uniform sampler2D low_ao;
layout(binding = 0, OB_UP_FORMAT) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, rs.full_size))) return;
    float d = texelFetch(full_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(OB_UP_SKY));
        return;
    }
    vec3 n = texelFetch(full_normal, pix, 0).xyz;
    ivec2 low_size = rs.ao_size;
    /* p's position on the AO grid: sample q lies at full pixel k q + o. */
    vec2 u = (vec2(pix) - float(rs.ao_o)) / float(rs.ao_k);
    ivec2 centre = clamp(ivec2(round(u)), ivec2(0), low_size - 1);
    OB_UP_T sum = OB_UP_T(0.0), best_ao = OB_UP_SKY;
    float weight = 0.0;
    float best = 1e30;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(centre + ivec2(x, y), ivec2(0), low_size - 1);
            float qd = texelFetch(low_depth, q, 0).r;
            if (qd <= 0.0) continue; /* the sky has no AO to give */
            OB_UP_T qa = OB_UP_FETCH(low_ao, q);
            float rel = abs(qd - d) / d;
            vec2 off = abs(vec2(q) - u);
            float c = max(0.0, 1.0 - off.x / 1.5) * max(0.0, 1.0 - off.y / 1.5);
            /* cos^8 by squaring: pow() is several times dearer on llvmpipe. */
            float cn = max(0.0, dot(n, texelFetch(low_normal, q, 0).xyz));
            cn *= cn;
            cn *= cn;
            float g = exp(-(rel / rs.upsample_depth_sigma) * (rel / rs.upsample_depth_sigma)) * cn * cn;
            sum += qa * c * g;
            weight += c * g;
            /* Fallback when no neighbour is similar enough (a thin feature the AO grid missed):
             * the neighbour nearest in depth, so foreground never takes background AO. */
            if (rel < best) {
                best = rel;
                best_ao = qa;
            }
        }
    }
    imageStore(ao_out, pix, vec4(weight > 1e-4 ? sum / weight : best_ao));
}
