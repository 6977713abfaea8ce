#version 450 core
/* `vbgi`: visibility-bitmask AO and one indirect bounce in the same march; the body is
 * shaders/visibility_bitmask.glsl. */
#define OB_VBGI 1
#include "visibility_bitmask.glsl"
