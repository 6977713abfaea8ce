/* Visibility-bitmask AO and one-bounce indirect light (Therrien, Levesque & Gilet 2023, "Screen
 * Space Indirect Lighting with Visibility Bitmask", §3), the body of vbao.glsl and vbgi.glsl
 * (vbgi.glsl defines OB_VBGI). Built on gtao's slices (shaders/slice_march.glsl: the same slice
 * set-up, steps, jitter and depth march).
 *
 * A horizon method keeps, per side of a slice, the highest angle seen and takes everything below
 * it as occluded: every occluder is infinitely thick. Here the half circle of directions above
 * P's tangent in the slice, θ' = θ - n(φ) in [-π/2, π/2] around the projected normal, is cut into
 * 32 sectors, one bit each (§3.1). Each sample within R is a front point (the depth buffer) and a
 * back point pushed away from the eye along its view ray by a thickness t (§3.2); the angles of
 * the two bound an interval, and the sectors it covers are set (a front beyond R whose back still
 * reaches into the sphere: from where it enters, ob_column_entry). Light passes through the
 * sectors no sample set, behind thin objects too.
 *
 * Visibility per slice is the unset part of the mask, weighted
 *   uniform (the paper's, §3.1):   1 - popcount(mask) / 32, the mean over slices; or
 *   cosine (AO_R's weighting):     the integral of cos(θ - n) |sin θ| over the unset sectors, with
 *                                  |n_φ| per slice and the open hemisphere's quadrature as the
 *                                  denominator (gtao.glsl, Jimenez et al. 2016 eq. 3, 5, 10):
 *                                  a run of sectors [θa, θb] weighs S(θb) - S(θa), S(θ) = sign(θ) â(θ, n)
 *                                  with â eq. 10's closed form.
 *
 * vbgi (§3.3): each sample adds its direct radiance L_s times the cosine-weighted measure of the
 * sectors it is the first to set (the newly occluded directions, through which P sees it), so that
 * the sum over slices estimates (1/π) ∫ L(ω) cos θ dω over the directions whose first hit within R
 * is a sample: the one-bounce term of ob_reference_bounce for a white receiver. The measure holds
 * the receiver's cosine; the sender's is the paper's heuristic (vb.emitter_cosine), otherwise a
 * sender facing away from P sends nothing (P would see its unlit back).
 *
 * AO is visibility: 1 = open. Sky (depth 0) writes 1 (and no bounce). */
#include "vbao_params.h"
#include "common.glsl"
#include "slice_march.glsl"
#include "bitmask.glsl"

layout(local_size_x = OB_VB_GROUP_X, local_size_y = OB_VB_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;          /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;          /* RGBA16F */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;            /* RG32F 4x4 rotation vectors */
layout(binding = OB_UNIT_SLICE_DEPTH_MIPS) uniform sampler2D depth_mips; /* MIP chain (OB_MARCH_DEPTH_MIPS) or the depth */
layout(binding = OB_UNIT_SLICE_MULTIPLIER) uniform sampler2D multiplier; /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D ao_out;
#ifdef OB_VBGI
layout(binding = OB_UNIT_SLICE_RADIANCE) uniform sampler2D radiance; /* full-resolution RGBA16F direct radiance */
layout(binding = OB_IMAGE_UNIT_BOUNCE, rgba16f) uniform writeonly image2D bounce_out;
#endif

/* The coverage rule (OB_SECTOR_COVERAGE_*, vbao's `coverage`) is the program's, a constant, so
 * ob_sector_bits works out only its own: `touch` here, the others variants (methods/slices.c). */
#ifndef OB_VB_COVERAGE
#define OB_VB_COVERAGE OB_SECTOR_COVERAGE_TOUCH
#endif
/* The joining rule (OB_CONNECT_*, vbao's `connect`) likewise: each mode's code alone in its
 * program. As a uniform branch the curve's code weighed on every mode: on an H200 `chord` took
 * 1.00 ms there (vbao high, 1080p), a program doing more than chord, without the rest of the
 * curve's code, 0.85 (docs/methods.md, "What the curve costs on a GPU"). */
#ifndef OB_VB_CONNECT
#define OB_VB_CONNECT OB_CONNECT_OFF
#endif

/* Bisections of the gap in which the surface leaves the sphere of radius R (ob_gap). */
const int REFINE_STEPS = 2;

/* A continuous surface between two steps turns at most this far from facing them: its points
 * lie within CONTINUOUS_STRETCH x the steps' screen distance of each other (1 / cos 70.5 deg).
 * Set before any measurement, as the slope beyond which a depth buffer's samples of one surface
 * are too sparse to join; docs/methods.md "Steps joined along a surface" has the sweep that
 * shows why it was not fitted. */
const float CONTINUOUS_STRETCH = 3.0;

/* The last step taken on one side of a slice, for joining the next to it (OB_VB_CONNECT): its
 * offset from P, its distance from P in pixels and the rise of its front; `solid`: it occluded
 * (within R, or its column entered the sphere). Under `ends` and `curve` also its surface's unit
 * tangent in the slice's 2D coordinates and the sectors its stratum's outer half adds if its run
 * ends there (`ends`).
 * The march starts each side from P itself, whose tangent is the slice's (1, 0). */
struct ob_prev_step {
    vec3 w;
    float px;
    float rise;
    bool solid;
    vec2 tangent;
    uint ends;
};

ob_prev_step ob_prev_step_at_p() { return ob_prev_step(vec3(0.0), 0.0, 0.0, true, vec2(1.0, 0.0), 0u); }

/* The normal of the sample at AO-grid texel q, as ob_march_fetch read its depth (vbgi's packed
 * texel holds the same half floats). */
vec3 ob_march_normal(ivec2 q)
{
#ifdef OB_MARCH_PACKED
    return ob_packed_normal(ob_march_packed);
#else
    return texelFetch(view_normal, q, 0).xyz;
#endif
}

/* The cubic Hermite curve from a to b with unit end tangents ta, tb (each turned to run along the
 * chord and scaled by its length, the usual choice: for a short arc of a circle, close to the
 * circle's own), at parameter 1/4, 1/2 and 3/4 (the basis weights written out). A surface
 * between two of its samples is a curve with those tangents: a straight chord where both
 * tangents lie along it, the chord pushed outward where the surface is convex between them. */
void ob_hermite_quarters(vec2 a, vec2 ta, vec2 b, vec2 tb, out vec2 q1, out vec2 q2, out vec2 q3)
{
    vec2 chord = b - a;
    float len = length(chord);
    vec2 ma = ta * (dot(ta, chord) < 0.0 ? -len : len), mb = tb * (dot(tb, chord) < 0.0 ? -len : len);
    q1 = 0.84375 * a + 0.140625 * ma + 0.15625 * b - 0.046875 * mb;
    q2 = 0.5 * (a + b) + 0.125 * (ma - mb);
    q3 = 0.15625 * a + 0.046875 * ma + 0.84375 * b - 0.140625 * mb;
}

/* The rise of a point of the slice's 2D coordinates (ob_rise_angle_of) where it lies within R of
 * P, else `outside` (a curve point beyond R is no occluder of AO_R). */
float ob_rise_within(vec2 xy, float radius, float outside)
{
    return dot(xy, xy) <= radius * radius ? ob_rise_angle_of(xy) : outside;
}

/* The facet wedge's rise on its side (slice_march.glsl ob_facet_trace), 0 for none. On a flat
 * surface f is n but for the rounding of the two formats, RGBA16F (n) and RG16F octahedral (f),
 * each within 1e-3 rad: a wedge under OB_FACET_EPSILON is that rounding and sets nothing. */
float ob_facet_wedge(ob_slice s, vec3 n, vec3 f, out bool positive)
{
    float rise = ob_rise_angle_of(ob_facet_trace(s, n, f, positive));
    return rise > OB_FACET_EPSILON ? rise : 0.0;
}

/* The wedge is exact, not a sample standing for its stratum, so it is counted exactly: the
 * sectors it covers whole as bits (`all`), and the rest, from their edge to the rise, by its own
 * cosine measure where no sample set that sector (ob_wedge_rest). The steps' `touch` would have
 * turned every wedge into whole sectors, `half` a wedge of 0.6 sector into one: its measure grows
 * with the square of the rise, so either reads darker than AO_R on average. */
uint ob_wedge_bits(float rise, float ang_n, bool positive)
{
    return ob_sample_bits(0.0, rise, ang_n, positive, OB_SECTOR_COVERAGE_ALL);
}

/* The cosine measure (uniform: the share of the half circle) of the wedge's part sector, the one
 * its rise ends in, when `mask` leaves that sector unset; 0 otherwise. Side + rises from θ = n +
 * π/2 toward V, side - from θ = n - π/2 (bitmask.glsl ob_sample_bits). */
float ob_wedge_rest(float rise, float ang_n, float cos_n, float sin_n, bool positive, uint mask, bool cosine)
{
    const float width = OB_BITMASK_PI / float(OB_SECTORS);
    float whole = floor(rise / width) * width;
    /* The part sector's bit: counted from the tangent at bit 31 on side +, bit 0 on side -. */
    int k = int(floor(rise / width));
    int bit = positive ? OB_SECTORS - 1 - k : k;
    bool open = rise > whole && k < OB_SECTORS && ((mask >> uint(clamp(bit, 0, OB_SECTORS - 1))) & 1u) == 0u;
    float t0 = positive ? ang_n + 0.5 * OB_BITMASK_PI - rise : ang_n - 0.5 * OB_BITMASK_PI + whole;
    float t1 = positive ? ang_n + 0.5 * OB_BITMASK_PI - whole : ang_n - 0.5 * OB_BITMASK_PI + rise;
    float part = cosine ? ob_sector_s(t1, ang_n, cos_n, sin_n) - ob_sector_s(t0, ang_n, cos_n, sin_n)
                        : (rise - whole) / OB_BITMASK_PI;
    return open ? part : 0.0;
}

/* One sample on one side of slice s (positive: along +dir), at AO-grid position `at`, dist_px
 * from P. `refine`: a bisection step of the gap, counting only while it is open (it joins no
 * step: it lands between steps already taken). Updates the mask, the highest front rise within R
 * (for the gap), vbgi's bounce and the side's last step. */
void bitmask_step(ob_slice s, vec2 at, float dist_px, vec3 p, bool positive, bool refine, float wedge,
                  inout uint mask, inout float rise, inout ob_gap gap, inout vec3 bounce, inout ob_prev_step prev)
{
    vec3 w;
    ivec2 texel;
    bool hit = ob_march_fetch(depth_mips, at, dist_px, p, vb.mip_scale, vb.max_mip, w, texel) &&
               (refine ? ob_gap_open(gap) : dist_px <= s.radius_px);
    /* Within R by the squared distance (ob_column_entry takes the same dot): no square root per
     * sample unless vbgi's bounce block needs |w|. */
    float w2 = dot(w, w);
    bool inside = hit && w2 < vb.radius * vb.radius;
    vec3 t = positive ? s.t_pos : -s.t_pos; /* t_neg is -t_pos: one vector fewer held through the march */
    /* §3.2: the back of the sample, its front pushed away from the eye along its view ray u by
     * the thickness (-Z for an orthographic camera: common.glsl ob_view_ray). */
    vec3 sv = p + w;
    float sv_inv = inversesqrt(max(dot(sv, sv), 1e-20));
    bool ortho = frame.orthographic != 0;
    vec3 u = ortho ? vec3(0.0, 0.0, -1.0) : sv * sv_inv;
    float thick = vb.thickness + vb.thickness_slope * max(-sv.z, 0.0);
#ifdef OB_MARCH_LAYERS
    /* The sample's true back: the second layer on the same view ray, at least the steps' spacing
     * (ob_layer_thickness; linear depth scales along the ray, so depth z1 + t lies |sv| t / z1
     * along it, t along an orthographic camera's); nothing behind: the constant above. Its own
     * program variant (OB_SLICE_LAYERS): llvmpipe would run the block for every sample with the
     * layer off too. A back written negated (second_back.glsl: part of the footprint's solid has
     * no known back) is at least the deepest known and at least the constant: the thicker. */
    float z1 = max(-sv.z, 1e-20), z2 = ob_second_depth(texel);
    float t2 = ob_layer_thickness(z1, abs(z2), -p.z, vb.radius, s.radius_px, vb.steps);
    thick = t2 > 0.0 ? max(t2 / (ortho ? 1.0 : z1 * sv_inv), z2 < 0.0 ? thick : 0.0) : thick;
#endif
    /* The front and its view ray in the slice's 2D coordinates (ob_rise_angle_of): the back and
     * the column's entry are the front moved along the ray there, and no 3D point past this line
     * stays live (vbgi's w aside). On llvmpipe the same bytes as the 3D points' dots, with fewer
     * values held through the march, which it spilled: vbao 5-6 % and vbgi 3-10 % faster
     * (bench/results/2026-11-23-llvmpipe-vbao-slice-2d.md). */
    vec2 front = vec2(dot(w, t), dot(w, s.n_slice)), ray = vec2(dot(u, t), dot(u, s.n_slice));
    /* A front beyond R whose solid still enters the sphere within its thickness: the interval
     * runs from where it enters (ob_column_entry) to its back, as for a front inside R. Per
     * sample, not once per side as gtao does (gtao.glsl column_candidate): a horizon keeps only
     * the highest entry, but the mask is the union of every sample's interval, and the steps of a
     * stair or the fins of an engine each add their own (one candidate per side kept half of
     * vbao's gain on the views of docs/methods.md, for 7-15 % of its pass on llvmpipe). */
    float t_entry;
    bool column = hit && !inside && ob_column_reach(dot(w, u), w2, vb.radius, thick, t_entry);
    float rise_front = ob_rise_angle_of(column ? front + t_entry * ray : front);
    float rise_back = ob_rise_angle_of(front + thick * ray);
    bool solid = inside || column;
    /* The sample's own interval, from its front to its back. Every interval this step adds below
     * holds rise_front too (the joined one runs from the last step's front to this one's, the
     * extended ones widen this one), so their union is one interval and one ob_sample_bits call
     * sets it: under `touch` (the default) exactly the union of the intervals' own sectors, under
     * `half` and `all` the sectors the union covers, which the surface between them does. */
    vec2 span = vec2(min(rise_front, rise_back), max(rise_front, rise_back));
    /* Steps joined along a surface. The march sees a surface only at its steps, and an interval
     * covers only the directions from a step's front to its back: the directions between two
     * steps on one surface stay open, though the surface between them blocks them. Most of all at
     * a crease, where the first step lands well up the wall and the wall's foot, between P and
     * that step, is never sampled: fewer steps read more open (docs/methods.md, "Sample count on
     * the check views"). Where the previous step (P itself for the first) and this one both
     * occlude and lie on one continuous surface (no depth jump: their fronts within
     * CONTINUOUS_STRETCH x their screen distance, in world units at the deeper one), the sectors
     * between their front rises are set too: the surface between two points of it subtends the
     * angles between theirs. A silhouette over a floor jumps in depth and is not joined, so the
     * gap under a floating slab stays open. */
    float deeper = max(-(p.z + w.z), -(p.z + prev.w.z));
    float px_world = ob_pixel_world(deeper, -p.z, vb.radius, s.radius_px);
    /* Squared: no square root per step in the march. */
    vec3 jump = w - prev.w;
    float reach = CONTINUOUS_STRETCH * (dist_px - prev.px) * px_world;
    bool continuous = dot(jump, jump) <= reach * reach;
    bool join = OB_VB_CONNECT != OB_CONNECT_OFF && !refine && solid && prev.solid && continuous;
    vec2 rises = vec2(min(prev.rise, rise_front), max(prev.rise, rise_front));
    /* `ends` and `curve` (docs/methods.md, "Steps joined along a curve"): what the steps leave out
     * of the surfaces they land on, from the samples' own normals; one normal fetch per step. */
    vec2 tangent = vec2(1.0, 0.0);
    uint ends = 0u, deferred = 0u;
#if OB_VB_CONNECT >= OB_CONNECT_ENDS
    if (!refine) {
        /* The sample's surface in the slice: the line across its normal's in-slice part (the
         * normal's part along the slice axis tilts the surface across the slice, not within it). */
        vec3 n_s = ob_march_normal(texel);
        vec2 n2 = vec2(dot(n_s, t), dot(n_s, s.n_slice));
        float n2_len = length(n2);
        vec2 f0 = column ? front + t_entry * ray : front;
        vec2 a = vec2(dot(prev.w, t), dot(prev.w, s.n_slice));
        /* A normal across the slice leaves no direction in it: the chord's then. */
        vec2 chord = f0 - a;
        tangent = n2_len > 1e-3 ? vec2(n2.y, -n2.x) / n2_len : chord * inversesqrt(max(dot(chord, chord), 1e-30));
        /* The last step's outer half, now that its run has ended (this step is open, or not on
         * its surface); after the march, the last step's (main). */
        deferred = join ? 0u : prev.ends;
        /* Not between two steps on P's own plane (no rise at either): there the curve stands off
         * the plane by the normals' rounding alone (8-bit normals: 4e-3 rad), which `touch` turns
         * into a whole sector (test_host_inputs' RGBA8 normals read 0.046 darker so). Only a
         * sample with an interval of its own (P's open plane has none) is extended. */
        bool curved = OB_VB_CONNECT == OB_CONNECT_CURVE && join && rises.y > 0.0;
        bool extend = solid && span.y > 0.0;
        /* Neither holds for a step on P's open plane, where most of a scene's samples land: a
         * SIMD group all of whose lanes are there skips the curve's points and their angles. */
        if (curved || extend) {
#if OB_VB_CONNECT == OB_CONNECT_CURVE
            /* 1. Between two joined steps the surface is a curve, not the chord: on a convex
             *    surface (a rounded bar, a sphere, a link of a chain) its highest point seen from
             *    P lies between the steps more often than on one, and a sparse march reads the top
             *    of every convex occluder low. The cubic through both fronts with both tangents
             *    bounds the angles it subtends; its points within R widen the joined interval.
             *    `curve` alone: `ends` without it costs an H200 0.7x the AO pass, for 0.0004 of
             *    RMSE on the check views and as much the other way on the choose views. */
            vec2 q1, q2, q3;
            ob_hermite_quarters(a, prev.tangent, f0, tangent, q1, q2, q3);
            float r1 = ob_rise_within(q1, vb.radius, rise_front), r2 = ob_rise_within(q2, vb.radius, rise_front),
                  r3 = ob_rise_within(q3, vb.radius, rise_front);
            rises = curved ? vec2(min(rises.x, min(r1, min(r2, r3))), max(rises.y, max(r1, max(r2, r3)))) : rises;
#endif
            /* 2. A step stands for its stratum, half the steps' spacing h on either side along
             *    the screen (the strata of ob_slice_step_px, shifted by the jitter). Where a run of
             *    joined steps ends, the surface goes on, on average, half a stratum past its last
             *    step: a sparse march puts the top edge of every occluder one step's jitter too
             *    low, and the start of a run as far too late. So a run's first step adds the inner
             *    half of its stratum and its last step the outer half, laid along its surface's
             *    tangent, the outer ends within R. With the steps jittered uniformly in their
             *    strata, the extended run's end is where the surface ends, on average, at every
             *    step count. Laid along the surface and not across the view ray, the extension
             *    never leaves a plane.
             * 3. A run's inner half is h pixels of the screen, so on the surface it is the length
             *    whose projection is h pixels: h pixels' world length at the sample's depth over
             *    the sine between the tangent and the view ray (a floor or a wall seen at a
             *    grazing angle holds much more surface in a pixel than one facing the camera), up
             *    to CONTINUOUS_STRETCH times (the join's own bound on a surface's slope), and no
             *    farther than the gap back to the march's previous step, or its start 1.5 px
             *    out: that step saw something else, or P's own surface, so the run began after
             *    it. Without the stretch a run's start covered only that sine's part of its
             *    stratum: a sphere's underside over its floor read 0.06 too open at the low preset
             *    (docs/methods.md, "Each step's stratum on the screen"). Without the bound a first
             *    step jittered close to P reached past P, and a sheet beside P (cornell's light
             *    under its ceiling) set a whole side. The outer half is not stretched: nothing the
             *    march saw bounds it, and along the tangent of a smoothed normal (a low-poly
             *    model shaded smooth) three times the length left the surface by three times as
             *    much: test_vbao's smoothed cube went from RMSE 0.066 to 0.102.
             *    Either half is turned outward by the sign of its screen motion, its cross
             *    product with the view ray (the sample's own offset from P has the outward
             *    sign), not by its dot with a screen step at constant depth: on a wall seen
             *    edge-on off the screen's centre the two disagree. */
            float h = 0.5 * max(s.radius_px - 1.5, 0.0) / float(vb.steps);
            vec2 ray_dir = ray * inversesqrt(max(dot(ray, ray), 1e-20));
            float sin_tr = ray_dir.x * tangent.y - ray_dir.y * tangent.x;
            float out_side = ray_dir.x * f0.y - ray_dir.y * f0.x;
            vec2 te = sin_tr * out_side < 0.0 ? -tangent : tangent;
            vec2 e = te * (h * ob_pixel_world(max(-sv.z, 1e-20), -p.z, vb.radius, s.radius_px));
            /* The inner half: stretched to h pixels of screen (h stretch |sin| of them after the
             * stretch), within the gap to the previous step. */
            float stretch = min(1.0 / max(abs(sin_tr), 1e-6), CONTINUOUS_STRETCH);
            float gap_px = max(dist_px - max(prev.px, 1.5), 0.0);
            vec2 e_in = e * (stretch * min(1.0, gap_px / max(h * stretch * abs(sin_tr), 1e-6)));
            vec2 b0 = front + thick * ray, o0 = f0 + e, o1 = b0 + e;
            float r2_max = vb.radius * vb.radius;
            o0 = dot(o0, o0) > r2_max ? f0 : o0;
            o1 = dot(o1, o1) > r2_max ? b0 : o1;
            float ro0 = ob_rise_angle_of(o0), ro1 = ob_rise_angle_of(o1);
            /* Clipped to the facet's wedge as the sample's own interval is (below). */
            vec2 outer = vec2(max(min(span.x, min(ro0, ro1)), wedge), max(span.y, max(ro0, ro1)));
            ends = extend && outer.y > ob_wedge_top(wedge) ? ob_sample_bits(outer.x, outer.y, s.ang_n, positive,
                                                                            OB_VB_COVERAGE)
                                                             : 0u;
            bool starts = extend && !(prev.solid && continuous);
            float ri0 = ob_rise_angle_of(f0 - e_in), ri1 = ob_rise_angle_of(b0 - e_in);
            span = starts ? vec2(min(span.x, min(ri0, ri1)), max(span.y, max(ri0, ri1))) : span;
        }
    }
#endif
    span = join ? vec2(min(span.x, rises.x), max(span.y, rises.y)) : span;
    /* Below the facet's wedge (`wedge`, this side's rise of P's own triangle; 0 without one) a
     * sample adds nothing: whatever lies behind the plane of P's triangle is seen from P through
     * the wedge alone. A step on that plane (P's own triangle, or a flat face's others) rises to
     * the wedge's edge but for rounding, and `touch` would round that up to the wedge's part
     * sector, which ob_wedge_rest counts exactly: such a step must rise past the facet normal's
     * rounding to count. */
    span.x = max(span.x, wedge);
    uint bits = solid && span.y > ob_wedge_top(wedge) ? ob_sample_bits(span.x, span.y, s.ang_n, positive, OB_VB_COVERAGE)
                                                      : 0u;
    prev = refine ? prev : ob_prev_step(w, dist_px, rise_front, solid, tangent, ends);
#ifdef OB_VBGI
    /* The sender's direct radiance through the directions it is the first to occlude, only where
     * it occludes a sector first: most samples set none (open surfaces, or sectors already set),
     * and a SIMD group none of whose lanes has a fresh bit skips the block, the sender's two
     * fetches and the measure's two cosines (on an H100 the bounce's fetches were two of its three
     * per sample; llvmpipe runs a block its lanes disagree on for all of them). */
    uint fresh = bits & ~mask;
    if (fresh != 0u) {
#ifdef OB_MARCH_PACKED
        /* The sample's texel as ob_march_fetch read it. */
        vec3 n_s = ob_packed_normal(ob_march_packed);
        vec3 l_s = ob_packed_radiance(ob_march_packed);
#else
        vec3 n_s = texelFetch(view_normal, texel, 0).xyz;
        ivec2 full = clamp(texel * frame.ao_k + frame.ao_o, ivec2(0), textureSize(radiance, 0) - 1);
        vec3 l_s = texelFetch(radiance, full, 0).rgb;
#endif
        /* The newly set sectors' cosine measure: the interval's exact one (two cosines,
         * ob_run_measure) times the share of its sectors still unset, exact when none or all of
         * them were set before, and no loop over the runs of the new bits per sample (llvmpipe
         * runs such a loop as long as its slowest lane). fresh != 0 means bits != 0. Here, after
         * the sender's values, and not before the test: llvmpipe ran the same instructions 3-5 %
         * faster so (the order changes what LLVM keeps in registers; first in the block, ~1 %:
         * bench/results/2026-11-24-llvmpipe-vbgi-measure-sink.md). */
        int count = bitCount(bits);
        float measure = ob_run_measure(findLSB(bits), count, s.ang_n, s.cos_n, s.sin_n);
        float share = float(bitCount(fresh)) / float(count);
        float facing = -dot(n_s, w) / max(sqrt(w2), 1e-20);
        float emit = vb.emitter_cosine != 0 ? max(facing, 0.0) : (facing > 0.0 ? 1.0 : 0.0);
        bounce += l_s * (emit * share * measure);
    }
#endif
    /* The previous step's outer half sends vbgi no light: its sender was that step, whose radiance
     * is gone; it still occludes. */
    mask |= bits | deferred;
    if (refine) ob_gap_halve(gap, inside);
    else ob_gap_note(gap, inside, hit && !inside && rise_front > rise, dist_px);
    rise = solid ? max(rise, rise_front) : rise;
}

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ob_march_self = pix;
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(1.0));
#ifdef OB_VBGI
        imageStore(bounce_out, pix, vec4(0.0, 0.0, 0.0, 1.0));
#endif
        return;
    }
    vec2 centre, to_view;
    vec3 p, v, n;
    ob_slice_pixel(pix, d, view_normal, centre, p, v, n, to_view);
#ifdef OB_MARCH_FACETS
    vec3 facet = ob_facet_normal(pix);
#endif
    vec2 jit = ob_slice_jitters(pix, vb.noise, noise_tile, vec2(vb.slice_offset, vb.step_offset));
    int slices = ob_slice_count(pix, vb.slices, vb.adaptive, vb.adaptive_base, multiplier), steps = vb.steps;
    bool cosine = vb.weighting == OB_DIRECTIONS_MODE_COSINE;

    float visible = 0.0, total = 0.0, cos_total = 0.0;
    vec3 bounce = vec3(0.0);
    vec2 dir = ob_slice_first_dir(jit.x, slices), turn = ob_slice_rotation(slices);
    for (int k = 0; k < slices; ++k, dir = ob_slice_turn(dir, turn)) {
        ob_slice s;
        bool weighty = ob_slice_setup(dir, p, v, n, d, to_view, vb.radius, s);
        /* A slice across the normal weighs nothing in the cosine quadrature; the uniform one
         * counts it open, as the paper does. */
        if (!weighty) {
            visible += cosine ? 0.0 : 1.0;
            total += cosine ? 0.0 : 1.0;
            continue;
        }
        /* P's own triangle's wedge first: a sample inside it sets no fresh sector (vbgi: P's own
         * surface sends it nothing). */
#ifdef OB_MARCH_FACETS
        bool wedge_pos;
        float wedge = ob_facet_wedge(s, n, facet, wedge_pos);
        vec2 wedges = wedge_pos ? vec2(wedge, 0.0) : vec2(0.0, wedge);
        uint mask = ob_wedge_bits(wedge, s.ang_n, wedge_pos);
#else
        const vec2 wedges = vec2(0.0);
        uint mask = 0u;
#endif
        vec2 rise = vec2(0.0);
        ob_gap gap_pos = ob_gap_none(), gap_neg = ob_gap_none();
        vec3 slice_bounce = vec3(0.0);
        ob_prev_step prev_pos = ob_prev_step_at_p(), prev_neg = prev_pos;
        for (int j = 0; j < steps; ++j) {
            float dist_px = ob_slice_step_px(j, jit.y, steps, s.radius_px);
            vec2 off = s.dir * dist_px;
            bitmask_step(s, centre + off, dist_px, p, true, false, wedges.x, mask, rise.x, gap_pos, slice_bounce,
                         prev_pos);
            bitmask_step(s, centre - off, dist_px, p, false, false, wedges.y, mask, rise.y, gap_neg, slice_bounce,
                         prev_neg);
        }
        /* Each side with a gap gets REFINE_STEPS bisections, one step per pass of the loop
         * (ob_gap_next_side). The one branch of the march: most pixels (open surfaces) have no
         * gap, so whole SIMD groups skip the loop, and a group runs it as often as its busiest
         * lane needs. */
        /* The outer halves of the strata of each side's last step (its run ends at the march's end). */
        mask |= prev_pos.ends | prev_neg.ends;
        ivec2 left = ob_gap_refinements(gap_pos, gap_neg, REFINE_STEPS);
        for (int b = 0; b < 2 * REFINE_STEPS; ++b) {
            if (left.x + left.y == 0) break;
            bool positive;
            ob_gap g = ob_gap_next_side(gap_pos, gap_neg, left, positive);
            float r = positive ? rise.x : rise.y, mid = ob_gap_mid(g);
            ob_prev_step unused = ob_prev_step_at_p();
            bitmask_step(s, centre + (positive ? mid : -mid) * s.dir, mid, p, positive, true,
                         positive ? wedges.x : wedges.y, mask, r, g, slice_bounce, unused);
            gap_pos = positive ? g : gap_pos;
            gap_neg = positive ? gap_neg : g;
            rise = positive ? vec2(r, rise.y) : vec2(rise.x, r);
        }
        /* The open half circle's cosine measure: â(n + π/2) + â(n - π/2) = cos n + n sin n. */
        float open = s.cos_n + s.ang_n * s.sin_n;
#ifdef OB_MARCH_FACETS
        float rest = ob_wedge_rest(wedge, s.ang_n, s.cos_n, s.sin_n, wedge_pos, mask, cosine);
#else
        const float rest = 0.0;
#endif
        if (cosine) {
            visible += s.len_n * (open - ob_bits_measure(mask, s.ang_n, s.cos_n, s.sin_n) - rest);
            total += s.len_n * open;
        } else {
            visible += 1.0 - float(bitCount(mask)) / float(OB_SECTORS) - rest;
            total += 1.0;
        }
        cos_total += s.len_n * open;
        bounce += s.len_n * slice_bounce;
    }
    /* Cosine weighting: 1 - the occluded measure over N slices' expected open measure, an
     * estimate linear in its slices, so that every slice count has the same mean (the presets keep
     * their steps and change their slices: methods/vbao.c). Over the slices' own open sum (the
     * ratio), one slice read up to 0.006 too open on the check views. Unclamped: one slice's
     * estimate leaves [0, 1] by its noise, and the filter clamps what it averages (filter_params.h
     * OB_FILTER_RESULT). The uniform weighting's open measure is 1 a slice: the ratio is linear. */
    float expected = cosine ? float(slices) * ob_slice_expected_open(p, v, n, d, to_view) : total;
    float ao = expected > 0.0 ? 1.0 - (total - visible) / expected : 1.0;
    imageStore(ao_out, pix, vec4(ao));
#ifdef OB_VBGI
    float bounce_norm = cosine ? expected : cos_total;
    imageStore(bounce_out, pix, vec4(bounce_norm > 0.0 ? bounce / bounce_norm : vec3(0.0), 1.0));
#endif
}
