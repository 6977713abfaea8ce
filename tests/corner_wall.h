/* The analytic crease of `corner`, shared by test_gtao.c and test_bitmask.c: one frame of a method
 * looking down at the floor beside the wall x = 0 (away from the wall z = 0), read back with world
 * points, and AO_R's closed form beside one wall (docs/architecture.md): a floor point at h from the wall
 * has AO_R = 1 - (acos a - a sqrt(1 - a^2)) / π, a = h / R. */
#ifndef OB_TEST_CORNER_WALL_H
#define OB_TEST_CORNER_WALL_H

#include <cglm/cglm.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "check.h"
#include "obscura/eval.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static inline double ao_r_one_wall(double h, double r)
{
    double a = h / r;
    if (a >= 1.0) return 1.0;
    return 1.0 - (acos(a) - a * sqrt(1.0 - a * a)) / M_PI;
}

typedef struct corner_wall {
    int width, height;
    float *ao;     /* OB_IMAGE_AO_RAW_F32 */
    float *depth;  /* linear depth, 0 = sky */
    float *pos;    /* world positions, 3 per pixel */
    float *wn;     /* world normals, 3 per pixel */
    float *bent;   /* OB_IMAGE_BENT_NORMAL_F32 (view space), 3 per pixel */
    float inv_view[16];
} corner_wall;

/* One frame of s's method (its AO unfiltered, as s asks) at width x height. */
static inline bool corner_wall_render(ob_context *ctx, const ob_settings *s, int width, int height, corner_wall *f)
{
    memset(f, 0, sizeof *f);
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "corner"});
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = width, .height = height});
    CHECK(scene && r, "corner scene and renderer");
    bool ok = scene && r && ob_renderer_set_scene(r, scene) == OB_OK;
    const ob_camera cam = {.eye = {1.6f, 2.2f, 2.0f}, .target = {0.35f, 0.0f, 2.0f}, .up = {0, 1, 0},
                           .fov_y_deg = 60.0f, .near_z = 0.05f, .far_z = 20.0f, .name = "wall"};
    ok = ok && ob_render_frame(r, &cam, s) == OB_OK;
    CHECK(ok, "corner frame");
    size_t n = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
    f->ao = malloc(n * sizeof(float));
    f->depth = malloc(n * sizeof(float));
    f->pos = malloc(n * 3 * sizeof(float));
    f->wn = malloc(n * 3 * sizeof(float));
    f->bent = malloc(n * 3 * sizeof(float));
    float *normals = malloc(n * 3 * sizeof(float));
    if (ok) {
        ob_read_image(r, OB_IMAGE_AO_RAW_F32, f->ao, n * sizeof(float));
        ob_read_image(r, OB_IMAGE_DEPTH_F32, f->depth, n * sizeof(float));
        ob_read_image(r, OB_IMAGE_NORMAL_F32, normals, n * 3 * sizeof(float));
        ob_read_image(r, OB_IMAGE_BENT_NORMAL_F32, f->bent, n * 3 * sizeof(float));
        /* The renderer's camera matrices, for the world points. */
        mat4 view, proj, inv_view;
        glm_lookat((float *)cam.eye, (float *)cam.target, (float *)cam.up, view);
        glm_perspective(glm_rad(cam.fov_y_deg), (float)width / (float)height, cam.near_z, cam.far_z, proj);
        glm_mat4_inv(view, inv_view);
        memcpy(f->inv_view, inv_view, sizeof f->inv_view);
        const float info[4] = {1.0f / proj[0][0], 1.0f / proj[1][1], proj[2][0], proj[2][1]};
        ob_reference_points(f->depth, normals, width, height, info, (const float *)inv_view, f->pos, f->wn);
    }
    free(normals);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
    return ok;
}

/* Pixel i is floor far (> R) from the wall z = 0 and from the planes' far edges: *h is its
 * distance from the wall x = 0. */
static inline bool corner_wall_floor(const corner_wall *f, size_t i, float radius, double *h)
{
    const float *p = &f->pos[3 * i], *nn = &f->wn[3 * i];
    bool floor = f->depth[i] > 0.0f && nn[1] > 0.99f && fabsf(p[1]) < 1e-3f;
    if (!floor || p[2] < 1.2f || p[2] > 2.8f || p[0] > 4.0f - radius) return false;
    *h = p[0];
    return true;
}

static inline void corner_wall_free(corner_wall *f)
{
    free(f->ao);
    free(f->depth);
    free(f->pos);
    free(f->wn);
    free(f->bent);
    memset(f, 0, sizeof *f);
}

#endif
