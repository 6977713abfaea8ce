#version 450 core
/* Packed samples (src/methods/packed.c; ssdo's and vbgi's `packed`): per AO-grid texel the three
 * things a sample of ssdo.glsl or visibility_bitmask.glsl (vbgi) reads there, in one RGBA32UI
 * texel, so that a sample makes one fetch instead of three: its linear depth, and as a sender of
 * the bounce its normal and its pixel's direct radiance. llvmpipe runs the senders' fetches for
 * every sample, occluded or not, and a fetch costs it about as much whatever the texel's size
 * (docs/adding-a-method.md).
 * The layout and the pack/unpack functions: packed_samples.glsl (lossless, so a packed
 * program's outputs are the plain one's bit for bit: test_ssdo, test_vbao). */
#include "frame_params.h"
#include "packed_samples.glsl"

#define OB_PACK_GROUP 8 /* packed.c dispatches 8x8 groups */
layout(local_size_x = OB_PACK_GROUP, local_size_y = OB_PACK_GROUP) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;  /* AO grid, R32F */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;  /* AO grid, RGBA16F */
layout(binding = OB_UNIT_RADIANCE) uniform sampler2D direct_map; /* full resolution RGBA16F direct radiance */
layout(binding = OB_IMAGE_UNIT_PACKED, rgba32ui) uniform writeonly uimage2D packed_out;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, ivec2(frame.ao_size)))) return;
    float d = texelFetch(linear_depth, q, 0).r;
    vec3 n = texelFetch(view_normal, q, 0).xyz;
    /* The AO texel's full-resolution pixel, where both methods read a sender's radiance. */
    ivec2 full = clamp(q * frame.ao_k + frame.ao_o, ivec2(0), textureSize(direct_map, 0) - 1);
    vec3 l = texelFetch(direct_map, full, 0).rgb;
    imageStore(packed_out, q, ob_pack_sample(d, n, l));
}
