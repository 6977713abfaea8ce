#version 450 core
/* Test probe for shaders/shadow.glsl (tests/test_shadow.c): ob_shadow() at arbitrary world points,
 * without the lighting pass. Point i: position xyz and light index in w; normal xyz. */
#include "lighting_params.h"
#include "shadow.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer probe_points { vec4 points[]; };
layout(std430, binding = 1) readonly buffer probe_normals { vec4 normals[]; };
layout(std430, binding = 2) writeonly buffer probe_visibility { float visibility[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(points.length())) return;
    vec4 p = points[i];
    visibility[i] = ob_shadow(int(p.w), p.xyz, normals[i].xyz);
}
