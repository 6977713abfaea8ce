#version 450 core
/* Horizon-based ambient occlusion (Bavoil & Sainz 2008, "Image-Space Horizon-Based Ambient
 * Occlusion"), as described in Belonogov 2018 §3.3 and Puri 2024 §2.4/§3.4:
 *
 *   A = 1 - 1/(2π) ∫_{θ=-π}^{π} ∫_{α=t(θ)}^{h(θ)} W(ω) cos(α) dα dθ                  (eq. 3.1)
 *     = 1 - 1/(2π) ∫ (sin h(θ) - sin t(θ)) W(θ) dθ,    W = max(0, 1 - r/R)            (eq. 3.2)
 *
 * θ is the azimuth around the view axis, α the elevation above the plane perpendicular to it,
 * t(θ) the elevation of the surface tangent and h(θ) the elevation of the horizon found by
 * marching the depth buffer (the neighbourhood is treated as a height field, Belonogov 2018 §3.3.1).
 * The θ integral is a sum over N_d screen directions 2πk/N_d, rotated per pixel (Puri 2024 §2.4:
 * NVIDIA's sample rotates its 4 directions randomly; Belonogov 2018 §3.3.1 blurs the noise away); each
 * direction marches N_s texel-snapped steps out to the world radius R projected to pixels
 * (Puri 2024 §3.4: the radius scales with depth and is clamped).
 *
 * AO is visibility: 1 = open. Sky (depth 0) writes 1.
 * `deinterleave on` compiles OB_DEINTERLEAVED: far steps read the nearest pixel of their own 4x4 class
 * (Bavoil 2014, as NVIDIA's HBAO+ marches its quarter-resolution layers); `depth_mips on`
 * OB_TAPS_DEPTH_MIPS: steps 20 px or more out read the depth MIP chain (SAO §2.2). Both in taps.glsl. */
#include "hbao_params.h"
#include "common.glsl"
#include "noise.glsl"
#include "taps.glsl"

layout(local_size_x = OB_HBAO_GROUP_X, local_size_y = OB_HBAO_GROUP_Y) in;

layout(binding = OB_UNIT_DEPTH) uniform sampler2D linear_depth;           /* R32F, 0 = no geometry */
layout(binding = OB_UNIT_NORMAL) uniform sampler2D view_normal;           /* RGBA16F */
layout(binding = OB_UNIT_NOISE) uniform sampler2D noise_tile;             /* RG32F 4x4 rotation vectors */
layout(binding = OB_UNIT_SAMPLE_MULTIPLIER) uniform sampler2D multiplier; /* adaptive: 1..3 per OB_EDGE_BLOCK^2 pixels */
layout(binding = OB_IMAGE_UNIT_OUT, r32f) uniform writeonly image2D ao_out;

/* 4x4 ordered-dither (Bayer) ranks: every value 0..15 once per tile. */
const float ob_bayer4[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0,
                                      3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

/* Where along each direction the first step lands, in [0,1). It must vary per pixel (a fixed
 * start turns the N_s rings of samples into visible contour bands) but independently of the
 * rotation, or each rotation would always march the same distances:
 *   - texture4: the 4x4 Bayer rank. The rotation texture is a shuffled 4x4 set (sampling.h), so
 *     the two are unrelated, and the 4x4 box blur averages all 16 jitters exactly, as it does the
 *     16 rotations (Puri 2024 §3.3);
 *   - ign: interleaved gradient noise of the transposed pixel. IGN weights x and y very unequally
 *     (0.067 vs 0.0058), so IGN(y, x) is a different low-discrepancy pattern from the IGN(x, y)
 *     that gives the rotation. */
float hbao_jitter(ivec2 pix, int mode)
{
    if (mode == OB_NOISE_IGN) return ob_interleaved_gradient_noise(vec2(pix.yx));
    ivec2 t = pix % 4;
    return (ob_bayer4[t.y * 4 + t.x] + 0.5) / 16.0;
}

/* sin of the elevation t of the surface tangent in the slice of the view-space direction D
 * (D.z = 0) through P (Puri 2024 §2.4: t = atan(T.z / |T.xy|)). The pixels on a screen line
 * through P see the plane through the eye, P and P + D, not the plane of D and the Z axis
 * through P; the tangent in that slice is the line where it meets P's tangent plane:
 *   T = (P x D) x n = D (P.n) - P (D.n),   oriented along D,
 * where `p` is the view ray through P (common.glsl ob_view_ray): P itself, or -Z for an
 * orthographic camera, whose slices are the planes of D and the Z axis (and pn = p.n),
 * so on a flat surface every sample of the slice lies exactly on T. The vertical-slice tangent
 * (D, -n.xy.D / n.z) is off by the perspective angle: with it the open floor of `corner` read
 * 0.957 with no angle bias, with this one 0.980 (the rest is texel snapping, see main), and 1.000
 * with both fixes. A surface seen exactly edge-on (T = 0) gets t = 0. */
float hbao_sin_tangent(vec3 p, float pn, vec3 n, vec2 d)
{
    float dn = dot(d, n.xy);
    vec3 t = vec3(d, 0.0) * pn - p * dn;
    float len2 = dot(t, t);
    if (len2 <= 1e-12 * dot(d, d) * dot(p, p)) return 0.0;
    float s = t.z * inversesqrt(len2);
    /* Orient T toward D on screen. P + λT projects to a screen offset along
     * T.xy * depth + P.xy * T.z (the derivative of P.xy / -P.z), not along T.xy: on surfaces
     * seen at a grazing angle T.z dominates and the sign of dot(T.xy, D) is wrong. With the
     * orthographic ray (0, 0, -1) this is T.xy, the orthographic projection's own. */
    return dot(t.xy * -p.z + p.xy * t.z, d) < 0.0 ? -s : s;
}

void main()
{
    ivec2 pix = ob_invocation_pixel(); /* taps.glsl */
    ivec2 size = ivec2(frame.ao_size);
    if (any(greaterThanEqual(pix, size))) return;

    float d = texelFetch(linear_depth, pix, 0).r;
    if (d <= 0.0) {
        imageStore(ao_out, pix, vec4(1.0));
        return;
    }
    float radius = hbao.radius;
    float inv_radius = hbao.inv_radius;
    /* R projected at P's depth: R_px = R * (height/2) * P11 / d (no d for an orthographic camera:
     * ob_depth_scale), clamped so that close-ups do not march (and miss the cache) across half the
     * screen. */
    float radius_px = min(radius * hbao.px_per_unit / ob_depth_scale(d), hbao.max_radius_px);
    if (radius_px < 1.0) {
        imageStore(ao_out, pix, vec4(1.0)); /* R covers less than a pixel: nothing to march */
        return;
    }

    vec2 centre = vec2(pix) + 0.5;
    vec3 p = ob_view_position(centre, d, frame.ao_inv_size, frame.ao_proj_info);
    vec3 n = normalize(texelFetch(view_normal, pix, 0).xyz);
    /* Interpolated vertex normals at a silhouette can face away from the camera. The tangent's
     * orientation (hbao_sin_tangent) then flips: marching inward over the visible surface
     * starts from a tangent pointing into the screen, and the whole surface reads as occluder
     * (single black pixels along the sphere's outline in `sphere-on-plane`). Tilt such normals
     * until they face the camera by a little. */
    vec3 ray = ob_view_ray(p);
    vec3 to_eye = -normalize(ray);
    float nv = dot(n, to_eye);
    if (nv < 0.02) n = normalize(n + (0.02 - nv) * to_eye);
    int mode = hbao.noise;
    vec2 rot = ob_rotation(pix, mode, noise_tile);
    float jitter = hbao_jitter(pix, mode);
    /* Adaptive sample counts (SSDO thesis §4.1): more directions at depth and normal edges. */
    int directions = hbao.adaptive != 0 ? hbao.adaptive_base * int(texelFetch(multiplier, pix / OB_EDGE_BLOCK, 0).r)
                                        : hbao.directions;
    int steps = hbao.steps;
    /* Step j (0-based) lands at 1 + (j + jitter) * (R_px - 1) / N_s pixels: the N_s steps
     * stratify [1, R_px) and the jitter shifts all of them together. Starting one pixel out
     * means the snapped first sample is never P's own texel (an offset of length >= 1 has a
     * component >= 1/sqrt(2), which floor(0.5 + c) always moves off the centre texel). */
    float step_px = (radius_px - 1.0) / float(steps);
    float start_px = 1.0 + jitter * step_px;
    float sin_bias = hbao.sin_bias, cos_bias = hbao.cos_bias;
    /* A screen offset (dx, dy) px is a view-space offset (dx/P00 * 2/w, dy/P11 * 2/h) * d at P's
     * depth (without d, orthographic): the same direction only for square pixels, so directions
     * are converted. */
    vec2 to_view = frame.ao_proj_info.xy * frame.ao_inv_size;
    float pn = dot(ray, n);

    float occlusion = 0.0;
    float angle_step = 6.28318530718 / float(directions);
    for (int k = 0; k < directions; ++k) {
        /* Evenly spaced azimuths 2πk/N_d, rotated by the per-pixel (cos, sin). */
        float a = angle_step * float(k);
        vec2 base = vec2(cos(a), sin(a));
        vec2 dir = vec2(base.x * rot.x - base.y * rot.y, base.x * rot.y + base.y * rot.x);

        /* sin(t + bias): the angle bias (NVIDIA's HBAO) lifts the tangent so that horizons only
         * slightly above it - the creases of a tessellated curved surface, depth and normal
         * quantisation - do not count as occlusion. */
        float sin_t = hbao_sin_tangent(ray, pn, n, dir * to_view);
        float cos_t = sqrt(max(1.0 - sin_t * sin_t, 0.0)); /* t in [-π/2, π/2] */
        /* t + bias stops at π/2: past it sin would fall again and lower the horizon. */
        float sin_h = sin_t >= cos_bias ? 1.0 : sin_t * cos_bias + cos_t * sin_bias;

        /* The incremental horizon of Bavoil & Sainz's own implementation: every sample that
         * rises above the horizon so far adds its rise (sin e - sin h) weighted by its own
         * W(r), and becomes the new horizon. The rises telescope to sin h - sin(t + bias), so
         * without attenuation this is eq. 3.2's integrand; with it, W is evaluated per horizon
         * rise instead of once at the final horizon, so a far occluder behind a near one adds
         * only what it adds above the near one, at its own (smaller) weight. */
        float ao_dir = 0.0;
        for (int j = 0; j < steps; ++j) {
            vec2 offset = dir * (start_px + float(j) * step_px);
            ivec2 q = ivec2(floor(centre + offset)); /* snap to the texel centre */
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) break;
            q = ob_tap_pixel(q, size);
            float sd = ob_tap_depth(linear_depth, q);
            if (sd <= 0.0) continue; /* sky: no occluder there */
            vec2 snapped = vec2(q) + 0.5;
            vec3 s = ob_view_position(snapped, sd, frame.ao_inv_size, frame.ao_proj_info);
            vec3 h = s - p;
            float r2 = dot(h, h);
            if (r2 >= radius * radius || r2 <= 0.0) continue; /* W = 0 beyond R */
            float r = sqrt(r2);
            float sin_e = h.z / r;
            /* Snapping moves the sample off slice k into a slice of its own, where the tangent
             * has another elevation; on a surface seen at a grazing angle a few degrees of
             * azimuth change it a lot, and the max over the samples turns that scatter into
             * occlusion (the open floor of `corner` read 0.980 instead of 1 with no bias).
             * Carry the sample into slice k by its rise above the tangent of its own slice:
             * exact on any plane, one more tangent per sample. */
            sin_e += sin_t - hbao_sin_tangent(ray, pn, n, (snapped - centre) * to_view);
            if (sin_e > sin_h) {
                ao_dir += max(0.0, 1.0 - r * inv_radius) * (sin_e - sin_h);
                sin_h = sin_e;
            }
        }
        occlusion += ao_dir;
    }
    /* The 1/(2π) ∫ dθ of eq. 3.2 is the mean over the N_d directions. */
    float ao = clamp(1.0 - hbao.intensity * occlusion / float(directions), 0.0, 1.0);
    imageStore(ao_out, pix, vec4(ao));
}
