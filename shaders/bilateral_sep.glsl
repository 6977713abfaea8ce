#version 450 core
/* One direction of the separable bilateral filter (Belonogov 2018 §4.3.2, eq. 4.6 along x, then eq. 4.7
 * along y on the result): the weights of `bilateral` (spatial Gaussian x depth Gaussian of
 * |d_q - d_p| / d_p) on a line of 2r+1 taps instead of the (2r+1)^2 window. Not exactly
 * separable (the seed says so too): a tap diagonal to p is reached through an intermediate pixel
 * whose depth, not p's, decided the first pass's weight. O(r) taps per pixel per pass.
 * Sky pixels (depth 0) are written as 1 and never enter a geometry pixel's sum; taps outside the
 * image are skipped. The centre tap always has weight w0 > 0, so W_p never vanishes. */
#include "filter_params.h"

layout(local_size_x = OB_FILTER_GROUP_X, local_size_y = OB_FILTER_GROUP_Y) in;

layout(binding = OB_UNIT_FILTER_IN) uniform sampler2D ao_in;
layout(binding = OB_UNIT_FILTER_DEPTH) uniform sampler2D linear_depth;
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
        float w = flt.weights[abs(i)].x * exp(rel * rel * flt.depth_falloff);
        sum += w * OB_FILTER_FETCH(ao_in, q);
        weight += w;
    }
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight)));
}
