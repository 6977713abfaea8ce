/* The guard band (Belonogov 2018 §3.2.2, ob_settings.guard):
 *   - the widened projection is exact: depth, normals, albedo and direct light read back with a
 *     band equal those without it, and AO pixels farther than the search from the border too (the
 *     band rounds to a multiple of 4 k, so the 4x4 rotation tile falls on the same pixels), also at
 *     half resolution;
 *   - a wall just beyond the top edge of `corner`: the floor pixels beside it read darker with the
 *     band than without and closer to the ray-traced AO_R of the very same points;
 *   - sizes and errors: every read-back and ob_query_renderer_size stay the visible size, a band
 *     above GL_MAX_TEXTURE_SIZE is OB_ERR_BAD_SIZE and leaves the renderer working, bad text
 *     assignments are refused, and a band switched on and off between frames gives the same
 *     frames again. */
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"

enum { W = 96, H = 72 };

/* A frame's read-backs, each the visible W x H (or the AO grid's size for raw). */
typedef struct frame {
    float depth[W * H], normal[3 * W * H], albedo[3 * W * H], direct[3 * W * H], ao[W * H], raw[W * H];
    size_t raw_count;
    uint8_t final[4 * W * H], view_ao[4 * W * H];
} frame;

static bool render(ob_renderer *r, const ob_camera *cam, const ob_settings *s, frame *f)
{
    if (ob_render_frame(r, cam, s) != OB_OK) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "render: %s\n", msg);
        return false;
    }
    f->raw_count = ob_image_size(r, OB_IMAGE_AO_RAW_F32) / sizeof(float);
    bool ok = ob_read_image(r, OB_IMAGE_DEPTH_F32, f->depth, sizeof f->depth) == OB_OK &&
              ob_read_image(r, OB_IMAGE_NORMAL_F32, f->normal, sizeof f->normal) == OB_OK &&
              ob_read_image(r, OB_IMAGE_ALBEDO_F32, f->albedo, sizeof f->albedo) == OB_OK &&
              ob_read_image(r, OB_IMAGE_RADIANCE_F32, f->direct, sizeof f->direct) == OB_OK &&
              ob_read_image(r, OB_IMAGE_AO_F32, f->ao, sizeof f->ao) == OB_OK &&
              ob_read_image(r, OB_IMAGE_AO_RAW_F32, f->raw, sizeof f->raw) == OB_OK &&
              ob_read_image(r, OB_IMAGE_FINAL_RGBA8, f->final, sizeof f->final) == OB_OK &&
              ob_read_view(r, OB_VIEW_AO, f->view_ao, sizeof f->view_ao) == OB_OK;
    CHECK(ok, "read-backs of the visible size");
    return ok;
}

static double worst(const float *a, const float *b, size_t n)
{
    double w = 0.0;
    for (size_t i = 0; i < n; ++i) w = fmax(w, fabs((double)a[i] - (double)b[i]));
    return w;
}

/* The G-buffer and the direct light do not depend on anything beyond the frame: with the widened
 * projection they are the same numbers; AO far enough from the border is too. */
static void test_exact(ob_context *ctx, ob_scene *scene, const char *method, int divisor)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_camera cam;
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK && ob_find_camera(scene, "front", &cam) == OB_OK,
          "cornell renderer");
    if (!r) return;
    ob_settings s;
    ob_settings_init(&s, method);
    ob_settings_set_ao_divisor(&s, divisor);
    static frame plain, banded;
    bool ok = render(r, &cam, &s, &plain);
    s.guard = 10; /* rounded up to 12 */
    ok = ok && render(r, &cam, &s, &banded);
    int w = 0, h = 0;
    ob_query_renderer_size(r, &w, &h);
    CHECK(w == W && h == H, "ob_query_renderer_size stays the visible %dx%d with a band, got %dx%d", W, H, w, h);
    CHECK(plain.raw_count == banded.raw_count, "the raw AO grid keeps its size (%zu vs %zu)", plain.raw_count,
          banded.raw_count);
    if (!ok) {
        ob_destroy_renderer(r);
        return;
    }
    size_t n = (size_t)W * H;
    /* Rasterisation ties aside (a pixel centre exactly on an edge), the same fragments: the
     * projection differs only by a scale the rasteriser applies with the viewport. */
    int depth_off = 0, normal_off = 0;
    for (size_t i = 0; i < n; ++i) {
        depth_off += fabsf(plain.depth[i] - banded.depth[i]) > 1e-4f * fmaxf(plain.depth[i], 1.0f);
        normal_off += fabsf(plain.normal[3 * i] - banded.normal[3 * i]) > 1e-3f ||
                      fabsf(plain.normal[3 * i + 1] - banded.normal[3 * i + 1]) > 1e-3f;
    }
    printf("  %s ao/%d, guard 10 px (rounded up to 4 k): depth differs at %d px, normals at %d, albedo worst %.2g, direct worst %.2g\n",
           method, divisor, depth_off, normal_off, worst(plain.albedo, banded.albedo, 3 * n),
           worst(plain.direct, banded.direct, 3 * n));
    CHECK(depth_off <= 2, "depth with the band = depth without (%d px differ)", depth_off);
    CHECK(normal_off <= 2, "normals with the band = normals without (%d px differ)", normal_off);
    CHECK(worst(plain.albedo, banded.albedo, 3 * n) < 1e-3, "albedo with the band = albedo without");
    CHECK(worst(plain.direct, banded.direct, 3 * n) < 1e-2, "direct light with the band = without");
    /* AO: the search reaches at most this far on screen here; beyond it from every border the band
     * changes nothing, so no pixel shifted. */
    const int margin = 24;
    double interior = 0.0, border = 0.0;
    size_t worst_i = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + (size_t)x;
            double d = fabs((double)plain.ao[i] - (double)banded.ao[i]);
            bool inside = x >= margin && x < W - margin && y >= margin && y < H - margin;
            if (inside && d > interior) worst_i = i;
            if (inside) interior = fmax(interior, d);
            else border = fmax(border, d);
        }
    printf("  %s ao/%d: AO worst |diff| %.2g inside a %d px margin, %.2g in it\n", method, divisor, interior, margin,
           border);
    CHECK(interior < 2e-3, "%s AO inside the margin is the same with the band (worst %.3g at (%d, %d): %.4f, %.4f)",
          method, interior, (int)(worst_i % W), (int)(worst_i / W), (double)plain.ao[worst_i], (double)banded.ao[worst_i]);
    ob_destroy_renderer(r);
}

/* A camera looking down at the floor of `corner` beside the wall x = 0, the wall just beyond the
 * top edge: the top rows see floor within R of it, the band sees the wall itself. */
static void test_wall_beyond_edge(ob_context *ctx, ob_scene *scene)
{
    const float radius = ob_query_scene_ao_radius(scene);
    const ob_camera cam = {.eye = {1.2f, 1.6f, 2.0f}, .target = {0.77f, 0.0f, 2.0f}, .up = {0, 1, 0},
                           .fov_y_deg = 40.0f, .near_z = 0.05f, .far_z = 20.0f, .name = "beyond"};
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK, "corner renderer");
    if (!r) return;
    static const char *const methods[] = {"gtao", "ssao", "hbao"};
    size_t n = (size_t)W * H;
    float *pos = malloc(n * 3 * sizeof(float)), *wn = malloc(n * 3 * sizeof(float)), *ref = malloc(n * sizeof(float));
    static frame plain, banded;
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; ++m) {
        ob_settings s;
        ob_settings_init(&s, methods[m]);
        bool ok = render(r, &cam, &s, &plain);
        CHECK(ob_settings_set(&s, "guard=24") == OB_OK, "guard=24");
        ok = ok && render(r, &cam, &s, &banded);
        if (!ok) break;
        if (m == 0) {
            /* The world points of the visible frame and AO_R there (the reference stays the
             * visible frame: the band changed none of its points, test_exact). */
            mat4 view, proj, inv_view;
            glm_lookat((float *)cam.eye, (float *)cam.target, (float *)cam.up, view);
            glm_perspective(glm_rad(cam.fov_y_deg), (float)W / (float)H, cam.near_z, cam.far_z, proj);
            glm_mat4_inv(view, inv_view);
            const float info[4] = {1.0f / proj[0][0], 1.0f / proj[1][1], proj[2][0], proj[2][1]};
            ob_reference_points(plain.depth, plain.normal, W, H, info, (const float *)inv_view, pos, wn);
            CHECK(ob_reference_ao(scene, pos, wn, n, &(ob_reference_desc){.spp = 256, .radius = radius, .seed = 7},
                                  ref, NULL) == OB_OK,
                  "reference");
        }
        /* Floor pixels within R / 2 of the wall: all in the top rows, the wall off screen. */
        double sum_plain = 0.0, sum_banded = 0.0, sum_ref = 0.0, err_plain = 0.0, err_banded = 0.0;
        int count = 0, lowest_row = H;
        for (size_t i = 0; i < n; ++i) {
            const float *p = &pos[3 * i];
            if (plain.depth[i] <= 0.0f || wn[3 * i + 1] < 0.99f || p[0] > 0.5f * radius || p[2] < 1.0f || p[2] > 3.0f)
                continue;
            ++count;
            lowest_row = (int)(i / W) < lowest_row ? (int)(i / W) : lowest_row;
            sum_plain += plain.ao[i];
            sum_banded += banded.ao[i];
            sum_ref += ref[i];
            err_plain += fabs((double)plain.ao[i] - ref[i]);
            err_banded += fabs((double)banded.ao[i] - ref[i]);
        }
        CHECK(count > 3 * W / 2, "%s: floor pixels beside the off-screen wall (%d)", methods[m], count);
        if (count == 0) continue;
        printf("  %s, wall beyond the top edge, %d floor px within R/2 (rows %d..%d): AO %.3f without the band, %.3f "
               "with 24 px, AO_R %.3f; mean |error| %.3f -> %.3f\n",
               methods[m], count, lowest_row, H - 1, sum_plain / count, sum_banded / count, sum_ref / count,
               err_plain / count, err_banded / count);
        CHECK(lowest_row >= H - H / 4, "%s: those pixels lie along the top edge (from row %d)", methods[m], lowest_row);
        /* gtao and hbao march into the band along the floor and find the wall; ssao's kernel
         * points reach it less often (its radius check halves what it finds), but it too. */
        CHECK(sum_banded < sum_plain - 0.02 * count, "%s: the band darkens them (%.3f -> %.3f)", methods[m],
              sum_plain / count, sum_banded / count);
        CHECK(err_banded < err_plain - 0.02 * count, "%s: the band brings them closer to AO_R (%.3f -> %.3f)",
              methods[m], err_plain / count, err_banded / count);
    }
    free(pos);
    free(wn);
    free(ref);
    ob_destroy_renderer(r);
}

/* Errors, sizes and switching the band on and off. */
static void test_sizes(ob_context *ctx, ob_scene *scene)
{
    ob_settings s;
    ob_settings_init(&s, "ssao");
    CHECK(ob_settings_set(&s, "guard=16") == OB_OK && s.guard == 16 && ob_settings_get(&s, "guard") == 16.0f,
          "guard=16 sets ob_settings.guard");
    CHECK(ob_settings_set(&s, "guard=-1") == OB_ERR_OUT_OF_RANGE, "guard=-1 is out of range");
    CHECK(ob_settings_set(&s, "guard=5000") == OB_ERR_OUT_OF_RANGE, "guard=5000 is out of range");
    CHECK(ob_settings_set(&s, "guard=1.5") == OB_ERR_INVALID_ARGUMENT, "guard=1.5 is not whole pixels");
    CHECK(ob_settings_set(&s, "guard=ten") == OB_ERR_INVALID_ARGUMENT, "guard=ten is refused");
    CHECK(s.guard == 16, "a refused assignment leaves the band as it was");
    ob_clear_error();

    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    ob_camera cam;
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK && ob_find_camera(scene, "front", &cam) == OB_OK,
          "cornell renderer");
    if (!r) return;
    static frame a, b;
    s.guard = 0;
    bool ok = render(r, &cam, &s, &a);
    /* Beyond the GL's limit: refused at the frame, the renderer still whole at its old band. */
    s.guard = OB_GUARD_MAX;
    int max = ob_query_max_texture_size(ctx);
    if (W + 2 * OB_GUARD_MAX > max) {
        CHECK(ob_render_frame(r, &cam, &s) == OB_ERR_BAD_SIZE, "a band above GL_MAX_TEXTURE_SIZE (%d)", max);
        const char *msg = NULL;
        ob_get_error(&msg);
        CHECK(msg && strstr(msg, "guard band"), "the message names the guard band: %s", msg ? msg : "");
    }
    s.guard = -4;
    CHECK(ob_render_frame(r, &cam, &s) == OB_ERR_OUT_OF_RANGE, "a negative band is refused");
    ob_clear_error();
    s.guard = 8;
    ok = ok && render(r, &cam, &s, &b);
    s.guard = 0;
    ok = ok && render(r, &cam, &s, &b);
    CHECK(ok, "frames with the band switched on and off");
    if (ok) {
        CHECK(memcmp(a.final, b.final, sizeof a.final) == 0, "off, on, off again: the same final image");
        CHECK(worst(a.ao, b.ao, (size_t)W * H) == 0.0, "off, on, off again: the same AO");
    }
    /* A resize keeps the band; the read-backs follow the visible size. */
    s.guard = 8;
    CHECK(ob_renderer_resize(r, W / 2, H / 2) == OB_OK && ob_render_frame(r, &cam, &s) == OB_OK, "resize with a band");
    CHECK(ob_image_size(r, OB_IMAGE_AO_F32) == (size_t)(W / 2) * (H / 2) * sizeof(float) &&
              ob_image_size(r, OB_IMAGE_FINAL_RGBA8) == (size_t)(W / 2) * (H / 2) * 4,
          "image sizes are the visible frame's after a resize");
    ob_destroy_renderer(r);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    ob_scene *cornell = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    ob_scene *corner = ob_load_scene(&(ob_scene_desc){.name = "corner"});
    CHECK(cornell && corner, "scenes");
    if (cornell && corner) {
        test_exact(ctx, cornell, "gtao", 1);
        test_exact(ctx, cornell, "ssao", 2);
        test_exact(ctx, cornell, "ssdo", 1);
        test_wall_beyond_edge(ctx, corner);
        test_sizes(ctx, cornell);
    }
    ob_destroy_scene(cornell);
    ob_destroy_scene(corner);
    ob_destroy_context(ctx);
    return check_finish("test_guard");
}
