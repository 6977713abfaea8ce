/* Alchemy AO constants (McGuire et al. 2011; seed 004 §2.5, §3.4). Filled by src/methods/alchemy.c. */
#ifndef OB_ALCHEMY_PARAMS_H
#define OB_ALCHEMY_PARAMS_H
#include "ob_shared.h"

#define OB_ALCHEMY_GROUP_X 8
#define OB_ALCHEMY_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_alchemy_constants, OB_BINDING_PASS)
    OB_VEC4 proj_info;   /* 1/P00, 1/P11, P20, P21 */
    OB_VEC4 size;        /* width, height, 1/width, 1/height */
    OB_VEC4 params;      /* radius (world), sigma, k, beta */
    OB_VEC4 params2;     /* epsilon, turns, projection scale (pixels per world unit at depth 1), unused */
    OB_IVEC4 counts;     /* samples, noise mode (noise.glsl), unused, unused */
OB_CONSTANTS_END(ob_alchemy_constants, alchemy)

#endif
