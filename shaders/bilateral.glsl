#version 450 core
/* The full 2D bilateral filter (Belonogov 2018 §4.3.2, eq. 4.5) over a (2r+1)^2 window, with the range
 * term taken on depth instead of intensity, as the seed does for occlusion:
 *     B_p = 1/W_p sum_q G_s(||p - q||) G_d(|d_q - d_p| / d_p) AO_q.
 * The spatial 2D Gaussian is the product of the 1D weights (exp(-(x^2+y^2)/2s^2) factorises), so
 * this filter and `bilateral_sep` weigh every tap alike and differ only by the separable
 * approximation of eq. 4.6-4.7. O(r^2) taps per pixel: slow on purpose, it is the quality
 * reference.
 * The depth difference is relative to d_p so one sigma_depth works in metres and millimetres.
 * Sky pixels (depth 0) are written as 1 and never enter a geometry pixel's sum; taps outside the
 * image are skipped rather than clamped, so no border pixel is counted twice. The centre tap
 * always has weight w0^2 > 0, so W_p never vanishes. */
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
    int radius = flt.radius;
    float inv_dp = 1.0 / dp;
    OB_FILTER_T sum = OB_FILTER_T(0.0);
    float weight = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        float wy = flt.weights[abs(y)].x;
        for (int x = -radius; x <= radius; ++x) {
            ivec2 q = pix + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float dq = texelFetch(linear_depth, q, 0).r;
            if (dq <= 0.0) continue;
            float rel = (dq - dp) * inv_dp;
            float w = wy * flt.weights[abs(x)].x * exp(rel * rel * flt.depth_falloff);
            sum += w * OB_FILTER_FETCH(ao_in, q);
            weight += w;
        }
    }
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight)));
}
