/* Compose constants: direct light + ambient x AO, in linear HDR radiance. The camera, the size and
 * the ambient light (constant, hemisphere, environment SH) are the frame's (frame_params.h). */
#ifndef OB_COMPOSE_PARAMS_H
#define OB_COMPOSE_PARAMS_H
#include "frame_params.h"

#define OB_COMPOSE_GROUP_X 8
#define OB_COMPOSE_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_compose_constants, OB_BINDING_PASS)
    OB_INT ao_all_light; /* 1: AO darkens all light, 0: only the ambient term (ob_settings.ao_all_light) */
    OB_INT directional;  /* 1: the AO texture holds a directional method's RGB modulation factor M */
    OB_INT add_bounce;   /* 1: add the one-bounce light x albedo (a method that writes a bounce) */
    OB_INT multibounce;  /* 1: visibility through Jimenez et al. 2016's multi-bounce fit with the albedo */
    OB_INT bent_normal;  /* 1: the ambient is looked up along the method's bent normal (unit 7) */
    OB_INT guard;        /* the guard band, px per side: output pixel p reads the inputs at p + guard (the crop) */
    OB_FLOAT pad1;
    OB_FLOAT pad2;
OB_CONSTANTS_END(ob_compose_constants, cmp)
OB_CONSTANTS_SIZE(ob_compose_constants, 32);

#endif
