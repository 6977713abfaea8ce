#version 450 core
/* The crease-preserving denoiser (`crease`, src/filters/crease.c; issue 13). A small centred
 * window whose weights come from the receiver's plane rather than from a wide spatial kernel:
 *
 *   (1) spatial:  s(o) = b(o.x) b(o.y),  b(i) = 1 for |i| < r, 1/2 for |i| = r.
 *       With r = 2 that is [1/2 1 1 1 1/2] per axis: every residue mod 4 gets total weight 1, so
 *       a 4x4-periodic pattern (the rotation tile of noise.glsl, seed 004 §3.3) sums to its mean
 *       exactly, as box4 does, but centred on p (box4's -2..1 shifts the image by half a pixel).
 *   (2) plane:    x_q = |n_p . (P_q - P_p)| / d_p,  g_q = exp(-x_q^2 / 2 s_p^2)
 *       the distance of q's view position from p's tangent plane, relative to p's depth so the
 *       same s_p works in metres and millimetres. Along p's own plane x_q = 0 at any distance and
 *       any viewing angle (a grazing floor is not cut up as a depth test would cut it); a depth
 *       step or a surface behind a silhouette is off the plane.
 *   (3) normal:   h_q = exp(-theta_q^2 / 2 s_n^2),  theta_q = acos(n_p . n_q)
 *       a wall meeting the floor passes through the floor's plane at the crease itself, where
 *       (2) cannot tell them apart; the normals can.
 *   (4) pairs:    w(+o) = w(-o) = s(o) min(g h (+o), g h (-o))
 *       Each offset is weighed together with its mirror. Where the wall cuts the window off on
 *       one side, the other side loses the same taps, so the window's centroid stays at p and AO
 *       that varies linearly across it keeps its value at p. Near a crease AO does vary about
 *       linearly: AO_R(h) = 1 - (acos a - a sqrt(1 - a^2)) / pi, a = h/R (DESIGN.md
 *       "Conventions") has slope 2/(pi R) at the crease. A one-sided window (as geometry's 11x11
 *       Gaussian along the floor) averages p with floor farther from the wall, which is brighter:
 *       that was issue 13's +0.26 at the corner crease.
 *   B_p = sum_o w(o) I(p + o) / sum_o w(o); the centre has s = 1, g = h = 1, so W_p >= 1.
 * Taps outside the image or on the sky (depth 0) have g h = 0 (and so do their mirrors); sky
 * pixels are written as the sky's value. View positions are rebuilt exactly as the methods
 * rebuild them (common.glsl ob_view_position with the frame's AO-grid projection), so the plane
 * test agrees with the geometry the AO was computed on, at every --ao-scale. */
#include "filter_params.h"
#include "frame_params.h"
#include "common.glsl"

layout(local_size_x = OB_FILTER_GROUP_X, local_size_y = OB_FILTER_GROUP_Y) in;

layout(binding = 0) uniform sampler2D ao_in;
layout(binding = 1) uniform sampler2D linear_depth;
layout(binding = 2) uniform sampler2D view_normal;
layout(binding = 0, OB_FILTER_FORMAT) uniform writeonly image2D ao_out;

/* g h of eq. (2)-(3) for tap q, 0 off the image or on the sky. */
float range_weight(ivec2 q, ivec2 size, vec3 pp, vec3 np, float inv_dp)
{
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return 0.0;
    float dq = texelFetch(linear_depth, q, 0).r;
    if (dq <= 0.0) return 0.0;
    vec3 pq = ob_view_position(vec2(q) + 0.5, dq, frame.ao_inv_size, frame.ao_proj_info);
    float x = dot(np, pq - pp) * inv_dp;
    /* RGBA16F normals can give a dot a hair above 1: clamp before acos. */
    float theta = acos(clamp(dot(np, texelFetch(view_normal, q, 0).xyz), -1.0, 1.0));
    return exp(x * x * flt.depth_falloff + theta * theta * flt.normal_falloff);
}

#ifdef OB_CREASE_TILED
/* The tiled program (`tiled` on, radius <= OB_CREASE_TILE_RADIUS): the work group first turns its
 * (8 + 2r)^2 texels into view positions, normals and AO in shared memory, once each, where the
 * plain program fetched and rebuilt every one of them for each of the up to 25 pixels whose
 * window covers it (24 range weights a pixel, each two fetches and a reconstruction). The weights
 * are the same equations; acos becomes Abramowitz & Stegun 4.4.45 (|error| <= 6.7e-5 rad, so
 * theta^2 / 2 s_n^2 moves by under 1e-3 of itself at s_n = 20 deg), and exp an exp2 with the
 * falloffs scaled by log2(e) on the CPU. The plain program stays as the baseline (tiled off). */
const int TILE_W = OB_FILTER_GROUP_X + 2 * OB_CREASE_TILE_RADIUS;
const int TILE_H = OB_FILTER_GROUP_Y + 2 * OB_CREASE_TILE_RADIUS;
shared vec4 tile_pos[TILE_H][TILE_W];    /* view position, w = 1 on geometry inside the image, else 0 */
shared vec3 tile_normal[TILE_H][TILE_W];
shared OB_FILTER_T tile_ao[TILE_H][TILE_W];

float fast_acos(float x)
{
    float a = abs(x);
    float r = sqrt(1.0 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
    return x < 0.0 ? 3.14159265 - r : r;
}

void main()
{
    ivec2 size = flt.size;
    int r = flt.radius;
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * ivec2(OB_FILTER_GROUP_X, OB_FILTER_GROUP_Y) - ivec2(r);
    int tw = OB_FILTER_GROUP_X + 2 * r, th = OB_FILTER_GROUP_Y + 2 * r;
    for (int i = int(gl_LocalInvocationIndex); i < tw * th; i += OB_FILTER_GROUP_X * OB_FILTER_GROUP_Y) {
        ivec2 t = ivec2(i % tw, i / tw);
        ivec2 q = origin + t;
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
        ivec2 qc = clamp(q, ivec2(0), size - 1);
        float dq = texelFetch(linear_depth, qc, 0).r;
        bool valid = inside && dq > 0.0;
        vec3 pq = ob_view_position(vec2(qc) + 0.5, dq, frame.ao_inv_size, frame.ao_proj_info);
        tile_pos[t.y][t.x] = vec4(pq, valid ? 1.0 : 0.0);
        tile_normal[t.y][t.x] = texelFetch(view_normal, qc, 0).xyz;
        tile_ao[t.y][t.x] = OB_FILTER_FETCH(ao_in, qc);
    }
    barrier();
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pix, size))) return;
    ivec2 c = ivec2(gl_LocalInvocationID.xy) + ivec2(r);
    vec4 pp = tile_pos[c.y][c.x];
    if (pp.w == 0.0) {
        imageStore(ao_out, pix, OB_FILTER_SKY);
        return;
    }
    vec3 np = tile_normal[c.y][c.x];
    float inv_dp = -1.0 / pp.z; /* the linear depth d_p = -z */
    float weight = 1.0;
    OB_FILTER_T sum = tile_ao[c.y][c.x];
    /* Half of the window, (y > 0) or (y = 0, x > 0); each offset brings its mirror (eq. 4). Row 0
     * starts at x = 1 rather than skipping x <= 0 with a `continue`: llvmpipe runs a skipped
     * iteration's body anyway (masked), a fifth of the pairs at r = 2. */
    for (int y = 0; y <= r; ++y) {
        for (int x = y == 0 ? 1 : -r; x <= r; ++x) {
            ivec2 a = c + ivec2(x, y), b = c - ivec2(x, y);
            vec4 pa = tile_pos[a.y][a.x], pb = tile_pos[b.y][b.x];
            float xa = dot(np, pa.xyz - pp.xyz) * inv_dp, xb = dot(np, pb.xyz - pp.xyz) * inv_dp;
            float ta = fast_acos(clamp(dot(np, tile_normal[a.y][a.x]), -1.0, 1.0));
            float tb = fast_acos(clamp(dot(np, tile_normal[b.y][b.x]), -1.0, 1.0));
            float ga = pa.w * exp2(xa * xa * flt.depth_falloff + ta * ta * flt.normal_falloff);
            float gb = pb.w * exp2(xb * xb * flt.depth_falloff + tb * tb * flt.normal_falloff);
            float w = flt.weights[abs(x)].x * flt.weights[y].x * min(ga, gb);
            sum += w * (tile_ao[a.y][a.x] + tile_ao[b.y][b.x]);
            weight += 2.0 * w;
        }
    }
    imageStore(ao_out, pix, vec4(sum / weight));
}
#else
void main()
{
    ivec2 pix = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = flt.size;
    if (any(greaterThanEqual(pix, size))) return;
    float dp = texelFetch(linear_depth, pix, 0).r;
    if (dp <= 0.0) {
        imageStore(ao_out, pix, OB_FILTER_SKY);
        return;
    }
    vec3 pp = ob_view_position(vec2(pix) + 0.5, dp, frame.ao_inv_size, frame.ao_proj_info);
    vec3 np = texelFetch(view_normal, pix, 0).xyz;
    float inv_dp = 1.0 / dp;
    int r = flt.radius;
    float weight = 1.0;
    OB_FILTER_T sum = OB_FILTER_FETCH(ao_in, pix);
    /* Half of the window, (y > 0) or (y = 0, x > 0); each offset brings its mirror (eq. 4); row 0
     * from x = 1, as in the tiled program. */
    for (int y = 0; y <= r; ++y) {
        for (int x = y == 0 ? 1 : -r; x <= r; ++x) {
            ivec2 o = ivec2(x, y);
            float s = flt.weights[abs(x)].x * flt.weights[y].x;
            float w = s * min(range_weight(pix + o, size, pp, np, inv_dp), range_weight(pix - o, size, pp, np, inv_dp));
            if (w <= 0.0) continue;
            sum += w * (OB_FILTER_FETCH(ao_in, pix + o) + OB_FILTER_FETCH(ao_in, pix - o));
            weight += 2.0 * w;
        }
    }
    imageStore(ao_out, pix, vec4(sum / weight));
}
#endif
