#version 450 core
/* Ground-truth ambient occlusion (Jimenez, Wu, Pesce & Jarabo 2016, "Practical Realtime
 * Strategies for Accurate Indirect Occlusion", §4-5): the cosine-weighted visibility of
 * DESIGN.md's AO_R, integrated analytically between two horizons per slice.
 *
 *   A(x) = 1/π ∫_0^π ∫_{h1(φ)}^{h2(φ)} cos(θ - n(φ))^+ |sin θ| dθ dφ                 (eq. 3, 5)
 *
 * φ picks a slice: the plane through the eye, x and a screen direction d(φ). In it θ is the angle
 * from the view vector V (toward the eye), n(φ) the angle of the normal projected onto the slice,
 * and h1, h2 the horizons found by marching the depth buffer on both sides (eq. 6-7: the largest
 * cos θ among the samples within R, never below the tangent, θ = n ± π/2). The inner integral has
 * the closed form (eq. 10)
 *
 *   â(h, n) = 1/4 (-cos(2h - n) + cos n + 2 h sin n),      a(φ) = â(h1, n) + â(h2, n),
 *
 * and the projected normal's length |n_φ| weights each slice, so that the mean over slices of
 * |n_φ| a(φ) is the cosine-weighted integral over the normal's hemisphere (exactly 1 when open,
 * at any angle between the normal and V). The φ integral is the mean over N_slices directions
 * (k + jitter) π / N_slices.
 *
 * What counts as an occluder is AO_R's: a depth-buffer sample within R of x (falloff 0 gives the
 * definition's hard cut; falloff f fades occluders over the last f R). Like every horizon method
 * this treats the depth buffer as a height field: everything below the horizon is occluded, so
 * thin objects occlude too much behind them (`thin` stretches the depth component of a sample's
 * distance, as in Jimenez et al. §5's thickness heuristic, so thin objects count less).
 *
 * AO is visibility: 1 = open. Sky (depth 0) writes 1. */
#include "gtao_params.h"
#include "common.glsl"
#include "slice_march.glsl"

layout(local_size_x = OB_GTAO_GROUP_X, local_size_y = OB_GTAO_GROUP_Y) in;

layout(binding = 0) uniform sampler2D linear_depth; /* R32F, 0 = no geometry */
layout(binding = 1) uniform sampler2D view_normal;  /* RGBA16F */
layout(binding = 2) uniform sampler2D noise_tile;   /* RG32F 4x4 rotation vectors */
layout(binding = 3) uniform sampler2D depth_mips;   /* R32F MIP chain of linear depth (level 0 = linear_depth)
                                                       in the OB_MARCH_DEPTH_MIPS program; otherwise
                                                       linear_depth itself */
layout(binding = 0, r32f) uniform writeonly image2D ao_out;
layout(binding = 1, rgba16f) uniform writeonly image2D bent_out; /* view-space bent normal (bent_normals = 1) */

/* The cosine-weighted mean direction of the visible arc [h0, h1] of a slice (the first moment of
 * eq. 3's integrand: ∫ (sin θ, cos θ) cos(θ - n) |sin θ| dθ in closed form, Jimenez et al. 2016
 * §5 "Bent normals"), in view space: along V (cos θ) and along o (sin θ). */
vec3 slice_bent(float h0, float h1, float n, vec3 v, vec3 o)
{
    float t0 = (6.0 * sin(h0 - n) - sin(3.0 * h0 - n) + 6.0 * sin(h1 - n) - sin(3.0 * h1 - n) + 16.0 * sin(n) -
                3.0 * (sin(h0 + n) + sin(h1 + n))) / 12.0;
    float t1 = (-cos(3.0 * h0 - n) - cos(3.0 * h1 - n) + 8.0 * cos(n) - 3.0 * (cos(h0 + n) + cos(h1 + n))) / 12.0;
    return t1 * v + t0 * o;
}

/* Bisections of the last gap in which the surface leaves the sphere of radius R (see main). */
const int REFINE_STEPS = 2;

/* The rise of a sample above the tangent, as k = 1 - cos(rise) = 2 sin²(rise / 2): 0 for none,
 * up to 2 for a sample straight up the far side. In the slice's coordinates the sample is at
 * x = dot(w, t) along the tangent and y = dot(w, n) / |n_φ| across it, toward the normal (the
 * normal's part across the slice is perpendicular to every in-slice direction). A sample on P's
 * plane gives y = 0, no rise, also where snapping to the texel centre moved it off the slice, so
 * open planes read exactly 1 (the sample's own angle from V would sit above this slice's tangent
 * there). The rise is the angle of (x, y) in [0, π], past the slice's zenith too, which occluders
 * on the side the normal leans away from reach, and k grows monotonically with it over that
 * range: the march keeps the largest k and main takes one asin per side, no angle per sample.
 * 1 - x / r directly would cancel for small rises (1e-7 of cos is 3e-4 rad); for x > 0 it is
 * y² / (r (r + x)). Below the tangent (y <= 0) nothing rises. */
float rise_key(vec3 w, vec3 t, vec3 n_slice)
{
    float x = dot(w, t), y = dot(w, n_slice);
    float r = sqrt(x * x + y * y);
    float k = x > 0.0 ? y * y / (r * (r + x)) : 1.0 - x / r;
    return y > 0.0 ? k : 0.0;
}

/* One horizon-search step on one side of slice s, at AO-grid position `at`, dist_px from P;
 * t is that side's tangent. `rise` is the largest weighted rise_key so far (0 = none);
 * inside_px the last step within R; [gap_lo, gap_hi] the first gap in which the surface leaves
 * the sphere of radius R while standing above the horizon so far (gap_hi 0: none yet), for the
 * refinement in main. eq. 6-7 with AO_R's range: a sample counts by its weight, faded in cosine
 * as XeGTAO fades its horizon cosines (falloff 0: weight 0 or 1, exact). Selects, not branches:
 * llvmpipe runs both sides of a branch its lanes disagree on. */
void horizon_step(ob_slice s, vec2 at, float dist_px, vec3 p, vec3 t, inout float rise, inout float inside_px,
                  inout float gap_lo, inout float gap_hi)
{
    vec3 w;
    /* Where R projects to under 1.5 px, the first step is already past it: no search. */
    bool hit = ob_march_fetch(depth_mips, at, dist_px, p, gtao.mip_scale, gtao.max_mip, w) && dist_px <= s.radius_px;
    float w_len = length(vec3(w.xy, w.z * (1.0 + gtao.thin)));
    float weight = hit ? clamp(w_len * gtao.falloff_mul + gtao.falloff_add, 0.0, 1.0) : 0.0;
    float k = rise_key(w, t, s.n_slice);
    /* Beyond R: only where the surface out there stands above the horizon so far can the part of
     * it inside R raise the horizon (not on an open floor, say). */
    bool opens_gap = hit && weight <= 0.0 && gap_hi == 0.0 && k > rise;
    gap_lo = opens_gap ? inside_px : gap_lo;
    gap_hi = opens_gap ? dist_px : gap_hi;
    inside_px = weight > 0.0 ? dist_px : inside_px;
    rise = max(rise, weight * k);
}

/* One bisection of [gap_lo, gap_hi] (nothing when gap_hi is 0): the half in which the surface
 * leaves the sphere of radius R is kept, and a midpoint inside R raises the horizon. */
void horizon_refine(ob_slice s, vec2 centre, float sgn, vec3 p, vec3 t, inout float rise, inout float gap_lo,
                    inout float gap_hi)
{
    float mid = 0.5 * (gap_lo + gap_hi);
    vec3 w;
    bool hit = ob_march_fetch(depth_mips, centre + sgn * s.dir * mid, mid, p, gtao.mip_scale, gtao.max_mip, w);
    float w_len = length(vec3(w.xy, w.z * (1.0 + gtao.thin)));
    float weight = hit && gap_hi > 0.0 ? clamp(w_len * gtao.falloff_mul + gtao.falloff_add, 0.0, 1.0) : 0.0;
    rise = max(rise, weight * rise_key(w, t, s.n_slice));
    bool inside = weight > 0.0;
    gap_lo = inside ? mid : gap_lo;
    gap_hi = inside || gap_hi == 0.0 ? gap_hi : mid;
}

void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;
    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(1.0));
        if (gtao.bent_normals != 0) imageStore(bent_out, pix, vec4(0.0));
        return;
    }
    vec2 centre = vec2(pix) + 0.5;
    vec3 p = ob_view_position(centre, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 v = -normalize(p);
    vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
    /* Interpolated normals at silhouettes can face away from the eye; the integral then has no
     * visible hemisphere left. Tilt them until they face the eye by a little (as hbao.glsl). */
    float nv = dot(n, v);
    if (nv < 0.02) n = normalize(n + (0.02 - nv) * v);

    /* A screen offset (dx, dy) px at P's depth is the view offset (dx, dy) * to_view * d. */
    vec2 to_view = frame.ao_proj_info.xy * frame.ao_inv_size * 2.0;
    vec2 jit = ob_slice_jitters(pix, gtao.noise, noise_tile, vec2(gtao.slice_offset, gtao.step_offset));
    int slices = gtao.slices, steps = gtao.steps;

    float visibility = 0.0, open_sky = 0.0;
    vec3 bent = vec3(0.0); /* Σ |n_φ| (b(φ) - b_open(φ)), see the end */
    /* Slice k's direction at angle (k + jitter) π / N: the first from the jitter, each next one
     * turned by π / N (two sines per pixel instead of two per slice). */
    float phi0 = jit.x * OB_PI / float(slices), dphi = OB_PI / float(slices);
    vec2 dir = vec2(cos(phi0), sin(phi0));
    vec2 turn = vec2(cos(dphi), sin(dphi));
    for (int k = 0; k < slices; ++k, dir = vec2(dir.x * turn.x - dir.y * turn.y, dir.x * turn.y + dir.y * turn.x)) {
        ob_slice s;
        if (!ob_slice_setup(dir, p, v, n, d, to_view, gtao.radius, s)) continue;

        /* Both sides in one loop, the same distance on each: side 0 along +dir (θ > 0), side 1
         * along -dir (θ < 0). */
        vec2 rise = vec2(0.0), inside_px = vec2(0.0), gap_lo = vec2(0.0), gap_hi = vec2(0.0);
        for (int j = 0; j < steps; ++j) {
            float dist_px = ob_slice_step_px(j, jit.y, steps, s.radius_px);
            vec2 off = s.dir * dist_px;
            horizon_step(s, centre + off, dist_px, p, s.t_pos, rise.x, inside_px.x, gap_lo.x, gap_hi.x);
            horizon_step(s, centre - off, dist_px, p, s.t_neg, rise.y, inside_px.y, gap_lo.y, gap_hi.y);
        }
        /* The surface left the sphere of radius R between gap_lo and gap_hi. On a wall that
         * climbs away from P (every crease) the horizon within R is exactly where it leaves, so
         * sparse steps always stop short of it and read too little occlusion. Bisect that gap a
         * few times (after the march, so SIMD lanes stay in step): each halving halves the
         * shortfall, for one fetch. */
        for (int b = 0; b < REFINE_STEPS; ++b) {
            horizon_refine(s, centre, 1.0, p, s.t_pos, rise.x, gap_lo.x, gap_hi.x);
            horizon_refine(s, centre, -1.0, p, s.t_neg, rise.y, gap_lo.y, gap_hi.y);
        }
        /* h: each side's horizon angle from V toward its side, the tangent's angle (π/2 ± n)
         * less the highest rise (rise_key inverted); a horizon on one side cannot pass V. eq. 10 with θ signed: the
         * horizon of side 1 is at -h.y, that of side 0 at h.x. */
        vec2 h = max(vec2(OB_HALF_PI + s.ang_n, OB_HALF_PI - s.ang_n) - 2.0 * asin(sqrt(min(0.5 * rise, vec2(1.0)))),
                     vec2(0.0));
        float h0 = -h.y, h1 = h.x;
        float a = 0.25 * (-cos(2.0 * h0 - s.ang_n) + s.cos_n + 2.0 * h0 * s.sin_n) +
                  0.25 * (-cos(2.0 * h1 - s.ang_n) + s.cos_n + 2.0 * h1 * s.sin_n);
        visibility += s.len_n * a;
        /* The same slice with nothing above its tangents: â(n + π/2) + â(n - π/2) = cos n + n sin n. */
        open_sky += s.len_n * (s.cos_n + s.ang_n * s.sin_n);
        if (gtao.bent_normals != 0)
            bent += s.len_n * (slice_bent(h0, h1, s.ang_n, v, s.o) -
                               slice_bent(s.ang_n - OB_HALF_PI, s.ang_n + OB_HALF_PI, s.ang_n, v, s.o));
    }
    /* The mean over slices of |n_φ| a(φ) is the φ integral only in the limit: with a few slices
     * an open surface seen at an angle reads 0.990-1.010 (corner, 3 slices). Dividing by the same
     * quadrature of the unoccluded hemisphere, whose exact integral is 1, makes open surfaces
     * exactly 1 at any slice count and converges to the same value. */
    imageStore(ao_out, pix, vec4(open_sky > 0.0 ? clamp(visibility / open_sky, 0.0, 1.0) : 1.0));
    if (gtao.bent_normals != 0) {
        /* The bent normal: the visible hemisphere's cosine-weighted mean direction. Open, it is
         * 2/3 n exactly; the slices estimate only how occlusion moves it from there (the same
         * quadrature of the open hemisphere subtracted, as for the visibility), so an open
         * surface gets its own normal at any slice count. */
        vec3 b = (2.0 / 3.0) * n + bent / float(slices);
        imageStore(bent_out, pix, vec4(dot(b, b) > 1e-12 ? normalize(b) : n, 0.0));
    }
}
