#version 450 core
/* Screen-space directional occlusion with one indirect bounce (Ritschel, Grosch & Seidel 2009,
 * as described in SSDO thesis §3.3 and §4.2; Belonogov 2018 §4.1-4.2). One program, four stages
 * (ssdo.stage), so `ssdo`'s two passes, its fused one (both outputs from one dispatch, the
 * default) and `ssdo_merged` take exactly the same samples. The second depth layer
 * (OB_SSDO_LAYERS) and the extra view (OB_SSDO_EXTRA_VIEW) are program variants, so the default
 * program carries none of their code (as options read per sample they cost every frame 40 % on
 * llvmpipe):
 *
 *   - samples P + r_i w_i in the normal hemisphere in 3D (w_i from a Halton 2,5 kernel, r_i from
 *     base 3, SSDO thesis §5.3), rotated per pixel, back-projected; a sample behind the depth buffer
 *     whose occluder rises above P's tangent plane within range is an occluder (V = 0);
 *   - the modulation factor per channel (SSDO thesis eq. 4.4)
 *         M = sum L_in(w_i) V(w_i) cos(theta_i) / sum L_in(w_i) cos(theta_i),
 *     the ratio of the direct term of eq. 3.3 with and without visibility (eq. 4.2-4.3), so the
 *     constant rho / pi and the sample's solid angle 2 pi / N cancel. With cosine-weighted
 *     directions (eq. 5.2, `ssdo_merged`) the cosine is in the pdf and drops out of both sums;
 *     with uniform directions (eq. 5.3, `ssdo`'s pass 1) it stays;
 *   - the bounce (eq. 3.4): each occluder pixel is a patch of area A_s = pi r^2 / N sending its
 *     direct radiance L_s to P:  sum L_s A_s cos(theta_s) cos(theta_r) / d^2, back-facing
 *     senders (cos theta_s <= 0) dropped. Stored as the radiance a white receiver reflects
 *     (x 1/pi, without the receiver's albedo, which compose applies at full resolution so the
 *     filters never blur texture detail into it). `ssdo_merged` darkens it by M (SSDO thesis §4.2).
 *
 * L_in(w): the ambient (constant, sky/ground hemisphere, or the environment's SH irradiance / pi
 * as a smooth stand-in for its radiance) plus every light spread into a normalised cosine lobe
 * (k + 1) / (2 pi) max(0, w . l)^k around its direction, so that its integral over the sphere
 * is the light's irradiance at normal incidence. A delta light would never be hit by a sample
 * direction; the lobe is our choice (ssdo.lobe = k). Shadow maps are not consulted here:
 * they already shadow the direct light that M multiplies. */
#include "ssdo_params.h"
#include "common.glsl"
#include "noise.glsl"
#include "light_eval.glsl"

layout(local_size_x = OB_SSDO_GROUP_X, local_size_y = OB_SSDO_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;          /* AO grid, R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;          /* AO grid, RGBA16F */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;            /* RG32F 4x4 rotation vectors */
layout(binding = OB_UNIT_RADIANCE) uniform sampler2D direct_map;         /* full resolution RGBA16F direct radiance */
layout(binding = OB_UNIT_SSDO_MULTIPLIER) uniform sampler2D multiplier;  /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_UNIT_SECOND_DEPTH) uniform sampler2D second_layer;   /* full-res R32F second depth layer (ssdo.layers) */
layout(binding = OB_UNIT_EXTRA_DEPTH) uniform sampler2D extra_depth;     /* the extra view (ssdo.extra_view): R32F depth, */
layout(binding = OB_UNIT_EXTRA_NORMAL) uniform sampler2D extra_normal;   /*   RGBA16F normals in its own view space, */
layout(binding = OB_UNIT_EXTRA_RADIANCE) uniform sampler2D extra_direct; /*   RGBA16F direct radiance */
#ifdef OB_SSDO_PACKED
/* Each AO texel's depth, normal and direct radiance in one texel (shaders/sample_pack.glsl). */
#include "packed_samples.glsl"
layout(binding = OB_UNIT_PACKED_SAMPLES) uniform usampler2D packed_samples;
#endif
#include "taps.glsl" /* `deinterleave on`: OB_DEINTERLEAVED; `depth_mips on`: OB_TAPS_DEPTH_MIPS */
layout(binding = OB_IMAGE_UNIT_OUT, rgba16f) uniform writeonly image2D m_out;
layout(binding = OB_IMAGE_UNIT_BOUNCE, rgba16f) uniform writeonly image2D bounce_out;

const float PI = 3.14159265;

/* The number of lights, frame.light_count, is compiled in (methods/ssdo.c picks the program by
 * it; the program without the define is the one for no light). With a constant trip count the
 * loops below unroll and light_dir and light_e stay in registers. With the uniform count they
 * were arrays indexed by a loop variable, which llvmpipe reads lane by lane from memory (a GPU
 * compiler may put them in local memory): with fzk-haus's three lights that cost ssdo a third of
 * its pass on llvmpipe (bench/results/2026-11-23-llvmpipe-instructions.md). */
#ifndef OB_SSDO_LIGHTS
#define OB_SSDO_LIGHTS 0
#endif

/* The lights as seen from one point, in view space: direction and irradiance (colour x
 * intensity x falloff x the lobe's normalisation). They depend on P only, so they are worked out
 * once per pixel and each sample pays one dot and one pow per light. */
vec3 light_dir[OB_SSDO_LIGHTS > 0 ? OB_SSDO_LIGHTS : 1];
vec3 light_e[OB_SSDO_LIGHTS > 0 ? OB_SSDO_LIGHTS : 1];

void lights_at(vec3 p, mat3 to_view)
{
    float k = ssdo.lobe;
    float lobe_norm = (k + 1.0) / (2.0 * PI);
    for (int i = 0; i < OB_SSDO_LIGHTS; ++i) {
        vec3 l;
        /* The same falloff, window and cone as lighting.glsl. */
        float falloff = ob_light_falloff(int(frame.light_color[i].w), frame.light_position[i], frame.light_direction[i].xyz,
                                         frame.light_spot[i].xy, p, l);
        light_dir[i] = to_view * l;
        light_e[i] = frame.light_color[i].rgb * (falloff * lobe_norm);
    }
}

/* Incoming radiance from view direction w (see the top comment); up is world +Y in view space. */
vec3 incoming(vec3 w, vec3 up, mat3 to_world)
{
    /* The ambient mode is compiled in (methods/ssdo.c picks the program by frame.ambient_mode):
     * llvmpipe runs an if block whose uniform condition is false as it runs any other, and the SH
     * branch's products per sample cost the default constant mode a third of the pass. */
#if defined(OB_SSDO_AMBIENT_HEMISPHERE)
    vec3 l_in = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * dot(w, up));
#elif defined(OB_SSDO_AMBIENT_ENVIRONMENT)
    vec3 l_in = max(ob_sh_irradiance(frame.sh, to_world * w), vec3(0.0));
#else
    vec3 l_in = frame.ambient.rgb;
#endif
    for (int i = 0; i < OB_SSDO_LIGHTS; ++i) {
#ifdef OB_SSDO_LOBE_POW
        l_in += light_e[i] * pow(max(dot(w, light_dir[i]), 0.0), ssdo.lobe);
#else
        /* The default lobe, k = 8 (methods/ssdo.c picks this program only then): three squarings.
         * llvmpipe's pow is an exp2 of a log2, a third of ssdo_merged's pass at 16 samples. */
        float c = max(dot(w, light_dir[i]), 0.0);
        c *= c;
        c *= c;
        l_in += light_e[i] * (c * c);
#endif
    }
    return l_in;
}

#ifdef OB_SSDO_EXTRA_VIEW
/* Belonogov 2018 §4.4's extra view, for a sample s that this view says is occluded (behind its depth
 * buffer): the extra camera, turned 90 degrees around the target, sees it too. In front of the
 * extra view's surface at its pixel (or over its sky), s lies on a ray that camera sees through,
 * in free space: no occluder. Behind that surface too, it stays occluded, and the sender of its
 * bounce is whichever view's surface point lies nearer s; the extra view's is the one this view
 * sees at a grazing angle or not at all. Outside the extra image nothing changes. */
mat4 extra_from_view, extra_to_view, extra_proj; /* the ssdo block's, read once in main (see ao_proj there) */

void extra_test(vec3 s, float bias, inout vec3 scene_p, inout float occ, inout vec3 send_n, inout vec3 send_l)
{
    vec4 se = extra_from_view * vec4(s, 1.0);
    vec4 ce = extra_proj * se;
    if (ce.w <= 0.0) return;
    vec2 uv = ce.xy / ce.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return;
    ivec2 size = textureSize(extra_depth, 0);
    ivec2 qe = ivec2(uv * vec2(size));
    float de = texelFetch(extra_depth, qe, 0).r;
    if (de <= 0.0 || -se.z < de - bias) {
        occ = 0.0;
        return;
    }
    vec3 pe = ob_view_position(vec2(qe) + 0.5, de, 1.0 / vec2(size), ssdo.extra_proj_info);
    vec3 pe_here = (extra_to_view * vec4(pe, 1.0)).xyz;
    if (distance(pe_here, s) < distance(scene_p, s)) {
        scene_p = pe_here;
        send_n = mat3(extra_to_view) * texelFetch(extra_normal, qe, 0).xyz;
        send_l = texelFetch(extra_direct, qe, 0).rgb;
    }
}

#endif

void main()
{
    ivec2 pix = ob_invocation_pixel(); /* taps.glsl */
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    int stage = ssdo.stage;
    bool want_m = stage != OB_SSDO_STAGE_BOUNCE;
    bool want_bounce = stage != OB_SSDO_STAGE_DIRECT && ssdo.bounce != 0;

    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        /* The sky: nothing occludes it and it sends no bounce. */
        if (want_m) imageStore(m_out, pix, vec4(1.0));
        if (stage != OB_SSDO_STAGE_DIRECT) imageStore(bounce_out, pix, vec4(0.0));
        return;
    }
    vec3 p = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
    vec3 p_world = (frame.inv_view * vec4(p, 1.0)).xyz;
    mat3 to_world = mat3(frame.inv_view);
    mat3 to_view = transpose(to_world); /* inv_view's rotation is orthonormal */
    vec3 up = to_view[1];
    if (want_m) lights_at(p_world, to_view);
    vec3 rnd = vec3(ob_rotation(pix, ssdo.noise, noise_tile), 0.0);
    /* Gram-Schmidt as in ssao.glsl. */
    vec3 t = rnd - n * dot(rnd, n);
    if (dot(t, t) < 1e-6) t = abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0));
    t = normalize(t);
    mat3 tbn = mat3(t, cross(n, t), n);

    float radius = ssdo.radius;
    float bias = ssdo.bias;
    /* Adaptive sample counts (SSDO thesis §4.1 proposes them for SSDO): the first base x 1, 2 or 3
     * Halton directions, evenly spread at every prefix; M is a ratio of sums and needs no
     * rescaling, the bounce's patch area A_s = pi r^2 / N takes this pixel's N. */
    int count = ssdo.adaptive != 0 ? ssdo.adaptive_base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r)
                                   : ssdo.samples;
    bool cosine_pdf = stage == OB_SSDO_STAGE_MERGED;
    /* Patches closer than their own radius sqrt(A_s / pi) = r / sqrt(N) would make 1/d^2 blow up. */
    float min_d2 = radius * radius / float(max(count, 1));
    ivec2 full_size = textureSize(direct_map, 0);
    /* The projection read once, into registers: read from the constant block inside the loop,
     * llvmpipe loaded the matrix again for every sample, 22 % of the pass's instructions
     * (bench/results/2026-11-23-llvmpipe-instructions.md). */
    mat4 ao_proj = frame.ao_proj;
#ifdef OB_SSDO_EXTRA_VIEW
    extra_from_view = ssdo.extra_from_view;
    extra_to_view = ssdo.extra_to_view;
    extra_proj = ssdo.extra_proj;
#endif
    vec3 lit = vec3(0.0), total = vec3(0.0), bounce = vec3(0.0);
    float vis = 0.0, vis_all = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 dir = tbn * ssdo.kernel[i].xyz;
        /* Eq. 4.4 keeps cos(theta) for uniform directions; cosine-weighted ones carry it. */
        float w = cosine_pdf ? 1.0 : max(ssdo.kernel[i].z, 0.0);
        float occ = 0.0;
        ivec2 q = ivec2(0);
        vec3 scene_p = vec3(0.0);
#ifdef OB_SSDO_EXTRA_VIEW
        /* The sender of a bounce: the occluding surface point, its normal and direct radiance
         * (this view's unless the extra view's surface lies nearer the sample). */
        vec3 send_n = vec3(0.0), send_l = vec3(0.0);
#endif
        vec3 s = p + dir * (radius * ssdo.kernel[i].w);
        vec4 clip = ao_proj * vec4(s, 1.0);
#ifdef OB_SSDO_PACKED
        uvec4 texel = uvec4(0u); /* sample_pack.glsl's: depth, normal and radiance of q */
#endif
        if (clip.w > 0.0) {
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)))) {
                /* Deinterleaved, the nearest pixel of this pixel's class (its depth from the class's
                 * layer; a packed texel, the sender's normal and light from their full textures);
                 * from the MIP chain, the pixel the chain picked at the tap's level (its depth from
                 * that level, the sender's normal and light from their full textures). */
                q = ob_tap_pixel(ivec2(uv * frame.ao_size), size);
#ifdef OB_SSDO_PACKED
                texel = texelFetch(packed_samples, q, 0);
                float scene_d = ob_packed_depth(texel);
#else
                float scene_d = ob_tap_depth(linear_depth, q);
#endif
                if (scene_d > 0.0) {
                    scene_p = ob_view_position(vec2(q) + 0.5, scene_d, frame.ao_inv_size, frame.ao_proj_info);
                    /* As ssao.glsl: an occluder rises above P's tangent plane (no self-occlusion
                     * of flat surfaces read at pixel centres), and fades out beyond the radius
                     * (Puri 2024 §3.3's range check) so foreground silhouettes do not occlude. */
                    bool above = dot(scene_p - p, n) > bias;
                    float range = smoothstep(0.0, 1.0, radius / abs(d - scene_d));
                    /* Belonogov 2018 around Fig. 4.6: with a second layer a sample behind the first
                     * surface is inside the object only up to the second; behind that it is free
                     * (0 = nothing behind the first: the single-layer test). */
                    bool inside = true;
#ifdef OB_SSDO_LAYERS
                    float back = texelFetch(second_layer, min(q * frame.ao_k + frame.ao_o, full_size - 1), 0).r;
                    inside = back <= 0.0 || -s.z <= back;
#endif
                    occ = above && scene_d <= -s.z - bias && inside ? range : 0.0;
#ifdef OB_SSDO_EXTRA_VIEW
                    if (want_bounce && occ > 0.0) {
#ifdef OB_SSDO_PACKED
                        send_n = ob_packed_normal(texel);
                        send_l = ob_packed_radiance(texel);
#else
                        send_n = texelFetch(view_normal, q, 0).xyz;
                        send_l = texelFetch(direct_map, min(q * frame.ao_k + frame.ao_o, full_size - 1), 0).rgb;
#endif
                    }
                    if (occ > 0.0) extra_test(s, bias, scene_p, occ, send_n, send_l);
#endif
                }
            }
        }
        if (want_m) {
            vec3 l_in = incoming(dir, up, to_world);
            lit += l_in * (w * (1.0 - occ));
            total += l_in * w;
            vis += w * (1.0 - occ);
            vis_all += w;
        }
        if (want_bounce && occ > 0.0) {
            vec3 v = p - scene_p;
            float len2 = max(dot(v, v), 1e-12);
            vec3 vd = v * inversesqrt(len2);
#ifndef OB_SSDO_EXTRA_VIEW
#ifdef OB_SSDO_PACKED
            vec3 send_n = ob_packed_normal(texel);
#else
            vec3 send_n = texelFetch(view_normal, q, 0).xyz;
#endif
#endif
            float cos_s = dot(send_n, vd); /* the sender must face P */
            float cos_r = dot(n, -vd);     /* and P must face the sender */
            if (cos_s > 0.0 && cos_r > 0.0) {
#ifndef OB_SSDO_EXTRA_VIEW
#ifdef OB_SSDO_PACKED
                vec3 send_l = ob_packed_radiance(texel);
#else
                vec3 send_l = texelFetch(direct_map, clamp(q * frame.ao_k + frame.ao_o, ivec2(0), full_size - 1), 0).rgb;
#endif
#endif
                bounce += send_l * (occ * cos_s * cos_r / max(len2, min_d2));
            }
        }
    }
    vec3 m = vec3(1.0);
    if (want_m) {
        /* A channel that no light reaches has no ratio: it takes the plain visibility. */
        float v0 = vis_all > 0.0 ? vis / vis_all : 1.0;
        for (int c = 0; c < 3; ++c) m[c] = total[c] > 1e-6 ? lit[c] / total[c] : v0;
        m = clamp(m, 0.0, 1.0);
        imageStore(m_out, pix, vec4(m, 1.0));
    }
    if (stage != OB_SSDO_STAGE_DIRECT) {
        /* A_s / pi x strength, from the CPU; the merged variant darkens the bounce by M. */
        bounce *= ssdo.bounce_scale * float(ssdo.samples) / float(max(count, 1));
        if (stage == OB_SSDO_STAGE_MERGED) bounce *= m;
        imageStore(bounce_out, pix, vec4(want_bounce ? bounce : vec3(0.0), 1.0));
    }
}
