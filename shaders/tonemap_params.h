/* Tone mapping (seed 003 §5.5 steps 6-8): add the bloom, scale by the key (eq. 2.2), Reinhard
 * with L_white (eq. 2.4), sRGB. */
#ifndef OB_TONEMAP_PARAMS_H
#define OB_TONEMAP_PARAMS_H
#include "hdr_shared.h"

#define OB_TONEMAP_GROUP_X 8
#define OB_TONEMAP_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_tonemap_constants, OB_BINDING_PASS)
    OB_VEC4 size;     /* width, height; 1 / (OB_BLOOM_FACTOR bloom width), 1 / (.. height) */
    OB_VEC4 params;   /* enabled (1 or 0), exposure, L_white (<= 0: eq. 2.3), bloom strength */
OB_CONSTANTS_END(ob_tonemap_constants, tmo)

#endif
