#version 450 core
/* Log-average luminance, SSDO thesis eq. 2.1: L_avg = exp(1/N sum ln(delta + L(x,y))) over every
 * pixel, the background included (the sky has radiance too). Two dispatches of this file:
 *   partial (default): each work group sums ln(delta + L) over its 64x64 pixels into partial[];
 *   OB_LUMINANCE_FINAL: one work group sums the partials, takes the exp and picks the key
 *   (eq. 2.2's alpha, or the automatic one of §6.5), so bloom and tonemap read them on the GPU. */
#define OB_HDR_RESULT_ACCESS
#include "luminance_params.h"

layout(local_size_x = OB_LUMINANCE_THREADS) in;

shared float sums[OB_LUMINANCE_THREADS];

/* Tree sum of sums[] into sums[0]; every thread has stored its value before the call. Pairwise
 * sums keep float round-off small: at 1920x1080 the log-average is within 4e-7 (relative) of
 * ob_hdr_log_average()'s double sum over the same pixels. */
void reduce(uint i)
{
    barrier();
    for (uint s = OB_LUMINANCE_THREADS / 2; s > 0; s >>= 1) {
        if (i < s) sums[i] += sums[i + s];
        barrier();
    }
}

#ifndef OB_LUMINANCE_FINAL
layout(binding = OB_UNIT_SOURCE) uniform sampler2D radiance;

void main()
{
    uint i = gl_LocalInvocationIndex;
    ivec2 local = ivec2(i % OB_LUMINANCE_GROUP, i / OB_LUMINANCE_GROUP);
    ivec2 base = ivec2(gl_WorkGroupID.xy) * OB_LUMINANCE_SPAN + local;
    float delta = lum.delta;
    float s = 0.0;
    for (int ty = 0; ty < OB_LUMINANCE_TILE; ++ty)
        for (int tx = 0; tx < OB_LUMINANCE_TILE; ++tx) {
            ivec2 p = base + ivec2(tx, ty) * OB_LUMINANCE_GROUP;
            if (any(greaterThanEqual(p, ivec2(lum.width, lum.height)))) continue;
            /* World luminance of the radiance as given: exposure is applied later, as a
             * compensation on top of the key (eq. 2.2), so it is not measured away here. */
            s += log(delta + ob_luminance(ob_hdr_sanitize(texelFetch(radiance, p, 0).rgb)));
        }
    sums[i] = s;
    reduce(i);
    if (i == 0) hdr.partial[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = sums[0];
}
#else
void main()
{
    uint i = gl_LocalInvocationIndex;
    float s = 0.0;
    for (int k = int(i); k < lum.partial_count; k += OB_LUMINANCE_THREADS) s += hdr.partial[k];
    sums[i] = s;
    reduce(i);
    if (i == 0) {
        float delta = lum.delta;
        /* Eq. 2.1, less delta afterwards: exp(mean ln(delta + L)) of a constant image c is
         * c + delta, 1% high for c = 0.01; subtracting it makes a uniform image average to
         * itself and leaves scenes (L >> delta) unchanged. It never goes below 0 since every
         * ln(delta + L) >= ln(delta). Same formula as ob_hdr_log_average(). */
        float avg = max(exp(sums[0] * lum.inv_pixel_count) - delta, 0.0);
        float key = lum.key > 0.0 ? lum.key : ob_hdr_auto_key(avg);
        /* Eq. 2.2's alpha / L_avg with the exposure compensation folded in; delta keeps a black
         * frame finite (its pixels are all 0, so any finite scale gives black). */
        hdr.result = vec4(avg, key, lum.exposure * key / max(avg, delta), 0.0);
    }
}
#endif
