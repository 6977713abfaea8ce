#version 450 core
/* The second layer over each pixel's footprint (src/passes/second_back.c): the back a method
 * gives a sample (slice_march.glsl ob_layer_thickness). The peel pass (peel.frag.glsl) finds the
 * back of the solid on the ray through the pixel's centre, but a sample stands for the whole pixel
 * it was taken from: on a thin part seen near its edge, a fin or a chain's link, the solid behind
 * the rest of the footprint reaches deeper, and a back read at the centre alone let light through
 * that the part blocks (docs/methods.md, "The back over a pixel's footprint"). Along each axis the
 * footprint ends half way to the neighbour, where the back is the mean of the two (linear between
 * the centres); the pixel's back is the deepest of those four edges and its own centre.
 *
 * A neighbour counts only where it shows the same solid: its front lies in front of this pixel's
 * back (the solids overlap along the view). A neighbour in a hole (the floor behind a sheet) or
 * beside a silhouette (a wall far behind) is left out, and a pixel whose back is unknown (0:
 * peel.frag.glsl found no closing surface) stays unknown.
 *
 * A neighbour of the same solid whose own back is unknown says that part of the footprint's solid
 * reaches back further than anything known: the peel found no closing surface on its ray, and a
 * method's answer there is its own constant thickness. The pixel's back is then written negated,
 * -deepest: at least the deepest known, and at least the method's constant (visibility_bitmask.glsl
 * takes the thicker). On a Quake stair whose risers are one pixel tall, the ray through a riser's
 * centre clips the step's nose and leaves through the tread, while the riser's lower half, on the
 * neighbour's ray, runs into the solid below: read at the centre alone, two layers read that stair
 * more open than one (docs/methods.md, "The back over a pixel's footprint").
 *
 * A sheet is its own back (back = front), so no neighbour's front lies in front of it but one
 * nearer on the same sheet, whose back is nearer too, or a nearer object's: a sheet stays a sheet,
 * never flagged. */
#include "ob_shared.h"

#define OB_SECOND_BACK_GROUP 8
layout(local_size_x = OB_SECOND_BACK_GROUP, local_size_y = OB_SECOND_BACK_GROUP) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D front_depth;   /* the first layer's linear depth, full resolution */
layout(binding = OB_UNIT_SECOND_DEPTH) uniform sampler2D second; /* the peel pass's linear depth, same size */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D back;
/* The size of all three, 16 bytes at the pass binding (ob_second_back_run). */
layout(std140, binding = OB_BINDING_PASS) uniform second_back_block { ivec4 size; } sb;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = sb.size.xy;
    if (any(greaterThanEqual(p, size))) return;
    float z2 = texelFetch(second, p, 0).r, deepest = z2;
    bool sheet = z2 <= texelFetch(front_depth, p, 0).r, open_behind = false;
    if (z2 > 0.0) {
        const ivec2 step[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int k = 0; k < 4; ++k) {
            ivec2 q = p + step[k];
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float q2 = texelFetch(second, q, 0).r, q1 = texelFetch(front_depth, q, 0).r;
            if (q1 <= 0.0 || q1 >= z2) continue;
            if (q2 > 0.0) deepest = max(deepest, 0.5 * (z2 + q2));
            else open_behind = true;
        }
    }
    imageStore(back, p, vec4(open_behind && !sheet ? -deepest : deepest));
}
