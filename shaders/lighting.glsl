#version 450 core
/* Direct light over the G-buffer (Belonogov 2018 §4.5, SSDO thesis §5.2): for every light, Lambert +
 * Blinn-Phong, times its shadow-map visibility, into an RGBA16F radiance target. Directional
 * lights give intensity x colour at normal incidence; point and spot lights fall off as 1/d^2,
 * with a smooth window to zero at `range` ((1 - (d/range)^4)^2, as in UE4 and Filament), and spot
 * lights fade between the inner and outer cone. Sky pixels are left at 0 (compose paints them).
 * Alpha holds the key light's (light 0's) visibility, 0 where it faces away: the shadow view. */
#include "lighting_params.h"
#include "common.glsl"
#include "shadow.glsl"
#include "light_eval.glsl"

layout(local_size_x = OB_LIGHTING_GROUP_X, local_size_y = OB_LIGHTING_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;
layout(binding = OB_UNIT_ALBEDO) uniform sampler2D albedo_map;
layout(binding = OB_IMAGE_UNIT_OUT, rgba16f) uniform writeonly image2D radiance_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, ivec2(frame.size)))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(radiance_out, pix, vec4(0.0));
        return;
    }
    vec3 pv = ob_view_position(vec2(pix) + 0.5, d, frame.inv_size, frame.proj_info);
    vec3 p = (frame.inv_view * vec4(pv, 1.0)).xyz;
    vec3 n = normalize(mat3(frame.inv_view) * texelFetch(view_normal, pix, 0).xyz);
    vec3 v = normalize(frame.inv_view[3].xyz - p);
    vec3 albedo = texelFetch(albedo_map, pix, 0).rgb;
    float ks = lit.specular_ks, shininess = lit.specular_shininess;

    vec3 sum = vec3(0.0);
    float key_visibility = 1.0; /* light 0's shadow, for --view shadow */
    for (int i = 0; i < frame.light_count; ++i) {
        vec3 l;
        float falloff = ob_light_falloff(int(frame.light_color[i].w), frame.light_position[i], frame.light_direction[i].xyz,
                                         frame.light_spot[i].xy, p, l);
        float ndl = max(dot(n, l), 0.0);
        bool contributes = ndl > 0.0 && falloff > 0.0;
        /* Shadow lookups only where the light contributes (and light 0's for the shadow view). */
        float vis = contributes || i == 0 ? ob_shadow(i, p, n) : 0.0;
        if (i == 0) key_visibility = ndl > 0.0 ? vis : 0.0;
        if (!contributes) continue;
        vec3 h = normalize(l + v);
        /* Blinn-Phong lobe normalised so the highlight's energy does not grow with shininess. */
        float spec = ks * (shininess + 8.0) / 8.0 * pow(max(dot(n, h), 0.0), shininess);
        sum += (albedo + spec) * ndl * falloff * vis * frame.light_color[i].rgb;
    }
    imageStore(radiance_out, pix, vec4(sum, key_visibility));
}
