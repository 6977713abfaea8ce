#version 450 core
/* Direct light (Lambert + Blinn-Phong) + ambient x AO, then sRGB. HDR tone mapping comes later;
 * here radiance is clamped to [0,1] before the sRGB transfer. */
#include "compose_params.h"
#include "common.glsl"

layout(local_size_x = OB_COMPOSE_GROUP_X, local_size_y = OB_COMPOSE_GROUP_Y) in;

layout(binding = 0) uniform sampler2D linear_depth;
layout(binding = 1) uniform sampler2D view_normal;
layout(binding = 2) uniform sampler2D albedo_map;
layout(binding = 3) uniform sampler2D ao_map;
layout(binding = 0, rgba8) uniform writeonly image2D final_out;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, ivec2(cmp.size.xy)))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    vec3 color = cmp.background.rgb;
    if (d > 0.0) {
        vec3 p = ob_view_position(vec2(pix) + 0.5, d, cmp.size, cmp.proj_info);
        vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
        vec3 albedo = texelFetch(albedo_map, pix, 0).rgb;
        float ao = texelFetch(ao_map, pix, 0).r;
        vec3 l = cmp.light_dir.xyz;
        vec3 v = normalize(-p);
        vec3 h = normalize(l + v);
        float ndl = max(dot(n, l), 0.0);
        /* Blinn-Phong lobe, normalised so the highlight's energy does not grow with shininess. */
        float shininess = cmp.specular.y;
        float spec = ndl > 0.0 ? cmp.specular.x * (shininess + 8.0) / 8.0 * pow(max(dot(n, h), 0.0), shininess) : 0.0;
        vec3 direct = (albedo * ndl + spec * ndl) * cmp.light_color.rgb;
        color = direct + cmp.ambient.rgb * albedo * ao;
    }
    imageStore(final_out, pix, vec4(ob_linear_to_srgb(color), 1.0));
}
