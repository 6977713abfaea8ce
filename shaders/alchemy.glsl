#version 450 core
/* Alchemy screen-space ambient obscurance (McGuire, Osman, Bukowski, Hennessy 2011; Puri 2024
 * §2.5 and §3.4). Samples lie on a spiral in a disk of world radius r around C, projected to the
 * screen (r_px = r * scale / z; r * scale for an orthographic camera); each gives v_i = P_i - C
 * and the final equation (Puri 2024 §2.5):
 *
 *   A = max(0, 1 - (2 sigma / s) * sum_i max(0, v_i . n - beta z_C) / (v_i . v_i + eps))^k
 *
 * with the Heaviside H(r - |v_i|) of the step before it, so nothing beyond r occludes.
 * Two deliberate choices, both documented in docs/methods.md:
 *   - v_i is measured in units of r: the sum has units 1/length, so in metres and millimetres the
 *     same sigma would differ 1000x; with r = 1 this is the paper's equation exactly.
 *   - z_C is the view-space z (negative in front of the camera, as in the paper), so the bias
 *     term subtracts beta * depth: Puri 2024 §3.4's code adds beta*z to the normal instead.
 * `deinterleave on` compiles OB_DEINTERLEAVED: far taps read the nearest pixel of their own 4x4 class;
 * `depth_mips on` OB_TAPS_DEPTH_MIPS: taps 20 px or more out read the depth MIP chain (taps.glsl). */
#include "alchemy_params.h"
#include "common.glsl"
#include "noise.glsl"
#include "taps.glsl"

layout(local_size_x = OB_ALCHEMY_GROUP_X, local_size_y = OB_ALCHEMY_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;           /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;           /* RGBA16F */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;             /* RG32F 4x4 rotation vectors */
layout(binding = OB_UNIT_SAMPLE_MULTIPLIER) uniform sampler2D multiplier; /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D ao_out;

void main()
{
    ivec2 pix = ob_invocation_pixel(); /* taps.glsl */
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(1.0));
        return;
    }
    vec3 c = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
    vec2 rot = ob_rotation(pix, alchemy.noise, noise_tile);
    float phi = atan(rot.y, rot.x);

    float r = alchemy.radius;
    float sigma = alchemy.sigma;
    float k = alchemy.k;
    float bias = alchemy.beta * d / r; /* beta * |z_C|, in units of r */
    float eps = alchemy.epsilon;
    float turns = alchemy.turns;
    float r_px = r * alchemy.px_per_unit / ob_depth_scale(d); /* no d for an orthographic camera */
    /* Adaptive sample counts (SSDO thesis §4.1): a denser spiral at depth and normal edges. */
    int s = alchemy.adaptive != 0 ? alchemy.adaptive_base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r)
                                  : alchemy.samples;

    float sum = 0.0;
    for (int i = 0; i < s; ++i) {
        /* Spiral: alpha in (0,1) sets the turn and, through sqrt, an even density over the disk. */
        float alpha = (float(i) + 0.5) / float(s);
        float theta = 6.28318530718 * alpha * turns + phi;
        vec2 q = vec2(pix) + 0.5 + sqrt(alpha) * r_px * vec2(cos(theta), sin(theta));
        ivec2 qi = ivec2(floor(q));
        if (any(lessThan(qi, ivec2(0))) || any(greaterThanEqual(qi, size))) continue;
        qi = ob_tap_pixel(qi, size); /* taps.glsl */
        float qd = ob_tap_depth(linear_depth, qi);
        if (qd <= 0.0) continue;
        vec3 v = (ob_view_position(vec2(qi) + 0.5, qd, frame.ao_inv_size, frame.ao_proj_info) - c) / r;
        float vv = dot(v, v);
        if (vv > 1.0) continue; /* H(r - |v|) */
        sum += max(0.0, dot(v, n) - bias) / (vv + eps);
    }
    float a = pow(max(0.0, 1.0 - 2.0 * sigma / float(max(s, 1)) * sum), k);
    imageStore(ao_out, pix, vec4(clamp(a, 0.0, 1.0)));
}
