#version 450 core
/* Variance shadow maps (SSDO thesis §2.1 "Variance Shadow Mapping", §5.1): the moments (z, z^2) of
 * the light's depth map, blurred with a separable Gaussian (sigma = vsm_blur texels). Unlike a
 * depth map, moments may be prefiltered: the blurred pair is the local mean E[z] and E[z^2] of
 * the depths, from which the lookup takes the variance (eq. 5.1) for Chebyshev's bound.
 *   OB_SHADOW_VSM_MOMENTS: the x pass, depth layer -> moments, blurred along x -> scratch
 *   otherwise:             the y pass, scratch -> blurred along y -> the moments layer
 * Reading the depth once in the x pass saves a full-size dispatch and a texture's worth of
 * traffic against a separate "depth -> moments" pass. Stored as RG32F by default: SSDO thesis §6.1
 * found 16-bit floats too imprecise (light leaks near contacts, speckles from tiny variances);
 * OB_SHADOW_VSM_FORMAT rg16f stores them in 16 bits to measure that (docs/lighting.md). Taps past
 * the border repeat the edge texel, so the normalised weights always sum to 1. */
#define OB_SHADOW_VSM_PASS 1
#include "shadow_params.h"

layout(local_size_x = OB_SHADOW_GROUP_X, local_size_y = OB_SHADOW_GROUP_Y) in;

#ifdef OB_SHADOW_VSM_MOMENTS
layout(binding = OB_UNIT_SOURCE) uniform sampler2DArray depth_in; /* the depth maps, comparison mode off */
#else
layout(binding = OB_UNIT_SOURCE) uniform sampler2D moments_in;    /* the x pass's output */
#endif
#ifndef OB_SHADOW_VSM_FORMAT
#define OB_SHADOW_VSM_FORMAT rg32f
#endif
layout(binding = OB_IMAGE_UNIT_OUT, OB_SHADOW_VSM_FORMAT) uniform writeonly image2D moments_out;

/* Each invocation filters a run of OB_SHADOW_VSM_RUN texels along the axis from one window of
 * RUN + 2 radius fetches: (RUN + 2r) / RUN fetches per texel instead of 2r + 1. On llvmpipe the
 * fetches and the per-invocation cost dominate: 2048^2 at sigma 2 took 252 ms with one texel per
 * invocation, 143 ms with runs of 8 (runs of 4: 160, 16 and 32: ~138). The weighted sums are the
 * same, so the moments are too. */
vec2 ob_vsm_fetch(ivec2 q)
{
#ifdef OB_SHADOW_VSM_MOMENTS
    float z = texelFetch(depth_in, ivec3(q, vsm.layer), 0).r;
    return vec2(z, z * z);
#else
    return texelFetch(moments_in, q, 0).rg;
#endif
}

void main()
{
    ivec2 size = vsm.size;
    ivec2 dir = vsm.axis;
    ivec2 across = ivec2(1) - dir;
    int radius = vsm.radius;
    int n = size.x * dir.x + size.y * dir.y; /* texels along the axis */
    int line = int(gl_GlobalInvocationID.y);
    int start = int(gl_GlobalInvocationID.x) * OB_SHADOW_VSM_RUN;
    if (line >= size.x * across.x + size.y * across.y || start >= n) return;
    vec2 window[OB_SHADOW_VSM_RUN + 2 * OB_SHADOW_VSM_MAX_RADIUS];
    int count = min(OB_SHADOW_VSM_RUN, n - start) + 2 * radius;
    for (int i = 0; i < count; ++i) {
        int a = clamp(start - radius + i, 0, n - 1);
        window[i] = ob_vsm_fetch(dir * a + across * line);
    }
    for (int k = 0; k < OB_SHADOW_VSM_RUN && start + k < n; ++k) {
        vec2 m = vec2(0.0);
        for (int i = -radius; i <= radius; ++i) m += vsm.weights[abs(i)].x * window[k + radius + i];
        imageStore(moments_out, dir * (start + k) + across * line, vec4(m, 0.0, 0.0));
    }
}
