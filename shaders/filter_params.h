/* Constants shared by the filter passes (src/filters/). Each filter fills what it uses. */
#ifndef OB_FILTER_PARAMS_H
#define OB_FILTER_PARAMS_H
#include "ob_shared.h"

#define OB_FILTER_GROUP_X 8
#define OB_FILTER_GROUP_Y 8
/* Largest kernel radius (taps each side): 16 gives 33x33, beyond seed 003 §6.2's 11x11. */
#define OB_FILTER_MAX_RADIUS 16

/* Each filter shader is compiled twice: as is for R32F AO, and with OB_FILTER_RGB defined for
 * SSDO's RGBA16F modulation factor and bounce (the same weights on every channel). The sky's
 * value is then falloff.z from the CPU (ob_filter_inputs.sky: 1 for M, 0 for the bounce). */
#ifdef OB_GLSL
#ifdef OB_FILTER_RGB
#define OB_FILTER_FORMAT rgba16f
#define OB_FILTER_T vec4
#define OB_FILTER_FETCH(tex, q) texelFetch(tex, q, 0)
#define OB_FILTER_SKY vec4(flt.falloff.z)
#else
#define OB_FILTER_FORMAT r32f
#define OB_FILTER_T float
#define OB_FILTER_FETCH(tex, q) texelFetch(tex, q, 0).r
#define OB_FILTER_SKY vec4(1.0)
#endif
#endif

OB_CONSTANTS_BEGIN(ob_filter_constants, OB_BINDING_PASS)
    OB_VEC4 size;       /* width, height, 1/width, 1/height */
    OB_IVEC4 axis;      /* separable pass direction (1,0) or (0,1); radius in taps; unused */
    OB_VEC4 sigma;      /* spatial sigma (px), depth sigma (relative), normal sigma (radians), unused */
    /* The range Gaussians' exponents, derived on the CPU (ob_filter_constants_init) so a tap costs
     * one exp(): w = exp(x^2 * falloff) with falloff = -1/(2 sigma^2).
     * x: relative depth difference, y: angle between normals (radians); z: the sky's value in the
     * RGB variant; w unused. */
    OB_VEC4 falloff;
    OB_VEC4 weights[OB_FILTER_MAX_RADIUS + 1]; /* spatial Gaussian weights w[0..radius] in .x */
OB_CONSTANTS_END(ob_filter_constants, flt)

#endif
