#version 450 core
#include "gbuffer_params.h"
#include "octahedral.glsl"

in vec3 v_view_pos;
in vec3 v_view_normal;
in vec2 v_uv;
flat in float v_part;

layout(binding = OB_UNIT_DIFFUSE_MAP) uniform sampler2D diffuse_map; /* sRGB texture: sampled as linear */

layout(location = 0) out float out_linear_depth;   /* R32F, positive distance along -Z */
layout(location = 1) out vec4 out_normal;          /* RGBA16F, view space, unit length; w: the part, + front face, - back */
layout(location = 2) out vec4 out_albedo;          /* RGBA16F, linear */
layout(location = 3) out vec2 out_facet;           /* RG16F, the triangle's own view normal, octahedral */

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
    /* The normal of the triangle itself, which the interpolated n is not on a smooth-shaded curved
     * mesh: a ray leaving the pixel's point above n's tangent plane but below the triangle's
     * plane enters the surface at once, and the ground truth counts it occluded (vbao's facet
     * wedge, visibility_bitmask.glsl). The position is linear across the triangle, so its screen
     * derivatives span the triangle's plane exactly (a 2x2 quad's helper pixels interpolate the
     * same triangle); their cross product faces the eye on a visible triangle, front or back.
     * Degenerate (a triangle seen edge-on): n. */
    vec3 f = cross(dFdx(v_view_pos), dFdy(v_view_pos));
    float len = length(f);
    f = len > 0.0 && !isnan(len) && !isinf(len) ? f / len : n;
    out_facet = ob_oct_encode(f);
}
