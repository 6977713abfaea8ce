/* Per-pixel rotation of a sample pattern: either the 4x4 tiled texture of the seeds (seed 004
 * §3.3: 16 rotations, removed again by a 4x4 blur) or interleaved gradient noise (Jimenez 2014,
 * "Next Generation Post Processing in Call of Duty: Advanced Warfare"), which needs no texture
 * and spreads rotations over more pixels but leaves structure a 4x4 box does not cancel. */
#ifndef OB_NOISE_GLSL
#define OB_NOISE_GLSL

#include "ob_enums.h" /* OB_NOISE_* */

float ob_interleaved_gradient_noise(vec2 pixel)
{
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

/* A unit vector in the xy plane; `tile` is the RG32F 4x4 rotation texture. */
vec2 ob_rotation(ivec2 pix, int mode, sampler2D tile)
{
    if (mode == OB_NOISE_IGN) {
        float a = 6.28318530718 * ob_interleaved_gradient_noise(vec2(pix));
        return vec2(cos(a), sin(a));
    }
    return texelFetch(tile, pix % 4, 0).xy;
}

#endif
