#version 450 core
/* `vbao`: visibility-bitmask ambient occlusion; the body is shaders/visibility_bitmask.glsl. */
#include "visibility_bitmask.glsl"
