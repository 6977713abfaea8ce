/* Bloom (SSDO thesis §5.5 steps 2-4): bright pass at reduced resolution, then a separable Gaussian. */
#ifndef OB_BLOOM_PARAMS_H
#define OB_BLOOM_PARAMS_H
#include "hdr_shared.h"

#define OB_BLOOM_GROUP_X 8
#define OB_BLOOM_GROUP_Y 8
/* Full pixels per bloom pixel along each axis. Quarter resolution: §5.5 notes "lower resolution
 * can be used ... this improves speed and blurring is more effective". Against half resolution
 * with the same halo (sigma 8 full pixels) it costs 6.5 instead of 22.8 ms at 1280x720 on
 * llvmpipe, and a tone-mapped pattern of single bright pixels, a bright line and a square on a
 * grey ramp differs by 0.5/255 on average, 14/255 at most (at the halo's edge). */
#define OB_BLOOM_FACTOR 4
/* Gaussian taps each side in bloom pixels; sigma is half of it (radius = 2 sigma, as the gaussian
 * filter), so the halo has sigma OB_BLOOM_FACTOR x 2 = 8 full pixels. */
#define OB_BLOOM_RADIUS 4

OB_CONSTANTS_BEGIN(ob_bloom_constants, OB_BINDING_PASS)
    OB_IVEC2 full_size;  /* the radiance, px: the bright pass skips full pixels past it */
    OB_IVEC2 bloom_size; /* the bloom targets, px: full_size / OB_BLOOM_FACTOR rounded up */
    OB_INT axis_x;       /* the blur's direction, (1,0) then (0,1) (separable, Belonogov 2018 eq. 4.4) */
    OB_INT axis_y;
    OB_INT radius;       /* blur taps each side, always OB_BLOOM_RADIUS */
    OB_FLOAT threshold;  /* bright pass: scaled luminance (eq. 2.2 units, as L_white) where bloom starts */
    /* The blur's normalised 1D Gaussian: w_i for tap offset i = 0..radius in .x; .yzw unused
     * (std140 strides array elements by 16 bytes anyway). */
    OB_VEC4 weights[OB_BLOOM_RADIUS + 1];
OB_CONSTANTS_END(ob_bloom_constants, blm)
OB_CONSTANTS_SIZE(ob_bloom_constants, 2 * 16 + (OB_BLOOM_RADIUS + 1) * 16);

#endif
