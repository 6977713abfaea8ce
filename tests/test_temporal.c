/* Temporal accumulation (issue 17, ob_settings.temporal, passes/temporal.c):
 *   - a still camera on `corner` with the noise advancing every frame converges: with temporal on
 *     the frame-to-frame change of the AO falls, after the history length, below a tenth of what it
 *     is with a one-frame history (the same moving noise through the spatial filter alone), for gtao (R2 jitters), ssao at 1/2 (the per-frame
 *     rotation of its noise), the RGB chain of ssdo at 1/4, and with the pass after the filter;
 *   - reprojection after a small camera move on `cornell` maps every pixel to within 0.5 px of the
 *     same world point, checked against the G-buffer positions of both frames (the pass's motion
 *     read back, the positions from each frame's depth through its own camera);
 *   - a sideways move that uncovers floor and wall behind cornell's blocks resets the history's age
 *     exactly where the previous frame's depth shows an occluder in front of the point, and keeps
 *     it (N) where the point was visible;
 *   - a slow sideways pan fades one-pixel detail (against the same camera held still), and
 *     temporal_detail 0.8 keeps more of it; with the camera still it changes nothing;
 *   - sub-pixel jitter (test_jitter): the offsets, the raster they move, a still camera's history
 *     kept where it was written, and its convergence to the footprint's mean AO;
 *   - text settings and their errors. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"

enum { W = 96, H = 72, N = 16 };

static bool render(ob_renderer *r, const ob_camera *cam, const ob_settings *s)
{
    if (ob_render_frame(r, cam, s) == OB_OK) return true;
    const char *msg = NULL;
    ob_get_error(&msg);
    fprintf(stderr, "render: %s\n", msg);
    return false;
}

/* Mean |a - b| over pixels with geometry, `channels` values a pixel. */
static double mean_change(const float *a, const float *b, const float *depth, int n, int channels)
{
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < n; ++i)
        if (depth[i] > 0.0f)
            for (int c = 0; c < channels; ++c) {
                sum += fabs((double)a[i * channels + c] - (double)b[i * channels + c]);
                ++count;
            }
    return count ? sum / count : 0.0;
}

/* The mean frame-to-frame change of the final image `kind` (the AO, or the bounce: 3 values a
 * pixel) over frames [from, to) of a still camera. */
static double still_change(ob_renderer *r, const ob_camera *cam, const ob_settings *s, int from, int to,
                           ob_image_kind kind)
{
    static float values[2][W * H * 3], depth[W * H];
    const int channels = kind == OB_IMAGE_BOUNCE_F32 ? 3 : 1;
    const size_t size = sizeof(float) * W * H * (size_t)channels;
    double sum = 0.0;
    int count = 0;
    for (int f = 0; f < to; ++f) {
        if (!render(r, cam, s) || ob_read_image(r, kind, values[f & 1], size) != OB_OK) return -1.0;
        if (f == 0) ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, sizeof depth);
        if (f > from) {
            sum += mean_change(values[f & 1], values[(f - 1) & 1], depth, W * H, channels);
            ++count;
        }
    }
    return count ? sum / count : -1.0;
}

static void test_converges(ob_context *ctx, ob_scene *corner, const char *method, int divisor, int at,
                           ob_image_kind kind)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r && ob_renderer_set_scene(r, corner) == OB_OK, "corner renderer");
    if (!r) return;
    /* Looking into the corner from the open side: the creases and the open floor. */
    const ob_camera cam = {.eye = {2.6f, 1.9f, 2.6f}, .target = {0.4f, 0.2f, 0.4f}, .fov_y_deg = 60.0f};
    ob_settings s;
    ob_settings_init(&s, method);
    ob_settings_set_ao_divisor(&s, divisor);
    /* Under temporal the noise moves every frame by itself: gtao's R2 jitters, the others' rotation. */
    s.temporal_frames = N;
    s.temporal_at = at;
    s.temporal = true;
    double on = still_change(r, &cam, &s, 2 * N, 3 * N, kind);
    /* The baseline: the same moving noise with a history of one frame, i.e. the spatial filter alone. */
    ob_settings one = s;
    one.temporal_frames = 1;
    double spatial = still_change(r, &cam, &one, 2, 2 + N, kind);
    const char *what = kind == OB_IMAGE_BOUNCE_F32 ? "bounce" : "ao";
    printf("  %s %s/%d temporal %s: frame-to-frame change %.5f with a %d-frame history, %.5f with 1 frame\n", method,
           what, divisor, at == OB_TEMPORAL_AFTER_FILTER ? "after" : "before", on, N, spatial);
    CHECK(spatial > 5e-4, "%s %s: the noise moves from frame to frame without accumulation (%.5f)", method, what,
          spatial);
    CHECK(on >= 0.0 && on < 0.1 * spatial, "%s %s/%d: after %d frames the change %.5f is below a tenth of %.5f",
          method, what, divisor, N, on, spatial);
    ob_destroy_renderer(r);
}

/* A camera's view and projection as ob_render_frame makes them (no guard band, no shift). */
typedef struct cam_mats {
    mat4 view, inv_view, proj;
} cam_mats;

static cam_mats mats(ob_camera c)
{
    cam_mats m;
    vec3 up = {0.0f, 1.0f, 0.0f};
    glm_lookat(c.eye, c.target, up, m.view);
    glm_mat4_inv(m.view, m.inv_view);
    glm_perspective(glm_rad(c.fov_y_deg), (float)W / (float)H, c.near_z, c.far_z, m.proj);
    return m;
}

/* World position of pixel (x, y) (row 0 at the bottom) from its linear depth. */
static void world_at(cam_mats *m, float x, float y, float d, vec3 out)
{
    float nx = (x + 0.5f) / (float)W * 2.0f - 1.0f, ny = (y + 0.5f) / (float)H * 2.0f - 1.0f;
    vec4 v = {(nx + m->proj[2][0]) * d / m->proj[0][0], (ny + m->proj[2][1]) * d / m->proj[1][1], -d, 1.0f};
    vec4 w;
    glm_mat4_mulv(m->inv_view, v, w);
    glm_vec3_copy(w, out);
}

/* Pixel (continuous, centres at + 0.5) and linear depth of a world point in a camera. */
static void project(cam_mats *m, const vec3 p, float *x, float *y, float *d)
{
    vec4 w = {p[0], p[1], p[2], 1.0f}, v, c;
    glm_mat4_mulv(m->view, w, v);
    glm_mat4_mulv(m->proj, v, c);
    *x = (c[0] / c[3] * 0.5f + 0.5f) * (float)W;
    *y = (c[1] / c[3] * 0.5f + 0.5f) * (float)H;
    *d = -v[2];
}

typedef struct frame_data {
    float depth[W * H], normal[3 * W * H], motion[2 * W * H], age[W * H];
} frame_data;

static bool grab(ob_renderer *r, frame_data *f)
{
    return ob_read_image(r, OB_IMAGE_DEPTH_F32, f->depth, sizeof f->depth) == OB_OK &&
           ob_read_image(r, OB_IMAGE_NORMAL_F32, f->normal, sizeof f->normal) == OB_OK &&
           ob_read_image(r, OB_IMAGE_MOTION_F32, f->motion, sizeof f->motion) == OB_OK &&
           ob_read_image(r, OB_IMAGE_HISTORY_AGE_F32, f->age, sizeof f->age) == OB_OK;
}

/* Pixel (x, y) of `a` and its three neighbours up and right all on one flat surface (same normal). */
static bool flat_quad(const frame_data *a, int x, int y)
{
    if (x < 0 || y < 0 || x + 1 >= W || y + 1 >= H) return false;
    const int i0 = y * W + x;
    const int q[4] = {i0, i0 + 1, i0 + W, i0 + W + 1};
    for (int k = 0; k < 4; ++k) {
        if (a->depth[q[k]] <= 0.0f) return false;
        float dot = 0.0f;
        for (int c = 0; c < 3; ++c) dot += a->normal[3 * q[k] + c] * a->normal[3 * i0 + c];
        /* One plane: normals within 2.6 deg. The G-buffer's RGBA16F normals of one plane differ by
         * an fp16 rounding (4.9e-4 per component), which 0.9999 did not allow on an NVIDIA H100,
         * where interpolation lands them on different fp16 values (549 of 6912 pixels passed). */
        if (dot < 0.999f) return false;
    }
    return true;
}

/* Frame a's linear depth at continuous pixel (qx, qy), bilinear between the four centres around it
 * (x0, y0 the lower left one). */
static float depth_at(const frame_data *a, float qx, float qy, int x0, int y0)
{
    float tx = qx - 0.5f - (float)x0, ty = qy - 0.5f - (float)y0;
    const float *d = a->depth;
    return (1 - ty) * ((1 - tx) * d[y0 * W + x0] + tx * d[y0 * W + x0 + 1]) +
           ty * ((1 - tx) * d[(y0 + 1) * W + x0] + tx * d[(y0 + 1) * W + x0 + 1]);
}

/* Frame a saw the point at depth d at continuous pixel (qx, qy): the four centres around it lie on
 * one flat surface whose depth there is d within 0.5 %. */
static bool seen_on_flat_quad(const frame_data *a, float qx, float qy, int x0, int y0, float d)
{
    return flat_quad(a, x0, y0) && fabsf(depth_at(a, qx, qy, x0, y0) - d) < 0.005f * d;
}

static void test_reprojection(ob_context *ctx, ob_scene *cornell)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_camera a;
    CHECK(r && ob_renderer_set_scene(r, cornell) == OB_OK && ob_find_camera(cornell, "front", &a) == OB_OK,
          "cornell renderer");
    if (!r) return;
    a.near_z = 0.05f;
    a.far_z = 10.0f;
    if (a.fov_y_deg <= 0.0f) a.fov_y_deg = 60.0f;
    /* A small move: sideways, up and turning a little (target moves less than the eye). */
    ob_camera b = a;
    b.eye[0] += 0.04f;
    b.eye[1] += 0.02f;
    b.target[0] += 0.015f;
    ob_settings s;
    ob_settings_init(&s, "ssao");
    s.temporal = true;
    static frame_data fa, fb;
    bool ok = render(r, &a, &s) && grab(r, &fa) && render(r, &b, &s) && grab(r, &fb);
    CHECK(ok, "two frames with temporal on");
    if (!ok) {
        ob_destroy_renderer(r);
        return;
    }
    cam_mats ma = mats(a), mb = mats(b);
    double worst = 0.0, moved = 0.0;
    int checked = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const int i = y * W + x;
            if (fb.depth[i] <= 0.0f) continue;
            vec3 pb;
            world_at(&mb, (float)x, (float)y, fb.depth[i], pb);
            /* Where the pass says this point was, in frame a's pixels (continuous). */
            float qx = (float)x + 0.5f + fb.motion[2 * i], qy = (float)y + 0.5f + fb.motion[2 * i + 1];
            int x0 = (int)floorf(qx - 0.5f), y0 = (int)floorf(qy - 0.5f);
            if (!flat_quad(&fa, x0, y0)) continue;
            /* Only points that frame a saw: its depth where a's camera puts the point (the test's own
             * projection, not the pass's) is the point's own. */
            float cx = 0.0f, cy = 0.0f, cd = 0.0f;
            project(&ma, pb, &cx, &cy, &cd);
            int cx0 = (int)floorf(cx - 0.5f), cy0 = (int)floorf(cy - 0.5f);
            if (!flat_quad(&fa, cx0, cy0) || fabsf(depth_at(&fa, cx, cy, cx0, cy0) - cd) > 0.005f * cd) continue;
            /* Frame a's G-buffer position there: bilinear between its four pixel centres on one plane. */
            float tx = qx - 0.5f - (float)x0, ty = qy - 0.5f - (float)y0;
            vec3 p00, p10, p01, p11, pa;
            world_at(&ma, (float)x0, (float)y0, fa.depth[y0 * W + x0], p00);
            world_at(&ma, (float)x0 + 1, (float)y0, fa.depth[y0 * W + x0 + 1], p10);
            world_at(&ma, (float)x0, (float)y0 + 1, fa.depth[(y0 + 1) * W + x0], p01);
            world_at(&ma, (float)x0 + 1, (float)y0 + 1, fa.depth[(y0 + 1) * W + x0 + 1], p11);
            for (int c = 0; c < 3; ++c)
                pa[c] = (1 - ty) * ((1 - tx) * p00[c] + tx * p10[c]) + ty * ((1 - tx) * p01[c] + tx * p11[c]);
            /* The world distance in frame a's pixels at that depth: one pixel spans 2 d / (P11 H). */
            float px_size = 2.0f * fa.depth[y0 * W + x0] / (ma.proj[1][1] * (float)H);
            double err = glm_vec3_distance(pa, pb) / px_size;
            worst = fmax(worst, err);
            moved = fmax(moved, hypot(fb.motion[2 * i], fb.motion[2 * i + 1]));
            ++checked;
        }
    printf("  reprojection after a small move: %d px checked, motion up to %.2f px, worst %.3f px from the same "
           "world point\n",
           checked, moved, worst);
    CHECK(checked > W * H / 3, "most pixels lie on flat quads of the previous frame (%d)", checked);
    CHECK(moved > 1.0, "the camera move shifts pixels by more than a pixel (%.2f)", moved);
    CHECK(worst < 0.5, "every pixel maps within 0.5 px of its world point (worst %.3f px)", worst);
    ob_destroy_renderer(r);
}

/* Where pixel (x, y) of frame b (camera mb) was in frame a (camera ma): its continuous pixel
 * (qx, qy), its linear depth d there and the bottom-left pixel (x0, y0) of its bilinear quad. False
 * on the sky or when the quad leaves the image. */
static bool seen_from(cam_mats *ma, cam_mats *mb, const frame_data *fb, int x, int y, float *qx, float *qy, float *d,
                      int *x0, int *y0)
{
    const float depth = fb->depth[y * W + x];
    if (depth <= 0.0f) return false;
    vec3 p;
    world_at(mb, (float)x, (float)y, depth, p);
    project(ma, p, qx, qy, d);
    *x0 = (int)floorf(*qx - 0.5f);
    *y0 = (int)floorf(*qy - 0.5f);
    return *x0 >= 0 && *y0 >= 0 && *x0 + 1 < W && *y0 + 1 < H;
}

/* Cornell's front camera still for N + 2 frames with temporal on (into fa), then one frame after a
 * move (into fb): `sideways` world units along +x (eye and target), then the eye `dolly` of the way
 * to the target. *a and *b get the two cameras. False (and a failed check) if a frame failed. */
static bool still_then_move(ob_context *ctx, ob_scene *cornell, const char *method, float sideways, float dolly,
                            ob_camera *a, ob_camera *b, frame_data *fa, frame_data *fb)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    bool ok = r && ob_renderer_set_scene(r, cornell) == OB_OK && ob_find_camera(cornell, "front", a) == OB_OK;
    CHECK(ok, "cornell renderer");
    if (ok) {
        a->near_z = 0.05f;
        a->far_z = 10.0f;
        if (a->fov_y_deg <= 0.0f) a->fov_y_deg = 60.0f;
        *b = *a;
        b->eye[0] += sideways;
        b->target[0] += sideways;
        for (int k = 0; k < 3; ++k) b->eye[k] += dolly * (b->target[k] - b->eye[k]);
        ob_settings s;
        ob_settings_init(&s, method);
        s.temporal = true;
        s.temporal_frames = N;
        for (int f = 0; f < N + 2 && ok; ++f) ok = render(r, a, &s);
        ok = ok && grab(r, fa) && render(r, b, &s) && grab(r, fb);
        CHECK(ok, "frames with temporal on");
    }
    ob_destroy_renderer(r);
    return ok;
}

static void test_disocclusion(ob_context *ctx, ob_scene *cornell)
{
    /* A sideways step: the blocks slide across the back wall and floor more than those do. */
    ob_camera a, b;
    static frame_data fa, fb;
    if (!still_then_move(ctx, cornell, "ssao", 0.15f, 0.0f, &a, &b, &fa, &fb)) return;
    int still_full = 0, geometry = 0;
    for (int i = 0; i < W * H; ++i) {
        geometry += fa.depth[i] > 0.0f;
        still_full += fa.depth[i] > 0.0f && fa.age[i] == (float)N;
    }
    CHECK(still_full == geometry, "a still camera fills every history to N (%d of %d)", still_full, geometry);
    cam_mats ma = mats(a), mb = mats(b);
    int hidden = 0, hidden_reset = 0, seen = 0, seen_kept = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const int i = y * W + x;
            float qx = 0.0f, qy = 0.0f, d = 0.0f;
            int x0 = 0, y0 = 0;
            if (!seen_from(&ma, &mb, &fb, x, y, &qx, &qy, &d, &x0, &y0)) continue;
            /* All four of frame a's pixels around the point in front of it by 5 % (an occluder), or a
             * flat quad whose depth there is the point's within 0.5 % (seen). Anything between is an
             * edge, left unjudged. */
            int front = 0;
            for (int k = 0; k < 4; ++k) {
                float da = fa.depth[(y0 + (k >> 1)) * W + x0 + (k & 1)];
                front += da > 0.0f && da < 0.95f * d;
            }
            if (front == 4) {
                ++hidden;
                hidden_reset += fb.age[i] == 1.0f;
            } else if (seen_on_flat_quad(&fa, qx, qy, x0, y0, d)) {
                ++seen;
                seen_kept += fb.age[i] == (float)N;
            }
        }
    printf("  disocclusion: %d px uncovered (%d reset to age 1), %d px seen before (%d kept age %d)\n", hidden,
           hidden_reset, seen, seen_kept, N);
    CHECK(hidden >= 20, "the move uncovers pixels behind the blocks (%d)", hidden);
    CHECK(hidden_reset == hidden, "every uncovered pixel starts its history again (%d of %d)", hidden_reset, hidden);
    CHECK(seen > W * H / 3 && seen_kept >= seen * 99 / 100, "pixels seen before keep their history (%d of %d)",
          seen_kept, seen);
}

/* A dolly toward the box: every point's pixel footprint shrinks by s = d_before / d_after, and the
 * history's age is discounted by 2^(-4.5 |log2 s|) (passes/temporal.c FOOTPRINT_FALLOFF): a point
 * seen before on a flat quad keeps age min(N 2^(-4.5 |log2 s|) + 1, N), not N. */
static void test_dolly(ob_context *ctx, ob_scene *cornell)
{
    ob_camera a, b;
    static frame_data fa, fb;
    if (!still_then_move(ctx, cornell, "gtao", 0.0f, 0.12f, &a, &b, &fa, &fb)) return;
    cam_mats ma = mats(a), mb = mats(b);
    int seen = 0, matched = 0, shortened = 0;
    double worst = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const int i = y * W + x;
            float qx = 0.0f, qy = 0.0f, d = 0.0f;
            int x0 = 0, y0 = 0;
            if (!seen_from(&ma, &mb, &fb, x, y, &qx, &qy, &d, &x0, &y0)) continue;
            if (!seen_on_flat_quad(&fa, qx, qy, x0, y0, d)) continue;
            const double trust = exp2(-4.5 * fabs(log2((double)d / (double)fb.depth[i])));
            const double expect = fmin((double)N * trust + 1.0, (double)N);
            const double e = fabs((double)fb.age[i] - expect);
            ++seen;
            matched += e < 0.05;
            shortened += fb.age[i] < (float)N - 1.0f;
            worst = fmax(worst, e);
        }
    printf("  dolly: %d px seen before, %d with the age the footprint rule gives (worst off by %.4f), %d shortened\n",
           seen, matched, worst, shortened);
    CHECK(seen > W * H / 3, "the dolly keeps most pixels in view (%d)", seen);
    CHECK(matched >= seen * 99 / 100, "ages follow the footprint rule (%d of %d)", matched, seen);
    CHECK(shortened >= seen * 99 / 100, "a dolly of 12 %% shortens the histories (%d of %d)", shortened, seen);
}

/* RMS of a - b over pixels with geometry. */
static double rms_diff(const float *a, const float *b, const float *depth, int n)
{
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < n; ++i)
        if (depth[i] > 0.0f) {
            sum += ((double)a[i] - (double)b[i]) * ((double)a[i] - (double)b[i]);
            ++count;
        }
    return count ? sqrt(sum / count) : 0.0;
}

/* Cornell's front camera moved sideways (+x) by `start` world units, then panned on by `step` a
 * frame for `frames` frames (step 0: still there), temporal on with ob_settings.temporal_detail =
 * detail; the last frame's AO into ao (and its depth into depth when not NULL). */
static bool pan(ob_context *ctx, ob_scene *cornell, float start, float step, int frames, float detail, float *ao,
                float *depth)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_camera cam;
    bool ok = r && ob_renderer_set_scene(r, cornell) == OB_OK && ob_find_camera(cornell, "front", &cam) == OB_OK;
    if (ok) {
        cam.near_z = 0.05f;
        cam.far_z = 10.0f;
        if (cam.fov_y_deg <= 0.0f) cam.fov_y_deg = 60.0f;
        ob_settings s;
        ob_settings_init(&s, "gtao");
        s.temporal = true;
        s.temporal_frames = N;
        s.temporal_detail = detail;
        for (int f = 0; f < frames && ok; ++f) {
            ob_camera c = cam;
            const float x = start + step * (float)f;
            c.eye[0] += x;
            c.target[0] += x;
            ok = render(r, &c, &s);
        }
        ok = ok && ob_read_image(r, OB_IMAGE_AO_F32, ao, sizeof(float) * W * H) == OB_OK;
        if (ok && depth) ok = ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, sizeof(float) * W * H) == OB_OK;
    }
    CHECK(ok, "cornell pan with temporal_detail %.2f", (double)detail);
    ob_destroy_renderer(r);
    return ok;
}

/* ob_settings.temporal_detail: a slow pan (0.005 units a frame, 0.4-0.5 px at the blocks and the back
 * wall, so every frame resamples the history between pixels) fades one-pixel detail, the blocks'
 * contact creases and silhouettes, toward the resampled average; the bound keeps more of it. The
 * measure is the last frame against the same camera held still for 2N frames (the history converged
 * with no resampling, the noise averaged as well): the bound brings the panned frame closer to it.
 * With the camera still there is nothing to bound, and the images are the same to rounding. */
static void test_detail(ob_context *ctx, ob_scene *cornell)
{
    static float still[W * H], still_bound[W * H], plain[W * H], bound[W * H], depth[W * H];
    const float step = 0.005f;
    const int frames = N + 8;
    const float end = step * (float)(frames - 1); /* where the pan ends, and the still camera stands */
    if (!pan(ctx, cornell, end, 0.0f, 2 * N, 0.0f, still, depth) ||
        !pan(ctx, cornell, end, 0.0f, 2 * N, 0.8f, still_bound, NULL) ||
        !pan(ctx, cornell, 0.0f, step, frames, 0.0f, plain, NULL) ||
        !pan(ctx, cornell, 0.0f, step, frames, 0.8f, bound, NULL))
        return;
    const double e_plain = rms_diff(plain, still, depth, W * H), e_bound = rms_diff(bound, still, depth, W * H);
    const double e_still = rms_diff(still_bound, still, depth, W * H);
    printf("  detail: panned last frame against the still one, RMS %.5f with no bound, %.5f with 0.8; still "
           "camera, bound against none: %.6f\n",
           e_plain, e_bound, e_still);
    CHECK(e_plain > 2e-3, "a sub-pixel pan fades the history's detail (RMS %.5f against the still camera)", e_plain);
    CHECK(e_bound < 0.7 * e_plain, "temporal_detail 0.8 keeps more of it: RMS %.5f, below 0.7 x %.5f", e_bound,
          e_plain);
    CHECK(e_still < 1e-4, "a still camera is the same with the bound (RMS %.6f)", e_still);
}

/* Sub-pixel jitter (ob_settings.jitter, ob_jitter_offset). */
static void test_jitter_offsets(void)
{
    float o[2] = {1.0f, 1.0f}, p[2];
    /* Halton (2, 3) from index 1, minus one half: (1/2, 1/3), (1/4, 2/3), (3/4, 1/9), ... */
    const float want[3][2] = {{0.0f, 1.0f / 3.0f - 0.5f}, {-0.25f, 2.0f / 3.0f - 0.5f}, {0.25f, 1.0f / 9.0f - 0.5f}};
    for (int i = 0; i < 3; ++i)
        CHECK(ob_jitter_offset(i, 8, o) == OB_OK && fabsf(o[0] - want[i][0]) < 1e-6f && fabsf(o[1] - want[i][1]) < 1e-6f,
              "jitter position %d is Halton (2, 3) point %d minus 1/2: (%g, %g)", i, i + 1, (double)o[0], (double)o[1]);
    CHECK(ob_jitter_offset(8, 8, o) == OB_OK && ob_jitter_offset(0, 8, p) == OB_OK && o[0] == p[0] && o[1] == p[1],
          "position 8 of 8 is position 0 again");
    CHECK(ob_jitter_offset(-1, 8, o) == OB_OK && ob_jitter_offset(7, 8, p) == OB_OK && o[0] == p[0] && o[1] == p[1],
          "position -1 of 8 is position 7");
    double mx = 0.0, my = 0.0;
    bool inside = true;
    for (int i = 0; i < 8; ++i) {
        ob_jitter_offset(i, 8, o);
        inside = inside && fabsf(o[0]) < 0.5f && fabsf(o[1]) < 0.5f;
        mx += o[0] / 8.0;
        my += o[1] / 8.0;
    }
    CHECK(inside && fabs(mx) < 0.06 && fabs(my) < 0.01, "8 positions inside the pixel around its centre (mean %g, %g)",
          mx, my);
    CHECK(ob_jitter_offset(0, 0, o) == OB_ERR_INVALID_ARGUMENT && ob_jitter_offset(0, 8, NULL) == OB_ERR_INVALID_ARGUMENT,
          "0 positions or a NULL offset refused");
    ob_settings s;
    ob_settings_init(&s, "vbao");
    CHECK(ob_settings_set(&s, "jitter=on") == OB_OK && s.jitter == OB_JITTER_POSITIONS_DEFAULT, "jitter=on");
    CHECK(ob_settings_set(&s, "jitter=4") == OB_OK && s.jitter == 4 && ob_settings_get(&s, "jitter") == 4.0f, "jitter=4");
    CHECK(ob_settings_set(&s, "jitter=off") == OB_OK && s.jitter == 0, "jitter=off");
    CHECK(ob_settings_set(&s, "jitter=65") == OB_ERR_OUT_OF_RANGE, "jitter=65 refused");
    CHECK(ob_settings_set(&s, "jitter=some") == OB_ERR_INVALID_ARGUMENT, "jitter=some refused");
}

/* The jitter on a scene of thin holes (grille, front: a drilled sheet and plate, one-pixel edges
 * everywhere at 96 x 72):
 *   - it moves the raster as documented: one position, (0, -1/6) px, is the camera's lens shift
 *     by 2 (0, -1/6) / size, depth for depth;
 *   - a still camera jittered over 8 positions reads its history where it wrote it: motion 0 (the
 *     jitter's change is no motion) and the history's age reaches N on most pixels;
 *   - and so the accumulation converges to the AO averaged over the 8 positions (the pixel's
 *     footprint): against the mean of 64 jittered frames with a one-frame history, the jittered
 *     history is far closer than an unjittered one, which holds the pixel centres' AO (with the
 *     accumulation before the edge-aware filter, which a jitter moves to after it, 0.035 against
 *     the unjittered 0.038). */
static void test_jitter(ob_context *ctx, ob_scene *grille)
{
    static float a[W * H], b[W * H], target[W * H], depth[W * H];
    static frame_data f;
    ob_camera cam;
    CHECK(ob_find_camera(grille, "front", &cam) == OB_OK, "grille's camera front");
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r && ob_renderer_set_scene(r, grille) == OB_OK, "grille renderer");
    if (!r) return;
    ob_settings s;
    ob_settings_init(&s, "vbao");
    s.jitter = 1;
    bool ok = render(r, &cam, &s) && ob_read_image(r, OB_IMAGE_DEPTH_F32, a, sizeof a) == OB_OK;
    ob_camera shifted = cam;
    shifted.shift[1] += 2.0f * (1.0f / 3.0f - 0.5f) / (float)H;
    s.jitter = 0;
    ok = ok && render(r, &shifted, &s) && ob_read_image(r, OB_IMAGE_DEPTH_F32, b, sizeof b) == OB_OK;
    ok = ok && render(r, &cam, &s) && ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, sizeof depth) == OB_OK;
    int differ_shift = 0, differ_centre = 0;
    for (int i = 0; ok && i < W * H; ++i) differ_shift += a[i] != b[i], differ_centre += a[i] != depth[i];
    CHECK(ok && differ_shift == 0 && differ_centre > 0,
          "jitter 1 is the lens shift (0, -1/6 px): %d pixels differ from it, %d from the unjittered raster", differ_shift,
          differ_centre);

    /* A still camera under 8 positions, temporal on. */
    s.temporal = true;
    s.temporal_frames = N;
    s.jitter = 8;
    ob_renderer_reset_history(r);
    for (int i = 0; ok && i < 4 * N; ++i) ok = render(r, &cam, &s);
    ok = ok && grab(r, &f) && ob_read_image(r, OB_IMAGE_AO_F32, a, sizeof a) == OB_OK;
    double worst = 0.0;
    int geometry = 0, full = 0;
    for (int i = 0; ok && i < W * H; ++i)
        if (depth[i] > 0.0f) {
            ++geometry;
            full += f.age[i] >= (float)N - 0.5f;
            worst = fmax(worst, fmax(fabs(f.motion[2 * i]), fabs(f.motion[2 * i + 1])));
        }
    printf("  jitter 8, still camera: motion %.2g px at most, %.1f %% of %d pixels with the whole history\n", worst,
           100.0 * full / (geometry ? geometry : 1), geometry);
    CHECK(ok && worst < 1e-3, "a still jittered camera has no motion (%g px at most)", worst);
    /* A hole's rim samples the sheet one frame and the floor the next: the rim keeps its history
     * too (a rule that rejected the other surface kept 93.7 %). */
    CHECK(ok && full >= 0.98 * geometry, "its history is kept: %d of %d pixels at age %d", full, geometry, N);

    /* The footprint's AO: 64 jittered frames with a one-frame history, averaged. */
    ob_settings one = s;
    one.temporal_frames = 1;
    memset(target, 0, sizeof target);
    for (int i = 0; ok && i < 4 * N; ++i) {
        ok = render(r, &cam, &one) && ob_read_image(r, OB_IMAGE_AO_F32, b, sizeof b) == OB_OK;
        for (int k = 0; ok && k < W * H; ++k) target[k] += b[k] / (float)(4 * N);
    }
    /* The unjittered history after as many frames. */
    ob_settings centre = s;
    centre.jitter = 0;
    ob_renderer_reset_history(r);
    for (int i = 0; ok && i < 4 * N; ++i) ok = render(r, &cam, &centre);
    ok = ok && ob_read_image(r, OB_IMAGE_AO_F32, b, sizeof b) == OB_OK;
    if (ok) {
        const double jittered = rms_diff(a, target, depth, W * H), unjittered = rms_diff(b, target, depth, W * H);
        printf("  against the footprint's mean AO: jittered history RMS %.5f, unjittered %.5f\n", jittered, unjittered);
        CHECK(jittered < 0.5 * unjittered, "the jittered history converges to the footprint's AO: RMS %.5f, below half "
              "the unjittered history's %.5f", jittered, unjittered);
    }
    CHECK(ok, "jitter frames rendered");
    ob_destroy_renderer(r);
}

static void test_settings(void)
{
    ob_settings s;
    ob_settings_init(&s, "gtao");
    CHECK(ob_settings_set(&s, "temporal=on") == OB_OK && s.temporal, "temporal=on");
    CHECK(ob_settings_set(&s, "temporal_at=after") == OB_OK && s.temporal_at == OB_TEMPORAL_AFTER_FILTER,
          "temporal_at=after");
    CHECK(ob_settings_set(&s, "temporal_frames=8") == OB_OK && s.temporal_frames == 8, "temporal_frames=8");
    CHECK(ob_settings_get(&s, "temporal_frames") == 8.0f && ob_settings_get(&s, "temporal") == 1.0f, "get");
    CHECK(ob_settings_set(&s, "temporal=maybe") == OB_ERR_INVALID_ARGUMENT, "temporal=maybe refused");
    CHECK(ob_settings_set(&s, "temporal_at=middle") == OB_ERR_INVALID_ARGUMENT, "temporal_at=middle refused");
    CHECK(ob_settings_set(&s, "temporal_frames=0") == OB_ERR_OUT_OF_RANGE, "temporal_frames=0 refused");
    CHECK(ob_settings_set(&s, "temporal_frames=1.5") == OB_ERR_INVALID_ARGUMENT, "temporal_frames=1.5 refused");
    CHECK(ob_settings_set(&s, "temporal_detail=0.8") == OB_OK && s.temporal_detail == 0.8f, "temporal_detail=0.8");
    CHECK(ob_settings_get(&s, "temporal_detail") == 0.8f, "get temporal_detail");
    CHECK(ob_settings_set(&s, "temporal_detail=1") == OB_ERR_OUT_OF_RANGE, "temporal_detail=1 refused");
    CHECK(ob_settings_set(&s, "temporal_detail=-0.1") == OB_ERR_OUT_OF_RANGE, "temporal_detail=-0.1 refused");
    CHECK(ob_settings_set(&s, "temporal_detail=nan") == OB_ERR_OUT_OF_RANGE, "temporal_detail=nan refused");
    CHECK(ob_settings_set(&s, "temporal_detail=much") == OB_ERR_INVALID_ARGUMENT, "temporal_detail=much refused");
    CHECK(ob_settings_set(&s, "temporal=off") == OB_OK && !s.temporal, "temporal=off");
    /* gtao's own parameter is still its own. */
    CHECK(ob_settings_set(&s, "gtao.temporal=1") == OB_OK, "gtao.temporal=1");
}

int main(void)
{
    test_settings();
    test_jitter_offsets();
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    ob_scene *cornell = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    ob_scene *corner = ob_load_scene(&(ob_scene_desc){.name = "corner"});
    CHECK(cornell && corner, "scenes");
    if (cornell && corner) {
        test_converges(ctx, corner, "gtao", 1, OB_TEMPORAL_BEFORE_FILTER, OB_IMAGE_AO_F32);
        test_converges(ctx, corner, "gtao", 1, OB_TEMPORAL_AFTER_FILTER, OB_IMAGE_AO_F32);
        test_converges(ctx, corner, "ssao", 2, OB_TEMPORAL_BEFORE_FILTER, OB_IMAGE_AO_F32);
        test_converges(ctx, corner, "ssdo", 4, OB_TEMPORAL_BEFORE_FILTER, OB_IMAGE_AO_F32);
        /* A bounce accumulates in the main chain's dispatch: beside a visibility with no result
         * image (vbgi before the filter), with one (after), and beside M (ssdo). */
        test_converges(ctx, corner, "vbgi", 1, OB_TEMPORAL_BEFORE_FILTER, OB_IMAGE_BOUNCE_F32);
        test_converges(ctx, corner, "vbgi", 2, OB_TEMPORAL_AFTER_FILTER, OB_IMAGE_BOUNCE_F32);
        test_converges(ctx, corner, "ssdo", 4, OB_TEMPORAL_BEFORE_FILTER, OB_IMAGE_BOUNCE_F32);
        test_reprojection(ctx, cornell);
        test_disocclusion(ctx, cornell);
        test_dolly(ctx, cornell);
        test_detail(ctx, cornell);
        ob_scene *grille = ob_load_scene(&(ob_scene_desc){.name = "grille"});
        CHECK(grille != NULL, "grille");
        if (grille) test_jitter(ctx, grille);
        ob_destroy_scene(grille);
    }
    ob_destroy_scene(cornell);
    ob_destroy_scene(corner);
    ob_destroy_context(ctx);
    return check_finish("test_temporal");
}
