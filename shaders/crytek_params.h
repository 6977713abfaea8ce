/* Crytek SSAO constants (seed 004 §2.2; Mittring 2007). Filled by src/methods/crytek.c. */
#ifndef OB_CRYTEK_PARAMS_H
#define OB_CRYTEK_PARAMS_H
#include "ob_shared.h"

#define OB_CRYTEK_GROUP_X 8
#define OB_CRYTEK_GROUP_Y 8
#define OB_CRYTEK_MAX_SAMPLES 256

OB_CONSTANTS_BEGIN(ob_crytek_constants, OB_BINDING_PASS)
    OB_MAT4 proj;
    OB_VEC4 proj_info;   /* 1/P00, 1/P11, P20, P21 */
    OB_VEC4 size;        /* width, height, 1/width, 1/height */
    OB_VEC4 params;      /* radius (world), bias (world), intensity (exponent), correction (0/1) */
    OB_IVEC4 counts;     /* sample count, noise mode (noise.glsl), adaptive (0/1), adaptive base count */
    OB_VEC4 kernel[OB_CRYTEK_MAX_SAMPLES]; /* offsets inside the unit sphere */
OB_CONSTANTS_END(ob_crytek_constants, crytek)

#endif
