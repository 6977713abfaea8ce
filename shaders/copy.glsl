#version 450 core
/* The `none` filter (src/filters/none.c): the raw AO goes on as it is, copied texel for texel
 * (clamped to [0, 1] as every filter clamps its result).
 * A compute pass rather than glCopyImageSubData, which NVIDIA's driver runs on the graphics
 * pipe: 0.185 ms for one 1920x1080 R32F copy on an H100, as long as box4 and gaussian together
 * (bench/results/2026-11-23-h100-egl.md). */
#include "filter_params.h"

layout(local_size_x = OB_FILTER_GROUP_X, local_size_y = OB_FILTER_GROUP_Y) in;

layout(binding = OB_UNIT_FILTER_IN) uniform sampler2D ao_in;
layout(binding = OB_IMAGE_UNIT_OUT, OB_FILTER_FORMAT) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, flt.size))) return;
    /* OB_FILTER_RESULT: a method's raw estimate may leave [0, 1] by its noise (vbao's one slice). */
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(OB_FILTER_FETCH(ao_in, pix))));
}
