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
#include "noise.glsl"

layout(local_size_x = OB_GTAO_GROUP_X, local_size_y = OB_GTAO_GROUP_Y) in;

layout(binding = 0) uniform sampler2D linear_depth; /* R32F, 0 = no geometry */
layout(binding = 1) uniform sampler2D view_normal;  /* RGBA16F */
layout(binding = 2) uniform sampler2D noise_tile;   /* RG32F 4x4 rotation vectors */
layout(binding = 3) uniform sampler2D depth_mips;   /* R32F MIP chain of linear depth (level 0 = linear_depth);
                                                       without the chain, linear_depth itself */
layout(binding = 0, r32f) uniform writeonly image2D ao_out;
layout(binding = 1, rgba16f) uniform writeonly image2D bent_out; /* view-space bent normal (bent_normals = 1) */

const float PI = 3.14159265358979;
const float HALF_PI = 1.57079632679490;

/* STEPS: uniform strata of [1.5 px, R's projection] (XeGTAO squares them toward the centre).
 * With the definition's hard cut at R, the horizon of a crease is where the wall leaves the
 * sphere of radius R, at the far end of the search; on the training views squared steps read
 * more too-open bias (docs/methods.md). */

/* 4x4 ordered-dither ranks: every value 0..15 once per tile (the same ranks as hbao.glsl). */
const float bayer4[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0,
                                   3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

/* Per-pixel jitters in [0, 1) of the slice angles (x) and of the step distances (y).
 *   texture4: the slice jitter is the angle of the 4x4 rotation tile (16 shuffled angles) and the
 *     step jitter the 4x4 Bayer rank; the two are unrelated, and a 4x4 window averages all 16 of
 *     each exactly (seed 004 §3.3);
 *   ign: interleaved gradient noise of the pixel and of the transposed pixel (see hbao.glsl).
 * gtao.slice_offset / step_offset move both along an R2 sequence with the frame index when
 * temporal noise is on. */
vec2 jitters(ivec2 pix)
{
    vec2 j;
    if (gtao.noise == OB_NOISE_IGN) {
        j = vec2(ob_interleaved_gradient_noise(vec2(pix)), ob_interleaved_gradient_noise(vec2(pix.yx)));
    } else {
        vec2 r = texelFetch(noise_tile, pix % 4, 0).xy;
        ivec2 t = pix % 4;
        j = vec2(fract(atan(r.y, r.x) / (2.0 * PI) + 1.0), (bayer4[t.y * 4 + t.x] + 0.5) / 16.0);
    }
    return fract(j + vec2(gtao.slice_offset, gtao.step_offset));
}

/* Depth at texel q of MIP `level` and the centre of the full-resolution pixel it came from. The
 * chain's level 0 is the AO grid's depth itself (without the chain, unit 3 holds that depth and
 * every level is 0), so there is one fetch path and no branch: llvmpipe runs both sides of a
 * branch its lanes disagree on, and a second fetch path per sample doubled gtao's cost.
 * The chain picks one child per level, SAO's rotated grid (shaders/depth_mips.glsl: texel p of
 * level L is texel 2p + (p.y & 1, p.x & 1) of level L - 1), so following the same picks back down
 * finds the one pixel whose depth a coarse texel holds, and the sample is reconstructed where
 * that surface point really is: exact on planes, as at level 0. (Where the pick was sky and a
 * sibling's depth stood in, the centre is a pixel off.) Beyond a level's last texel (odd sizes)
 * the chain holds nothing: clamp, as the pass does (GL's level size, max(1, size >> L)). */
float sample_depth(ivec2 q, int level, ivec2 size, out vec2 centre)
{
    ivec2 ql = min(q >> level, max(size >> level, ivec2(1)) - 1);
    float sd = texelFetch(depth_mips, ql, level).r;
    ivec2 c = ql;
    for (int l = level; l > 0; --l) c = 2 * c + ivec2(c.y & 1, c.x & 1);
    centre = vec2(c) + 0.5;
    return sd;
}

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

/* atan2 to about 2e-4 rad (a minimax polynomial on [0, 1] after folding the octants), for the
 * per-sample angle: the GLSL built-in costs several times as much on llvmpipe, and 1e-5 rad is
 * far below what the depth buffer resolves (about 1e-4 of visibility). y = 0 gives exactly 0, so samples on P's plane
 * still rise by exactly nothing. */
float fast_atan2(float y, float x)
{
    float ax = abs(x), ay = abs(y);
    float hi = max(ax, ay);
    if (hi <= 0.0) return 0.0;
    float a = min(ax, ay) / hi;
    float a2 = a * a;
    float r = ((-0.0464964749 * a2 + 0.15931422) * a2 - 0.327622764) * a2 * a + a;
    if (ay > ax) r = HALF_PI - r;
    if (x < 0.0) r = PI - r;
    return y < 0.0 ? -r : r;
}

/* What a sample told the horizon search. */
const int SAMPLE_NONE = 0;   /* sky, P's own texel or straight along the view ray: no occluder */
const int SAMPLE_INSIDE = 1; /* a surface point within R (weight > 0): theta is its horizon angle */
const int SAMPLE_BEYOND = 2; /* a surface point at R or farther */

/* Bisections of the last gap in which the surface leaves the sphere of radius R (see main). */
const int REFINE_STEPS = 2;

/* The sample at AO-grid position `at`, dist_px from P along the slice: its horizon angle from V
 * on this side (the tangent's angle minus the sample's weighted rise above the tangent t). A
 * sample beyond R gets the angle it would have inside, for deciding whether to refine. */
int sample_theta(vec2 at, float dist_px, vec3 p, vec3 n, vec3 t, float inv_len_n, float tangent, out float theta)
{
    theta = tangent;
    /* floor(log2(dist x mip_scale)) as the position of the highest set bit: no log2 per sample
     * (below 1 findMSB gives -1, clamped to 0). max_mip is 0 without the chain. */
    int level = clamp(findMSB(int(dist_px * gtao.mip_scale)), 0, gtao.max_mip);
    vec2 qc;
    float sd = sample_depth(ivec2(floor(at)), level, ivec2(frame.ao_size), qc);
    if (sd <= 0.0) return SAMPLE_NONE; /* sky: nothing there */
    vec3 w = ob_view_position(qc, sd, frame.ao_inv_size, frame.ao_proj_info) - p;
    if (dot(w, w) <= 0.0) return SAMPLE_NONE;
    float w_len = length(vec3(w.xy, w.z * (1.0 + gtao.thin)));
    float weight = clamp(w_len * gtao.falloff_mul + gtao.falloff_add, 0.0, 1.0);
    /* The sample's angle above the tangent, in the slice's coordinates: along the tangent,
     * dot(w, t); across it, toward the normal, dot(w, n) / |n_φ| (the normal's part across the
     * slice is perpendicular to every in-slice direction). A sample on P's plane gives exactly 0,
     * also where snapping to the texel centre moved it off the slice, so open planes read exactly
     * 1 (the sample's own angle from V would sit above this slice's tangent there). atan2 keeps
     * angles past the slice's zenith, which occluders on the side the normal leans away from
     * reach. eq. 6-7 with AO_R's range: the horizon rises to the sample by its weight. */
    float rise = fast_atan2(dot(w, n) * inv_len_n, dot(w, t));
    if (weight <= 0.0) {
        theta = tangent - max(rise, 0.0);
        return SAMPLE_BEYOND;
    }
    theta = tangent - weight * max(rise, 0.0);
    return SAMPLE_INSIDE;
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
    float radius = gtao.radius;
    vec2 jit = jitters(pix);
    int slices = gtao.slices, steps = gtao.steps;

    float visibility = 0.0, open_sky = 0.0;
    vec3 bent = vec3(0.0); /* Σ |n_φ| (b(φ) - b_open(φ)), see the end */
    /* Slice k's direction at angle (k + jitter) π / N: the first from the jitter, each next one
     * turned by π / N (two sines per pixel instead of two per slice). */
    float phi0 = jit.x * PI / float(slices), dphi = PI / float(slices);
    vec2 dir = vec2(cos(phi0), sin(phi0));
    vec2 turn = vec2(cos(dphi), sin(dphi));
    for (int k = 0; k < slices; ++k, dir = vec2(dir.x * turn.x - dir.y * turn.y, dir.x * turn.y + dir.y * turn.x)) {
        /* The slice: the plane through the eye and the screen line through P along dir. Its
         * normal is P x (the view offset of a step along dir), exact for any pixel aspect and an
         * off-centre frustum; o is dir's side of the slice, perpendicular to V. */
        vec3 dv = vec3(dir * to_view, 0.0);
        vec3 axis = normalize(cross(v, dv));
        vec3 o = cross(axis, v);
        /* n(φ) and |n_φ| (eq. 5): the normal projected onto the slice. */
        vec3 pn = n - axis * dot(n, axis);
        float len_n = length(pn);
        /* A normal (almost) across the slice: the slice carries no weight (|n_φ| ~ 0). */
        if (len_n < 1e-4) continue;
        float inv_len_n = 1.0 / len_n;
        float cos_n = dot(pn, v) * inv_len_n, sin_n = dot(pn, o) * inv_len_n;
        float ang_n = fast_atan2(sin_n, cos_n);
        /* R along this screen direction, in AO pixels. */
        float radius_px = radius / (d * length(dir * to_view));

        /* side 0 marches along +dir (θ > 0), side 1 along -dir (θ < 0). h[s] is the horizon's
         * angle from V measured toward its side, starting at the tangent, so it never drops
         * below the surface. */
        float h[2];
        for (int side = 0; side < 2; ++side) {
            float sgn = side == 0 ? 1.0 : -1.0;
            /* The surface falls away on the side the normal leans to: its tangent lies at
             * π/2 + n from V on side 0 and at π/2 - n on side 1. */
            float tangent = HALF_PI + sgn * ang_n;
            /* The tangent's unit direction: cos(π/2 + sgn n) v + sin(π/2 + sgn n) sgn o. */
            vec3 t = (-sgn * sin_n) * v + (sgn * cos_n) * o;
            float horizon = tangent;
            /* The last step within R (0 = P itself), and the first gap in which the surface
             * leaves the sphere of radius R, for the refinement below. */
            float inside_px = 0.0, gap_lo = 0.0, gap_hi = 0.0;
            for (int j = 0; j < steps; ++j) {
                float s = (float(j) + jit.y) / float(steps);
                /* Uniform strata (see STEPS above), at least 1.5 px out, so the first step never
                 * reads P's own texel. */
                float dist_px = 1.5 + s * max(radius_px - 1.5, 0.0);
                if (dist_px > radius_px) break;
                vec2 at = centre + sgn * dir * dist_px;
                if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, vec2(size)))) break;
                float theta = 0.0;
                int status = sample_theta(at, dist_px, p, n, t, inv_len_n, tangent, theta);
                if (status == SAMPLE_INSIDE) {
                    horizon = min(horizon, theta);
                    inside_px = dist_px;
                } else if (status == SAMPLE_BEYOND && gap_hi == 0.0 && theta < horizon) {
                    /* Only where the surface out there stands above the horizon so far can the
                     * part of it inside R raise the horizon (not on an open floor, say). */
                    gap_lo = inside_px;
                    gap_hi = dist_px;
                }
            }
            /* The surface left the sphere of radius R between gap_lo and gap_hi. On a wall that
             * climbs away from P (every crease) the horizon within R is exactly where it leaves,
             * so sparse steps always stop short of it and read too little occlusion. Bisect that
             * gap a few times (after the march, so SIMD lanes stay in step): each halving halves
             * the shortfall, for one fetch. */
            for (int b = 0; b < REFINE_STEPS && gap_hi > 0.0; ++b) {
                float mid = 0.5 * (gap_lo + gap_hi), theta = 0.0;
                if (sample_theta(centre + sgn * dir * mid, mid, p, n, t, inv_len_n, tangent, theta) == SAMPLE_INSIDE) {
                    horizon = min(horizon, theta);
                    gap_lo = mid;
                } else {
                    gap_hi = mid;
                }
            }
            h[side] = max(horizon, 0.0); /* a horizon on this side cannot pass V */
        }
        /* eq. 10 with θ signed: the horizon of side 1 is at -h[1], that of side 0 at h[0]. */
        float h0 = -h[1], h1 = h[0];
        float a = 0.25 * (-cos(2.0 * h0 - ang_n) + cos_n + 2.0 * h0 * sin_n) +
                  0.25 * (-cos(2.0 * h1 - ang_n) + cos_n + 2.0 * h1 * sin_n);
        visibility += len_n * a;
        /* The same slice with nothing above its tangents: â(n + π/2) + â(n - π/2) = cos n + n sin n. */
        open_sky += len_n * (cos_n + ang_n * sin_n);
        if (gtao.bent_normals != 0)
            bent += len_n * (slice_bent(h0, h1, ang_n, v, o) - slice_bent(ang_n - HALF_PI, ang_n + HALF_PI, ang_n, v, o));
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
