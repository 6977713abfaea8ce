/* Tone mapping (SSDO thesis §5.5 steps 6-8): add the bloom, scale by the key (eq. 2.2), Reinhard
 * with L_white (eq. 2.4), sRGB. */
#ifndef OB_TONEMAP_PARAMS_H
#define OB_TONEMAP_PARAMS_H
#include "hdr_shared.h"

#define OB_TONEMAP_GROUP_X 8
#define OB_TONEMAP_GROUP_Y 8

OB_CONSTANTS_BEGIN(ob_tonemap_constants, OB_BINDING_PASS)
    OB_IVEC2 size;            /* the radiance and the output, px */
    /* Bloom texture coordinates per full pixel: 1 / (OB_BLOOM_FACTOR x bloom size), not 1 / size,
     * because the bloom rounds its size up and so covers a little more than the frame; (0,0)
     * without bloom. */
    OB_VEC2 bloom_uv_scale;
    OB_INT hdr_enabled;       /* 1: eq. 2.2 + Reinhard; 0: exposure x radiance clamped (ob_hdr_settings.enabled) */
    OB_FLOAT exposure;        /* linear factor: HDR off, the whole mapping; HDR on, folded into the luminance
                                 pass's scale and unused here */
    OB_FLOAT l_white;         /* eq. 2.4's L_white in scaled luminance; <= 0 selects eq. 2.3 */
    OB_FLOAT bloom_strength;  /* factor on the blurred bright pass added before eq. 2.4; 0 = no bloom */
OB_CONSTANTS_END(ob_tonemap_constants, tmo)
OB_CONSTANTS_SIZE(ob_tonemap_constants, 2 * 16);

#endif
