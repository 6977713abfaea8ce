/* The visibility bitmask of a slice (Therrien, Levesque & Gilet 2023, §3.1-3.2): 32 sectors
 * uniform in angle over the half circle above P's tangent, θ' = θ - n(φ) in [-π/2, π/2] around
 * the projected normal; bit i covers the fraction [i, i + 1] / 32 of it, from the tangent on the
 * side opposite dir (0) to the tangent on dir's side (1). Pure functions of their arguments, so
 * tests/test_bitmask.c runs them through shaders/bitmask_probe.glsl against a C copy, bit for
 * bit. Used by visibility_bitmask.glsl (vbao, vbgi); include after slice_march.glsl (ob_fast_atan2). */
#ifndef OB_BITMASK_GLSL
#define OB_BITMASK_GLSL

#include "ob_enums.h" /* OB_SECTOR_COVERAGE_* */

const int OB_SECTORS = 32;
const float OB_BITMASK_PI = 3.14159265358979;

/* The rise above a side's tangent t of the in-slice offset w at slice coordinates xy =
 * (dot(w, t), dot(w, n_slice)) (see ob_rise_key in slice_march.glsl), in [0, π]; 0 on or below
 * the tangent. A sample on P's own plane rises by rounding alone, and the `touch` rule would
 * turn that into a whole sector: rises under OB_RISE_EPSILON count as none. 1e-3 rad (0.06°, a
 * hundredth of a sector) is the angle of the G-buffer's RGBA16F normals (half an fp16 ulp at 1
 * is 4.9e-4 per component): with 1e-4 an NVIDIA H100 read the corner's open floor 0.9992 under
 * `touch`, where llvmpipe's rounding (|y| ~ 1e-7 |w|) stayed under it
 * (bench/results/2026-11-23-h100-egl.md). */
const float OB_RISE_EPSILON = 1e-3;

float ob_rise_angle_of(vec2 xy)
{
    float rise = xy.y > 0.0 ? ob_fast_atan2(xy.y, xy.x) : 0.0;
    return rise > OB_RISE_EPSILON ? rise : 0.0;
}

/* The sectors [lo, hi] (fractions of the half circle) sets under `coverage`. An empty interval
 * sets nothing. All three rules are worked out and one selected: the choice is uniform, but
 * llvmpipe runs both sides of any branch inside the divergent march. */
uint ob_sector_bits(float lo, float hi, int coverage)
{
    float a = lo * float(OB_SECTORS), b = hi * float(OB_SECTORS);
    vec3 start = vec3(floor(a), ceil(a - 0.5), ceil(a)); /* touch, half (centre inside), all */
    vec3 end = vec3(ceil(b), floor(b + 0.5), floor(b));
    int c = clamp(coverage, OB_SECTOR_COVERAGE_TOUCH, OB_SECTOR_COVERAGE_ALL);
    int s0 = int(clamp(start[c], 0.0, float(OB_SECTORS))), e0 = int(clamp(end[c], 0.0, float(OB_SECTORS)));
    int count = hi > lo ? e0 - s0 : 0;
    return count > 0 ? (0xFFFFFFFFu >> uint(OB_SECTORS - count)) << uint(s0) : 0u;
}

/* The sectors a sample sets, from the rises of its front and back above its side's tangent
 * (§3.2: the back is the front pushed away from the eye by the thickness). Side + (`positive`,
 * along dir) has its tangent at 1 and rises toward V, side - has it at 0; a sample on one side
 * cannot occlude the other side of V, at u0 = (π/2 - n) / π. */
uint ob_sample_bits(float rise_front, float rise_back, float ang_n, bool positive, int coverage)
{
    float u0 = (0.5 * OB_BITMASK_PI - ang_n) / OB_BITMASK_PI;
    vec2 r = vec2(rise_front, rise_back) / OB_BITMASK_PI;
    vec2 u = positive ? clamp(1.0 - r, u0, 1.0) : clamp(r, 0.0, u0);
    return ob_sector_bits(min(u.x, u.y), max(u.x, u.y), coverage);
}

/* ∫_0^θ cos(θ' - n) |sin θ'| dθ' with the sign of θ (Jimenez et al. 2016 eq. 10's â made odd), so
 * that the cosine weight of [θa, θb] is S(θb) - S(θa) on either side of V. */
float ob_sector_s(float theta, float ang_n, float cos_n, float sin_n)
{
    float a = 0.25 * (-cos(2.0 * theta - ang_n) + cos_n + 2.0 * theta * sin_n);
    return theta < 0.0 ? -a : a;
}

/* The cosine weight of `count` sectors from sector `first` on. */
float ob_run_measure(int first, int count, float ang_n, float cos_n, float sin_n)
{
    const float width = OB_BITMASK_PI / float(OB_SECTORS);
    float t0 = ang_n - 0.5 * OB_BITMASK_PI + float(first) * width;
    return ob_sector_s(t0 + float(count) * width, ang_n, cos_n, sin_n) - ob_sector_s(t0, ang_n, cos_n, sin_n);
}

/* The cosine weight of a set of sectors, without a loop over its runs. Sector i spans
 * [θ_i, θ_i+1], θ_b = n - π/2 + b π/32, and weighs S(θ_i+1) - S(θ_i) (ob_sector_s), so a run
 * [s, e) weighs S(θ_e) - S(θ_s) and the mask Σ_b c_b S(θ_b), with c_b = +1 where a run ends at
 * boundary b, -1 where one starts, 0 elsewhere. With the angle sum,
 *   -cos(2θ_b - n) = cos(n + b π/16) = cos n C_b - sin n S_b,   C_b = cos(b π/16), S_b = sin(b π/16),
 * so S(θ_b) = ±1/4 (cos n (1 + C_b) - sin n S_b + 2 θ_b sin n), and the measure is three sums over
 * the boundaries of constants that do not depend on the pixel, taken in one straight pass over
 * the 32 bits: a loop over the runs ran, on llvmpipe, as many times as the SIMD group's most
 * broken mask, and took a quarter of vbao's pass (docs/methods.md). The sign is θ_b's: the
 * boundaries below V get -1, folded into which of two masks a transition goes to. */
float ob_bits_measure(uint bits, float ang_n, float cos_n, float sin_n)
{
    uint starts = bits & ~(bits << 1u); /* boundary b = i where a run starts at sector i */
    uint ends = ~bits & (bits << 1u);   /* boundary b = i where a run ends before sector i (i >= 1) */
    /* Boundaries below V (θ_b < 0): b < (π/2 - n) 32/π; at θ_b = 0 S is 0 either way. */
    int below = int(clamp(ceil((0.5 * OB_BITMASK_PI - ang_n) * float(OB_SECTORS) / OB_BITMASK_PI), 0.0, 32.0));
    uint neg = below >= 32 ? 0xFFFFFFFFu : (1u << uint(below)) - 1u;
    uint plus = (ends & ~neg) | (starts & neg), minus = (starts & ~neg) | (ends & neg);
    float sum_c = 0.0, sum_s = 0.0, sum_b = 0.0, sum_k = 0.0; /* Σ k (1 + C_b), Σ k S_b, Σ k b, Σ k */
    vec2 cs = vec2(1.0, 0.0);                                 /* (C_b, S_b) */
    const vec2 turn = vec2(cos(OB_BITMASK_PI / 16.0), sin(OB_BITMASK_PI / 16.0));
    for (int b = 0; b < OB_SECTORS; ++b) {
        float k = float((plus >> uint(b)) & 1u) - float((minus >> uint(b)) & 1u);
        sum_c += k * (1.0 + cs.x);
        sum_s += k * cs.y;
        sum_b += k * float(b);
        sum_k += k;
        cs = vec2(cs.x * turn.x - cs.y * turn.y, cs.x * turn.y + cs.y * turn.x);
    }
    /* Boundary 32 (the tangent on dir's side, θ = n + π/2 > 0: C = 1, S = 0) ends the last run. */
    float k32 = float(bits >> 31u);
    sum_c += 2.0 * k32;
    sum_b += 32.0 * k32;
    sum_k += k32;
    /* Σ k θ_b = (n - π/2) Σ k + π/32 Σ k b. */
    float sum_theta = (ang_n - 0.5 * OB_BITMASK_PI) * sum_k + OB_BITMASK_PI / float(OB_SECTORS) * sum_b;
    return 0.25 * (cos_n * sum_c - sin_n * sum_s + 2.0 * sin_n * sum_theta);
}

#endif
