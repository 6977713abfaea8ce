#version 450 core
/* Ground-truth ambient occlusion (Jimenez, Wu, Pesce & Jarabo 2016, "Practical Realtime
 * Strategies for Accurate Indirect Occlusion", §4-5): the cosine-weighted visibility of
 * docs/architecture.md's AO_R, integrated analytically between two horizons per slice.
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
 * definition's hard cut; falloff f fades occluders over the last f R), and where the solid behind
 * a sample beyond R, at most gtao.column deep, enters the sphere of radius R (ob_column_entry).
 * Like every horizon method this treats the depth buffer as a height field: everything below the
 * horizon is occluded, so thin objects occlude too much behind them (`thin` stretches the depth
 * component of a sample's distance, as in Jimenez et al. §5's thickness heuristic, so thin
 * objects count less).
 *
 * AO is visibility: 1 = open. Sky (depth 0) writes 1. */
#include "gtao_params.h"
#include "common.glsl"
#include "slice_march.glsl"

layout(local_size_x = OB_GTAO_GROUP_X, local_size_y = OB_GTAO_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth; /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal; /* RGBA16F */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;   /* RG32F 4x4 rotation vectors */
/* R32F MIP chain of linear depth (level 0 = linear_depth) in the OB_MARCH_DEPTH_MIPS program;
 * otherwise linear_depth itself. */
layout(binding = OB_UNIT_SLICE_DEPTH_MIPS) uniform sampler2D depth_mips;
layout(binding = OB_UNIT_SLICE_MULTIPLIER) uniform sampler2D multiplier; /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D ao_out;
/* view-space bent normal (OB_GTAO_BENT) */
layout(binding = OB_IMAGE_UNIT_BENT_NORMAL, rgba16f) uniform writeonly image2D bent_out;

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

/* With a second depth layer (gtao.layers): does the current horizon ray pass behind the object under
 * a sample? The horizon-based integral takes everything below the highest sample as occluded,
 * each occluder infinitely thick behind its surface. The second layer bounds the object: on the
 * sample's view ray it occupies [z1, z2], and a sample between the layers is inside, one behind the
 * second free (Belonogov 2018 §4.4). Compiled in the OB_MARCH_LAYERS variant only (methods/method.h
 * OB_SLICE_LAYERS: llvmpipe would run the block for every sample with the layer off too). Apply that to the ray at the current horizon on this side: where it
 * crosses the sample's view ray (in the slice plane, which holds both) at depth z_h, z1 < z_h <= z2
 * means the ray runs into the object, so every direction between it and the sample is blocked and
 * the sample may raise the horizon; z_h > z2 means the ray passes behind the object, the directions
 * just above it are free, and the sample (a thin or floating occluder) must not raise it. With
 * z2 = 0 (nothing behind), or a crossing in front of the sample or behind the eye, the height
 * field's rule stands. In the slice: the horizon line through P at rise ρ (key = 1 - cos ρ) has the
 * in-slice normal m = -sin ρ t + cos ρ n_slice; the sample's view ray λ F (the eye at the origin)
 * meets it at λ = (p · m) / (F · m), at linear depth λ z1. z2 here is the sample's back, z1 plus
 * ob_layer_thickness.
 * Measured (docs/methods.md, "A second depth layer"): a horizon holds one angle per side, so a
 * floating or thin occluder that this rule rightly lets the low directions pass under is then not
 * counted at all, and the cosine weights those low directions least: on every view tried the
 * result is more open and further from AO_R than the height field. It stays an option (default
 * off) as the measured answer; vbao's intervals are where a second layer belongs. */
bool behind_object(vec3 w, vec3 p, vec3 t, vec3 n_slice, float rise, float z2)
{
    float c = 1.0 - rise, sn = sqrt(max(rise * (2.0 - rise), 0.0));
    float pm = -sn * dot(p, t) + c * dot(p, n_slice);
    float fm = pm - sn * dot(w, t) + c * dot(w, n_slice);
    float lambda = pm / fm;
    float z1 = -(p.z + w.z);
    /* An orthographic camera's view ray is F + mu (0, 0, -1): it meets the line where
     * (w + mu (0, 0, -1)) . m = 0, mu = (F . m - p . m) / m.z behind the sample, at depth z1 + mu. */
    float mu = (fm - pm) / (-sn * t.z + c * n_slice.z);
    return frame.orthographic != 0 ? mu > 0.0 && z1 + mu > z2 : lambda > 1.0 && lambda * z1 > z2;
}

/* A side's candidate for ob_column_entry: the highest sample beyond R whose column may still reach
 * the sphere. The march keeps it (a compare and a select per sample) and the entry is worked out
 * once per side after it (column_rise): on llvmpipe, which runs every sample's arithmetic for
 * every lane, the entry per sample cost gtao high 30 % of its pass. */
struct column_candidate {
    vec3 w;  /* the sample's offset from P */
    float k; /* its own rise key (0 = none yet) */
};

/* Bisections of the last gap in which the surface leaves the sphere of radius R (see main). */
const int REFINE_STEPS = 2;

/* One horizon-search step on one side of slice s, at AO-grid position `at`, dist_px from P;
 * t is that side's tangent. `rise` is the largest weighted ob_rise_key so far (0 = none).
 * eq. 6-7 with AO_R's range: a sample counts by its weight, faded in cosine as XeGTAO fades its
 * horizon cosines (falloff 0: weight 0 or 1, exact). `refine`: a bisection step of the gap, which
 * counts only while the gap is open. Selects, not branches: llvmpipe runs both sides of a branch
 * its lanes disagree on. */
void horizon_step(ob_slice s, vec2 at, float dist_px, vec3 p, vec3 t, bool refine, inout float rise, inout ob_gap gap,
                  inout column_candidate cand)
{
    vec3 w;
    ivec2 texel;
    /* Where R projects to under 1.5 px, the first step is already past it: no search. */
    bool hit = ob_march_fetch(depth_mips, at, dist_px, p, gtao.mip_scale, gtao.max_mip, w, texel) &&
               (refine ? ob_gap_open(gap) : dist_px <= s.radius_px);
    float w_len = length(vec3(w.xy, w.z * (1.0 + gtao.thin)));
    float weight = hit ? clamp(w_len * gtao.falloff_mul + gtao.falloff_add, 0.0, 1.0) : 0.0;
    float k = ob_rise_key(w, t, s.n_slice);
    /* Beyond R but within reach of its column: the side's candidate if it stands highest. */
    bool shell = hit && weight <= 0.0 && dot(w, w) <= gtao.column_shell2 && k > cand.k;
    cand.k = shell ? k : cand.k;
    cand.w = shell ? w : cand.w;
#ifdef OB_MARCH_LAYERS
    float z1 = -(p.z + w.z);
    float t2 = ob_layer_thickness(z1, ob_second_depth(texel), -p.z, gtao.radius, s.radius_px, gtao.steps);
    k = t2 > 0.0 && behind_object(w, p, t, s.n_slice, rise, z1 + t2) ? 0.0 : k;
#endif
    if (refine) ob_gap_halve(gap, weight > 0.0);
    else ob_gap_note(gap, weight > 0.0, hit && weight <= 0.0 && k > rise, dist_px);
    rise = max(rise, weight * k);
}

/* The rise key of where the candidate's solid, up to gtao.column behind its front, enters the
 * sphere on which the weight reaches 1 (R itself with falloff 0); 0 when it does not. */
float column_rise(column_candidate cand, vec3 p, vec3 t, vec3 n_slice)
{
    vec3 entry;
    bool meets = cand.k > 0.0 &&
                 ob_column_entry(cand.w, normalize(ob_view_ray(p + cand.w)), gtao.full_reach, gtao.column, entry);
    return meets ? ob_rise_key(entry, t, n_slice) : 0.0;
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
#ifdef OB_GTAO_BENT
        imageStore(bent_out, pix, vec4(0.0));
#endif
        return;
    }
    vec2 centre, to_view;
    vec3 p, v, n;
    ob_slice_pixel(pix, d, view_normal, centre, p, v, n, to_view);
#ifdef OB_MARCH_FACETS
    vec3 facet = ob_facet_normal(pix);
#endif
    vec2 jit = ob_slice_jitters(pix, gtao.noise, noise_tile, vec2(gtao.slice_offset, gtao.step_offset));
    int slices = ob_slice_count(pix, gtao.slices, gtao.adaptive, gtao.adaptive_base, multiplier), steps = gtao.steps;

    float visibility = 0.0, open_sky = 0.0;
    vec3 bent = vec3(0.0); /* Σ |n_φ| (b(φ) - b_open(φ)), see the end */
    vec2 dir = ob_slice_first_dir(jit.x, slices), turn = ob_slice_rotation(slices);
    for (int k = 0; k < slices; ++k, dir = ob_slice_turn(dir, turn)) {
        ob_slice s;
        if (!ob_slice_setup(dir, p, v, n, d, to_view, gtao.radius, s)) continue;

        /* Both sides in one loop, the same distance on each: side 0 along +dir (θ > 0), side 1
         * along -dir (θ < 0). */
        /* The horizon starts at P's own triangle where it rises above the tangent (the facet
         * wedge, slice_march.glsl ob_facet_trace): below it AO_R's rays enter the surface. Its key
         * as ob_rise_key's, 1 - cos(rise) = y^2 / (r (r + x)) with x = cos > 0 here. */
#ifdef OB_MARCH_FACETS
        bool wedge_pos;
        vec2 trace = ob_facet_trace(s, n, facet, wedge_pos);
        float trace_r = length(trace);
        float wedge = trace.y > tan(OB_FACET_EPSILON) * trace.x && trace.x > 0.0
                          ? trace.y * trace.y / (trace_r * (trace_r + trace.x))
                          : 0.0;
        vec2 rise = wedge_pos ? vec2(wedge, 0.0) : vec2(0.0, wedge);
#else
        vec2 rise = vec2(0.0);
#endif
        ob_gap gap_pos = ob_gap_none(), gap_neg = ob_gap_none();
        column_candidate cand_pos = column_candidate(vec3(0.0), 0.0), cand_neg = cand_pos;
        for (int j = 0; j < steps; ++j) {
            float dist_px = ob_slice_step_px(j, jit.y, steps, s.radius_px);
            vec2 off = s.dir * dist_px;
            horizon_step(s, centre + off, dist_px, p, s.t_pos, false, rise.x, gap_pos, cand_pos);
            horizon_step(s, centre - off, dist_px, p, s.t_neg, false, rise.y, gap_neg, cand_neg);
        }
        /* Bisect where the surface leaves the sphere of radius R (ob_gap in slice_march.glsl). */
        for (int b = 0; b < REFINE_STEPS; ++b) {
            /* Without a gap on either side a refinement step changes nothing: skipped. The one
             * branch of the march: most pixels (open surfaces) have no gap, so whole SIMD groups
             * skip its fetches, and a group whose lanes disagree runs it as a select would. */
            if (!ob_gap_open(gap_pos) && !ob_gap_open(gap_neg)) break;
            float mid_pos = ob_gap_mid(gap_pos), mid_neg = ob_gap_mid(gap_neg);
            horizon_step(s, centre + s.dir * mid_pos, mid_pos, p, s.t_pos, true, rise.x, gap_pos, cand_pos);
            horizon_step(s, centre - s.dir * mid_neg, mid_neg, p, s.t_neg, true, rise.y, gap_neg, cand_neg);
        }
        /* The solid behind each side's highest sample beyond R (ob_column_entry). */
        rise = max(rise, vec2(column_rise(cand_pos, p, s.t_pos, s.n_slice), column_rise(cand_neg, p, s.t_neg, s.n_slice)));
        /* h: each side's horizon angle from V toward its side, the tangent's angle (π/2 ± n)
         * less the highest rise (rise_key inverted); a horizon on one side cannot pass V. eq. 10 with θ signed: the
         * horizon of side 1 is at -h.y, that of side 0 at h.x. */
        vec2 h = max(vec2(OB_HALF_PI + s.ang_n, OB_HALF_PI - s.ang_n) - vec2(ob_rise_angle(rise.x), ob_rise_angle(rise.y)),
                     vec2(0.0));
        float h0 = -h.y, h1 = h.x;
        float a = 0.25 * (-cos(2.0 * h0 - s.ang_n) + s.cos_n + 2.0 * h0 * s.sin_n) +
                  0.25 * (-cos(2.0 * h1 - s.ang_n) + s.cos_n + 2.0 * h1 * s.sin_n);
        visibility += s.len_n * a;
        /* The same slice with nothing above its tangents: â(n + π/2) + â(n - π/2) = cos n + n sin n. */
        open_sky += s.len_n * (s.cos_n + s.ang_n * s.sin_n);
#ifdef OB_GTAO_BENT
        bent += s.len_n * (slice_bent(h0, h1, s.ang_n, v, s.o) -
                           slice_bent(s.ang_n - OB_HALF_PI, s.ang_n + OB_HALF_PI, s.ang_n, v, s.o));
#endif
    }
    /* The mean over slices of |n_φ| a(φ) is the φ integral only in the limit: with a few slices
     * an open surface seen at an angle reads 0.990-1.010 (corner, 3 slices). Dividing by the same
     * quadrature of the unoccluded hemisphere, whose exact integral is 1, makes open surfaces
     * exactly 1 at any slice count and converges to the same value. */
    imageStore(ao_out, pix, vec4(open_sky > 0.0 ? clamp(visibility / open_sky, 0.0, 1.0) : 1.0));
#ifdef OB_GTAO_BENT
    /* The bent normal: the visible hemisphere's cosine-weighted mean direction. Open, it is 2/3 n
     * exactly; the slices estimate only how occlusion moves it from there (the same quadrature of
     * the open hemisphere subtracted, as for the visibility), so an open surface gets its own
     * normal at any slice count. */
    vec3 b = (2.0 / 3.0) * n + bent / float(slices);
    imageStore(bent_out, pix, vec4(dot(b, b) > 1e-12 ? normalize(b) : n, 0.0));
#endif
}
