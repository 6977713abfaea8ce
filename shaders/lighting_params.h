/* Direct lighting constants (Belonogov 2018 §4.5; SSDO thesis §4.2, §5.2): the specular lobe and the shadow
 * maps. The lights themselves, the camera and the size are the frame's (frame_params.h).
 * Filled by src/passes/lighting.c (specular) and src/passes/shadow.c (the shadow members,
 * ob_shadows_fill). World space. */
#ifndef OB_LIGHTING_PARAMS_H
#define OB_LIGHTING_PARAMS_H
#include "frame_params.h"

#define OB_LIGHTING_GROUP_X 8
#define OB_LIGHTING_GROUP_Y 8
#define OB_MAX_SHADOW_MAPS 4

OB_CONSTANTS_BEGIN(ob_lighting_constants, OB_BINDING_PASS)
    OB_FLOAT specular_ks;        /* Blinn-Phong reflectance at normal incidence */
    OB_FLOAT specular_shininess; /* Blinn-Phong exponent */
    OB_INT shadow_method;        /* OB_SHADOW_METHOD_*; NONE: no map is read */
    OB_INT pcf_radius;           /* PCF taps each side (1 = 3x3), clamped to OB_SHADOW_MAX_PCF_RADIUS */
    OB_FLOAT vsm_min_variance;   /* VSM: floor of the moments' variance (normalised depth^2) */
    OB_FLOAT vsm_bleed;          /* VSM: light-bleeding reduction threshold in [0, 1) */
    OB_FLOAT pad0;
    OB_FLOAT pad1;
    OB_MAT4 shadow_matrix[OB_MAX_SHADOW_MAPS]; /* world -> light clip space (directional, spot) */
    OB_VEC4 shadow_params[OB_MAX_SHADOW_MAPS]; /* per map: constant bias, slope bias, layer in its texture
                                                  array, far (0 = directional, orthographic) */
OB_CONSTANTS_END(ob_lighting_constants, lit)
OB_CONSTANTS_SIZE(ob_lighting_constants, 2 * 16 + OB_MAX_SHADOW_MAPS * 64 + OB_MAX_SHADOW_MAPS * 16);

#endif
