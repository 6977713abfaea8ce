/* The slice set-up and the depth-buffer march of the slice methods, gtao.glsl and vbao.glsl
 * (Jimenez, Wu, Pesce & Jarabo 2016, §4-5; Therrien, Levesque & Gilet 2023, §3 build on the same
 * slices). A slice is the plane through the eye, the pixel's surface point P and a screen
 * direction d(φ); both methods march the depth buffer along d on both sides of P and differ only
 * in what they make of each sample (a horizon angle or a set of sectors).
 *
 * Include after common.glsl (ob_view_position) and frame_params.h. Define OB_MARCH_DEPTH_MIPS
 * before including it for the variant whose far steps read the depth MIP chain: the level is a
 * per-lane choice, and llvmpipe runs both sides of a branch its lanes disagree on, so the
 * full-resolution baseline is its own program instead of a runtime branch per sample. */
#ifndef OB_SLICE_MARCH_GLSL
#define OB_SLICE_MARCH_GLSL

#include "noise.glsl"
#include "octahedral.glsl"

const float OB_PI = 3.14159265358979;
const float OB_HALF_PI = 1.57079632679490;

/* 4x4 ordered-dither ranks: every value 0..15 once per tile (the same ranks as hbao.glsl). */
const float ob_slice_bayer4[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0,
                                            3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

/* Per-pixel jitters in [0, 1) of the slice angles (x) and of the step distances (y).
 *   texture4: the slice jitter is the angle of the 4x4 rotation tile (16 shuffled angles) and the
 *     step jitter the 4x4 Bayer rank; the two are unrelated, and a 4x4 window averages all 16 of
 *     each exactly (Puri 2024 §3.3);
 *   ign: interleaved gradient noise of the pixel and of the transposed pixel (see hbao.glsl).
 * `offsets` moves both along an R2 sequence with the frame index when temporal noise is on. */
vec2 ob_slice_jitters(ivec2 pix, int noise, sampler2D noise_tile, vec2 offsets)
{
    vec2 j;
    if (noise == OB_NOISE_IGN) {
        j = vec2(ob_interleaved_gradient_noise(vec2(pix)), ob_interleaved_gradient_noise(vec2(pix.yx)));
    } else {
        vec2 r = texelFetch(noise_tile, pix % 4, 0).xy;
        ivec2 t = pix % 4;
        j = vec2(fract(atan(r.y, r.x) / (2.0 * OB_PI) + 1.0), (ob_slice_bayer4[t.y * 4 + t.x] + 0.5) / 16.0);
    }
    return fract(j + offsets);
}

/* atan2 to about 2e-4 rad (a minimax polynomial on [0, 1] after folding the octants), for the
 * per-slice angles: the GLSL built-in costs several times as much on llvmpipe. y = 0 gives
 * exactly 0 for x > 0. */
float ob_fast_atan2(float y, float x)
{
    float ax = abs(x), ay = abs(y);
    float hi = max(ax, ay);
    if (hi <= 0.0) return 0.0;
    float a = min(ax, ay) / hi;
    float a2 = a * a;
    float r = ((-0.0464964749 * a2 + 0.15931422) * a2 - 0.327622764) * a2 * a + a;
    if (ay > ax) r = OB_HALF_PI - r;
    if (x < 0.0) r = OB_PI - r;
    return y < 0.0 ? -r : r;
}

/* Adaptive sample counts (SSDO thesis §4.1): the slices of a pixel, base x its OB_EDGE_BLOCK^2 block's
 * multiplier (1, 2 or 3, more at depth and normal edges) when adaptive, else the fixed count. */
int ob_slice_count(ivec2 pix, int fixed_slices, int adaptive, int base, sampler2D multiplier)
{
    return adaptive != 0 ? base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r) : fixed_slices;
}

/* The pixel's point P at linear depth d > 0: its AO-grid centre, view position p, unit view
 * vector v toward the eye (+Z for an orthographic camera: common.glsl ob_view_ray) and unit
 * normal n, and to_view, which turns a screen offset in AO pixels into a view offset per unit of
 * ob_depth_scale (per unit depth in perspective, absolute in orthographic). Interpolated normals
 * at silhouettes can face away from the eye; the integral then has no visible hemisphere left, so
 * they are tilted until they face it by a little (as hbao.glsl). */
void ob_slice_pixel(ivec2 pix, float d, sampler2D view_normal, out vec2 centre, out vec3 p, out vec3 v, out vec3 n,
                    out vec2 to_view)
{
    centre = vec2(pix) + 0.5;
    p = ob_view_position(centre, d, frame.ao_inv_size, frame.ao_proj_info);
    v = -normalize(ob_view_ray(p));
    n = normalize(texelFetch(view_normal, pix, 0).xyz);
    float nv = dot(n, v);
    if (nv < 0.02) n = normalize(n + (0.02 - nv) * v);
    to_view = frame.ao_proj_info.xy * frame.ao_inv_size * 2.0;
}

/* Slice k's screen direction is at angle (k + jitter) π / N: the first from the jitter, each next
 * one the last turned by π / N (ob_slice_turn with the (cos, sin) of ob_slice_rotation): four sines
 * per pixel instead of two per slice. */
vec2 ob_slice_first_dir(float jitter, int slices)
{
    float phi0 = jitter * OB_PI / float(slices);
    return vec2(cos(phi0), sin(phi0));
}

vec2 ob_slice_rotation(int slices)
{
    float dphi = OB_PI / float(slices);
    return vec2(cos(dphi), sin(dphi));
}

vec2 ob_slice_turn(vec2 dir, vec2 rot) { return vec2(dir.x * rot.x - dir.y * rot.y, dir.x * rot.y + dir.y * rot.x); }

/* One slice through P (view position p, unit view vector v toward the eye, unit normal n). */
struct ob_slice {
    vec2 dir;        /* the screen direction, unit, in AO pixels */
    vec3 axis;       /* the slice plane's unit normal */
    vec3 o;          /* unit, in the slice, perpendicular to v, on dir's side */
    vec3 n_slice;    /* n / |n_φ|: dot(w, n_slice) is an in-slice vector's height across the tangent */
    float len_n;     /* |n_φ|: the length of n projected onto the slice (eq. 5's weight) */
    float cos_n;     /* the projected normal's angle n(φ) from v toward o, and its cosine and sine */
    float sin_n;
    float ang_n;
    float radius_px; /* R along dir at P's depth, in AO pixels */
    vec3 t_pos;      /* the unit tangent of P's surface in the slice on dir's side (θ = π/2 + n) */
    vec3 t_neg;      /*   and on the opposite side (θ = -(π/2 - n)) */
    vec2 across;     /* a unit screen step along dir at constant depth, as (dot with t_pos, with n_slice) */
};

/* The slice along screen direction dir through P at linear depth d. to_view turns a screen
 * offset in AO pixels into a view offset per unit of ob_depth_scale(d). False when the normal lies
 * (almost) across the slice: the slice then carries no weight (|n_φ| ~ 0). */
bool ob_slice_setup(vec2 dir, vec3 p, vec3 v, vec3 n, float d, vec2 to_view, float radius, out ob_slice s)
{
    s.dir = dir;
    /* The slice's normal is V x (the view offset of a step along dir), V along the view ray through
     * P: exact for any pixel aspect, an off-centre frustum and an orthographic camera. */
    vec3 dv = vec3(dir * to_view, 0.0);
    s.axis = normalize(cross(v, dv));
    s.o = cross(s.axis, v);
    /* n(φ) and |n_φ| (eq. 5): the normal projected onto the slice. */
    vec3 pn = n - s.axis * dot(n, s.axis);
    s.len_n = length(pn);
    float inv_len_n = 1.0 / max(s.len_n, 1e-4);
    s.n_slice = n * inv_len_n;
    s.cos_n = dot(pn, v) * inv_len_n;
    s.sin_n = dot(pn, s.o) * inv_len_n;
    s.ang_n = ob_fast_atan2(s.sin_n, s.cos_n);
    s.radius_px = radius / (ob_depth_scale(d) * length(dir * to_view));
    /* The surface falls away on the side the normal leans to: its tangent lies at π/2 + n from v
     * on dir's side and at π/2 - n on the other, cos(π/2 ± n) v ± sin(π/2 ± n) o. */
    s.t_pos = -s.sin_n * v + s.cos_n * s.o;
    s.t_neg = s.sin_n * v - s.cos_n * s.o;
    /* A constant-depth offset along the screen line stays in the slice plane (the plane holds the
     * eye and the whole line), so two coordinates hold it. */
    vec3 dv_unit = normalize(dv);
    s.across = vec2(dot(dv_unit, s.t_pos), dot(dv_unit, s.n_slice));
    return s.len_n >= 1e-4;
}

/* E[|n_φ| (cos n + n sin n)]: the expected open measure of one slice at P, over the screen
 * directions the slices are drawn from (uniform in [0, π)), by an 8-direction midpoint rule. It is
 * 1 where the slice planes turn uniformly about v (eq. 5's weights integrate to π); off the
 * image's centre a perspective camera's screen directions turn them unevenly, and the rule
 * follows. Within 0.5 % of the integral for any normal at the centre. Dividing the slices'
 * occluded measure by N times this, rather than by the slices' own open sum, keeps the estimate
 * linear in its slices: one slice's mean is then three's (docs/methods.md, "Presets that keep
 * their mean"). */
float ob_slice_expected_open(vec3 p, vec3 v, vec3 n, float d, vec2 to_view)
{
    const int M = 8;
    float sum = 0.0;
    vec2 dir = ob_slice_first_dir(0.5, M), turn = ob_slice_rotation(M);
    for (int q = 0; q < M; ++q, dir = ob_slice_turn(dir, turn)) {
        ob_slice s;
        ob_slice_setup(dir, p, v, n, d, to_view, 1.0, s);
        sum += s.len_n * (s.cos_n + s.ang_n * s.sin_n);
    }
    return sum / float(M);
}

/* The world length of one AO pixel along a slice at linear depth z, R / radius_px at P's depth d
 * (the same everywhere for an orthographic camera: ob_depth_scale). */
float ob_pixel_world(float z, float d, float radius, float radius_px)
{
    return ob_depth_scale(z) * radius / (ob_depth_scale(d) * max(radius_px, 1e-6));
}

/* Step j (0-based, of `steps`) on one side: uniform strata of [1.5 px, R's projection], shifted
 * together by the jitter, at least 1.5 px out so the first step never reads P's own texel.
 * (XeGTAO squares them toward the centre; with the definition's hard cut at R, the horizon of a
 * crease is where the wall leaves the sphere of radius R, at the far end of the search, and on
 * the training views squared steps read more too-open bias: docs/methods.md.) */
float ob_slice_step_px(int j, float jitter, int steps, float radius_px)
{
    return 1.5 + (float(j) + jitter) / float(steps) * max(radius_px - 1.5, 0.0);
}

/* The AO-grid pixel being shaded: each method's main sets it before its march (ob_march_fetch
 * skips it). */
ivec2 ob_march_self = ivec2(-1);

#ifdef OB_MARCH_DEPTH_MIPS
#include "depth_mips_read.glsl"
/* Depth under AO pixel q at MIP `level`, and the centre of the full-resolution pixel it came from
 * (ob_depth_mip_source), where the sample is reconstructed; a sky pick is sky: no sample. */
float ob_march_depth(sampler2D depth, ivec2 q, int level, ivec2 size, out vec2 centre)
{
    ivec2 texel;
    centre = vec2(ob_depth_mip_source(q, level, size, texel)) + 0.5;
    return texelFetch(depth, texel, level).r;
}
#endif

#ifdef OB_MARCH_PACKED
/* Each AO texel's depth, normal and direct radiance in one texel (shaders/sample_pack.glsl;
 * vbgi's `packed`, never with the MIP chain): the march reads its depth from there and keeps the
 * texel in ob_march_packed for the sample's bounce, one fetch where there were three. */
#include "packed_samples.glsl"
layout(binding = OB_UNIT_PACKED_SAMPLES) uniform usampler2D ob_packed_samples;
uvec4 ob_march_packed = uvec4(0u);
#endif

/* The sample at AO-grid position `at`, dist_px from P: its offset w from p in view space, the
 * AO-grid texel whose surface point that is (for its normal or radiance), and whether there is a
 * surface there (false off the screen and on sky, w = 0 then). Without
 * OB_MARCH_DEPTH_MIPS every step reads `depth` at full resolution; with it, a step reads level
 * floor(log2(dist_px x mip_scale)) of the chain, at most max_mip (as the position of the highest
 * set bit: no log2 per sample; below 1 findMSB gives -1, clamped to 0). Off-screen samples read
 * the clamped edge and are discarded by a select, not a branch, for the reason above. */
bool ob_march_fetch(sampler2D depth, vec2 at, float dist_px, vec3 p, float mip_scale, int max_mip, out vec3 w,
                    out ivec2 texel)
{
    ivec2 size = ivec2(frame.ao_size);
    ivec2 q = ivec2(floor(at));
    bool on_screen = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
    q = clamp(q, ivec2(0), size - 1);
#ifdef OB_MARCH_DEPTH_MIPS
    int level = clamp(findMSB(int(dist_px * mip_scale)), 0, max_mip);
    vec2 qc;
    float sd = ob_march_depth(depth, q, level, size, qc);
#elif defined(OB_MARCH_PACKED)
    vec2 qc = vec2(q) + 0.5;
    ob_march_packed = texelFetch(ob_packed_samples, q, 0);
    float sd = ob_packed_depth(ob_march_packed);
#else
    vec2 qc = vec2(q) + 0.5;
    float sd = texelFetch(depth, q, 0).r;
#endif
    bool hit = on_screen && sd > 0.0;
    texel = ivec2(qc);
    w = hit ? ob_view_position(qc, sd, frame.ao_inv_size, frame.ao_proj_info) - p : vec3(0.0);
    /* P's own texel (a bisection step can land on it) is no sample. Its offset is 0 only where
     * both reconstructions round alike: NVIDIA's compiler contracts the two inlined copies into
     * FMAs differently, w came out ~1e-7 |p| in a random direction, and a rise of π read an open
     * floor 0.10 (test_gtao's CPU port on an H100). An integer compare: a distance test here
     * cost gtao high 6 % of its AO pass on the H100. */
    hit = hit && any(notEqual(texel, ob_march_self));
    w = hit ? w : vec3(0.0);
    return hit;
}

/* The second depth layer (depth peeling, passes/peel.c) behind the surface of AO-grid texel q: the
 * linear depth of the full-resolution pixel that texel's depth came from (0 = nothing behind). vbao
 * and vbgi read it over the pixel's footprint (second_back.glsl), negated where part of that
 * footprint's solid has no known back; gtao the peel pass's own layer, never negative. */
layout(binding = OB_UNIT_SECOND_DEPTH) uniform sampler2D second_layer;

float ob_second_depth(ivec2 q)
{
    ivec2 full = clamp(q * frame.ao_k + frame.ao_o, ivec2(0), textureSize(second_layer, 0) - 1);
    return texelFetch(second_layer, full, 0).r;
}

/* A sample's thickness from the second layer, z2 - z1 along its view ray, but never less than the
 * world distance between two consecutive steps at the sample's depth z1 (the step in pixels times
 * the pixel's size there, R / (d radius_px) per unit depth, d = P's depth; R / radius_px at every
 * depth for an orthographic camera: ob_depth_scale). The march sees an object only at its steps: a
 * thin slab seen from below covers the directions between its samples too, and a sample as thick
 * as the spacing closes those gaps; thinner, the gaps would open to light that the slab blocks.
 * z2 = 0 (nothing behind): -1, the method's own assumption. */
float ob_layer_thickness(float z1, float z2, float d, float radius, float radius_px, int steps)
{
    float spacing =
        max(radius_px - 1.5, 0.0) / float(steps) * ob_depth_scale(z1) * radius / (ob_depth_scale(d) * max(radius_px, 1e-6));
    return z2 > 0.0 ? max(z2 - z1, spacing) : -1.0;
}

#ifdef OB_MARCH_FACETS
/* The normal of P's own triangle: the G-buffer's facet normal (RG16F octahedral, written by
 * gbuffer.frag.glsl) of the full-resolution pixel AO texel pix came from, as ob_second_depth.
 * The program variant of a method's `facets` (OB_SLICE_FACETS), made only for a frame that has
 * them. */
layout(binding = OB_UNIT_FACET_NORMAL) uniform sampler2D ob_facet_normals;

vec3 ob_facet_normal(ivec2 pix)
{
    ivec2 full = clamp(pix * frame.ao_k + frame.ao_o, ivec2(0), textureSize(ob_facet_normals, 0) - 1);
    return ob_oct_decode(texelFetch(ob_facet_normals, full, 0).xy);
}
#endif

/* A smooth-shaded mesh's facet wedge in slice s (docs/methods.md, "Facets of a smooth-shaded
 * mesh"): the directions between P's tangent (from its interpolated normal n, around which the
 * slice is laid) and the trace of P's own triangle, unit normal f, on the side where the triangle
 * rises above the tangent. AO_R's rays leave P around n, and a ray below the triangle's plane
 * enters the surface at once: on a smooth-shaded mesh every point but the triangle's centre has
 * such a wedge, up to half the angle between two triangles where they are smoothed across a
 * crease. The depth buffer does not show it: the steps see it only where they land on P's own
 * triangle. In the slice's coordinates (along t_pos, along the normal's in-slice part) f's
 * in-slice part is f2; the triangle runs across it, (f2.y, -f2.x) on side + and (f2.y, f2.x) on
 * side -, and rises on the side f2 leans away from. Returns the trace on that side in that side's
 * coordinates (along its tangent, across it: ob_rise_key's x and y); y <= 0: no wedge. */
vec2 ob_facet_trace(ob_slice s, vec3 n, vec3 f, out bool positive)
{
    vec3 pn = n - s.axis * dot(n, s.axis);
    vec2 f2 = vec2(dot(f, s.t_pos), dot(f, pn) / max(s.len_n, 1e-4));
    positive = f2.x < 0.0;
    return vec2(f2.y, abs(f2.x));
}

/* A facet wedge under this many radians is the normals' rounding (RGBA16F n, RG16F octahedral f,
 * each within 1e-3 rad), not a tilt: 0.23 deg, 4 % of a bitmask sector, a cosine measure under
 * 4e-6. */
const float OB_FACET_EPSILON = 4e-3;

/* The rise a sample's interval must pass to count on a side whose facet wedge rises `wedge` (0:
 * none, every rise counts): the wedge's edge plus the normals' rounding (visibility_bitmask.glsl
 * bitmask_step says why). */
float ob_wedge_top(float wedge) { return wedge > 0.0 ? wedge + OB_FACET_EPSILON : 0.0; }

/* The rise of a sample above a side's tangent t, as k = 1 - cos(rise) = 2 sin²(rise / 2): 0 for
 * none, up to 2 for a sample straight up the far side. In the slice's coordinates the sample is
 * at x = dot(w, t) along the tangent and y = dot(w, n) / |n_φ| across it, toward the normal (the
 * normal's part across the slice is perpendicular to every in-slice direction). A sample on P's
 * plane gives y = 0, no rise, also where snapping to the texel centre moved it off the slice, so
 * open planes read exactly open (the sample's own angle from V would sit above this slice's
 * tangent there). The rise is the angle of (x, y) in [0, π], past the slice's zenith too, which
 * occluders on the side the normal leans away from reach, and k grows monotonically with it.
 * 1 - x / r directly would cancel for small rises (1e-7 of cos is 3e-4 rad); for x > 0 it is
 * y² / (r (r + x)). Below the tangent (y <= 0) nothing rises. ob_rise_angle inverts it. */
float ob_rise_key(vec3 w, vec3 t, vec3 n_slice)
{
    float x = dot(w, t), y = dot(w, n_slice);
    float r = sqrt(x * x + y * y);
    float k = x > 0.0 ? y * y / (r * (r + x)) : 1.0 - x / r;
    /* On P's plane y is 0 only up to rounding. A sample snapped off the slice can lie on the plane
     * behind the tangent (x <= 0; at grazing angles a row's step is mostly depth), where y = +1e-7
     * would read a rise of π: an H100 read open floor 0.88 so (test_gtao's CPU port). Rises under
     * 1e-3 rad (y < 1e-3 r, the angle of RGBA16F normals: bitmask.glsl OB_RISE_EPSILON) are none. */
    return y > 1e-3 * r ? k : 0.0;
}

/* The occluder that a sample beyond `reach` stands for inside the sphere of radius `reach` around
 * P. The march's model takes each depth-buffer sample S = p + w as the front of a solid running on
 * along its view ray u (unit, away from the eye). A front farther than `reach` from P is not
 * itself an occluder of AO_R, but the solid behind it may still pass through the sphere: the
 * point where it enters, X = S + t u with |X - p| = reach, is then solid under the same model, and
 * so is every direction from P whose ray reaches it (a ray from P that ends inside the solid
 * within reach crossed its surface within reach). X is the column's highest point inside the
 * sphere (farther along u it sinks away from the eye). With b = w.u and c = |w|^2 - reach^2 > 0
 * (S outside), the nearer root of |w + t u|^2 = reach^2 is t = -(b + sqrt(b^2 - c)); the column
 * meets the sphere behind S when b < 0 (it heads toward P) and b^2 >= c, and counts when t is
 * within `depth` of the front, the solid's assumed thickness there. Returns X - p then, else w
 * unchanged. On a real solid at least `depth` thick X lies inside it, below where its surface
 * leaves the sphere, so X never reads more than the truth there; where that surface is hidden from
 * the eye (a fin's far face beside P, the riser behind a step's nose seen from above) X stands in
 * for the occluder the depth buffer does not show. An infinite `depth` (gtao's height field taken
 * literally) brings back the halo behind every silhouette, which the cut at R exists to remove.
 * ob_column_reach is the same test from b = dot(w, u) and w2 = |w|^2, giving t: a caller that works
 * in the slice's 2D coordinates (visibility_bitmask.glsl) moves the front by t along the ray there. */
bool ob_column_reach(float b, float w2, float reach, float depth, out float t)
{
    float c = w2 - reach * reach;
    float disc = b * b - c;
    t = -(b + sqrt(max(disc, 0.0)));
    return c > 0.0 && b < 0.0 && disc >= 0.0 && t <= depth;
}

bool ob_column_entry(vec3 w, vec3 u, float reach, float depth, out vec3 entry)
{
    float t;
    bool meets = ob_column_reach(dot(w, u), dot(w, w), reach, depth, t);
    entry = meets ? w + t * u : w;
    return meets;
}

float ob_rise_angle(float key) { return 2.0 * asin(sqrt(clamp(0.5 * key, 0.0, 1.0))); }

/* Where the surface leaves the sphere of radius R. On a wall that climbs away from P (every
 * crease) the occluder within R reaches exactly up to where the wall leaves the sphere, so
 * sparse steps always stop short of it and read too little occlusion. The march notes the first
 * gap between the last step inside R and a step beyond it whose surface stands higher than
 * anything found so far (not on an open floor, say); after the march a few bisections of that
 * gap (ob_gap_mid, ob_gap_halve) each halve the shortfall for one fetch. After the march, so
 * SIMD lanes stay in step; selects, not branches, as everywhere in the march. */
struct ob_gap {
    float inside_px; /* the last step within R (0 = P itself) */
    float lo, hi;    /* the gap; hi = 0: none yet */
};

ob_gap ob_gap_none() { return ob_gap(0.0, 0.0, 0.0); }

/* After a step at dist_px: `inside` = a surface within R there, `beyond_higher` = a surface at or
 * beyond R that stands higher than the horizon so far. */
void ob_gap_note(inout ob_gap g, bool inside, bool beyond_higher, float dist_px)
{
    bool opens = beyond_higher && g.hi == 0.0;
    g.lo = opens ? g.inside_px : g.lo;
    g.hi = opens ? dist_px : g.hi;
    g.inside_px = inside ? dist_px : g.inside_px;
}

/* The next bisection's distance; a step there counts only where ob_gap_open(g). */
float ob_gap_mid(ob_gap g) { return 0.5 * (g.lo + g.hi); }
bool ob_gap_open(ob_gap g) { return g.hi > 0.0; }

/* The bisections each side still needs after the march: `steps` where it has a gap, else 0. */
ivec2 ob_gap_refinements(ob_gap pos, ob_gap neg, int steps)
{
    return ivec2(ob_gap_open(pos) ? steps : 0, ob_gap_open(neg) ? steps : 0);
}

/* The side the next bisection step takes, one step a pass: the side with more left (+ on a tie),
 * so a pixel with gaps on both sides alternates +, -, +, - (the order of a loop doing both sides
 * each pass) and one with a single gap spends every pass on it. Marks it taken in `left` and
 * returns that side's gap; a pixel with none left gets a closed gap (its step changes nothing).
 * A loop doing both sides each pass ran, on llvmpipe, both steps for every lane of a SIMD group
 * with any gap, though a crease pixel has its gap on one side only (the wall's). */
ob_gap ob_gap_next_side(ob_gap pos, ob_gap neg, inout ivec2 left, out bool positive)
{
    bool busy = left.x + left.y > 0;
    positive = left.x >= left.y;
    left -= busy ? (positive ? ivec2(1, 0) : ivec2(0, 1)) : ivec2(0);
    return busy ? (positive ? pos : neg) : ob_gap_none();
}

/* Keep the half in which the surface leaves the sphere: [mid, hi] when mid was inside R. */
void ob_gap_halve(inout ob_gap g, bool inside)
{
    float mid = ob_gap_mid(g);
    bool open = ob_gap_open(g);
    g.lo = open && inside ? mid : g.lo;
    g.hi = open && !inside ? mid : g.hi;
}

#endif
