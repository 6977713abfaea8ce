#version 450 core
/* Tone mapping, SSDO thesis §5.5 steps 6-8 (§2.2): L = exposure alpha / L_avg L_w (eq. 2.2) plus the
 * blurred bright pass, then Reinhard's operator on the luminance (eq. 2.4 with L_white, eq. 2.3
 * without), the colour scaled by L_d / L so hue and saturation are kept, then sRGB. With HDR
 * off: exposure x radiance clamped to [0,1], then sRGB. */
#include "tonemap_params.h"
#include "common.glsl"

layout(local_size_x = OB_TONEMAP_GROUP_X, local_size_y = OB_TONEMAP_GROUP_Y) in;

layout(binding = OB_UNIT_TONEMAP_RADIANCE) uniform sampler2D radiance;
layout(binding = OB_UNIT_TONEMAP_BLOOM) uniform sampler2D bloom; /* bilinear, 1/OB_BLOOM_FACTOR resolution */
layout(binding = OB_IMAGE_UNIT_OUT, rgba8) uniform writeonly image2D final_out;

/* Eq. 2.4: L_d = L (1 + L / L_white^2) / (1 + L), 1 at L = L_white; eq. 2.3 when l_white <= 0.
 * Same as ob_hdr_reinhard(). */
float reinhard(float l, float l_white)
{
    float burn = l_white > 0.0 ? 1.0 + l / (l_white * l_white) : 1.0;
    return l * burn / (1.0 + l);
}

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, tmo.size))) return;
    vec3 c = ob_hdr_sanitize(texelFetch(radiance, pix, 0).rgb);
    /* One sRGB encoding at the end for both branches: llvmpipe runs both sides of a uniform
     * branch, and the encoding's pow was, written out in each, taken twice a pixel. */
    vec3 mapped;
    if (tmo.hdr_enabled == 0) {
        mapped = tmo.exposure * c;
    } else {
        c *= hdr.result.z; /* eq. 2.2: exposure alpha / L_avg, from the luminance pass */
        if (tmo.bloom_strength > 0.0) {
            /* Step 6: bilinear upsampling; full pixel centre p + 0.5 lies at (p + 0.5) / FACTOR in
             * bloom pixels, exact for odd sizes too. */
            vec2 uv = (vec2(pix) + 0.5) * tmo.bloom_uv_scale;
            c += tmo.bloom_strength * textureLod(bloom, uv, 0.0).rgb;
        }
        float l = ob_luminance(c);
        /* Step 8. The ratio can push a saturated channel past 1; ob_linear_to_srgb clamps it. */
        mapped = l > 0.0 ? c * (reinhard(l, tmo.l_white) / l) : vec3(0.0);
    }
    imageStore(final_out, pix, vec4(ob_linear_to_srgb(mapped), 1.0));
}
