#version 450 core
/* Temporal accumulation at the AO resolution (issue 17; the reprojection cache of Nehab et al.
 * 2007 with the neighbourhood clamp of Karis 2014, "High Quality Temporal Supersampling"):
 *   1. reproject: this pixel's world point (from this frame's depth, frame.inv_view) into the
 *      previous frame's AO grid (tp.prev_view, tp.prev_ao_proj). The scene is static, so the camera
 *      alone moves a point; a moving object would need its own per-object motion vector (its
 *      previous model matrix through the G-buffer), which this pass would add to the camera's;
 *   2. reject disocclusions per bilinear tap: a tap of the previous frame counts when its point lies
 *      within OB_TEMPORAL_NEAR_PIXELS footprints of this point in 3D (any plane: a crease's other
 *      face), or else on this point's tangent plane (|dot(q - p, n)| <= plane_tolerance x depth,
 *      exact on planes seen at grazing angles where a depth ratio would not) with a normal that
 *      agrees (dot >= normal_cos); no tap left -> the history's age starts again at 0;
 *   3. resample: Catmull-Rom when all four taps count, else bilinear over those that do;
 *   4. clamp the history to the min/max of this frame's 4x4 neighbourhood (what the history may
 *      still hold of a surface that moved away or of a changed light);
 *   5. blend: age' = min(age t + 1, N), out = mix(history, current, max(1 / age', 1 / N)), so a new
 *      history is the plain mean of its first N frames, then an exponential of length N; t = 1
 *      unless the point's pixel footprint changed since the last frame (see 5 below).
 * The history carries its age: RG32F (value, age) for visibility, RGBA16F (rgb, age) for RGB (M,
 * bounce; OB_TEMPORAL_RGB). Before the filter the visibility chain writes no `result`: the filter
 * reads the new history's .r (4 bytes a pixel less to store; the OB_TEMPORAL_NO_RESULT program). A sky pixel passes through with age 0. `motion` gets the reprojection
 * offset in AO pixels (previous position - this one) for the tests and the debug views. */
#include "temporal_params.h"
#include "common.glsl"

layout(local_size_x = OB_TEMPORAL_GROUP_X, local_size_y = OB_TEMPORAL_GROUP_Y) in;

layout(binding = 0) uniform sampler2D current;     /* this frame's value (r or rgb) */
layout(binding = 1) uniform sampler2D history;     /* the previous frame's accumulation + age */
layout(binding = 2) uniform sampler2D depth;       /* this frame's linear depth, AO grid */
layout(binding = 3) uniform sampler2D normal;      /* this frame's view normal, AO grid */
/* The previous frame's view normal (xyz) and linear depth (w), AO grid: one RGBA16F fetch per tap
 * instead of two, written by the previous frame's dispatch (no copy pass). 16-bit depth is exact
 * to 2^-11 relative, far inside the 1 % plane tolerance. */
layout(binding = 4) uniform sampler2D prev_geometry;
#ifdef OB_TEMPORAL_RGB
layout(binding = 0, rgba16f) uniform writeonly image2D result;
layout(binding = 1, rgba16f) uniform writeonly image2D next_history;
#define VALUE(v) (v).rgb
#define AGE(v) (v).a
#else
layout(binding = 0, r32f) uniform writeonly image2D result;
layout(binding = 1, rg32f) uniform writeonly image2D next_history;
#define VALUE(v) (v).rrr
#define AGE(v) (v).g
#endif
layout(binding = 2, rg16f) uniform writeonly image2D motion;
layout(binding = 3, rgba16f) uniform writeonly image2D next_geometry; /* this frame's, for the next */

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    vec3 cur = VALUE(texelFetch(current, pix, 0));
    float d = texelFetch(depth, pix, 0).r;
    vec3 n = texelFetch(normal, pix, 0).xyz;
    imageStore(next_geometry, pix, vec4(n, d));
    if (d <= 0.0) {
#ifndef OB_TEMPORAL_NO_RESULT
        imageStore(result, pix, vec4(cur, 1.0));
#endif
#ifdef OB_TEMPORAL_RGB
        imageStore(next_history, pix, vec4(cur, 0.0));
#else
        imageStore(next_history, pix, vec4(cur.r, 0.0, 0.0, 0.0));
#endif
        imageStore(motion, pix, vec4(0.0));
        return;
    }
    /* 4's box: this frame's geometry pixels (the sky holds no AO) in the 4x4 window at offsets -1..2
     * around this one: one whole period of every method's 4x4 noise tile, so the box holds a value
     * of every rotation or jitter the tile gives here. A 3x3 box sees 9 of the 16, and with a
     * skewed per-pixel estimate (ssao's occlusion is a count of 16 samples: mostly near the mode,
     * rarely far darker) its min/max misses the rare side and clamps the history's mean toward the
     * mode, frame after frame: ssao's accumulated AO came out brighter than any single frame. */
    vec3 lo = cur, hi = cur;
#ifdef OB_TEMPORAL_RGB
    for (int y = -1; y <= 2; ++y)
        for (int x = -1; x <= 2; ++x) {
            ivec2 q = clamp(pix + ivec2(x, y), ivec2(0), size - 1);
            if (texelFetch(depth, q, 0).r <= 0.0) continue;
            vec3 v = VALUE(texelFetch(current, q, 0));
            lo = min(lo, v);
            hi = max(hi, v);
        }
#else
    /* One value: four 2x2 gathers of the value and four of the depth (8 fetches, not 32); the
     * edge clamp repeats the border. */
    for (int i = 0; i < 4; ++i) {
        vec2 corner = (vec2(pix) + 2.0 * vec2(i & 1, i >> 1)) * frame.ao_inv_size;
        vec4 dq = textureGather(depth, corner, 0);
        vec4 vq = textureGather(current, corner, 0);
        for (int k = 0; k < 4; ++k)
            if (dq[k] > 0.0) {
                lo.r = min(lo.r, vq[k]);
                hi.r = max(hi.r, vq[k]);
            }
    }
    lo = lo.rrr;
    hi = hi.rrr;
#endif
    /* 1: the previous frame's view space and AO grid position (pixel centres at + 0.5). */
    vec3 p = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 world = (frame.inv_view * vec4(p, 1.0)).xyz;
    vec3 pp = (tp.prev_view * vec4(world, 1.0)).xyz;
    vec4 clip = tp.prev_ao_proj * vec4(pp, 1.0);
    vec2 at = (clip.xy / clip.w * 0.5 + 0.5) * frame.ao_size;
    imageStore(motion, pix, vec4(at - (vec2(pix) + 0.5), 0.0, 0.0));
    vec3 np = mat3(tp.prev_view) * (mat3(frame.inv_view) * n);
    /* The four bilinear taps around it. */
    vec2 f = at - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 w = f - vec2(base);
    float weight = 0.0;
    float tolerance = tp.plane_tolerance * -pp.z;
    /* OB_TEMPORAL_NEAR_PIXELS previous AO pixels' width at the point's previous depth (common.glsl's
     * ob_view_position). */
    float footprint = OB_TEMPORAL_NEAR_PIXELS * 2.0 * -pp.z *
                      max(frame.ao_inv_size.x * tp.prev_ao_proj_info.x, frame.ao_inv_size.y * tp.prev_ao_proj_info.y);
    /* 2: which of the four bilinear taps are this point's surface (their geometry alone). */
    float tap_weight[4] = float[4](0.0, 0.0, 0.0, 0.0);
    for (int i = 0; i < 4 && tp.history_valid != 0 && clip.w > 0.0; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 q = base + o;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 g = texelFetch(prev_geometry, q, 0);
        if (g.w <= 0.0) continue;
        vec3 qp = ob_view_position(vec2(q) + 0.5, g.w, frame.ao_inv_size, tp.prev_ao_proj_info);
        /* A tap within OB_TEMPORAL_NEAR_PIXELS footprints of the point in 3D is its neighbourhood
         * whatever its plane: across a crease the other face's tap is as near as this face's, and
         * rejecting it would leave only the taps away from the crease (brighter), biasing every
         * crease brighter frame after frame. Farther taps must be the same surface. */
        bool near = dot(qp - pp, qp - pp) <= footprint * footprint;
        if (!near && (abs(dot(qp - pp, np)) > tolerance || dot(g.xyz, np) < tp.normal_cos)) continue;
        tap_weight[i] = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        weight += tap_weight[i];
    }
    vec4 h = vec4(0.0);
    if (weight > 0.999) {
        /* 3: all four taps this point's neighbourhood: resample with Catmull-Rom (Karis 2014), not
         * bilinear. Bilinear widens the history by a tent of variance w(1 - w) per axis at every
         * frame, ~1/6 px^2 on average, so the ~16 resamplings an exponential history of length 16
         * carries blur a one-pixel crease line away (sigma ~1.6 px); the cubic keeps it. Five
         * bilinear fetches make the 4x4 cubic less its four corners (products of two small negative
         * lobes): the middle two taps of each axis merge into one fetch at w2 / (w1 + w2) between
         * them. The outer taps are not checked: the neighbourhood clamp (4) bounds what they bring.
         * The age is the centre fetch's (bilinear between the four taps). */
        vec2 w0 = w * (-0.5 + w * (1.0 - 0.5 * w));
        vec2 w1 = 1.0 + w * w * (-2.5 + 1.5 * w);
        vec2 w2 = w * (0.5 + w * (2.0 - 1.5 * w));
        vec2 w3 = w * w * (-0.5 + 0.5 * w);
        vec2 w12 = w1 + w2;
        vec2 c1 = vec2(base) + 0.5; /* the centre of tap (0, 0) */
        vec2 t0 = (c1 - 1.0) * frame.ao_inv_size;
        vec2 t12 = (c1 + w2 / w12) * frame.ao_inv_size;
        vec2 t3 = (c1 + 2.0) * frame.ao_inv_size;
        vec4 centre = textureLod(history, t12, 0.0);
        h = textureLod(history, vec2(t12.x, t0.y), 0.0) * (w12.x * w0.y) +
            textureLod(history, vec2(t0.x, t12.y), 0.0) * (w0.x * w12.y) + centre * (w12.x * w12.y) +
            textureLod(history, vec2(t3.x, t12.y), 0.0) * (w3.x * w12.y) +
            textureLod(history, vec2(t12.x, t3.y), 0.0) * (w12.x * w3.y);
        h /= w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
        AGE(h) = AGE(centre);
    } else if (weight > 1e-3) {
        /* Some taps are another surface: bilinear over the rest. (A sliver of a tap, weight ~ 0,
         * is no history: its value would be one tap's alone.) */
        for (int i = 0; i < 4; ++i)
            if (tap_weight[i] > 0.0) h += tap_weight[i] * texelFetch(history, base + ivec2(i & 1, i >> 1), 0);
        h /= weight;
    }
    bool kept = weight > 1e-3;
    vec3 past = clamp(VALUE(h), lo, hi);
    /* 5's age, discounted by the change of the point's footprint (tp.footprint_falloff): a pixel's
     * size at the point is its depth times 1/P11 (common.glsl's ob_view_position), so s is that
     * ratio between the previous view and this one. A screen-space method's estimate at a point is
     * a function of how the depth buffer samples R around it, so history gathered from farther
     * (fewer pixels per R, thin steps missed) is a different, brighter estimate, not more samples of
     * this one: on a dolly toward the stair (`walk`) a full-length history kept that brightness and
     * was further from AO_R than the single frame (docs/temporal.md, "Footprint"). A still camera,
     * an orbit or a sideways move keep s = 1 and the whole age. */
    float s = (-pp.z * tp.prev_ao_proj_info.y) / (d * frame.ao_proj_info.y);
    float trust = exp2(-tp.footprint_falloff * abs(log2(s)));
    float age = min((kept ? AGE(h) * trust : 0.0) + 1.0, tp.history_frames);
    float alpha = max(1.0 / age, 1.0 / tp.history_frames);
    vec3 v = mix(past, cur, alpha);
#ifndef OB_TEMPORAL_NO_RESULT
    imageStore(result, pix, vec4(v, 1.0));
#endif
#ifdef OB_TEMPORAL_RGB
    imageStore(next_history, pix, vec4(v, age));
#else
    imageStore(next_history, pix, vec4(v.r, age, 0.0, 0.0));
#endif
}
