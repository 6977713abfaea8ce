/* SSDO's extra view (Belonogov 2018 §4.4, ssdo.extra_view): a second camera turned 90 degrees about the
 * up axis around the main camera's target, whose G-buffer and direct light the method reads.
 *   - ob_extra_view_camera: the eye turned by 90 degrees about the up axis through the target, at
 *     the same distance and height, the rest of the camera unchanged (pure);
 *   - the extra view's direct light (OB_IMAGE_EXTRA_RADIANCE_F32) is the frame a renderer makes of
 *     that camera itself (OB_IMAGE_RADIANCE_F32): the same pixels, so the method reads a real view;
 *   - the extra view only frees samples this view calls occluded (a point it sees in free space is
 *     free), so with the same kernel and noise M can only rise: never lower anywhere, higher
 *     somewhere on a view where it sees what this one hides (cornell's blocks);
 *   - without the option no extra view is made (the image reads zeros). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/renderer.h"
#include "scene/scene.h"
#include "obscura/eval.h"

enum { W = 96, H = 72 };

static void test_camera(void)
{
    ob_camera c = {.eye = {1.0f, 2.0f, 5.0f}, .target = {1.0f, 0.5f, 1.0f}, .fov_y_deg = 50.0f, .near_z = 0.1f,
                   .far_z = 30.0f, .shift = {0.1f, 0.0f}};
    ob_camera e;
    ob_extra_view_camera(&c, &e);
    /* v = (0, 1.5, 4) about +Y by 90 degrees: (4, 1.5, 0). */
    const float want[3] = {5.0f, 2.0f, 1.0f};
    float err = 0.0f;
    for (int i = 0; i < 3; ++i) err = fmaxf(err, fabsf(e.eye[i] - want[i]));
    CHECK(err < 1e-5f, "eye turned 90 degrees about +Y around the target: (%g, %g, %g)", e.eye[0], e.eye[1], e.eye[2]);
    CHECK(!memcmp(e.target, c.target, sizeof c.target) && e.fov_y_deg == c.fov_y_deg && e.near_z == c.near_z &&
              e.far_z == c.far_z,
          "target, fov and planes kept");
    CHECK(e.shift[0] == 0.0f && e.shift[1] == 0.0f, "the extra frustum is centred");
    /* A z-up camera turns about z. */
    ob_camera z = {.eye = {0.0f, -3.0f, 1.0f}, .target = {0.0f, 0.0f, 1.0f}, .up = {0.0f, 0.0f, 2.0f}};
    ob_extra_view_camera(&z, &e);
    CHECK(fabsf(e.eye[0] - 3.0f) < 1e-5f && fabsf(e.eye[1]) < 1e-5f && fabsf(e.eye[2] - 1.0f) < 1e-5f,
          "about the camera's up (z): (%g, %g, %g)", e.eye[0], e.eye[1], e.eye[2]);
}

static bool render(ob_renderer *r, const ob_camera *cam, const ob_settings *s)
{
    ob_error e = ob_render_frame(r, cam, s);
    const char *msg = NULL;
    ob_get_error(&msg);
    CHECK(e == OB_OK, "frame: %s", msg);
    return e == OB_OK;
}

static void test_frames(ob_context *ctx)
{
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    ob_camera cam = {0};
    CHECK(scene && ob_find_camera(scene, "front", &cam) == OB_OK, "cornell:front");
    ob_renderer *r = scene ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H}) : NULL;
    CHECK(r != NULL, "renderer");
    if (!r) {
        ob_destroy_scene(scene);
        return;
    }
    ob_renderer_set_scene(r, scene);
    size_t n = (size_t)W * H;
    float *extra = malloc(n * 3 * sizeof(float)), *direct = malloc(n * 3 * sizeof(float));
    float *m_off = malloc(n * 3 * sizeof(float)), *m_on = malloc(n * 3 * sizeof(float));
    ob_settings off, on;
    ob_settings_init(&off, "ssdo_merged");
    ob_settings_set_filter(&off, "none");
    on = off;
    CHECK(ob_settings_set(&on, "ssdo_merged.extra_view=on") == OB_OK, "extra_view=on");
    ob_camera fitted = cam;
    ob_camera_fit_planes(&fitted, ob_query_scene_stats(scene).bounds_min, ob_query_scene_stats(scene).bounds_max);

    bool ok = render(r, &cam, &off) && ob_read_image(r, OB_IMAGE_EXTRA_RADIANCE_F32, extra, n * 3 * sizeof(float)) == OB_OK &&
              ob_read_image(r, OB_IMAGE_AO_RGB_F32, m_off, n * 3 * sizeof(float)) == OB_OK;
    float most = 0.0f;
    for (size_t i = 0; ok && i < n * 3; ++i) most = fmaxf(most, fabsf(extra[i]));
    CHECK(ok && most == 0.0f, "no extra view without the option (max %g)", most);

    ok = ok && render(r, &cam, &on) && ob_read_image(r, OB_IMAGE_EXTRA_RADIANCE_F32, extra, n * 3 * sizeof(float)) == OB_OK &&
         ob_read_image(r, OB_IMAGE_AO_RGB_F32, m_on, n * 3 * sizeof(float)) == OB_OK;
    int lower = 0, higher = 0;
    for (size_t i = 0; ok && i < n * 3; ++i) {
        lower += m_on[i] < m_off[i] - 1e-6f;
        higher += m_on[i] > m_off[i] + 1e-3f;
    }
    printf("  cornell:front, ssdo_merged M with the extra view: %d channels higher, %d lower (of %zu)\n", higher, lower,
           n * 3);
    CHECK(ok && lower == 0, "the extra view only frees samples: %d channels lower", lower);
    CHECK(ok && higher > 20, "and frees some behind cornell's blocks: %d channels higher", higher);

    /* The extra camera rendered as the main one: the same direct light, pixel for pixel. */
    ob_camera turned;
    ob_extra_view_camera(&fitted, &turned);
    ok = ok && render(r, &turned, &off) && ob_read_image(r, OB_IMAGE_RADIANCE_F32, direct, n * 3 * sizeof(float)) == OB_OK;
    double worst = 0.0, sum = 0.0;
    for (size_t i = 0; ok && i < n * 3; ++i) {
        worst = fmax(worst, fabs((double)extra[i] - direct[i]));
        sum += direct[i];
    }
    CHECK(ok && sum > 0.0, "the extra camera sees lit geometry");
    CHECK(ok && worst < 1e-4, "the extra view is that camera's frame (max difference %g)", worst);
    free(extra);
    free(direct);
    free(m_off);
    free(m_on);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

int main(void)
{
    test_camera();
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    test_frames(ctx);
    ob_destroy_context(ctx);
    return check_finish("test_extra_view");
}
