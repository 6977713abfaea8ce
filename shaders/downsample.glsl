#version 450 core
/* Depth and normals at the AO resolution (Belonogov 2018 §4.7.1, SSDO thesis §4.4). Each AO pixel takes
 * ONE representative full-resolution pixel, the same sub-pixel o of every k x k block: averaging
 * normals would bend them where surfaces meet and create false occlusion (SSDO thesis §6.3, the dark
 * window border of Figure 6.10), and averaging depths would invent surfaces between foreground
 * and background. The renderer shifts the projection so that view positions reconstructed at
 * the AO pixel centres are exactly the chosen pixels' (renderer.c, low_res_projection). */
#include "resample_params.h"

layout(local_size_x = OB_RESAMPLE_GROUP_X, local_size_y = OB_RESAMPLE_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D full_depth;
layout(binding = OB_UNIT_NORMAL) uniform sampler2D full_normal;
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D low_depth;
layout(binding = OB_IMAGE_UNIT_DOWNSAMPLE_NORMAL, rgba16f) uniform writeonly image2D low_normal;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, rs.ao_size))) return;
    ivec2 src = min(pix * rs.ao_k + rs.ao_o, rs.full_size - 1);
    imageStore(low_depth, pix, texelFetch(full_depth, src, 0));
    imageStore(low_normal, pix, texelFetch(full_normal, src, 0));
}
