#version 450 core
/* The host path's output pass (src/passes/host.c): one of the AO chain's results (visibility or
 * M, a bent normal, the bounce), at the enlarged size, cropped to the visible frame and stored in
 * the host's texture in its own format. The format is the image's layout qualifier, so the program
 * is built once per format the host asks for: OB_HOST_OUT_FORMAT is defined by host.c. */
#include "host_params.h"

layout(local_size_x = OB_HOST_GROUP_X, local_size_y = OB_HOST_GROUP_Y) in;

layout(binding = OB_UNIT_SOURCE) uniform sampler2D source;
layout(binding = OB_IMAGE_UNIT_OUT, OB_HOST_OUT_FORMAT) uniform writeonly image2D result;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, ho.size))) return;
    vec4 v = texelFetch(source, pix + ho.offset, 0);
    if (ho.mode == OB_HOST_OUT_MEAN) {
        v = vec4((v.r + v.g + v.b) / 3.0);
    } else if (ho.mode == OB_HOST_OUT_GREY) {
        v = vec4(v.rrr, 1.0);
    } else if (ho.mode == OB_HOST_OUT_NORMAL) {
        float len = length(v.xyz);
        v = len > 0.0 ? vec4(mat3(ho.turn) * (v.xyz / len), 1.0) : vec4(0.0);
    }
    imageStore(result, pix, v);
}
