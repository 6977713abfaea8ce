/* The classic 4x4 box blur over the SSAO result (seed 004 §3.3): it spans exactly one tile of
 * the 4x4 rotation noise, so the noise pattern averages out. */
#ifndef OB_BLUR_PARAMS_H
#define OB_BLUR_PARAMS_H
#include "ob_shared.h"

#define OB_BLUR_GROUP_X 8
#define OB_BLUR_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_blur_constants, OB_BINDING_PASS)
    OB_VEC4 size; /* width, height, 1/width, 1/height */
OB_CONSTANTS_END(ob_blur_constants, blur)

#endif
