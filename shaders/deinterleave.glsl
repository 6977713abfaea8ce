#version 450 core
/* Deinterleaved depth (issue 18; Bavoil 2014, "Deinterleaved Texturing for Cache-Efficient
 * Interleaved Sampling", NVIDIA): the AO grid's linear depth split into 16 layers, one per
 * class of the 4x4 noise tile. Layer c = (cx, cy), c = cx + 4 cy, texel t holds AO pixel
 * 4 t + (cx, cy), so a class's pixels are adjacent in memory. A method's deinterleaved program
 * (OB_DEINTERLEAVED, taps.glsl) runs one layer per dispatch slice: its neighbouring
 * invocations share the class's one rotation, so their taps land on neighbouring texels of one
 * layer, where the plain program's 16 rotations scatter a group's taps over the whole radius
 * (what a GPU's texture cache pays for at large radii). Texels past the image (a size that is not
 * a multiple of 4) hold 0, no geometry; the taps never read them (taps.glsl clamps
 * to the class's last pixel). Source: src/methods/deinterleave.c. */
#include "frame_params.h"

#define OB_DEINTERLEAVE_GROUP 8 /* deinterleave.c dispatches 8x8 groups */
layout(local_size_x = OB_DEINTERLEAVE_GROUP, local_size_y = OB_DEINTERLEAVE_GROUP) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth; /* AO grid, R32F */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2DArray layers;

void main()
{
    /* One invocation per AO pixel of the 4-aligned grid that covers the image. */
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, 4 * ((size + 3) / 4)))) return;
    float d = all(lessThan(pix, size)) ? texelFetch(linear_depth, pix, 0).r : 0.0;
    ivec2 c = pix & 3;
    imageStore(layers, ivec3(pix >> 2, c.x + 4 * c.y), vec4(d));
}
