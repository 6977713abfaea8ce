/* Screen-space directional occlusion constants (Ritschel et al. 2009 as described in seed 003
 * §3.3; seed 003 §4.2's merged one-pass variant; seed 000 §4.1-4.2). Filled by src/methods/ssdo.c.
 * The lights are those of the lighting pass (lighting_params.h), world space. */
#ifndef OB_SSDO_PARAMS_H
#define OB_SSDO_PARAMS_H
#include "ob_shared.h"

#define OB_SSDO_GROUP_X 8
#define OB_SSDO_GROUP_Y 8
#define OB_SSDO_MAX_SAMPLES 256
#define OB_SSDO_MAX_LIGHTS 8

/* counts.w: which output a dispatch writes */
#define OB_SSDO_STAGE_DIRECT 0 /* `ssdo` pass 1: M from uniform directions (eq. 5.3) */
#define OB_SSDO_STAGE_MERGED 1 /* `ssdo_merged`: M (cosine directions, eq. 5.2) + bounce x M */
#define OB_SSDO_STAGE_BOUNCE 2 /* `ssdo` pass 2: the bounce from the same occluders (eq. 3.4) */

OB_CONSTANTS_BEGIN(ob_ssdo_constants, OB_BINDING_PASS)
    OB_MAT4 proj;
    OB_MAT4 inv_view;        /* view -> world: L_in is evaluated in world space */
    OB_VEC4 proj_info;       /* 1/P00, 1/P11, P20, P21 (of the AO grid) */
    OB_VEC4 size;            /* AO width, height, 1/width, 1/height */
    OB_VEC4 full_info;       /* full-resolution proj_info, for the world position of the sender */
    OB_VEC4 params;          /* radius (world), bias (world), bounce factor strength x A_s / pi, lobe exponent k */
    OB_IVEC4 counts;         /* sample count, noise mode, bounce on (0/1), stage (OB_SSDO_STAGE_*) */
    OB_IVEC4 grid;           /* k, o (AO pixel i reads full pixel k i + o), light count, ambient mode */
    OB_VEC4 ambient;         /* constant ambient radiance */
    OB_VEC4 sky;             /* hemisphere: radiance from +Y */
    OB_VEC4 ground;          /* hemisphere: radiance from -Y */
    OB_VEC4 sh[9];           /* environment: irradiance / pi SH (rgb), as compose */
    OB_VEC4 light_color[OB_SSDO_MAX_LIGHTS];     /* rgb x intensity; w = OB_LIGHT_TYPE_* */
    OB_VEC4 light_position[OB_SSDO_MAX_LIGHTS];  /* point/spot position; w = range */
    OB_VEC4 light_direction[OB_SSDO_MAX_LIGHTS]; /* directional: toward the light; spot: axis */
    OB_VEC4 light_spot[OB_SSDO_MAX_LIGHTS];      /* cos inner, cos outer */
    OB_VEC4 kernel[OB_SSDO_MAX_SAMPLES];         /* tangent-space unit direction xyz, step length w */
OB_CONSTANTS_END(ob_ssdo_constants, ssdo)

#endif
