/* Log-average luminance (SSDO thesis eq. 2.1) by a two-dispatch reduction (SSDO thesis §5.5 step 5 does
 * it with mipmaps; a compute reduction sums every pixel instead of the centre of a 3x3 image). */
#ifndef OB_LUMINANCE_PARAMS_H
#define OB_LUMINANCE_PARAMS_H
#include "hdr_shared.h"

/* 16x16 threads, each summing a 4x4 comb of pixels 16 apart: a group covers 64x64 pixels, so
 * 1280x720 leaves 240 partial sums for the second dispatch (one group of 256 threads) and the
 * texel reads of neighbouring threads stay adjacent. */
#define OB_LUMINANCE_GROUP 16
#define OB_LUMINANCE_TILE 4
#define OB_LUMINANCE_THREADS (OB_LUMINANCE_GROUP * OB_LUMINANCE_GROUP)
#define OB_LUMINANCE_SPAN (OB_LUMINANCE_GROUP * OB_LUMINANCE_TILE)

OB_CONSTANTS_BEGIN(ob_luminance_constants, OB_BINDING_PASS)
    OB_FLOAT exposure;         /* linear compensation on top of the key, folded into the result's scale */
    OB_FLOAT key;              /* eq. 2.2's alpha; 0 = the automatic key of §6.5 (ob_hdr_auto_key) */
    OB_FLOAT delta;            /* eq. 2.1's delta, OB_HDR_DELTA (luminance, radiance units) */
    OB_FLOAT inv_pixel_count;  /* eq. 2.1's 1/N: the final dispatch's mean of the partial sums */
    OB_INT width;              /* the radiance, px: the partial dispatch skips pixels past it */
    OB_INT height;
    OB_INT partial_count;      /* work groups of the partial dispatch = partial sums to reduce */
    OB_FLOAT pad0;
OB_CONSTANTS_END(ob_luminance_constants, lum)
OB_CONSTANTS_SIZE(ob_luminance_constants, 2 * 16);

#endif
