#version 450 core
/* Temporal accumulation at the AO resolution (issue 17; the reprojection cache of Nehab et al.
 * 2007 with the neighbourhood clamp of Karis 2014, "High Quality Temporal Supersampling"):
 *   1. reproject: this pixel's world point (from this frame's depth, frame.inv_view) into the
 *      previous frame's AO grid (tp.prev_view, tp.prev_ao_proj). The scene is static, so the camera
 *      alone moves a point; a moving object would need its own per-object motion vector (its
 *      previous model matrix through the G-buffer), which this pass would add to the camera's;
 *   2. reject disocclusions per bilinear tap: a tap of the previous frame counts only when its
 *      point lies on this point's tangent plane (|dot(q - p, n)| <= plane_tolerance x depth, which
 *      stays exact on planes seen at grazing angles where a depth ratio would not) and its normal
 *      agrees (dot >= normal_cos); no tap left -> the history's age starts again at 0;
 *   3. clamp the history to the min/max of this frame's 3x3 neighbourhood (what the history may
 *      still hold of a surface that moved away or of a changed light);
 *   4. blend: age' = min(age + 1, N), out = mix(history, current, max(1 / age', 1 / N)), so a new
 *      history is the plain mean of its first N frames, then an exponential of length N.
 * The history carries its age: RG32F (value, age) for visibility, RGBA16F (rgb, age) for RGB (M,
 * bounce; OB_TEMPORAL_RGB). A sky pixel passes through with age 0. `motion` gets the reprojection
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
        imageStore(result, pix, vec4(cur, 1.0));
#ifdef OB_TEMPORAL_RGB
        imageStore(next_history, pix, vec4(cur, 0.0));
#else
        imageStore(next_history, pix, vec4(cur.r, 0.0, 0.0, 0.0));
#endif
        imageStore(motion, pix, vec4(0.0));
        return;
    }
    /* 3's box: this frame's geometry pixels around this one (the sky holds no AO). */
    vec3 lo = cur, hi = cur;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(pix + ivec2(x, y), ivec2(0), size - 1);
            if (texelFetch(depth, q, 0).r <= 0.0) continue;
            vec3 v = VALUE(texelFetch(current, q, 0));
            lo = min(lo, v);
            hi = max(hi, v);
        }
    /* 1: the previous frame's view space and AO grid position (pixel centres at + 0.5). */
    vec3 p = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 world = (frame.inv_view * vec4(p, 1.0)).xyz;
    vec3 pp = (tp.prev_view * vec4(world, 1.0)).xyz;
    vec4 clip = tp.prev_ao_proj * vec4(pp, 1.0);
    vec2 at = (clip.xy / clip.w * 0.5 + 0.5) * frame.ao_size;
    imageStore(motion, pix, vec4(at - (vec2(pix) + 0.5), 0.0, 0.0));
    vec3 np = mat3(tp.prev_view) * (mat3(frame.inv_view) * n);
    /* 2: the four bilinear taps, each kept only on this point's surface. */
    vec2 f = at - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 w = f - vec2(base);
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    float tolerance = tp.plane_tolerance * -pp.z;
    for (int i = 0; i < 4 && tp.history_valid != 0 && clip.w > 0.0; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 q = base + o;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 g = texelFetch(prev_geometry, q, 0);
        if (g.w <= 0.0) continue;
        vec3 qp = ob_view_position(vec2(q) + 0.5, g.w, frame.ao_inv_size, tp.prev_ao_proj_info);
        if (abs(dot(qp - pp, np)) > tolerance) continue;
        if (dot(g.xyz, np) < tp.normal_cos) continue;
        float bw = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y);
        sum += bw * texelFetch(history, q, 0);
        weight += bw;
    }
    /* A sliver of a tap (weight ~ 0) is no history: its value would be one tap's alone. */
    bool kept = weight > 1e-3;
    vec4 h = kept ? sum / weight : vec4(0.0);
    vec3 past = clamp(VALUE(h), lo, hi);
    float age = min((kept ? AGE(h) : 0.0) + 1.0, tp.history_frames);
    float alpha = max(1.0 / age, 1.0 / tp.history_frames);
    vec3 v = mix(past, cur, alpha);
    imageStore(result, pix, vec4(v, 1.0));
#ifdef OB_TEMPORAL_RGB
    imageStore(next_history, pix, vec4(v, age));
#else
    imageStore(next_history, pix, vec4(v.r, age, 0.0, 0.0));
#endif
}
