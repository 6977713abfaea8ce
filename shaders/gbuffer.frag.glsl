#version 450 core
#include "gbuffer_params.h"

in vec3 v_view_pos;
in vec3 v_view_normal;
in vec2 v_uv;
flat in float v_part;

layout(binding = OB_UNIT_DIFFUSE_MAP) uniform sampler2D diffuse_map; /* sRGB texture: sampled as linear */

layout(location = 0) out float out_linear_depth;   /* R32F, positive distance along -Z */
layout(location = 1) out vec4 out_normal;          /* RGBA16F, view space, unit length; w: the part, + front face, - back */
layout(location = 2) out vec4 out_albedo;          /* RGBA16F, linear */

void main()
{
    vec3 n = normalize(v_view_normal);
    /* Two-sided: many models (walls, planes) are single sheets seen from either side, and the
     * hemisphere must open toward the viewer. */
    if (!gl_FrontFacing) n = -n;
    out_linear_depth = -v_view_pos.z;
    /* w keeps the surface's connected part and, in its sign, which side of its triangle the
     * pixel shows (by winding): the second layer (peel.frag.glsl) is the back of this surface's
     * solid only on the same part, showing the other side. */
    out_normal = vec4(n, gl_FrontFacing ? v_part : -v_part);
    vec3 albedo = gb.diffuse;
    if (gb.textured != 0) albedo *= texture(diffuse_map, v_uv).rgb;
    out_albedo = vec4(albedo, 1.0);
}
