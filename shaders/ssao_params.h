/* Hemisphere SSAO constants (seed 004 §2.3/§3.3, seed 000 §3.2). Filled by src/methods/ssao.c. */
#ifndef OB_SSAO_PARAMS_H
#define OB_SSAO_PARAMS_H
#include "ob_shared.h"

#define OB_SSAO_GROUP_X 8
#define OB_SSAO_GROUP_Y 8
#define OB_SSAO_MAX_SAMPLES 256
#define OB_SSAO_NOISE_SIZE 4

OB_CONSTANTS_BEGIN(ob_ssao_constants, OB_BINDING_PASS)
    OB_MAT4 proj;
    OB_VEC4 proj_info;   /* 1/P00, 1/P11, P20, P21 */
    OB_VEC4 size;        /* width, height, 1/width, 1/height */
    OB_VEC4 params;      /* radius (world), bias (world), intensity (exponent), unused */
    OB_IVEC4 counts;     /* sample count, noise mode (noise.glsl), adaptive (0/1), adaptive base count */
    OB_VEC4 kernel[OB_SSAO_MAX_SAMPLES]; /* tangent-space hemisphere offsets (z along the normal) */
OB_CONSTANTS_END(ob_ssao_constants, ssao)

#endif
