#version 450 core
/* Shadow maps, first step: depth only (SSDO thesis §5.1: "a framebuffer object with a depth texture
 * attached"). Directional maps keep the hardware depth, which an orthographic projection already
 * makes linear in the distance along the light. Spot and point maps (OB_SHADOW_DISTANCE) store the
 * linear distance to the light / far instead of the perspective's hyperbolic depth: the same value
 * on all six faces of a cube (so the lookup needs no face matrix), a bias that means the same
 * thing at every distance, and full float precision far from the light. The distance grows
 * monotonically along every ray from the light, so the depth test still keeps the nearest
 * surface. */
#define OB_SHADOW_DEPTH_PASS 1
#include "shadow_params.h"

#ifdef OB_SHADOW_DISTANCE
in vec3 v_world;
#endif

void main()
{
#ifdef OB_SHADOW_DISTANCE
    gl_FragDepth = length(v_world - shd.light_position) * shd.inv_far;
#endif
}
