/* The floor kernel (src/passes/floor.c, shaders/floor.glsl) fetches what it claims: on synthetic
 * depth and normal textures its output is, per pixel, the centre normal's z plus the depths at the
 * N tap positions of its table, computed again here on the CPU from ob_floor_fill's table; sky
 * pixels write 0. Pixels with a tap within TAP_EPS px of a texel edge are skipped (GPU and CPU
 * round the position differently there) and the test demands that most pixels are checked. Then
 * ob_render_floor through the public API: the method's N, rays and radius, one timed pass "floor",
 * and its refusals. Never speed. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "gpu/gpu.h"
#include "passes/passes.h"

enum { W = 37, H = 29 }; /* partial 8x8 groups on both axes */
static const double TAP_EPS = 5e-4;

static float depth_at(int x, int y)
{
    if ((x + 2 * y) % 13 == 0) return 0.0f;                 /* sky */
    return 1.0f + (float)((x * 5 + y * 11) % 23) / 16.0f;    /* multiples of 1/16: exact sums */
}

static float normal_z(int x) { return 0.25f + 0.125f * (float)(x % 4); } /* exact in half floats */

static void check_kernel(ob_floor *f, GLuint depth_tex, GLuint normal_tex, const float *depth, const ob_floor_desc *d,
                         const char *what)
{
    static float table[OB_FLOOR_MAX_TAPS * 4];
    ob_floor_constants c;
    CHECK(ob_floor_fill(d, W, H, &c, table) == OB_OK, "%s: fill", what);
    CHECK(ob_floor_run(f, d, depth_tex, normal_tex, W, H) == OB_OK, "%s: run", what);
    float out[W * H];
    glGetTextureImage(f->texture, 0, GL_RED, GL_FLOAT, (GLsizei)sizeof out, out);
    CHECK(glGetError() == GL_NO_ERROR, "%s: read back", what);
    int checked = 0, wrong = 0, off_centre = 0, sky = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float dc = depth[y * W + x], got = out[y * W + x];
            if (dc <= 0.0f) {
                sky += 1;
                wrong += got != 0.0f;
                continue;
            }
            float r_px = fminf(c.radius * c.px_per_unit / dc, c.max_radius_px);
            const float *rot = c.rotation[(x & 3) + 4 * (y & 3)];
            double want = normal_z(x);
            bool ambiguous = false;
            for (int i = 0; i < d->taps && !ambiguous; ++i) {
                const float *k = table + 4 * i;
                double dist = (double)k[2] + (double)k[3] * (double)r_px;
                double qx = x + 0.5 + ((double)k[0] * rot[0] - (double)k[1] * rot[1]) * dist;
                double qy = y + 0.5 + ((double)k[0] * rot[1] + (double)k[1] * rot[0]) * dist;
                ambiguous = fabs(qx - floor(qx + 0.5)) < TAP_EPS || fabs(qy - floor(qy + 0.5)) < TAP_EPS;
                int ix = (int)floor(qx), iy = (int)floor(qy);
                ix = ix < 0 ? 0 : ix >= W ? W - 1 : ix;
                iy = iy < 0 ? 0 : iy >= H ? H - 1 : iy;
                want += depth[iy * W + ix];
            }
            if (ambiguous) continue;
            ++checked;
            if (fabs(got - want) > 1e-4) {
                if (wrong < 5) fprintf(stderr, "%s: pixel %d,%d: %.6f, want %.6f\n", what, x, y, got, (double)want);
                ++wrong;
            }
            /* A kernel that fetched the centre N times would give this: the taps must differ. */
            off_centre += fabs(want - (normal_z(x) + d->taps * (double)dc)) > 1e-4;
        }
    CHECK(wrong == 0, "%s: %d of %d pixels differ from the CPU's sum of taps", what, wrong, checked + sky);
    CHECK(checked >= (W * H - sky) * 8 / 10, "%s: %d of %d pixels unambiguous", what, checked, W * H - sky);
    CHECK(off_centre >= checked / 2, "%s: only %d of %d pixels' taps leave the centre texel", what, off_centre,
          checked);
}

static void test_kernel(void)
{
    float depth[W * H], normal[W * H * 4];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            depth[y * W + x] = depth_at(x, y);
            float *n = normal + 4 * (y * W + x);
            n[0] = 0.5f;
            n[1] = -0.5f;
            n[2] = normal_z(x);
            n[3] = 0.0f;
        }
    GLuint depth_tex = ob_make_texture_2d(GL_R32F, W, H), normal_tex = ob_make_texture_2d(GL_RGBA16F, W, H);
    glTextureSubImage2D(depth_tex, 0, 0, 0, W, H, GL_RED, GL_FLOAT, depth);
    glTextureSubImage2D(normal_tex, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, normal);
    ob_floor f;
    CHECK(ob_floor_init(&f) == OB_OK, "init");
    /* The disk at 16 and 64 taps (R_px 2.5..6 px over the depths), rays of 4 x 3 clamped at 3 px,
     * and 8 rays x 8 steps reaching past the edges (taps clamped to the border). */
    check_kernel(&f, depth_tex, normal_tex, depth,
                 &(ob_floor_desc){.taps = 16, .radius = 1.0f, .px_per_unit = 6.0f}, "disk 16");
    check_kernel(&f, depth_tex, normal_tex, depth,
                 &(ob_floor_desc){.taps = 64, .radius = 2.0f, .px_per_unit = 3.0f}, "disk 64");
    check_kernel(&f, depth_tex, normal_tex, depth,
                 &(ob_floor_desc){.taps = 12, .rays = 4, .radius = 1.0f, .px_per_unit = 6.0f, .max_radius_px = 3.0f},
                 "rays 4x3 clamped");
    check_kernel(&f, depth_tex, normal_tex, depth,
                 &(ob_floor_desc){.taps = 64, .rays = 8, .radius = 4.0f, .px_per_unit = 10.0f}, "rays 8x8");
    /* Refusals of the pure half. */
    static float table[OB_FLOOR_MAX_TAPS * 4];
    ob_floor_constants c;
    CHECK(ob_floor_fill(&(ob_floor_desc){.taps = 10, .rays = 4, .radius = 1.0f, .px_per_unit = 1.0f}, W, H, &c, table) ==
              OB_ERR_INVALID_ARGUMENT, "10 taps on 4 rays refused");
    CHECK(ob_floor_fill(&(ob_floor_desc){.taps = OB_FLOOR_MAX_TAPS + 1, .radius = 1.0f, .px_per_unit = 1.0f}, W, H, &c,
                        table) == OB_ERR_INVALID_ARGUMENT, "too many taps refused");
    CHECK(ob_floor_fill(&(ob_floor_desc){.taps = 4, .px_per_unit = 1.0f}, W, H, &c, table) == OB_ERR_INVALID_ARGUMENT,
          "radius 0 refused");
    ob_clear_error();
    ob_floor_destroy(&f);
    glDeleteTextures(1, &depth_tex);
    glDeleteTextures(1, &normal_tex);
}

/* The public entry: N and the pattern from the method's settings, one timed pass. */
static void test_public(ob_context *ctx, ob_scene *scene, const ob_camera *cam)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = 48, .height = 32});
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK, "renderer");
    if (!r) return;
    ob_settings s;
    ob_settings_init(&s, "ssao");
    CHECK(ob_render_floor(r, &s, NULL) == OB_ERR_INVALID_ARGUMENT, "refused before any frame");
    CHECK(ob_render_floor(NULL, &s, NULL) == OB_ERR_INVALID_ARGUMENT, "NULL renderer refused");
    ob_clear_error();
    static const struct { const char *method; int samples, rays; } cases[] = {
        {"ssao", 16, 0}, {"alchemy", 24, 0}, {"hbao", 16, -1}, {"gtao", 24, -1}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        ob_settings_init(&s, cases[k].method);
        CHECK(ob_settings_set_samples(&s, cases[k].samples) == OB_OK, "%s: samples", cases[k].method);
        CHECK(ob_render_frame(r, cam, &s) == OB_OK, "%s: frame", cases[k].method);
        ob_floor_info info = {0};
        CHECK(ob_render_floor(r, &s, &info) == OB_OK, "%s: floor", cases[k].method);
        CHECK(info.taps == cases[k].samples, "%s: %d taps, want %d", cases[k].method, info.taps, cases[k].samples);
        if (cases[k].rays == 0) CHECK(info.rays == 0, "%s: a disk, got %d rays", cases[k].method, info.rays);
        else CHECK(info.rays > 0 && info.taps % info.rays == 0, "%s: %d rays", cases[k].method, info.rays);
        CHECK(info.radius > 0.0f, "%s: radius %g", cases[k].method, (double)info.radius);
        CHECK(ob_wait_timings(r) == OB_OK, "%s: wait", cases[k].method);
        ob_pass_timing t[4];
        int n = ob_query_timings(r, t, 4);
        CHECK(n == 1 && !strcmp(t[0].name, "floor") && t[0].ms >= 0.0 && isfinite(t[0].ms),
              "%s: one pass 'floor' timed (%d passes)", cases[k].method, n);
    }
    /* Another AO scale than the last frame's, and a method without samples. */
    ob_settings_init(&s, "ssao");
    ob_settings_set_ao_divisor(&s, 2);
    CHECK(ob_render_floor(r, &s, NULL) == OB_ERR_INVALID_ARGUMENT, "refused at another AO scale");
    ob_settings_init(&s, "none");
    CHECK(ob_render_frame(r, cam, &s) == OB_OK, "none frame");
    CHECK(ob_render_floor(r, &s, NULL) == OB_ERR_INVALID_ARGUMENT, "none: no sample count, refused");
    ob_clear_error();
    ob_destroy_renderer(r);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    test_kernel();
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    ob_camera cam;
    CHECK(scene && ob_find_camera(scene, "front", &cam) == OB_OK, "cornell, camera front");
    if (scene) test_public(ctx, scene, &cam);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_floor");
}
