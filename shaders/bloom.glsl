#version 450 core
/* Bloom, SSDO thesis §5.5 steps 2-4. Two programs from this file:
 *   OB_BLOOM_BRIGHT: at 1/OB_BLOOM_FACTOR resolution, each bloom pixel is the mean over its full
 *     pixels of the colour's excess above the threshold. The threshold is in scaled luminance
 *     (eq. 2.2, after exposure and key), the units of L_white, so "threshold 1.5, L_white 3" means
 *     the halo starts halfway to white whatever the scene's absolute radiance. Each full pixel is
 *     thresholded before the box average, so a one-pixel highlight is not diluted below it.
 *   default: one direction of the separable Gaussian (Belonogov 2018 eq. 4.4, as shaders/gaussian.glsl),
 *     run along x then y; taps past the border repeat the edge pixel. */
#include "bloom_params.h"

layout(local_size_x = OB_BLOOM_GROUP_X, local_size_y = OB_BLOOM_GROUP_Y) in;

layout(binding = OB_UNIT_SOURCE) uniform sampler2D src;
layout(binding = OB_IMAGE_UNIT_OUT, rgba16f) uniform writeonly image2D dst;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = blm.bloom_size;
    if (any(greaterThanEqual(pix, size))) return;
#ifdef OB_BLOOM_BRIGHT
    float scale = hdr.result.z; /* exposure key / L_avg from the luminance pass */
    float threshold = blm.threshold;
    vec3 sum = vec3(0.0);
    int n = 0;
    for (int y = 0; y < OB_BLOOM_FACTOR; ++y)
        for (int x = 0; x < OB_BLOOM_FACTOR; ++x) {
            ivec2 p = pix * OB_BLOOM_FACTOR + ivec2(x, y);
            if (any(greaterThanEqual(p, blm.full_size))) continue;
            vec3 c = scale * ob_hdr_sanitize(texelFetch(src, p, 0).rgb);
            float l = ob_luminance(c);
            /* Step 2, "store the difference from the threshold": the colour keeps its hue and
             * has its luminance cut down to the excess. */
            sum += l > threshold ? c * ((l - threshold) / l) : vec3(0.0);
            ++n;
        }
    /* Kept inside the half-float range: an infinity would turn the blur and the tone map NaN. */
    imageStore(dst, pix, vec4(min(sum / float(max(n, 1)), vec3(65504.0)), 1.0));
#else
    ivec2 dir = ivec2(blm.axis_x, blm.axis_y);
    int radius = blm.radius;
    vec3 sum = vec3(0.0);
    for (int i = -radius; i <= radius; ++i) {
        ivec2 q = clamp(pix + i * dir, ivec2(0), size - 1);
        sum += blm.weights[abs(i)].x * texelFetch(src, q, 0).rgb;
    }
    imageStore(dst, pix, vec4(sum, 1.0));
#endif
}
