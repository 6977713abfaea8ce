/* Per-pixel rotation of a sample pattern: either the 4x4 tiled texture of the seeds (Puri 2024
 * §3.3: 16 rotations, removed again by a 4x4 blur) or interleaved gradient noise (Jimenez 2014,
 * "Next Generation Post Processing in Call of Duty: Advanced Warfare"), which needs no texture
 * and spreads rotations over more pixels but leaves structure a 4x4 box does not cancel. */
#ifndef OB_NOISE_GLSL
#define OB_NOISE_GLSL

#include "ob_enums.h" /* OB_NOISE_* */
#include "frame_params.h" /* noise_turn */

float ob_interleaved_gradient_noise(vec2 pixel)
{
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

/* A unit vector in the xy plane; `tile` is the RG32F 4x4 rotation texture. Under temporal
 * accumulation (ob_settings.temporal) every pixel's rotation turns by the same frame.noise_turn,
 * which steps by the golden ratio's fraction per frame (src/core/frame.c): a turn common to all
 * pixels keeps the tile's (or IGN's) spread within the frame, and the golden-ratio sequence is the
 * 1D sequence whose first n terms leave the most even gaps on the circle for every n (three-gap
 * theorem; at most three gap sizes, ratio <= 1.618), so any run of frames the history averages
 * sees evenly spread rotations. The 2D R2 sequence serves the slice methods (slices.c) because
 * they jitter two things, the slice angle and the step offset. */
vec2 ob_rotation(ivec2 pix, int mode, sampler2D tile)
{
    vec2 r;
    if (mode == OB_NOISE_IGN) {
        float a = 6.28318530718 * ob_interleaved_gradient_noise(vec2(pix));
        r = vec2(cos(a), sin(a));
    } else {
        r = texelFetch(tile, pix % 4, 0).xy;
    }
    if (frame.noise_turn == 0.0) return r; /* bit for bit the still frame's noise */
    float t = 6.28318530718 * frame.noise_turn;
    float c = cos(t), s = sin(t);
    return vec2(c * r.x - s * r.y, s * r.x + c * r.y);
}

#endif
