/* Constants shared by the filter passes (src/filters/). Each filter fills what it uses. */
#ifndef OB_FILTER_PARAMS_H
#define OB_FILTER_PARAMS_H
#include "ob_shared.h"

#define OB_FILTER_GROUP_X 8
#define OB_FILTER_GROUP_Y 8
/* Largest kernel radius (taps each side): 16 gives 33x33, beyond SSDO thesis §6.2's 11x11. */
#define OB_FILTER_MAX_RADIUS 16
/* crease's tiled program holds a work group's window in shared memory up to this radius. */
#define OB_CREASE_TILE_RADIUS 4

/* Each filter shader is compiled twice: as is for R32F AO, and with OB_FILTER_RGB defined for
 * SSDO's RGBA16F modulation factor and bounce (the same weights on every channel). The sky's
 * value is then sky_value from the CPU (ob_filter_inputs.sky: 1 for M, 0 for the bounce). */
#ifdef OB_GLSL
#ifdef OB_FILTER_RGB
#define OB_FILTER_FORMAT rgba16f
#define OB_FILTER_T vec4
#define OB_FILTER_FETCH(tex, q) texelFetch(tex, q, 0)
#define OB_FILTER_SKY vec4(flt.sky_value)
#define OB_FILTER_RESULT(v) (v)
#else
#define OB_FILTER_FORMAT r32f
#define OB_FILTER_T float
#define OB_FILTER_FETCH(tex, q) texelFetch(tex, q, 0).r
#define OB_FILTER_SKY vec4(1.0)
/* AO is a fraction: a weighted mean of values in [0, 1] lies in it, but not after rounding
 * (llvmpipe's gaussian wrote 1 + 1 ulp; on an NVIDIA H200 the old entry point's filtered AO left
 * [0, 1], which a host's check of its output range refuses). */
#define OB_FILTER_RESULT(v) clamp(v, 0.0, 1.0)
#endif
#endif

OB_CONSTANTS_BEGIN(ob_filter_constants, OB_BINDING_PASS)
    OB_IVEC2 size;            /* the AO resolution, px: the filters run at it (ob_filter_inputs) */
    OB_IVEC2 axis;            /* a separable pass's direction, (1,0) then (0,1) (Belonogov 2018 eq. 4.6-4.7) */
    OB_INT radius;            /* taps each side of the centre, 0..OB_FILTER_MAX_RADIUS */
    /* The range Gaussians' exponents, derived on the CPU (ob_filter_constants_init) so a tap costs
     * one exp(): w = exp(x^2 * falloff) with falloff = -1/(2 sigma^2); 0 switches a term off. */
    OB_FLOAT depth_falloff;   /* x = relative depth difference |d_q - d_p| / d_p (unitless); crease:
                                 the same along n_p, |n_p . (P_q - P_p)| / d_p (crease.glsl eq. 2) */
    OB_FLOAT normal_falloff;  /* x = angle between the normals, radians (geometry, crease) */
    OB_FLOAT sky_value;       /* what the RGB variant writes at sky pixels: 1 for M, 0 for the bounce */
    /* The spatial Gaussian (Belonogov 2018 eq. 4.4), normalised: w_i for tap offset i = 0..radius in .x;
     * .yzw unused (std140 strides array elements by 16 bytes anyway). crease: its eq. 1 per axis
     * (1, ..., 1, 1/2 at the rim), unnormalised. */
    OB_VEC4 weights[OB_FILTER_MAX_RADIUS + 1];
OB_CONSTANTS_END(ob_filter_constants, flt)
OB_CONSTANTS_SIZE(ob_filter_constants, 2 * 16 + (OB_FILTER_MAX_RADIUS + 1) * 16);

#endif
