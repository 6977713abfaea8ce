#version 450 core
/* 4x4 box blur (offsets -2..1) of the raw AO, the seeds' classic (Puri 2024 §3.3): it spans
 * exactly one tile of the 4x4 rotation noise, so the noise pattern averages out. Pixels without
 * geometry are left out of the average so the sky's AO = 1 does not brighten silhouettes. Kept as
 * the baseline the geometry-aware filters are measured against. */
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
    if (texelFetch(linear_depth, pix, 0).r <= 0.0) {
        imageStore(ao_out, pix, OB_FILTER_SKY);
        return;
    }
    OB_FILTER_T sum = OB_FILTER_T(0.0);
    float weight = 0.0;
    for (int y = -2; y < 2; ++y) {
        for (int x = -2; x < 2; ++x) {
            ivec2 q = clamp(pix + ivec2(x, y), ivec2(0), size - 1);
            if (texelFetch(linear_depth, q, 0).r <= 0.0) continue;
            sum += OB_FILTER_FETCH(ao_in, q);
            weight += 1.0;
        }
    }
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / max(weight, 1.0))));
}
