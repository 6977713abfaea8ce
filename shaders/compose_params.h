/* Compose constants: direct light + ambient x AO, in linear HDR radiance. */
#ifndef OB_COMPOSE_PARAMS_H
#define OB_COMPOSE_PARAMS_H
#include "ob_shared.h"

#define OB_COMPOSE_GROUP_X 8
#define OB_COMPOSE_GROUP_Y 8

/* ambient.w: OB_AMBIENT_MODE_* (ob_enums.h) */

OB_CONSTANTS_BEGIN(ob_compose_constants, OB_BINDING_PASS)
    OB_VEC4 size;          /* width, height, 1/width, 1/height */
    OB_VEC4 proj_info;     /* 1/P00, 1/P11, P20, P21 */
    OB_MAT4 inv_view;      /* view -> world */
    OB_VEC4 ambient;       /* constant ambient radiance; w = mode */
    OB_VEC4 sky;           /* hemisphere: radiance from +Y */
    OB_VEC4 ground;        /* hemisphere: radiance from -Y */
    OB_VEC4 background;    /* radiance of pixels with no geometry (constant mode) */
    OB_IVEC4 flags;        /* AO darkens all light (0/1), directional RGB M (SSDO, 0/1), add the bounce
                              (0/1), unused */
    OB_VEC4 sh[9];         /* environment: irradiance SH coefficients E_lm / pi (rgb), order l=0..2 */
OB_CONSTANTS_END(ob_compose_constants, cmp)

#endif
