#version 450 core
/* The floor: a bare N-tap compute kernel, the least any screen-space AO pass can do at N taps
 * (`obscura bench --floor`; src/passes/floor.c builds the tap table).
 *
 * What it does, per pixel of the AO grid, in 8x8 work groups like every method:
 *   - fetches the pixel's linear depth (R32F) and stops at sky (d = 0), as every method does;
 *   - fetches the pixel's view normal (RGBA16F), as every method does, once;
 *   - projects the method's radius R to pixels at that depth, R_px = R x px_per_unit / d, clamped
 *     where the method clamps it (hbao.max_radius_px), as the methods do;
 *   - takes N depth taps, tap i at the pixel centre + rot(pixel) x dir_i x (a_i + b_i R_px), rot
 *     one of 16 rotations of a 4x4 tile (the methods' noise tile): a golden-angle spiral over the
 *     disk for the methods whose samples scatter over it (ssao, crytek, alchemy, ssdo), or D rays x
 *     S steps from 1.5 px to R_px for the horizon marchers (hbao, gtao, vbao), clamped to the edge;
 *   - writes the centre normal's z plus the sum of the N tap depths (R32F): the one addition per
 *     tap that keeps every fetch alive, and one value written per pixel.
 * What it does not: no reconstruction of view positions, no occlusion test, weights, range check,
 * horizon or bitmask arithmetic, no noise texture (its rotation comes from the constant block), no
 * adaptive counts, no depth MIPs, no second layer or radiance. Any AO method must at least fetch
 * its N taps and write one value, so its time over this kernel's, measured in the same run at the
 * same size, taps and radius, is what its own arithmetic and its less coherent taps cost. */
#include "floor_params.h"

layout(local_size_x = OB_FLOOR_GROUP_X, local_size_y = OB_FLOOR_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth; /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal; /* RGBA16F */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D floor_out;

/* Tap i: xy a unit direction, distance from the centre a + b R_px (z = a, w = b). */
layout(std430, binding = OB_FLOOR_TAPS_BINDING) readonly buffer floor_taps { vec4 tap[]; };

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, fl.size))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(floor_out, pix, vec4(0.0));
        return;
    }
    float sum = texelFetch(view_normal, pix, 0).z;
    float r_px = min(fl.radius * fl.px_per_unit / d, fl.max_radius_px);
    vec2 rot = fl.rotation[(pix.x & 3) + 4 * (pix.y & 3)].xy;
    vec2 centre = vec2(pix) + 0.5;
    ivec2 last = fl.size - 1;
    for (int i = 0; i < fl.taps; ++i) {
        vec4 k = tap[i];
        vec2 dir = vec2(k.x * rot.x - k.y * rot.y, k.x * rot.y + k.y * rot.x);
        vec2 q = centre + dir * (k.z + k.w * r_px);
        sum += texelFetch(linear_depth, clamp(ivec2(floor(q)), ivec2(0), last), 0).r;
    }
    imageStore(floor_out, pix, vec4(sum));
}
