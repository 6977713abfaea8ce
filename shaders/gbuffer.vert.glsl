#version 450 core
/* G-buffer: the one raster pass. Everything after it is a compute shader. */
#include "gbuffer_params.h"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in float in_part; /* the vertex's connected part, 1..2047, + OB_PART_SHEET_FLAG on a sheet (scene/parts.c) */

out vec3 v_view_pos;
out vec3 v_view_normal;
out vec2 v_uv;
flat out float v_part;
flat out float v_sheet; /* 1: the part is a sheet with holes, no thickness of its own (peel.frag.glsl) */

void main()
{
    vec4 vp = gb.view * vec4(in_position, 1.0);
    v_view_pos = vp.xyz;
    v_view_normal = mat3(gb.normal_matrix) * in_normal;
    v_uv = in_uv;
    v_sheet = in_part >= float(OB_PART_SHEET_FLAG) ? 1.0 : 0.0;
    v_part = in_part - float(OB_PART_SHEET_FLAG) * v_sheet;
    gl_Position = gb.proj * vp;
}
