#version 450 core
/* Compose (docs/architecture.md "The frame"): direct radiance (lighting.glsl) + ambient x albedo x AO into
 * linear HDR radiance for the tone map; AO darkens the ambient term, or all light on request.
 * SSDO (cmp.directional): the RGB modulation factor M darkens direct and ambient light alike (SSDO thesis
 * §4.2: M is the ratio of the direct term with and without visibility, eq. 4.2), and the bounce,
 * stored as what a white receiver reflects, is added times the albedo (cmp.add_bounce; SSDO thesis §3.3).
 * vbgi: a scalar visibility for the ambient like any AO method, and its bounce added the same way.
 * Ambient: a constant, a sky/ground hemisphere by the world normal, or the environment map's
 * diffuse irradiance from 9 spherical harmonics (Ramamoorthi & Hanrahan 2001, eq. 13), so that a
 * constant environment of radiance L gives exactly the constant ambient L. */
#include "compose_params.h"
#include "common.glsl"
#include "light_eval.glsl"

/* The frame's choices, compiled in (passes/compose.c makes a program per combination on first
 * use): llvmpipe runs an if block whose uniform condition is false as it runs any other, and the
 * environment's SH irradiance and background lookup, the bent normal, the multi-bounce fit and the
 * directional terms cost the default frame (constant ambient, one AO value) most of its compose
 * pass (bench/results/2026-11-23-llvmpipe-ssdo-mips-temporal-upsample.md).
 *   OB_COMPOSE_AMBIENT      OB_AMBIENT_MODE_* (default constant)
 *   OB_COMPOSE_DIRECTIONAL  ao_map holds a directional method's RGB modulation factor M
 *   OB_COMPOSE_BOUNCE       add the one-bounce light x albedo (a method that writes a bounce)
 *   OB_COMPOSE_BENT         look the ambient up along the bent normal (OB_UNIT_COMPOSE_BENT_NORMAL)
 *   OB_COMPOSE_MULTIBOUNCE  visibility through Jimenez et al. 2016's multi-bounce fit
 *   OB_COMPOSE_ALL_LIGHT    AO darkens all light, not only the ambient term */
#ifndef OB_COMPOSE_AMBIENT
#define OB_COMPOSE_AMBIENT OB_AMBIENT_MODE_CONSTANT
#endif

layout(local_size_x = OB_COMPOSE_GROUP_X, local_size_y = OB_COMPOSE_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;
layout(binding = OB_UNIT_ALBEDO) uniform sampler2D albedo_map;
layout(binding = OB_UNIT_COMPOSE_AO) uniform sampler2D ao_map;               /* R32F visibility, or RGBA16F M (SSDO) */
layout(binding = OB_UNIT_COMPOSE_DIRECT) uniform sampler2D direct_map;       /* RGBA16F direct radiance */
layout(binding = OB_UNIT_COMPOSE_ENVIRONMENT) uniform sampler2D environment; /* equirectangular, for the background */
layout(binding = OB_UNIT_COMPOSE_BOUNCE) uniform sampler2D bounce_map;       /* RGBA16F one-bounce light (SSDO) */
layout(binding = OB_UNIT_COMPOSE_BENT_NORMAL) uniform sampler2D bent_map;    /* RGBA16F view-space bent normal */
layout(binding = OB_IMAGE_UNIT_OUT, rgba16f) uniform writeonly image2D hdr_out;

/* Jimenez, Wu, Pesce & Jarabo 2016, §5 "Approximated multiple bounces": a cubic fit, per colour
 * channel, of the visibility after infinitely many diffuse bounces between surfaces of the
 * receiver's albedo, fitted by the paper to ray-traced references; never below one bounce. */
vec3 ob_multibounce(float v, vec3 albedo)
{
    vec3 a = 2.0404 * albedo - 0.3324;
    vec3 b = -4.7951 * albedo + 0.6417;
    vec3 c = 2.7552 * albedo + 0.6903;
    return max(vec3(v), ((v * a + b) * v + c) * v);
}

vec3 ob_environment_radiance(vec3 dir)
{
    /* Equirectangular, +Y up: u from atan2(x, -z), v from the elevation. */
    vec2 uv = vec2(atan(dir.x, -dir.z) * (0.5 / 3.14159265) + 0.5, acos(clamp(dir.y, -1.0, 1.0)) / 3.14159265);
    return textureLod(environment, uv, 0.0).rgb;
}

void main()
{
    /* The inputs carry the guard band (Belonogov 2018 §3.2.2) and frame.size is theirs; the output is the
     * visible frame at their centre, so everything after compose sees only what is shown. */
    ivec2 out_pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(out_pix, ivec2(frame.size) - 2 * cmp.guard))) return;
    ivec2 pix = out_pix + cmp.guard;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
#if OB_COMPOSE_AMBIENT == OB_AMBIENT_MODE_CONSTANT
        vec3 bg = frame.background.rgb;
#else
        vec3 view_dir = normalize(mat3(frame.inv_view) * ob_view_position(vec2(pix) + 0.5, 1.0, frame.inv_size, frame.proj_info));
#if OB_COMPOSE_AMBIENT == OB_AMBIENT_MODE_ENVIRONMENT
        vec3 bg = ob_environment_radiance(view_dir);
#else
        vec3 bg = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * view_dir.y);
#endif
#endif
        imageStore(hdr_out, out_pix, vec4(bg, 1.0));
        return;
    }
    vec3 albedo = texelFetch(albedo_map, pix, 0).rgb;
    vec3 direct = texelFetch(direct_map, pix, 0).rgb;

#if OB_COMPOSE_AMBIENT == OB_AMBIENT_MODE_CONSTANT
    vec3 ambient = frame.ambient.rgb;
#else
    /* The ambient light arrives through the unoccluded part of the hemisphere: with a bent normal
     * (Jimenez et al. 2016 §5, "Bent normals"), look it up along that cone's mean direction
     * instead of the normal. Filtering averaged it, so it is renormalised here. */
    vec3 na = normalize(mat3(frame.inv_view) * texelFetch(view_normal, pix, 0).xyz);
#ifdef OB_COMPOSE_BENT
    vec3 b = texelFetch(bent_map, pix, 0).xyz;
    if (dot(b, b) > 1e-8) na = normalize(mat3(frame.inv_view) * b);
#endif
#if OB_COMPOSE_AMBIENT == OB_AMBIENT_MODE_HEMISPHERE
    vec3 ambient = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * na.y);
#else
    vec3 ambient = max(ob_sh_irradiance(frame.sh, na), vec3(0.0));
#endif
#endif

#ifdef OB_COMPOSE_DIRECTIONAL
    vec3 m = texelFetch(ao_map, pix, 0).rgb;
    vec3 color = (direct + ambient * albedo) * m;
#else
    float ao = texelFetch(ao_map, pix, 0).r;
#ifdef OB_COMPOSE_MULTIBOUNCE
    vec3 vis = ob_multibounce(ao, albedo);
#else
    vec3 vis = vec3(ao);
#endif
#ifdef OB_COMPOSE_ALL_LIGHT
    vec3 color = direct * vis + ambient * albedo * vis;
#else
    vec3 color = direct + ambient * albedo * vis;
#endif
#endif
    /* A method's bounce, stored as what a white receiver reflects (ssdo beside M, vbgi beside a
     * scalar visibility, whose ambient occlusion is not the direct light's: shadows are, so the
     * direct light stays as it is). */
#ifdef OB_COMPOSE_BOUNCE
    color += texelFetch(bounce_map, pix, 0).rgb * albedo;
#endif
    imageStore(hdr_out, out_pix, vec4(color, 1.0));
}
