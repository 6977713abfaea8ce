/* Shadow-map lookups (SSDO thesis §2.1, §5.1, §6.1) for the direct-lighting pass: #include it after
 * lighting_params.h (which brings frame_params.h: the lights), then
 *     float ob_shadow(int light, vec3 world_pos, vec3 world_normal)
 * is the visibility in [0,1] of light `light` from a world point (1 = lit). The maps come from
 * src/passes/shadow.c (ob_shadows_render), the constants and texture bindings from
 * ob_shadows_fill. Samplers (units OB_UNIT_SHADOW_* of ob_units.h):
 *     8  ob_shadow_maps_2d      sampler2DArrayShadow   directional + spot depth, layer per map
 *     9  ob_shadow_maps_cube    samplerCubeArrayShadow point-light distance, cube per map
 *     10 ob_shadow_moments      sampler2DArray         directional + spot VSM moments
 * Per map m: lit.shadow_matrix[m] (world -> light clip space, 2D maps) and lit.shadow_params[m] =
 * (constant bias, slope bias, layer in its array, far). The biases are in the map's normalised
 * depth units (per unit of stored depth for spot/point maps, whose texels grow with distance);
 * far > 0 marks a map that stores distance / far (spot, point) rather than orthographic depth.
 *
 * Methods (lit.shadow_method):
 *   HARD: one comparison against the nearest texel (the texture's filter is GL_NEAREST).
 *   PCF:  (2r+1)^2 bilinear hardware comparisons one texel apart, r = lit.pcf_radius
 *         (SSDO thesis §5.1: "a small kernel ... I also enabled bilinear filtering"): each tap is
 *         itself a 2x2 percentage-closer filter, so 3x3 taps weigh a 4x4 texel footprint.
 *   VSM:  Chebyshev's one-tailed bound p_max = s^2 / (s^2 + (t - mu)^2) for t > mu (SSDO thesis §2.1,
 *         footnote 2) on the blurred moments, with variance at least lit.vsm_min_variance and light
 *         bleeding reduced by linstep(lit.vsm_bleed, 1, p_max) (SSDO thesis §6.1 names the bleeding
 *         and leaves the fix to [1]: the tail of p_max below `amount` is cut to black).
 *         Point lights fall back to PCF with radius lit.pcf_radius: blurring moments across
 *         six cube faces needs seam-aware filtering, and the cube's distance comparison already
 *         gives a soft edge with bilinear PCF.
 * Bias (SSDO thesis §2.1, "Bias"): a texel is a patch of size p facing the light, half of it above
 * the surface, so the reference must move back by b = p/2 tan(alpha). The slope term is
 * slope_bias x tan(alpha) x the filter's footprint in texels (1 for hard and VSM, 2r+2 for PCF,
 * whose farthest bilinear tap reads texels r+1 away), plus the constant bias, all in texels of the
 * map's world size; tan(alpha) is clamped to OB_SHADOW_MAX_SLOPE. */
#ifndef OB_SHADOW_GLSL
#define OB_SHADOW_GLSL
#include "shadow_params.h"

layout(binding = OB_UNIT_SHADOW_MAPS_2D) uniform sampler2DArrayShadow ob_shadow_maps_2d;
layout(binding = OB_UNIT_SHADOW_MAPS_CUBE) uniform samplerCubeArrayShadow ob_shadow_maps_cube;
layout(binding = OB_UNIT_SHADOW_MOMENTS) uniform sampler2DArray ob_shadow_moments;

/* The reference's offset toward the light, in normalised depth. `scale` is 1 for orthographic
 * maps and the stored depth (distance / far) for spot and point maps, whose texels' world size
 * grows linearly with the distance. */
float ob_shadow_bias(vec4 params, float cos_alpha, float footprint, float scale)
{
    float c = clamp(cos_alpha, 0.0, 1.0);
    float tan_alpha = min(sqrt(max(1.0 - c * c, 0.0)) / max(c, 1e-4), OB_SHADOW_MAX_SLOPE);
    return (params.x + params.y * footprint * tan_alpha) * scale;
}

/* Chebyshev's upper bound (SSDO thesis §2.1) with the variance floor and light-bleeding reduction. */
float ob_shadow_chebyshev(vec2 moments, float t)
{
    if (t <= moments.x) return 1.0;
    float variance = max(moments.y - moments.x * moments.x, lit.vsm_min_variance);
    float d = t - moments.x;
    float p_max = variance / (variance + d * d);
    float amount = lit.vsm_bleed;
    return clamp((p_max - amount) / max(1.0 - amount, 1e-4), 0.0, 1.0);
}

float ob_shadow_2d(int map, int method, vec3 world_pos, float cos_alpha, vec3 light_pos)
{
    vec4 params = lit.shadow_params[map];
    vec4 clip = lit.shadow_matrix[map] * vec4(world_pos, 1.0);
    if (!(clip.w > 0.0)) return 1.0; /* behind a spot light: outside its cone anyway */
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    bool distance_map = params.w > 0.0;
    float ref = distance_map ? length(world_pos - light_pos) / params.w : ndc.z * 0.5 + 0.5;
    /* Outside the map nothing was rendered, so nothing can shadow the point. */
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || !(ref <= 1.0)) return 1.0;
    float layer = params.z;
    float scale = distance_map ? ref : 1.0;
    int radius = clamp(lit.pcf_radius, 1, OB_SHADOW_MAX_PCF_RADIUS);
    if (method == OB_SHADOW_METHOD_VSM) {
        float t = ref - ob_shadow_bias(params, cos_alpha, 1.0, scale);
        return ob_shadow_chebyshev(texture(ob_shadow_moments, vec3(uv, layer)).rg, t);
    }
    if (method == OB_SHADOW_METHOD_HARD) {
        float t = ref - ob_shadow_bias(params, cos_alpha, 1.0, scale);
        return texture(ob_shadow_maps_2d, vec4(uv, layer, t));
    }
    float t = ref - ob_shadow_bias(params, cos_alpha, float(2 * radius + 2), scale);
    vec2 texel = 1.0 / vec2(textureSize(ob_shadow_maps_2d, 0).xy);
    float sum = 0.0;
    for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i)
            sum += texture(ob_shadow_maps_2d, vec4(uv + vec2(i, j) * texel, layer, t));
    float n = float(2 * radius + 1);
    return sum / (n * n);
}

float ob_shadow_cube(int map, int method, vec3 world_pos, float cos_alpha, vec3 light_pos)
{
    vec4 params = lit.shadow_params[map];
    vec3 v = world_pos - light_pos;
    float dist = length(v);
    float ref = dist / params.w;
    if (!(ref <= 1.0) || dist <= 0.0) return 1.0;
    float layer = params.z;
    if (method == OB_SHADOW_METHOD_HARD) {
        float t = ref - ob_shadow_bias(params, cos_alpha, 1.0, ref);
        return texture(ob_shadow_maps_cube, vec4(v, layer), t);
    }
    /* PCF (and VSM's fallback): offsets one texel apart in the plane across the direction. A
     * face texel spans 2/size at unit distance along the face's axis; |v| x 2/size is that at the
     * face centre and at most sqrt(3) too wide at a cube corner. */
    int radius = clamp(lit.pcf_radius, 1, OB_SHADOW_MAX_PCF_RADIUS);
    float t = ref - ob_shadow_bias(params, cos_alpha, float(2 * radius + 2), ref);
    vec3 dir = v / dist;
    vec3 a = abs(dir.x) < 0.57 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 t1 = normalize(cross(dir, a));
    vec3 t2 = cross(dir, t1);
    float step_len = dist * 2.0 / float(textureSize(ob_shadow_maps_cube, 0).x);
    t1 *= step_len;
    t2 *= step_len;
    float sum = 0.0;
    for (int j = -radius; j <= radius; ++j)
        for (int i = -radius; i <= radius; ++i)
            sum += texture(ob_shadow_maps_cube, vec4(v + float(i) * t1 + float(j) * t2, layer), t);
    float n = float(2 * radius + 1);
    return sum / (n * n);
}

/* The lighting pass's program variants (passes/lighting.c) compile the frame's shadow method in
 * (OB_SHADOW_FIXED_METHOD) and leave out the lookups no light of the frame needs (OB_SHADOW_NO_CUBE:
 * no point light has a map; OB_SHADOW_NO_2D: no directional or spot light has one): llvmpipe runs
 * an if block whose uniform condition is false as it runs any other, so every light paid for the
 * cube PCF, the 2D PCF, VSM and the hard lookup. Without the defines (shadow_probe.glsl) every
 * path is there and the constants choose. */
float ob_shadow(int light, vec3 world_pos, vec3 world_normal)
{
    int map = int(floor(frame.light_direction[light].w + 0.5));
#ifdef OB_SHADOW_FIXED_METHOD
    const int method = OB_SHADOW_FIXED_METHOD;
#else
    int method = lit.shadow_method;
#endif
    if (map < 0 || map >= OB_MAX_SHADOW_MAPS || method == OB_SHADOW_METHOD_NONE) return 1.0;
    int type = int(frame.light_color[light].w + 0.5);
    vec3 light_pos = frame.light_position[light].xyz;
    vec3 l = type == OB_LIGHT_TYPE_DIRECTIONAL ? frame.light_direction[light].xyz : light_pos - world_pos;
    float len_n = length(world_normal), len_l = length(l);
    float cos_alpha = len_n > 0.0 && len_l > 0.0 ? dot(world_normal, l) / (len_n * len_l) : 1.0;
#ifndef OB_SHADOW_NO_CUBE
    if (type == OB_LIGHT_TYPE_POINT) return ob_shadow_cube(map, method, world_pos, cos_alpha, light_pos);
#endif
#ifdef OB_SHADOW_NO_2D
    return 1.0;
#else
    return ob_shadow_2d(map, method, world_pos, cos_alpha, light_pos);
#endif
}

#endif
