/* Horizon-based AO constants (Bavoil & Sainz 2008; seed 000 §3.3 eq. 3.1-3.2, seed 004 §2.4 and
 * §3.4). Filled by src/methods/hbao.c. */
#ifndef OB_HBAO_PARAMS_H
#define OB_HBAO_PARAMS_H
#include "ob_shared.h"

#define OB_HBAO_GROUP_X 8
#define OB_HBAO_GROUP_Y 8
#define OB_HBAO_MAX_DIRECTIONS 32
#define OB_HBAO_MAX_STEPS 32
#define OB_HBAO_NOISE_SIZE 4

OB_CONSTANTS_BEGIN(ob_hbao_constants, OB_BINDING_PASS)
    OB_VEC4 proj_info;   /* 1/P00, 1/P11, P20, P21 */
    OB_VEC4 size;        /* width, height, 1/width, 1/height */
    OB_VEC4 params;      /* radius R (world), 1/R, pixels per world unit at depth 1 (height/2 * P11),
                            max radius (px) */
    OB_VEC4 bias;        /* sin(angle bias), cos(angle bias), intensity, unused */
    OB_IVEC4 counts;     /* directions, steps per direction, noise mode (noise.glsl), unused */
OB_CONSTANTS_END(ob_hbao_constants, hbao)

#endif
