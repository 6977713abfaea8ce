#version 450 core
/* Temporal accumulation at the AO resolution (issue 17; the reprojection cache of Nehab et al.
 * 2007 with the neighbourhood clamp of Karis 2014, "High Quality Temporal Supersampling"):
 *   1. reproject: this pixel's point (from this frame's depth) into the previous frame's view
 *      (tp.to_prev_view) and AO grid (tp.prev_ao_proj). The scene is static, so the camera
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
 *      unless the point's pixel footprint changed since the last frame (see 5 below); with
 *      tp.detail > 0 alpha is also bounded below so that the history keeps that share of one-pixel
 *      detail under sub-pixel motion (5 below).
 * The history carries its age: for visibility an R32F value and an R16F age beside it (one RG32F
 * texture was one store fewer, but llvmpipe's gather of an RG32F texel ran three times the
 * instructions of an R32F one, and the pass makes five: docs/temporal.md, "Cost"); for RGB (M;
 * OB_TEMPORAL_RGB) RGBA16F (rgb, age). A method's bounce (vbgi, ssdo) rides in the same dispatch
 * (OB_TEMPORAL_BOUNCE): it shares 1, 2 and 5's age with the main chain, which is the same point
 * and the same taps, and has its own clamp box and resampling; its history's .a holds the same
 * age. Before the filter the visibility chain writes no `result`: the filter reads the new history
 * (4 bytes a pixel less to store; the OB_TEMPORAL_NO_RESULT program). A sky pixel passes through
 * with age 0.
 * The OB_TEMPORAL_MOTION program is step 1 alone: it writes the reprojection offset in AO pixels
 * (previous position - this one; 0 on the sky) to `motion` when someone reads it back
 * (OB_IMAGE_MOTION_F32: the tests), instead of a store in every accumulation. */
#include "temporal_params.h"
#include "common.glsl"

layout(local_size_x = OB_TEMPORAL_GROUP_X, local_size_y = OB_TEMPORAL_GROUP_Y) in;

layout(binding = OB_UNIT_TEMPORAL_DEPTH) uniform sampler2D depth;       /* this frame's linear depth, AO grid */

/* 1: this frame's view-space point at pixel pix (linear depth d > 0) in the previous frame's view
 * (pp) and AO grid (the returned position, pixel centres at + 0.5); clip_w <= 0 when it lies behind
 * the previous camera. */
#ifdef OB_TEMPORAL_HOST_MOTION
layout(binding = OB_UNIT_TEMPORAL_HOST_MOTION) uniform sampler2D host_motion; /* a host's motion vectors, full resolution */
#endif

vec2 reproject(ivec2 pix, float d, out vec3 pp, out float clip_w)
{
    vec3 p = ob_view_position(vec2(pix) + 0.5, d, frame.ao_inv_size, frame.ao_proj_info);
    pp = (tp.to_prev_view * vec4(p, 1.0)).xyz;
#ifdef OB_TEMPORAL_HOST_MOTION /* a program of its own: llvmpipe runs an untaken branch masked */
    {
        /* The host's vector at the full pixel this AO pixel stands for moves the point itself (a
         * moving object); its previous depth is the camera's reprojection's, the one thing 2D
         * vectors do not say (exact for motion across the view, close for motion along it). */
        ivec2 full = min(pix * frame.ao_k + frame.ao_o, ivec2(frame.size) - 1);
        vec2 at = vec2(pix) + 0.5 + texelFetch(host_motion, full, 0).xy * tp.motion_scale / float(frame.ao_k);
        pp = ob_view_position(at, -pp.z, frame.ao_inv_size, tp.prev_ao_proj_info);
        clip_w = -pp.z;
        return at;
    }
#endif
    vec4 clip = tp.prev_ao_proj * vec4(pp, 1.0);
    clip_w = clip.w;
    return (clip.xy / clip.w * 0.5 + 0.5) * frame.ao_size;
}

#ifdef OB_TEMPORAL_MOTION
layout(binding = OB_IMAGE_UNIT_TEMPORAL_MOTION, rg16f) uniform writeonly image2D motion;

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, ivec2(frame.ao_size)))) return;
    float d = texelFetch(depth, pix, 0).r;
    vec3 pp;
    float clip_w;
    vec2 at = d > 0.0 ? reproject(pix, d, pp, clip_w) : vec2(pix) + 0.5;
    imageStore(motion, pix, vec4(at - (vec2(pix) + 0.5), 0.0, 0.0));
}
#else
layout(binding = OB_UNIT_TEMPORAL_CURRENT) uniform sampler2D current;     /* this frame's value (r or rgb) */
layout(binding = OB_UNIT_TEMPORAL_HISTORY) uniform sampler2D history;     /* the previous frame's accumulation (+ age: RGB) */
layout(binding = OB_UNIT_TEMPORAL_NORMAL) uniform sampler2D normal;      /* this frame's view normal, AO grid */
/* The previous frame's linear depth (R32F) and view normal (R32UI, pack_normal), AO grid, written
 * by the previous frame's dispatch (no copy pass): one gather of each gives the four taps' (2).
 * One RGBA16F texture (normal, depth) took llvmpipe four fetches at three gathers' cost each and
 * its costliest store (docs/temporal.md, "Cost"). */
layout(binding = OB_UNIT_TEMPORAL_PREV_DEPTH) uniform sampler2D prev_depth;
layout(binding = OB_UNIT_TEMPORAL_PREV_NORMAL) uniform usampler2D prev_normal;
#ifdef OB_TEMPORAL_RGB
layout(binding = OB_IMAGE_UNIT_TEMPORAL_RESULT, rgba16f) uniform writeonly image2D result;
layout(binding = OB_IMAGE_UNIT_TEMPORAL_NEXT_HISTORY, rgba16f) uniform writeonly image2D next_history;
#else
layout(binding = OB_IMAGE_UNIT_TEMPORAL_RESULT, r32f) uniform writeonly image2D result;
layout(binding = OB_IMAGE_UNIT_TEMPORAL_NEXT_HISTORY, r32f) uniform writeonly image2D next_history;
layout(binding = OB_UNIT_TEMPORAL_HISTORY_AGE) uniform sampler2D history_age;            /* R16F, the previous frame's */
layout(binding = OB_IMAGE_UNIT_TEMPORAL_NEXT_AGE, r16f) uniform writeonly image2D next_age; /* this frame's */
#endif
layout(binding = OB_IMAGE_UNIT_TEMPORAL_NEXT_DEPTH, r32f) uniform writeonly image2D next_depth; /* this frame's, for the next */
layout(binding = OB_IMAGE_UNIT_TEMPORAL_NEXT_NORMAL, r32ui) uniform writeonly uimage2D next_normal;
#ifdef OB_TEMPORAL_BOUNCE
layout(binding = OB_UNIT_TEMPORAL_BOUNCE_CURRENT) uniform sampler2D bounce_current; /* RGBA16F, 0 on the sky */
layout(binding = OB_UNIT_TEMPORAL_BOUNCE_HISTORY) uniform sampler2D bounce_history; /* RGBA16F (rgb, age) */
layout(binding = OB_IMAGE_UNIT_TEMPORAL_BOUNCE_RESULT, rgba16f) uniform writeonly image2D bounce_result;
layout(binding = OB_IMAGE_UNIT_TEMPORAL_BOUNCE_NEXT_HISTORY, rgba16f) uniform writeonly image2D bounce_next_history;
#endif

/* A view normal in octahedral coordinates (Meyer et al. 2010, "On Floating-Point Normal Vectors";
 * Cigolle et al. 2014, "A Survey of Efficient Representations for Independent Unit Vectors", §3.1)
 * as two snorm16: within ~1e-4 rad, far inside the 25 degree normal test. */
uint pack_normal(vec3 n)
{
    n /= max(abs(n.x) + abs(n.y) + abs(n.z), 1e-6); /* the sky's normal may be 0 */
    vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return packSnorm2x16(e);
}

/* pack_normal's direction back, not unit length (the test below divides by its length). */
vec3 unpack_normal(uint code)
{
    vec2 e = unpackSnorm2x16(code);
    vec3 m = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-m.z, 0.0);
    m.xy += vec2(m.x >= 0.0 ? -t : t, m.y >= 0.0 ? -t : t);
    return m;
}

/* Catmull-Rom's weights (Karis 2014) of the taps at offsets -1, 0, 1, 2 for a point at fraction t
 * past tap 0, along one axis. */
vec4 catmull_rom(float t)
{
    return vec4(t * (-0.5 + t * (1.0 - 0.5 * t)), 1.0 + t * t * (-2.5 + 1.5 * t), t * (0.5 + t * (2.0 - 1.5 * t)),
                t * t * (-0.5 + 0.5 * t));
}

#if defined(OB_TEMPORAL_RGB) || defined(OB_TEMPORAL_BOUNCE)
/* 4's box for an RGB chain: its values at this frame's geometry pixels of the 4x4 window, whose
 * depths main gathered (box_depth[i]: the 2x2 at pix + 2 (i & 1, i >> 1) - 1, in a gather's order
 * (0,1), (1,1), (1,0), (0,0)); the edge clamp repeats the border as the gather does. */
void rgb_box(sampler2D values, ivec2 pix, ivec2 size, vec4 box_depth[4], vec3 cur, out vec3 lo, out vec3 hi)
{
    const ivec2 order[4] = ivec2[4](ivec2(-1, 0), ivec2(0, 0), ivec2(0, -1), ivec2(-1, -1));
    lo = cur;
    hi = cur;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            ivec2 q = clamp(pix + 2 * ivec2(i & 1, i >> 1) + order[k], ivec2(0), size - 1);
            vec3 v = texelFetch(values, q, 0).rgb;
            lo = box_depth[i][k] > 0.0 ? min(lo, v) : lo;
            hi = box_depth[i][k] > 0.0 ? max(hi, v) : hi;
        }
}

/* 3 for an RGB chain: (rgb, age). Catmull-Rom from five bilinear fetches when all four taps count,
 * else bilinear over those that do (main says why each); the age always bilinear over the taps
 * that count, from the same four texel fetches as the fallback. */
vec4 rgb_resample(sampler2D hist, ivec2 base, vec2 w, float tap_weight[4], float weight, ivec2 size)
{
    vec4 h = vec4(0.0);
    for (int i = 0; i < 4; ++i)
        h += tap_weight[i] * texelFetch(hist, clamp(base + ivec2(i & 1, i >> 1), ivec2(0), size - 1), 0);
    h = weight > 1e-3 ? h / weight : vec4(0.0);
    if (weight > 0.999) {
        /* Five bilinear fetches make the 4x4 cubic less its four corners (products of two small
         * negative lobes): the middle two taps of each axis merge into one fetch at w2 / (w1 + w2)
         * between them. */
        vec4 wx = catmull_rom(w.x), wy = catmull_rom(w.y);
        vec2 w0 = vec2(wx.x, wy.x), w2 = vec2(wx.z, wy.z), w3 = vec2(wx.w, wy.w);
        vec2 w12 = vec2(wx.y, wy.y) + w2;
        vec2 c1 = vec2(base) + 0.5; /* the centre of tap (0, 0) */
        vec2 t0 = (c1 - 1.0) * frame.ao_inv_size;
        vec2 t12 = (c1 + w2 / w12) * frame.ao_inv_size;
        vec2 t3 = (c1 + 2.0) * frame.ao_inv_size;
        vec3 cubic = textureLod(hist, vec2(t12.x, t0.y), 0.0).rgb * (w12.x * w0.y) +
                     textureLod(hist, vec2(t0.x, t12.y), 0.0).rgb * (w0.x * w12.y) +
                     textureLod(hist, t12, 0.0).rgb * (w12.x * w12.y) +
                     textureLod(hist, vec2(t3.x, t12.y), 0.0).rgb * (w3.x * w12.y) +
                     textureLod(hist, vec2(t12.x, t3.y), 0.0).rgb * (w12.x * w3.y);
        h.rgb = cubic / (w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y);
    }
    return h;
}
#endif

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    /* 4's box: this frame's geometry pixels (the sky holds no AO) in the 4x4 window at offsets -1..2
     * around this one: one whole period of every method's 4x4 noise tile, so the box holds a value
     * of every rotation or jitter the tile gives here. A 3x3 box sees 9 of the 16, and with a
     * skewed per-pixel estimate (ssao's occlusion is a count of 16 samples: mostly near the mode,
     * rarely far darker) its min/max misses the rare side and clamps the history's mean toward the
     * mode, frame after frame: ssao's accumulated AO came out brighter than any single frame. The
     * window is four 2x2 gathers; a gather returns texels (0,1), (1,1), (1,0), (0,0) of its 2x2 as
     * x, y, z, w, and this pixel is texel (1, 1) of the first: its depth and (one value) its value
     * are that gather's .y, not two more fetches, each of which cost llvmpipe twice a gather. */
    vec4 box_depth[4];
    for (int i = 0; i < 4; ++i)
        box_depth[i] = textureGather(depth, (vec2(pix) + 2.0 * vec2(i & 1, i >> 1)) * frame.ao_inv_size, 0);
    float d = box_depth[0].y;
#ifdef OB_TEMPORAL_RGB
    vec3 cur = texelFetch(current, pix, 0).rgb;
#else
    vec4 box_value[4];
    for (int i = 0; i < 4; ++i)
        box_value[i] = textureGather(current, (vec2(pix) + 2.0 * vec2(i & 1, i >> 1)) * frame.ao_inv_size, 0);
    vec3 cur = vec3(box_value[0].y);
#endif
    vec3 n = texelFetch(normal, pix, 0).xyz;
    imageStore(next_depth, pix, vec4(d, 0.0, 0.0, 0.0));
    imageStore(next_normal, pix, uvec4(pack_normal(n), 0u, 0u, 0u));
#ifdef OB_TEMPORAL_BOUNCE
    vec3 bounce_cur = texelFetch(bounce_current, pix, 0).rgb;
#endif
    if (d <= 0.0) {
#ifndef OB_TEMPORAL_NO_RESULT
        imageStore(result, pix, vec4(cur, 1.0));
#endif
#ifdef OB_TEMPORAL_RGB
        imageStore(next_history, pix, vec4(cur, 0.0));
#else
        imageStore(next_history, pix, vec4(cur.r, 0.0, 0.0, 0.0));
        imageStore(next_age, pix, vec4(0.0));
#endif
#ifdef OB_TEMPORAL_BOUNCE
        imageStore(bounce_result, pix, vec4(bounce_cur, 1.0));
        imageStore(bounce_next_history, pix, vec4(bounce_cur, 0.0));
#endif
        return;
    }
    /* 4's min and max */
    vec3 lo, hi;
#ifdef OB_TEMPORAL_RGB
    rgb_box(current, pix, size, box_depth, cur, lo, hi);
#else
    /* One value: its four gathers beside the depth's (8 fetches, not 32). */
    lo = cur;
    hi = cur;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            lo.r = box_depth[i][k] > 0.0 ? min(lo.r, box_value[i][k]) : lo.r;
            hi.r = box_depth[i][k] > 0.0 ? max(hi.r, box_value[i][k]) : hi.r;
        }
    lo = lo.rrr;
    hi = hi.rrr;
#endif
    /* 1 */
    vec3 pp;
    float clip_w;
    vec2 at = reproject(pix, d, pp, clip_w);
    vec3 np = mat3(tp.to_prev_view) * n;
    /* The four bilinear taps around it: tap i is base + (i & 1, i >> 1). */
    vec2 f = at - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 w = f - vec2(base);
    float tolerance = tp.plane_tolerance * -pp.z;
    /* OB_TEMPORAL_NEAR_PIXELS previous AO pixels' width at the point's previous depth (common.glsl's
     * ob_view_position; the same at every depth for an orthographic camera, ob_depth_scale). */
    float footprint = OB_TEMPORAL_NEAR_PIXELS * 2.0 * ob_depth_scale(-pp.z) *
                      max(frame.ao_inv_size.x * tp.prev_ao_proj_info.x, frame.ao_inv_size.y * tp.prev_ao_proj_info.y);
    /* 2: which of the four bilinear taps are this point's surface (their geometry alone). The loop
     * has a constant trip count and no branch, so it unrolls and tap_weight stays in registers: a
     * data-dependent bound and `continue`s kept it a loop over a private array, which llvmpipe
     * indexes lane by lane. */
    bool any_history = tp.history_valid != 0 && clip_w > 0.0;
    /* The four taps' depths and normals: tap i is texel (i & 1, i >> 1) of the 2x2 at base, the
     * gathers' w, z, x, y. Off the grid the gathers repeat the edge, and `inside` drops the tap. */
    vec2 taps_at = (vec2(base) + 1.0) * frame.ao_inv_size;
    vec4 tap_depth = textureGather(prev_depth, taps_at, 0).wzxy;
    uvec4 tap_normal = textureGather(prev_normal, taps_at, 0).wzxy;
#ifdef OB_TEMPORAL_JITTER
    /* Under a sub-pixel jitter the previous frame sampled each pixel at another point of its
     * footprint, and at an edge that is another surface: a hole's rim is the sheet one frame and
     * the floor behind it the next. Rejecting such a tap restarts the rim's history every frame
     * and keeps it aliased, yet that history is the footprint's mean, which is what the jitter
     * accumulates (Karis 2014 keeps it and leans on the clamp alone). So the tap nearest to where
     * the point lands, when it lies within a quarter pixel of it (its footprint is then most of
     * this pixel's: a still camera, or a move of whole pixels), also counts when the previous
     * frame saw this point's surface in its 3x3 texels (one of them near it in 3D or on its
     * tangent plane). Farther taps keep the strict test: under a move their footprints are other
     * ones, and accepting another surface there dragged a silhouette's AO along an orbit
     * (sphere-on-plane:contact, docs/temporal.md, "Jitter"). Four gathers of the previous depth
     * (a 4x4 window from base - 1; gather i's x, y, z, w are its texels (0,1), (1,1), (1,0),
     * (0,0)), one bit per texel that shows the surface. */
    uint shows = 0u;
    for (int i = 0; i < 4; ++i) {
        ivec2 a = base - 1 + 2 * ivec2(i & 1, i >> 1);
        vec4 g = textureGather(prev_depth, vec2(a + 1) * frame.ao_inv_size, 0);
        const ivec2 texel[4] = ivec2[4](ivec2(0, 1), ivec2(1, 1), ivec2(1, 0), ivec2(0, 0));
        for (int k = 0; k < 4; ++k) {
            ivec2 q = a + texel[k];
            vec3 qp = ob_view_position(vec2(q) + 0.5, g[k], frame.ao_inv_size, tp.prev_ao_proj_info);
            bool on = dot(qp - pp, qp - pp) <= footprint * footprint || abs(dot(qp - pp, np)) <= tolerance;
            bool hit = g[k] > 0.0 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && on;
            ivec2 wq = q - (base - 1); /* window texel, 0..3 */
            shows |= hit ? 1u << uint(wq.y * 4 + wq.x) : 0u;
        }
    }
    /* The nearest tap (window texel 1 + its offset) and its 3x3 (rows of three bits). */
    ivec2 nearest = ivec2(greaterThan(w, vec2(0.5)));
    vec2 off = abs(w - vec2(nearest));
    uint rows3 = (shows >> uint(nearest.y * 4 + nearest.x)) & 0x7u;
    rows3 |= (shows >> uint((nearest.y + 1) * 4 + nearest.x)) & 0x7u;
    rows3 |= (shows >> uint((nearest.y + 2) * 4 + nearest.x)) & 0x7u;
    int seen_tap = off.x <= 0.25 && off.y <= 0.25 && rows3 != 0u ? nearest.y * 2 + nearest.x : -1;
#else
    const int seen_tap = -1;
#endif
    float tap_weight[4];
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 q = base + o;
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
        vec3 qp = ob_view_position(vec2(q) + 0.5, tap_depth[i], frame.ao_inv_size, tp.prev_ao_proj_info);
        /* A tap within OB_TEMPORAL_NEAR_PIXELS footprints of the point in 3D is its neighbourhood
         * whatever its plane: across a crease the other face's tap is as near as this face's, and
         * rejecting it would leave only the taps away from the crease (brighter), biasing every
         * crease brighter frame after frame. Farther taps must be the same surface. */
        bool near = dot(qp - pp, qp - pp) <= footprint * footprint;
        vec3 m = unpack_normal(tap_normal[i]);
        bool same = abs(dot(qp - pp, np)) <= tolerance && dot(m, np) >= tp.normal_cos * length(m);
        bool counts = any_history && inside && tap_depth[i] > 0.0 && (near || same || i == seen_tap);
        tap_weight[i] = counts ? (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y) : 0.0;
    }
    float weight = tap_weight[0] + tap_weight[1] + tap_weight[2] + tap_weight[3];
    /* A sliver of a tap (weight ~ 0) is no history: its value would be one tap's alone. */
    bool kept = weight > 1e-3;
    /* 3: resample. When all four taps are this point's neighbourhood, Catmull-Rom (Karis 2014), not
     * bilinear: bilinear widens the history by a tent of variance w(1 - w) per axis at every
     * frame, ~1/6 px^2 on average, so the ~16 resamplings an exponential history of length 16
     * carries blur a one-pixel crease line away (sigma ~1.6 px); the cubic keeps it. The outer
     * taps are not checked: the neighbourhood clamp (4) bounds what they bring. When some taps are
     * another surface, bilinear over the rest. The age is always the bilinear one over the taps
     * that count. */
#ifdef OB_TEMPORAL_RGB
    vec4 resampled = rgb_resample(history, base, w, tap_weight, weight, size);
    vec3 h = resampled.rgb;
    float h_age = resampled.a;
#else
    /* One value: the whole separable 4x4 cubic from four 2x2 gathers of the value (texel (a, b) of
     * the window is base - 1 + (a, b)), and the bilinear fallback and the age from the inner 2x2
     * (the same texels, and one gather of the age). Five fetches, none filtered: bilinear fetches
     * cost llvmpipe four texel reads and the filter arithmetic each. A gather returns
     * texels (0,1), (1,1), (1,0), (0,0) of its 2x2 as x, y, z, w. */
    float inv_weight = kept ? 1.0 / weight : 0.0;
    vec4 wx = catmull_rom(w.x), wy = catmull_rom(w.y); /* the window's columns and rows 0..3 */
    float cubic = 0.0;
    vec4 inner = vec4(0.0); /* taps 0..3 */
    for (int i = 0; i < 4; ++i) {
        ivec2 a = 2 * ivec2(i & 1, i >> 1); /* this gather's window texel (a.x, a.y) at its (0, 0) */
        vec4 v = textureGather(history, (vec2(base + a)) * frame.ao_inv_size, 0);
        cubic += wy[a.y] * (wx[a.x] * v.w + wx[a.x + 1] * v.z) + wy[a.y + 1] * (wx[a.x] * v.x + wx[a.x + 1] * v.y);
        /* window (1, 1), (2, 1), (1, 2), (2, 2) are taps 0, 1, 2, 3 */
        if (i == 0) inner.x = v.y;
        if (i == 1) inner.y = v.x;
        if (i == 2) inner.z = v.z;
        if (i == 3) inner.w = v.w;
    }
    vec4 ages = textureGather(history_age, taps_at, 0);
    vec4 tw = vec4(tap_weight[0], tap_weight[1], tap_weight[2], tap_weight[3]);
    float h_age = dot(tw, ages.wzxy) * inv_weight;
    vec3 h = vec3(weight > 0.999 ? cubic : dot(tw, inner) * inv_weight);
#endif
    vec3 past = clamp(h, lo, hi);
    /* 5's age, discounted by the change of the point's footprint (tp.footprint_falloff): a pixel's
     * size at the point is its depth times 1/P11 (1/P11 alone for an orthographic camera:
     * common.glsl's ob_view_position, ob_depth_scale), so s is that ratio between the previous view
     * and this one. A screen-space method's estimate at a point is
     * a function of how the depth buffer samples R around it, so history gathered from farther
     * (fewer pixels per R, thin steps missed) is a different, brighter estimate, not more samples of
     * this one: on a dolly toward the stair (`walk`) a full-length history kept that brightness and
     * was further from AO_R than the single frame (docs/temporal.md, "Footprint"). A still camera,
     * an orbit or a sideways move keep s = 1 and the whole age. */
    float s = (ob_depth_scale(-pp.z) * tp.prev_ao_proj_info.y) / (ob_depth_scale(d) * frame.ao_proj_info.y);
    float trust = exp2(-tp.footprint_falloff * abs(log2(s)));
    float age = min((kept ? h_age * trust : 0.0) + 1.0, tp.history_frames);
    float alpha = max(1.0 / age, 1.0 / tp.history_frames);
    /* The detail bound (tp.detail = A > 0; Yang, Nehab, Sander, Sitthi-amorn, Lawrence & Hoppe 2009,
     * "Amortized Supersampling", §4's blur bound, at the one-pixel frequency): resampling at this
     * frame's fraction w leaves the history's one-pixel detail times g, Catmull-Rom's response at
     * half a cycle per pixel (1 at w = 0, 0 at w = 1/2: |w0 - w1 + w2 - w3| per axis), so a blend
     * v = (1 - alpha) g h + alpha c keeps the share alpha / (1 - (1 - alpha) g) of a steady detail
     * of c; alpha >= A (1 - g) / (1 - A g) keeps at least A. Under a moving camera every frame
     * resamples, and a one-pixel crease line or window frame fades to the resampled average
     * (docs/temporal.md, "Thin detail under motion"); a still camera (g = 1) keeps the whole
     * history. */
    vec4 cx = catmull_rom(w.x), cy = catmull_rom(w.y);
    float g = abs(cx.x - cx.y + cx.z - cx.w) * abs(cy.x - cy.y + cy.z - cy.w);
    /* Only where a history was kept: there the taps lie on the grid and w is finite (a point on the
     * previous camera's plane, clip w = 0, would give a NaN that max() might pass on). */
    alpha = kept ? max(alpha, tp.detail * (1.0 - g) / (1.0 - tp.detail * g)) : alpha;
    vec3 v = mix(past, cur, alpha); /* alpha = 1 when no tap counts */
#ifndef OB_TEMPORAL_NO_RESULT
    imageStore(result, pix, vec4(v, 1.0));
#endif
#ifdef OB_TEMPORAL_RGB
    imageStore(next_history, pix, vec4(v, age));
#else
    imageStore(next_history, pix, vec4(v.r, 0.0, 0.0, 0.0));
    imageStore(next_age, pix, vec4(age, 0.0, 0.0, 0.0));
#endif
#ifdef OB_TEMPORAL_BOUNCE
    /* The bounce: the same taps, age and blend; its own box and history. */
    vec3 bounce_lo, bounce_hi;
    rgb_box(bounce_current, pix, size, box_depth, bounce_cur, bounce_lo, bounce_hi);
    vec3 bounce_past = clamp(rgb_resample(bounce_history, base, w, tap_weight, weight, size).rgb, bounce_lo, bounce_hi);
    vec3 bounce_v = mix(bounce_past, bounce_cur, alpha);
    imageStore(bounce_result, pix, vec4(bounce_v, 1.0));
    imageStore(bounce_next_history, pix, vec4(bounce_v, age));
#endif
}
#endif
