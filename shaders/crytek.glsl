#version 450 core
/* Crytek SSAO (Mittring 2007, "Finding next gen: CryEngine 2"; Puri 2024 §2.2):
 *   - N points in a sphere of radius r around the pixel's view-space position, no normals;
 *   - rotated per pixel about the view axis by the 4x4 noise (or IGN);
 *   - a point is occluded when the depth buffer in front of it is closer than it by more than
 *     `bias`, faded by the range check smoothstep(0, 1, r / |z_P - z_scene|);
 *   - occlusion factor = occluded / N, AO = 1 - occlusion factor (Puri 2024 §2.2).
 * Half of a sphere around a point on a plane lies inside the plane, so flat surfaces read about
 * 0.5: that is the method (its characteristic grey look), not a bug. The optional correction of
 * SSDO thesis §5.4 rescales AO' = min(1, 2 AO) so open planes read 1, wasting half the samples.
 * `deinterleave on` compiles OB_DEINTERLEAVED: far taps read the nearest pixel of their own 4x4 class;
 * `depth_mips on` OB_TAPS_DEPTH_MIPS: taps 20 px or more out read the depth MIP chain (taps.glsl). */
#include "crytek_params.h"
#include "common.glsl"
#include "noise.glsl"
#include "taps.glsl"

layout(local_size_x = OB_CRYTEK_GROUP_X, local_size_y = OB_CRYTEK_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;           /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;             /* RG32F 4x4 rotation vectors */
layout(binding = OB_UNIT_SAMPLE_MULTIPLIER) uniform sampler2D multiplier; /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ob_invocation_pixel(); /* taps.glsl */
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(1.0));
        return;
    }
    vec3 p = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    vec2 rot = ob_rotation(pix, crytek.noise, noise_tile);
    /* Rotation about the view axis: a sphere has no preferred frame, and the depth buffer's. */
    mat2 r2 = mat2(rot.x, rot.y, -rot.y, rot.x);

    float radius = crytek.radius;
    float bias = crytek.bias;
    /* Adaptive (SSDO thesis §4.1): base x 1, 2 or 3 from the edge pass; the Halton kernel's prefixes
     * are kernels of their own. */
    int count = crytek.adaptive != 0 ? crytek.adaptive_base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r) : crytek.samples;
    /* The projection read once, into registers: read from the constant block inside the loop,
     * llvmpipe loaded the matrix again for every sample (ssdo.glsl). */
    mat4 ao_proj = frame.ao_proj;
    float occlusion = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 k = crytek.kernel[i].xyz;
        vec3 s = p + vec3(r2 * k.xy, k.z) * radius;
        vec4 clip = ao_proj * vec4(s, 1.0);
        if (clip.w <= 0.0) continue;
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        float scene_d = ob_tap_depth(linear_depth, ob_tap_pixel(ivec2(uv * frame.ao_size), size));
        if (scene_d <= 0.0) continue;
        float range = smoothstep(0.0, 1.0, radius / abs(d - scene_d));
        occlusion += (scene_d <= -s.z - bias ? 1.0 : 0.0) * range;
    }
    float ao = clamp(1.0 - occlusion / float(max(count, 1)), 0.0, 1.0);
    if (crytek.correction != 0) ao = min(1.0, 2.0 * ao);
    imageStore(ao_out, pix, vec4(pow(ao, crytek.intensity)));
}
