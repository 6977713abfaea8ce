/* Helpers every screen-space pass shares. */
#ifndef OB_COMMON_GLSL
#define OB_COMMON_GLSL

/* View-space position from linear depth d (positive along -Z) at pixel centre `pixel`.
 * proj_info = (1/P00, 1/P11, P20, P21) of the projection matrix P (column-major), so that
 * off-centre frusta work too: ndc.x = (P00*X + P20*Z) / -Z  =>  X = (ndc.x + P20) * d / P00. */
vec3 ob_view_position(vec2 pixel, float d, vec4 size, vec4 proj_info)
{
    vec2 ndc = pixel * size.zw * 2.0 - 1.0;
    return vec3((ndc.x + proj_info.z) * d * proj_info.x, (ndc.y + proj_info.w) * d * proj_info.y, -d);
}

/* The same with the reciprocal size alone (frame_params.h's inv_size / ao_inv_size). */
vec3 ob_view_position(vec2 pixel, float d, vec2 inv_size, vec4 proj_info)
{
    vec2 ndc = pixel * inv_size * 2.0 - 1.0;
    return vec3((ndc.x + proj_info.z) * d * proj_info.x, (ndc.y + proj_info.w) * d * proj_info.y, -d);
}

/* Linear RGB -> sRGB transfer (IEC 61966-2-1). */
vec3 ob_linear_to_srgb(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    vec3 lo = c * 12.92;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(lo, hi, step(vec3(0.0031308), c));
}

#endif
