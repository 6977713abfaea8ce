/* Compose constants: direct light + ambient x AO, in linear HDR radiance. The camera, the size and
 * the ambient light (constant, hemisphere, environment SH) are the frame's (frame_params.h). */
#ifndef OB_COMPOSE_PARAMS_H
#define OB_COMPOSE_PARAMS_H
#include "frame_params.h"

#define OB_COMPOSE_GROUP_X 8
#define OB_COMPOSE_GROUP_Y 8

/* Which terms a frame composes are the program's (compose.glsl's OB_COMPOSE_* defines, made by
 * passes/compose.c on first use): the ambient mode, a directional method's M, its bounce, the bent
 * normal, the multi-bounce fit and AO on all light. */
OB_CONSTANTS_BEGIN(ob_compose_constants, OB_BINDING_PASS)
    OB_INT guard; /* the guard band, px per side: output pixel p reads the inputs at p + guard (the crop) */
    OB_INT pad0;
    OB_INT pad1;
    OB_INT pad2;
OB_CONSTANTS_END(ob_compose_constants, cmp)
OB_CONSTANTS_SIZE(ob_compose_constants, 16);

#endif
