#version 450 core
/* Normal-oriented hemisphere SSAO (StarCraft II; Filion & McNaughton 2008), as in Puri 2024 §2.3
 * and §3.3 and Belonogov 2018 §3.2:
 *   - a kernel of N points in the unit hemisphere around +Z, denser toward the centre;
 *   - rotated per pixel by a 4x4 tiled noise vector through a Gram-Schmidt TBN basis;
 *   - each point P + r * TBN * k is projected; it is occluded when the depth buffer there is in
 *     front of it by more than `bias`;
 *   - a range check smoothstep(0, 1, r / |z_P - z_scene|) fades occluders far outside the radius
 *     so silhouettes in front do not darken the background (Puri 2024 §3.3);
 *   - one addition: the occluder must lie above P's tangent plane (see the loop), which removes
 *     the grazing-angle self-occlusion that the bias alone only hides;
 *   - AO = (1 - occluded / N) ^ intensity: visibility in [0,1].
 * `deinterleave on` compiles OB_DEINTERLEAVED: far taps read the nearest pixel of their own 4x4 class;
 * `depth_mips on` OB_TAPS_DEPTH_MIPS: taps 20 px or more out read the depth MIP chain (taps.glsl). */
#include "ssao_params.h"
#include "common.glsl"
#include "noise.glsl"
#include "taps.glsl"

layout(local_size_x = OB_SSAO_GROUP_X, local_size_y = OB_SSAO_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;           /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;           /* RGBA16F */
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
    vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
    vec3 rnd = vec3(ob_rotation(pix, ssao.noise, noise_tile), 0.0);

    /* Gram-Schmidt: a tangent from the random vector, orthogonal to n. When the random vector is
     * (nearly) parallel to n, fall back to any perpendicular axis. */
    vec3 t = rnd - n * dot(rnd, n);
    if (dot(t, t) < 1e-6) t = abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0));
    t = normalize(t);
    mat3 tbn = mat3(t, cross(n, t), n);

    float radius = ssao.radius;
    float bias = ssao.bias;
    /* Adaptive (SSDO thesis §4.1): base x 1, 2 or 3 from the edge pass; the Halton kernel's prefixes
     * are kernels of their own. */
    int count = ssao.adaptive != 0 ? ssao.adaptive_base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r) : ssao.samples;
    /* The projection read once, into registers: read from the constant block inside the loop,
     * llvmpipe loaded the matrix again for every sample (ssdo.glsl). */
    mat4 ao_proj = frame.ao_proj;
    float occlusion = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 s = p + tbn * ssao.kernel[i].xyz * radius;
        vec4 clip = ao_proj * vec4(s, 1.0);
        if (clip.w <= 0.0) continue;
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
        ivec2 q = ob_tap_pixel(ivec2(uv * frame.ao_size), size);
        float scene_d = ob_tap_depth(linear_depth, q);
        if (scene_d <= 0.0) continue; /* sky: nothing there */
        float sample_d = -s.z;
        float range = smoothstep(0.0, 1.0, radius / abs(d - scene_d));
        /* The depth buffer is read at the pixel centre, not at the sample's exact position: on a
         * plane seen at a grazing angle, half a pixel of depth gradient puts the plane itself in
         * front of samples that hug it, and flat floors go grey. An occluder must also rise above
         * P's tangent plane (by `bias`); a flat surface then never occludes itself, while a wall
         * or a crease still does. */
        vec3 scene_p = ob_view_position(vec2(q) + 0.5, scene_d, frame.ao_inv_size, frame.ao_proj_info);
        bool above = dot(scene_p - p, n) > bias;
        occlusion += (above && scene_d <= sample_d - bias ? 1.0 : 0.0) * range;
    }
    float ao = pow(clamp(1.0 - occlusion / float(max(count, 1)), 0.0, 1.0), ssao.intensity);
    imageStore(ao_out, pix, vec4(ao));
}
