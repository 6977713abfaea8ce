/* Helpers every screen-space pass shares. */
#ifndef OB_COMMON_GLSL
#define OB_COMMON_GLSL

/* The camera kind, for the shaders that read the per-frame block (frame_params.h, included before
 * this file): a perspective camera's rays fan out from the eye, so a screen offset spans view
 * space in proportion to the depth; an orthographic camera's rays are parallel to -Z, and a screen
 * offset spans the same view distance at every depth. Selects on a uniform, not branches: the
 * perspective path computes the very same numbers as before (d itself, p itself), and on llvmpipe
 * an untaken uniform branch would still be run masked. */
#ifdef OB_FRAME_PARAMS_H
/* What screen sizes scale with at linear depth d: d itself in perspective (a pixel spans
 * d / (P00 w / 2) view units), 1 in orthographic (1 / (P00 w / 2) at every depth). */
float ob_depth_scale(float d) { return frame.orthographic != 0 ? 1.0 : d; }

/* The direction of the view ray through view point p, away from the eye, not normalised: p itself
 * in perspective, -Z in orthographic. */
vec3 ob_view_ray(vec3 p) { return frame.orthographic != 0 ? vec3(0.0, 0.0, -1.0) : p; }

/* View-space position from linear depth d (positive along -Z) at pixel centre `pixel`.
 * proj_info = (1/P00, 1/P11, P20, P21) of the projection matrix P (column-major), so that
 * off-centre frusta work too: ndc.x = (P00*X + P20*Z) / -Z  =>  X = (ndc.x + P20) * d / P00.
 * Orthographic (frame.orthographic; ob_proj_info fills (1/P00, 1/P11, -P30, -P31)):
 * ndc.x = P00*X + P30  =>  X = (ndc.x - P30) / P00, the same expression with d's factor 1. The
 * frame's camera kind applies to every proj_info passed (the frame's, the AO grid's, the previous
 * frame's; ssdo's extra view exists in ob_render_frame alone, which is always perspective). */
vec3 ob_view_position(vec2 pixel, float d, vec4 size, vec4 proj_info)
{
    vec2 ndc = pixel * size.zw * 2.0 - 1.0;
    float s = ob_depth_scale(d);
    return vec3((ndc.x + proj_info.z) * s * proj_info.x, (ndc.y + proj_info.w) * s * proj_info.y, -d);
}

/* The same with the reciprocal size alone (frame_params.h's inv_size / ao_inv_size). */
vec3 ob_view_position(vec2 pixel, float d, vec2 inv_size, vec4 proj_info)
{
    vec2 ndc = pixel * inv_size * 2.0 - 1.0;
    float s = ob_depth_scale(d);
    return vec3((ndc.x + proj_info.z) * s * proj_info.x, (ndc.y + proj_info.w) * s * proj_info.y, -d);
}
#endif

/* Linear RGB -> sRGB transfer (IEC 61966-2-1). */
vec3 ob_linear_to_srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    vec3 lo = c * 12.92;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(lo, hi, step(vec3(0.0031308), c));
}

#endif
