/* Direct lighting constants (seed 000 §4.5; seed 003 §4.2, §5.2): the lights and their shadow
 * maps. Filled by src/passes/lighting.c (lights) and src/passes/shadow.c (the shadow_* members,
 * ob_shadows_fill). World space unless noted. */
#ifndef OB_LIGHTING_PARAMS_H
#define OB_LIGHTING_PARAMS_H
#include "ob_shared.h"

#define OB_LIGHTING_GROUP_X 8
#define OB_LIGHTING_GROUP_Y 8
#define OB_MAX_LIGHTS 8
#define OB_MAX_SHADOW_MAPS 4

/* light_color.w: OB_LIGHT_TYPE_*; shadow_options.x: OB_SHADOW_METHOD_* (ob_enums.h) */

OB_CONSTANTS_BEGIN(ob_lighting_constants, OB_BINDING_PASS)
    OB_VEC4 size;            /* width, height, 1/width, 1/height */
    OB_VEC4 proj_info;       /* 1/P00, 1/P11, P20, P21 */
    OB_MAT4 inv_view;        /* view -> world */
    OB_IVEC4 counts;         /* light count, unused... */
    OB_VEC4 specular;        /* ks, shininess, unused, unused */
    OB_VEC4 light_color[OB_MAX_LIGHTS];     /* rgb x intensity; w = OB_LIGHT_TYPE_* */
    OB_VEC4 light_position[OB_MAX_LIGHTS];  /* point/spot position; w = range (0 = none) */
    OB_VEC4 light_direction[OB_MAX_LIGHTS]; /* directional: unit, toward the light; spot: unit axis
                                               from the light; w = shadow map index, -1 = unshadowed */
    OB_VEC4 light_spot[OB_MAX_LIGHTS];      /* cos(inner half-angle), cos(outer half-angle) */
    /* ---- filled by ob_shadows_fill (src/passes/shadow.c) ---- */
    OB_MAT4 shadow_matrix[OB_MAX_SHADOW_MAPS]; /* world -> light clip space (directional, spot) */
    OB_VEC4 shadow_params[OB_MAX_SHADOW_MAPS]; /* per map: constant bias, slope bias, layer in its texture
                                                  array, far (0 = directional, orthographic) */
    OB_VEC4 shadow_options;                    /* method (OB_SHADOW_METHOD_*), PCF radius, VSM min variance,
                                                  VSM light-bleeding reduction */
OB_CONSTANTS_END(ob_lighting_constants, lit)

#endif
