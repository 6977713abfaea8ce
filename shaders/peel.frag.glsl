#version 450 core
/* The second depth layer (depth peeling, Everitt 2001; seed 000 §4.4, seed 003 §6.4): the same
 * scene drawn again with the G-buffer's vertex shader, keeping per pixel the nearest surface that
 * lies behind the first layer by more than a small separation. Back faces count (culling is off,
 * as in the G-buffer): behind a closed object's front the second layer is its back, so the two
 * bound the object's extent along the view ray. A method reads it as "a sample between the two
 * layers is inside an object, a sample behind the second is free". */
#include "gbuffer_params.h"

in vec3 v_view_pos;
in vec3 v_view_normal;
in vec2 v_uv;

layout(binding = OB_UNIT_FIRST_LAYER) uniform sampler2D first_layer; /* the G-buffer's R32F linear depth, 0 = sky */

layout(location = 0) out float out_linear_depth;   /* R32F: the second layer's linear depth, 0 = none */

/* The separation, relative to the first layer's depth: it drops the first surface itself where a
 * second triangle coincides with it (duplicated or z-fighting faces), and nothing an occluder test
 * could tell apart (1e-3 of the depth is 100x the R32F resolution at any depth). */
const float SEPARATION = 1e-3;

void main()
{
    float z = -v_view_pos.z;
    float first = texelFetch(first_layer, ivec2(gl_FragCoord.xy), 0).r;
    /* Behind the sky there is nothing (first = 0 only where no triangle covers the pixel). */
    if (first <= 0.0 || z <= first * (1.0 + SEPARATION)) discard;
    out_linear_depth = z;
}
