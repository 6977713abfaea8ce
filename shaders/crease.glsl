#version 450 core
/* The crease-preserving denoiser (`crease`, src/filters/crease.c; issue 13). A small centred
 * window whose weights come from the receiver's plane rather than from a wide spatial kernel:
 *
 *   (1) spatial:  s(o) = b(o.x) b(o.y),  b(i) = 1 for |i| < r, 1/2 for |i| = r.
 *       With r = 2 that is [1/2 1 1 1 1/2] per axis: every residue mod 4 gets total weight 1, so
 *       a 4x4-periodic pattern (the rotation tile of noise.glsl, Puri 2024 §3.3) sums to its mean
 *       exactly, as box4 does, but centred on p (box4's -2..1 shifts the image by half a pixel).
 *   (2) plane:    x_q = |n_p . (P_q - P_p)| / d_p,  g_q = exp(-x_q^2 / 2 s_p^2)
 *       the distance of q's view position from p's tangent plane, relative to p's depth so the
 *       same s_p works in metres and millimetres (an orthographic camera's depth too: the
 *       distance from its plane, docs/embedding.md "Projection"). Along p's own plane x_q = 0
 *       at any distance and any viewing angle (a grazing floor is not cut up as a depth test
 *       would cut it); a depth step or a surface behind a silhouette is off the plane.
 *   (3) normal:   h_q = exp(-theta_q^2 / 2 s_n^2),  theta_q = acos(n_p . n_q)
 *       a wall meeting the floor passes through the floor's plane at the crease itself, where
 *       (2) cannot tell them apart; the normals can.
 *   (4) pairs:    w(+o) = w(-o) = s(o) min(g h (+o), g h (-o))
 *       Each offset is weighed together with its mirror. Where the wall cuts the window off on
 *       one side, the other side loses the same taps, so the window's centroid stays at p and AO
 *       that varies linearly across it keeps its value at p. Near a crease AO does vary about
 *       linearly: AO_R(h) = 1 - (acos a - a sqrt(1 - a^2)) / pi, a = h/R (docs/architecture.md
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

layout(binding = OB_UNIT_FILTER_IN) uniform sampler2D ao_in;
layout(binding = OB_UNIT_FILTER_DEPTH) uniform sampler2D linear_depth;
layout(binding = OB_UNIT_FILTER_NORMAL) uniform sampler2D view_normal;
layout(binding = OB_IMAGE_UNIT_OUT, OB_FILTER_FORMAT) uniform writeonly image2D ao_out;

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

/* acos by Abramowitz & Stegun 4.4.45 (|error| <= 6.7e-5 rad, so theta^2 / 2 s_n^2 moves by under
 * 1e-3 of itself at s_n = 20 deg): the tiled and block programs' eq. 3. */
float fast_acos(float x)
{
    float a = abs(x);
    float r = sqrt(1.0 - a) * (1.5707288 + a * (-0.2121144 + a * (0.0742610 - 0.0187293 * a)));
    return x < 0.0 ? 3.14159265 - r : r;
}

#ifdef OB_CREASE_TILED
/* The tiled program (`tiled` on, radius <= OB_CREASE_TILE_RADIUS): the work group first turns its
 * (8 + 2r)^2 texels into view positions, normals and AO in shared memory, once each, where the
 * plain program fetched and rebuilt every one of them for each of the up to 25 pixels whose
 * window covers it (24 range weights a pixel, each two fetches and a reconstruction). The weights
 * are the same equations; acos becomes fast_acos, and exp an exp2 with the falloffs scaled by
 * log2(e) on the CPU. The plain program stays as the baseline (tiled off).
 * On llvmpipe a shared-memory load whose address differs between lanes is a loop over the 8
 * lanes, one branch and one scalar load each (Mesa 22.3 lp_bld_nir_soa.c emit_load_mem): each
 * pair's 16 floats cost 128 of them, no cheaper than fetching them. The block program below reads
 * each texel once for 16 pixels and is 4x faster there (docs/filters.md). */
const int TILE_W = OB_FILTER_GROUP_X + 2 * OB_CREASE_TILE_RADIUS;
const int TILE_H = OB_FILTER_GROUP_Y + 2 * OB_CREASE_TILE_RADIUS;
shared vec4 tile_pos[TILE_H][TILE_W];    /* view position, w = 1 on geometry inside the image, else 0 */
shared vec3 tile_normal[TILE_H][TILE_W];
shared OB_FILTER_T tile_ao[TILE_H][TILE_W];

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
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight)));
}
#elif defined(OB_CREASE_BLOCK)
/* The block program (`tiled` block, radius 2 only): each invocation filters a 4x4 block of
 * pixels from the 8x8 window around it, fetched once into registers. Per pixel that is 64 / 16 = 4
 * texels of each texture instead of 25, and no shared memory (the tiled program's loads are
 * per-lane loops on llvmpipe, see above). Everything is unrolled by the macros below, so every
 * array index is a constant and the arrays stay in registers (an array indexed at run time would
 * go to scratch memory, per lane again). The weights are the tiled program's: eq. 1-4, fast_acos,
 * exp2 with the CPU's log2(e)-scaled falloffs. Eq. 2 needs no view positions: with
 * L(q) = n_p . P_q / d_q, which is linear in q's pixel coordinates (ob_view_position),
 *   n_p . (P_q - P_p) = d_q L(p + o) - d_p L(p),  L(p + o) = L(p) + o . dL/dq,
 * one multiply-add per tap. For an orthographic camera (frame.orthographic; crease.c compiles
 * OB_ORTHOGRAPHIC into its own program, so the perspective one keeps its instructions) P_q's x and
 * y do not scale with d_q: n_p . P_q = M(q) - n_p.z d_q with M linear in q's pixel coordinates,
 *   n_p . (P_q - P_p) = o . dM/dq - n_p.z (d_q - d_p),  dM/dq = dL/dq above.
 * Window texels past the image's edge or on the sky have d = 0 and weigh nothing, as in the other
 * programs; pixels of a block past the edge write nothing. */
const int BLOCK = 4;
const int WINDOW = BLOCK + 4; /* 2 px each side at r = 2 */
float win_depth[WINDOW * WINDOW];           /* 0 off the image and on the sky */
vec3 win_normal[WINDOW * WINDOW];
OB_FILTER_T win_ao[WINDOW * WINDOW];

/* the window texel at block offset (x, y), x, y in -2 .. BLOCK + 1 */
#define WIN(x, y) (((x) + 2) + WINDOW * ((y) + 2))

#define LOAD(x, y) { \
    ivec2 q = base + ivec2(x, y), qc = clamp(q, ivec2(0), size - 1); \
    float d = texelFetch(linear_depth, qc, 0).r; \
    win_depth[WIN(x, y)] = q == qc ? d : 0.0; \
    win_normal[WIN(x, y)] = texelFetch(view_normal, qc, 0).xyz; \
    win_ao[WIN(x, y)] = OB_FILTER_FETCH(ao_in, qc); }
#define LOAD_ROW(y) LOAD(-2, y) LOAD(-1, y) LOAD(0, y) LOAD(1, y) LOAD(2, y) LOAD(3, y) LOAD(4, y) LOAD(5, y)

/* n_p . (P_q - P_p) for the window texels at +o (index ia) and -o (ib), t = o . dL/dq. */
#ifdef OB_ORTHOGRAPHIC
#define PLANE_A(ia, t) (t - np.z * (win_depth[ia] - dp))
#define PLANE_B(ib, t) (-t - np.z * (win_depth[ib] - dp))
#else
#define PLANE_A(ia, t) (win_depth[ia] * (lp + t) - dp * lp)
#define PLANE_B(ib, t) (win_depth[ib] * (lp - t) - dp * lp)
#endif

/* Offsets (ox, oy) and (-ox, -oy) of pixel (bx, by) of the block: eq. 2-4 with eq. 1's weight. */
#define PAIR(bx, by, ox, oy) { \
    int ia = WIN(bx + ox, by + oy), ib = WIN(bx - ox, by - oy); \
    float t = float(ox) * dl.x + float(oy) * dl.y; \
    float xa = PLANE_A(ia, t) * inv_dp; \
    float xb = PLANE_B(ib, t) * inv_dp; \
    float ta = fast_acos(clamp(dot(np, win_normal[ia]), -1.0, 1.0)); \
    float tb = fast_acos(clamp(dot(np, win_normal[ib]), -1.0, 1.0)); \
    float ga = win_depth[ia] > 0.0 ? exp2(xa * xa * flt.depth_falloff + ta * ta * flt.normal_falloff) : 0.0; \
    float gb = win_depth[ib] > 0.0 ? exp2(xb * xb * flt.depth_falloff + tb * tb * flt.normal_falloff) : 0.0; \
    float w = (abs(ox) == 2 ? 0.5 : 1.0) * (oy == 2 ? 0.5 : 1.0) * min(ga, gb); \
    sum += w * (win_ao[ia] + win_ao[ib]); \
    weight += 2.0 * w; }

/* Pixel (bx, by) of the block: the half window (oy > 0, or oy = 0 and ox > 0), mirrors paired. */
#define PIXEL(bx, by) { \
    ivec2 pix = base + ivec2(bx, by); \
    float dp = win_depth[WIN(bx, by)]; \
    if (all(lessThan(pix, size))) { \
        if (dp <= 0.0) { \
            imageStore(ao_out, pix, OB_FILTER_SKY); \
        } else { \
            vec3 np = win_normal[WIN(bx, by)]; \
            vec2 ndc = (vec2(pix) + 0.5) * frame.ao_inv_size * 2.0 - 1.0; \
            float lp = np.x * pinfo.x * (ndc.x + pinfo.z) + np.y * pinfo.y * (ndc.y + pinfo.w) - np.z; \
            vec2 dl = np.xy * pinfo.xy * 2.0 * frame.ao_inv_size; \
            float inv_dp = 1.0 / dp; \
            float weight = 1.0; \
            OB_FILTER_T sum = win_ao[WIN(bx, by)]; \
            PAIR(bx, by, 1, 0) PAIR(bx, by, 2, 0) \
            PAIR(bx, by, -2, 1) PAIR(bx, by, -1, 1) PAIR(bx, by, 0, 1) PAIR(bx, by, 1, 1) PAIR(bx, by, 2, 1) \
            PAIR(bx, by, -2, 2) PAIR(bx, by, -1, 2) PAIR(bx, by, 0, 2) PAIR(bx, by, 1, 2) PAIR(bx, by, 2, 2) \
            imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight))); \
        } \
    } }
#define PIXEL_ROW(y) PIXEL(0, y) PIXEL(1, y) PIXEL(2, y) PIXEL(3, y)

void main()
{
    ivec2 size = flt.size;
    ivec2 base = BLOCK * ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(base, size))) return;
    vec4 pinfo = frame.ao_proj_info;
    LOAD_ROW(-2) LOAD_ROW(-1) LOAD_ROW(0) LOAD_ROW(1) LOAD_ROW(2) LOAD_ROW(3) LOAD_ROW(4) LOAD_ROW(5)
    PIXEL_ROW(0) PIXEL_ROW(1) PIXEL_ROW(2) PIXEL_ROW(3)
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
    imageStore(ao_out, pix, vec4(OB_FILTER_RESULT(sum / weight)));
}
#endif
