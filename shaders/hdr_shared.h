/* What the three HDR passes share (SSDO thesis §2.2, §5.5, §6.5): the luminance weights, eq. 2.1's
 * delta, the automatic key, and the small GPU buffer the luminance reduction writes and the bloom
 * and tone-map passes read, so no value makes a CPU round trip during a frame. */
#ifndef OB_HDR_SHARED_H
#define OB_HDR_SHARED_H
#include "ob_shared.h"

/* Eq. 2.1's delta, "a small constant used to avoid numerical underflow": ln(0) of a black pixel
 * would make the whole log-average 0. 1e-4 is far below any lit radiance the scenes produce
 * (the dimmest ambient-only corner of the Cornell box is ~1e-2), so it only matters for black. */
#define OB_HDR_DELTA 1.0e-4

/* Krawczyk's formula wants luminance in cd/m^2; a radiance of 1 (a white surface in our lights'
 * default units) is taken as 100 cd/m^2, an office-lit white page. With that the automatic key
 * makes the Cornell box and FZK-Haus about as bright as the plain clamp (key 0.4-0.5), where
 * using radiance as cd/m^2 gave keys of 0.06-0.12 and images half as bright. */
#define OB_HDR_NITS_PER_UNIT 100.0

/* Shader-storage binding of the result buffer (a different namespace from the uniform blocks). */
#define OB_BINDING_HDR_RESULT 0

/* The buffer's layout (std430): the reduction's answer, then one partial sum of ln(delta + L)
 * per work group of the first luminance dispatch. */
#define OB_HDR_RESULT_BYTES 16 /* vec4: log-average, key, scale = exposure key / log-average, 0 */

#ifdef OB_GLSL
#ifndef OB_HDR_RESULT_ACCESS
#define OB_HDR_RESULT_ACCESS readonly
#endif
layout(std430, binding = OB_BINDING_HDR_RESULT) OB_HDR_RESULT_ACCESS buffer ob_hdr_result_block {
    vec4 result;
    float partial[];
} hdr;

/* Rec. 709 / sRGB primaries' luminance (ITU-R BT.709, the primaries the radiance is in). */
float ob_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

/* Radiance as the passes see it: NaN (a broken upstream pass) counts as black, and anything past
 * the RGBA16F range as the largest half float, so one bad pixel cannot turn eq. 2.1's sum into
 * NaN or infinity and blank the whole frame. */
vec3 ob_hdr_sanitize(vec3 c)
{
    return mix(clamp(c, 0.0, 65504.0), vec3(0.0), bvec3(isnan(c.r), isnan(c.g), isnan(c.b)));
}

/* The automatic key (SSDO thesis §6.5 gives no formula): Krawczyk, Myszkowski, Seidel 2005,
 * "Lightness perception in tone reproduction for high dynamic range images", eq. 11:
 * alpha = 1.03 - 2 / (2 + log10(L_avg + 1)). It rises with the log-average, as §6.5 describes
 * (0.22 for the darker view of Fig. 6.17, 0.6 for the brighter). Same as ob_hdr_auto_key(). */
float ob_hdr_auto_key(float log_average)
{
    float l = max(log_average, 0.0) * OB_HDR_NITS_PER_UNIT;
    return 1.03 - 2.0 / (2.0 + log2(l + 1.0) * 0.30102999566);
}
#endif

#endif
