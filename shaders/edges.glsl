#version 450 core
/* Adaptive sample counts, the pre-pass (SSDO thesis §4.1 "Preprocessing", Figure 4.3): an edge
 * detector over depth and normals at a low resolution, one value per OB_EDGE_BLOCK^2 AO pixels
 * (plus a one-pixel border, so both sides of an edge see it). The weight is the largest relative
 * depth step or normal turn between neighbours in the block, against thresholds; it becomes a
 * multiplier 1, 2 or 3 on the method's base sample count (the Halton period, SSDO thesis §4.1). */
#include "resample_params.h"

layout(local_size_x = OB_RESAMPLE_GROUP_X, local_size_y = OB_RESAMPLE_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D ao_depth; /* at the AO resolution */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D ao_normal;
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D multiplier;

void main()
{
    ivec2 blk = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = rs.ao_size;
    ivec2 blocks = (size + OB_EDGE_BLOCK - 1) / OB_EDGE_BLOCK;
    if (any(greaterThanEqual(blk, blocks))) return;
    float depth_step = 0.0, normal_turn = 0.0;
    int sky = 0, geometry = 0;
    for (int y = -1; y <= OB_EDGE_BLOCK; ++y) {
        for (int x = -1; x <= OB_EDGE_BLOCK; ++x) {
            ivec2 p = clamp(blk * OB_EDGE_BLOCK + ivec2(x, y), ivec2(0), size - 1);
            float d = texelFetch(ao_depth, p, 0).r;
            if (d <= 0.0) {
                ++sky;
                continue;
            }
            ++geometry;
            vec3 n = texelFetch(ao_normal, p, 0).xyz;
            for (int k = 0; k < 2; ++k) {
                ivec2 q = clamp(p + (k == 0 ? ivec2(1, 0) : ivec2(0, 1)), ivec2(0), size - 1);
                float qd = texelFetch(ao_depth, q, 0).r;
                if (qd <= 0.0) continue;
                depth_step = max(depth_step, abs(qd - d) / d);
                normal_turn = max(normal_turn, 1.0 - dot(n, texelFetch(ao_normal, q, 0).xyz));
            }
        }
    }
    /* A silhouette against the sky is an edge too: occluders hide right behind it. */
    float w = max(depth_step / rs.edge_depth_step, normal_turn / rs.edge_normal_turn);
    if (sky > 0 && geometry > 0) w = max(w, 1.0);
    float m = w >= 1.0 ? 3.0 : w >= 0.33 ? 2.0 : 1.0;
    imageStore(multiplier, blk, vec4(m));
}
