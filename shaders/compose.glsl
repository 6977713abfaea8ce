#version 450 core
/* Compose (DESIGN.md "The frame"): direct radiance (lighting.glsl) + ambient x albedo x AO into
 * linear HDR radiance for the tone map; AO darkens the ambient term, or all light on request.
 * SSDO (cmp.directional): the RGB modulation factor M darkens direct and ambient light alike (seed 003
 * §4.2: M is the ratio of the direct term with and without visibility, eq. 4.2), and the bounce,
 * stored as what a white receiver reflects, is added times the albedo (cmp.add_bounce; seed 003 §3.3).
 * vbgi: a scalar visibility for the ambient like any AO method, and its bounce added the same way.
 * Ambient: a constant, a sky/ground hemisphere by the world normal, or the environment map's
 * diffuse irradiance from 9 spherical harmonics (Ramamoorthi & Hanrahan 2001, eq. 13), so that a
 * constant environment of radiance L gives exactly the constant ambient L. */
#include "compose_params.h"
#include "common.glsl"
#include "light_eval.glsl"

layout(local_size_x = OB_COMPOSE_GROUP_X, local_size_y = OB_COMPOSE_GROUP_Y) in;

layout(binding = 0) uniform sampler2D linear_depth;
layout(binding = 1) uniform sampler2D view_normal;
layout(binding = 2) uniform sampler2D albedo_map;
layout(binding = 3) uniform sampler2D ao_map;         /* R32F visibility, or RGBA16F M (SSDO) */
layout(binding = 4) uniform sampler2D direct_map;     /* RGBA16F direct radiance */
layout(binding = 5) uniform sampler2D environment;    /* equirectangular radiance, for the background */
layout(binding = 6) uniform sampler2D bounce_map;     /* RGBA16F one-bounce indirect light (SSDO) */
layout(binding = 7) uniform sampler2D bent_map;       /* RGBA16F view-space bent normal (cmp.bent_normal) */
layout(binding = 0, rgba16f) uniform writeonly image2D hdr_out;

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
    /* The inputs carry the guard band (seed 000 §3.2.2) and frame.size is theirs; the output is the
     * visible frame at their centre, so everything after compose sees only what is shown. */
    ivec2 out_pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(out_pix, ivec2(frame.size) - 2 * cmp.guard))) return;
    ivec2 pix = out_pix + cmp.guard;
    float d = texelFetch(linear_depth, pix, 0).r;
    int mode = frame.ambient_mode;
    if (d <= 0.0) {
        vec3 view_dir = normalize(mat3(frame.inv_view) * ob_view_position(vec2(pix) + 0.5, 1.0, frame.inv_size, frame.proj_info));
        vec3 bg = mode == OB_AMBIENT_MODE_ENVIRONMENT ? ob_environment_radiance(view_dir)
                : mode == OB_AMBIENT_MODE_HEMISPHERE  ? mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * view_dir.y)
                                                      : frame.background.rgb;
        imageStore(hdr_out, out_pix, vec4(bg, 1.0));
        return;
    }
    vec3 n = normalize(mat3(frame.inv_view) * texelFetch(view_normal, pix, 0).xyz);
    vec3 albedo = texelFetch(albedo_map, pix, 0).rgb;
    float ao = texelFetch(ao_map, pix, 0).r;
    vec3 direct = texelFetch(direct_map, pix, 0).rgb;

    /* The ambient light arrives through the unoccluded part of the hemisphere: with a bent normal
     * (Jimenez et al. 2016 §5, "Bent normals"), look it up along that cone's mean direction
     * instead of the normal. Filtering averaged it, so it is renormalised here. */
    vec3 na = n;
    if (cmp.bent_normal != 0) {
        vec3 b = texelFetch(bent_map, pix, 0).xyz;
        if (dot(b, b) > 1e-8) na = normalize(mat3(frame.inv_view) * b);
    }
    vec3 ambient = frame.ambient.rgb;
    if (mode == OB_AMBIENT_MODE_HEMISPHERE) ambient = mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * na.y);
    else if (mode == OB_AMBIENT_MODE_ENVIRONMENT) ambient = max(ob_sh_irradiance(frame.sh, na), vec3(0.0));

    vec3 color;
    if (cmp.directional != 0) {
        vec3 m = texelFetch(ao_map, pix, 0).rgb;
        color = (direct + ambient * albedo) * m;
        if (cmp.add_bounce != 0) color += texelFetch(bounce_map, pix, 0).rgb * albedo;
    } else {
        vec3 vis = cmp.multibounce != 0 ? ob_multibounce(ao, albedo) : vec3(ao);
        color = (cmp.ao_all_light != 0 ? direct * vis : direct) + ambient * albedo * vis;
        /* vbgi: a bounce beside a scalar visibility. The ambient's occlusion is not the direct
         * light's (shadows are), so the direct light stays as it is. */
        if (cmp.add_bounce != 0) color += texelFetch(bounce_map, pix, 0).rgb * albedo;
    }
    imageStore(hdr_out, out_pix, vec4(color, 1.0));
}
