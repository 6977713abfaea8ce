#version 450 core
/* One value into every texel of an R32F target, or (OB_FILL_RGB) an RGBA16F one: the `none`
 * frame's visibility 1 and the bounce target's 0 (src/passes/fill.c). A compute pass rather than
 * glClearTexImage, which NVIDIA's driver runs on the graphics pipe: 0.15 ms for one 1920x1080
 * R32F clear on an H100, where this pass's work is one store per texel
 * (bench/results/2026-11-23-h100-egl.md). */
#include "ob_shared.h"

#define OB_FILL_GROUP 8
layout(local_size_x = OB_FILL_GROUP, local_size_y = OB_FILL_GROUP) in;

#ifdef OB_FILL_RGB
layout(binding = OB_IMAGE_UNIT_OUT, rgba16f) uniform writeonly image2D target;
#else
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D target;
#endif
/* The value, 16 bytes at the pass binding (ob_fill_run). */
layout(std140, binding = OB_BINDING_PASS) uniform fill_block { vec4 value; } fill;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, imageSize(target)))) return;
    imageStore(target, pix, fill.value);
}
