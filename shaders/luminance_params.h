/* Log-average luminance (seed 003 eq. 2.1) by a two-dispatch reduction (seed 003 §5.5 step 5 does
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
    OB_IVEC4 size;    /* width, height, partial sums (work groups of the first dispatch), unused */
    OB_VEC4 params;   /* exposure, key (0 = automatic), delta, 1 / pixel count */
OB_CONSTANTS_END(ob_luminance_constants, lum)

#endif
