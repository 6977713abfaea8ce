#version 450 core
/* One direction of the separable geometry-aware bilateral filter (SSDO thesis §3.5 "Geometry-aware
 * Filter", after Reinbothe et al.; separated into x and y passes as in §4.3): the domain is the
 * spatial Gaussian (Belonogov 2018 eq. 4.4), the range the product of a depth and a normal kernel,
 *     w_q = G_s(|p - q|) exp(-(|d_q - d_p| / d_p)^2 / 2 s_d^2) exp(-theta^2 / 2 s_n^2),
 *     theta = acos(clamp(n_p . n_q, -1, 1)),
 * so AO is not blurred between objects (depth) nor around creases and edges of one object
 * (normals), which the depth term alone misses where both faces meet at the same depth.
 * The two range Gaussians are one exp() of the summed exponents (falloffs from the CPU).
 * Sky pixels (depth 0) are written as 1 and never enter a geometry pixel's sum; taps outside the
 * image are skipped. The centre tap always has weight w0 > 0, so W_p never vanishes. */
#include "filter_params.h"

layout(local_size_x = OB_FILTER_GROUP_X, local_size_y = OB_FILTER_GROUP_Y) in;

layout(binding = OB_UNIT_FILTER_IN) uniform sampler2D ao_in;
layout(binding = OB_UNIT_FILTER_DEPTH) uniform sampler2D linear_depth;
layout(binding = OB_UNIT_FILTER_NORMAL) uniform sampler2D view_normal;
layout(binding = OB_IMAGE_UNIT_OUT, OB_FILTER_FORMAT) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = flt.size;
    if (any(greaterThanEqual(pix, size))) return;
    float dp = texelFetch(linear_depth, pix, 0).r;
    if (dp <= 0.0) {
        imageStore(ao_out, pix, OB_FILTER_SKY);
        return;
    }
    vec3 np = texelFetch(view_normal, pix, 0).xyz;
    ivec2 dir = flt.axis;
    int radius = flt.radius;
    float inv_dp = 1.0 / dp;
    float weight = flt.weights[0].x;
    OB_FILTER_T sum = weight * OB_FILTER_FETCH(ao_in, pix);
    for (int i = -radius; i <= radius; ++i) {
        if (i == 0) continue;
        ivec2 q = pix + i * dir;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        float dq = texelFetch(linear_depth, q, 0).r;
        if (dq <= 0.0) continue;
        float rel = (dq - dp) * inv_dp;
        /* RGBA16F normals can give a dot a hair above 1: clamp before acos. */
        float theta = acos(clamp(dot(np, texelFetch(view_normal, q, 0).xyz), -1.0, 1.0));
        float w = flt.weights[abs(i)].x * exp(rel * rel * flt.depth_falloff + theta * theta * flt.normal_falloff);
        sum += w * OB_FILTER_FETCH(ao_in, q);
        weight += w;
    }
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight)));
}
