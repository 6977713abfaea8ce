/* Lighting/compose constants: one directional light (Lambert + Blinn-Phong, seed 000 §4.5) plus
 * an ambient term multiplied by AO. */
#ifndef OB_COMPOSE_PARAMS_H
#define OB_COMPOSE_PARAMS_H
#include "ob_shared.h"

#define OB_COMPOSE_GROUP_X 8
#define OB_COMPOSE_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_compose_constants, OB_BINDING_PASS)
    OB_VEC4 size;          /* width, height, 1/width, 1/height */
    OB_VEC4 proj_info;     /* 1/P00, 1/P11, P20, P21 */
    OB_VEC4 light_dir;     /* view space, toward the light, unit */
    OB_VEC4 light_color;   /* linear RGB x intensity */
    OB_VEC4 ambient;       /* linear RGB */
    OB_VEC4 background;    /* linear RGB */
    OB_VEC4 specular;      /* ks, shininess, unused, unused */
OB_CONSTANTS_END(ob_compose_constants, cmp)

#endif
