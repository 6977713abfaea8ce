/* Light and ambient evaluation shared by the direct-lighting pass, SSDO's incoming radiance and
 * compose, so the three agree by construction (the reference ray tracer, src/reference, mirrors
 * the same formulas on the CPU). */
#ifndef OB_LIGHT_EVAL_GLSL
#define OB_LIGHT_EVAL_GLSL

#include "ob_enums.h" /* OB_LIGHT_TYPE_* */

/* The unit direction toward a light from p and its falloff: 1 for directional lights; 1/d^2 for
 * point and spot lights, times a smooth window to zero at `range` ((1 - (d/range)^4)^2, as in UE4
 * and Filament; range 0 = none), and for spot lights the smoothstep between the outer and inner
 * cone. position_range = (position, range); direction = toward the light (directional) or the
 * spot's axis; spot_cos = (cos inner, cos outer). */
float ob_light_falloff(int type, vec4 position_range, vec3 direction, vec2 spot_cos, vec3 p, out vec3 l)
{
    if (type == OB_LIGHT_TYPE_DIRECTIONAL) {
        l = direction;
        return 1.0;
    }
    vec3 to_light = position_range.xyz - p;
    float dist2 = max(dot(to_light, to_light), 1e-8);
    l = to_light * inversesqrt(dist2);
    float falloff = 1.0 / dist2;
    float range = position_range.w;
    if (range > 0.0) {
        float x = dist2 / (range * range);
        float w = clamp(1.0 - x * x, 0.0, 1.0);
        falloff *= w * w;
    }
    if (type == OB_LIGHT_TYPE_SPOT) falloff *= smoothstep(spot_cos.y, spot_cos.x, dot(-l, direction));
    return falloff;
}

/* Irradiance / pi for a world normal from 9 spherical-harmonic coefficients that the CPU already
 * convolved with the clamped cosine and folded the basis constants into (src/passes/environment.c;
 * Ramamoorthi & Hanrahan 2001, eq. 13). */
vec3 ob_sh_irradiance(vec4 sh[9], vec3 n)
{
    return sh[0].rgb + sh[1].rgb * n.y + sh[2].rgb * n.z + sh[3].rgb * n.x + sh[4].rgb * (n.x * n.y) +
           sh[5].rgb * (n.y * n.z) + sh[6].rgb * (3.0 * n.z * n.z - 1.0) + sh[7].rgb * (n.x * n.z) +
           sh[8].rgb * (n.x * n.x - n.y * n.y);
}

#endif
