/* GPU integration tests on the real GLSL (llvmpipe in CI): the G-buffer against analytic depth
 * and normals in `corner`, SSAO's behaviour on open and creased surfaces, determinism, the
 * engine-texture entry point, and driver errors mapped to shaders/FILE:LINE. */
#include <cglm/cglm.h>
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gpu/gpu.h"
#include "gpu/shaders_embedded.h"
#include "obscura/eval.h"

enum { W = 128, H = 96 };

/* The test camera: explicit planes so the test can rebuild the same matrices. */
static const ob_camera test_cam = {
    .eye = {5.0f, 3.0f, 5.0f}, .target = {0.8f, 0.4f, 0.8f}, .up = {0.0f, 1.0f, 0.0f},
    .fov_y_deg = 70.0f, .near_z = 0.1f, .far_z = 100.0f, .name = "test"};

static void matrices(mat4 view, mat4 proj)
{
    vec3 eye, target, up;
    memcpy(eye, test_cam.eye, sizeof eye);
    memcpy(target, test_cam.target, sizeof target);
    memcpy(up, test_cam.up, sizeof up);
    glm_lookat(eye, target, up, view);
    glm_perspective(glm_rad(test_cam.fov_y_deg), (float)W / (float)H, test_cam.near_z, test_cam.far_z, proj);
}

/* Pixel (GL convention: row 0 at the bottom) of a world point, or false if off screen. */
static bool project(const float p[3], int *px, int *py)
{
    mat4 view, proj, vp;
    matrices(view, proj);
    glm_mat4_mul(proj, view, vp);
    vec4 wp = {p[0], p[1], p[2], 1.0f}, clip;
    glm_mat4_mulv(vp, wp, clip);
    if (clip[3] <= 0.0f) return false;
    float x = (clip[0] / clip[3] * 0.5f + 0.5f) * W, y = (clip[1] / clip[3] * 0.5f + 0.5f) * H;
    *px = (int)x;
    *py = (int)y;
    return *px >= 0 && *px < W && *py >= 0 && *py < H;
}

/* Ray through a pixel centre against the corner's three planes (each a 4x4 square). */
static bool analytic_hit(int x, int y, float *depth, vec3 normal_world, float *edge_dist)
{
    mat4 view, inv;
    mat4 proj;
    matrices(view, proj);
    glm_mat4_inv(view, inv);
    float t = tanf(glm_rad(test_cam.fov_y_deg) * 0.5f);
    vec3 dir_view = {((x + 0.5f) / W * 2.0f - 1.0f) * t * (float)W / (float)H, ((y + 0.5f) / H * 2.0f - 1.0f) * t, -1.0f};
    vec3 dir;
    glm_mat4_mulv3(inv, dir_view, 0.0f, dir);
    const float *e = test_cam.eye;
    float best = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
        if (fabsf(dir[axis]) < 1e-6f) continue;
        float s = -e[axis] / dir[axis];
        if (s <= 0.0f || s >= best) continue;
        float h[3] = {e[0] + s * dir[0], e[1] + s * dir[1], e[2] + s * dir[2]};
        bool inside = true;
        float edge = INFINITY;
        for (int k = 0; k < 3; ++k) {
            if (k == axis) continue;
            if (h[k] < 0.0f || h[k] > 4.0f) inside = false;
            edge = fminf(edge, fminf(h[k], 4.0f - h[k]));
        }
        if (!inside) continue;
        best = s;
        glm_vec3_zero(normal_world);
        normal_world[axis] = 1.0f;
        *edge_dist = edge;
    }
    /* |dir_view| has z = -1, so the ray parameter is the linear depth. */
    *depth = best;
    return isfinite(best);
}

static ob_renderer *make(ob_context *ctx, ob_scene *scene)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    const char *msg = NULL;
    ob_get_error(&msg);
    CHECK(r != NULL, "renderer: %s", msg);
    if (r) CHECK(ob_renderer_set_scene(r, scene) == OB_OK, "scene upload");
    return r;
}

static void test_gbuffer(ob_renderer *r, const ob_settings *s)
{
    CHECK(ob_render_frame(r, &test_cam, s) == OB_OK, "frame");
    float *depth = malloc(ob_image_size(r, OB_IMAGE_DEPTH_F32));
    float *normal = malloc(ob_image_size(r, OB_IMAGE_NORMAL_F32));
    CHECK(ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, ob_image_size(r, OB_IMAGE_DEPTH_F32)) == OB_OK, "read depth");
    CHECK(ob_read_image(r, OB_IMAGE_NORMAL_F32, normal, ob_image_size(r, OB_IMAGE_NORMAL_F32)) == OB_OK, "read normals");
    mat4 view, proj;
    matrices(view, proj);
    int compared = 0, sky = 0;
    double worst_depth = 0.0, worst_normal = 1.0;
    for (int y = 2; y < H; y += 5) {
        for (int x = 2; x < W; x += 5) {
            float d = 0.0f, edge = 0.0f;
            vec3 nw = {0.0f, 0.0f, 0.0f}; /* analytic_hit sets it on a hit; Release builds cannot see that */
            float got_d = depth[y * W + x];
            if (!analytic_hit(x, y, &d, nw, &edge)) {
                /* Background: no geometry, depth cleared to 0. */
                CHECK(got_d == 0.0f, "pixel %d,%d should be sky, depth %g", x, y, (double)got_d);
                ++sky;
                continue;
            }
            if (edge < 0.05f) continue; /* a pixel footprint away from creases and borders */
            vec3 nv;
            glm_mat4_mulv3(view, nw, 0.0f, nv);
            const float *g = &normal[(y * W + x) * 3];
            double rel = fabs(got_d - d) / d;
            double dot = g[0] * nv[0] + g[1] * nv[1] + g[2] * nv[2];
            if (rel > worst_depth) worst_depth = rel;
            if (dot < worst_normal) worst_normal = dot;
            ++compared;
        }
    }
    /* R32F linear depth is interpolated from the vertices in float: 1e-4 relative is ample. */
    CHECK(worst_depth < 1e-4, "linear depth within 1e-4 relative of analytic (worst %.2e)", worst_depth);
    /* RGBA16F normals: 11-bit mantissa, so dot >= 0.9995. */
    CHECK(worst_normal > 0.9995, "view normals match analytic (worst dot %.6f)", worst_normal);
    CHECK(compared > 200 && sky > 10, "compared %d geometry and %d sky pixels", compared, sky);
    free(depth);
    free(normal);
}

static float ao_at(const float *ao, const float p[3])
{
    int x = 0, y = 0;
    if (!project(p, &x, &y)) return NAN;
    return ao[y * W + x];
}

static void test_ssao(ob_renderer *r, const ob_settings *s)
{
    CHECK(ob_render_frame(r, &test_cam, s) == OB_OK, "frame");
    size_t n = ob_image_size(r, OB_IMAGE_AO_F32);
    float *ao = malloc(n), *raw = malloc(n), *raw2 = malloc(n);
    CHECK(ob_read_image(r, OB_IMAGE_AO_F32, ao, n) == OB_OK, "read ao");
    CHECK(ob_read_image(r, OB_IMAGE_AO_RAW_F32, raw, n) == OB_OK, "read raw ao");

    /* Open floor, 3 radii from both walls: nothing occludes the hemisphere. */
    const float open[3] = {3.0f, 0.0f, 3.0f};
    float a = ao_at(ao, open);
    CHECK(a > 0.9f, "open plane AO %g > 0.9", (double)a);

    /* Walking along the floor toward the wall x = 0: AO falls monotonically. A 1.5 m radius
     * spreads the falloff over enough pixels of this small image to resolve it. */
    ob_settings wide = *s;
    CHECK(ob_settings_set(&wide, "ssao.radius=1.5") == OB_OK, "radius 1.5");
    CHECK(ob_render_frame(r, &test_cam, &wide) == OB_OK, "frame");
    CHECK(ob_read_image(r, OB_IMAGE_AO_F32, ao, n) == OB_OK, "read ao");
    const float xs[] = {1.8f, 1.2f, 0.8f, 0.5f, 0.3f, 0.15f};
    float prev = 2.0f, first = NAN, last = NAN;
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; ++i) {
        const float p[3] = {xs[i], 0.0f, 2.0f};
        float v = ao_at(ao, p);
        CHECK(isfinite(v), "point %g,0,2 on screen", (double)xs[i]);
        /* 0.02: the residue of the 4x4 noise after the 4x4 blur. */
        CHECK(v <= prev + 0.02f, "AO at x=%g is %g, after %g further out", (double)xs[i], (double)v, (double)prev);
        printf("  floor AO at %.2f m from the wall: %.4f\n", (double)xs[i], (double)v);
        if (i == 0) first = v;
        last = v;
        prev = v;
    }
    CHECK(first - last > 0.1f, "the crease darkens: %g far vs %g near", (double)first, (double)last);

    /* Visibility is in [0,1] everywhere; the sky is 1. */
    int out_of_range = 0;
    for (size_t i = 0; i < n / sizeof(float); ++i) out_of_range += !(raw[i] >= 0.0f && raw[i] <= 1.0f);
    CHECK(out_of_range == 0, "%d raw AO values outside [0,1]", out_of_range);

    /* The same frame again gives the same bytes. */
    CHECK(ob_render_frame(r, &test_cam, s) == OB_OK, "frame 2");
    CHECK(ob_read_image(r, OB_IMAGE_AO_RAW_F32, raw2, n) == OB_OK, "read raw ao 2");
    CHECK(memcmp(raw, raw2, n) == 0, "identical AO bytes on a second frame");

    /* ob_compute_ao on an engine's own textures gives the pipeline's raw AO exactly. */
    float *depth = malloc(n), *normal3 = malloc(n * 3), *normal4 = malloc(n * 4), *ext = malloc(n);
    ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, n);
    ob_read_image(r, OB_IMAGE_NORMAL_F32, normal3, n * 3);
    for (int i = 0; i < W * H; ++i) {
        memcpy(&normal4[i * 4], &normal3[i * 3], 3 * sizeof(float));
        normal4[i * 4 + 3] = 1.0f;
    }
    GLuint tex[3] = {ob_make_texture_2d(GL_R32F, W, H), ob_make_texture_2d(GL_RGBA32F, W, H),
                     ob_make_texture_2d(GL_R32F, W, H)};
    glTextureSubImage2D(tex[0], 0, 0, 0, W, H, GL_RED, GL_FLOAT, depth);
    glTextureSubImage2D(tex[1], 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, normal4);
    mat4 view, proj;
    matrices(view, proj);
    ob_settings s2 = *s;
    /* The pipeline resolved the radius from the scene; give the engine path the same value. */
    char set[64];
    snprintf(set, sizeof set, "ssao.radius=%.9g", (double)0.5f);
    CHECK(ob_settings_set(&s2, set) == OB_OK, "set radius");
    CHECK(ob_compute_ao(r, tex[0], tex[1], (const float *)proj, &s2, tex[2]) == OB_OK, "ob_compute_ao");
    glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)n, ext);
    double max_diff = 0.0;
    for (int i = 0; i < W * H; ++i) max_diff = fmax(max_diff, fabs(ext[i] - raw[i]));
    /* RGBA16F normals read back as floats are exact, so the result must be identical. */
    CHECK(max_diff == 0.0, "engine-texture AO differs from the pipeline by %g", max_diff);
    /* ... and with the settings' filter, the pipeline's filtered AO exactly. */
    CHECK(ob_render_frame(r, &test_cam, s) == OB_OK, "frame 3");
    float *filtered = malloc(n);
    CHECK(ob_read_image(r, OB_IMAGE_AO_F32, filtered, n) == OB_OK, "read filtered ao");
    CHECK(ob_compute_ao_filtered(r, tex[0], tex[1], (const float *)proj, &s2, tex[2]) == OB_OK, "ob_compute_ao_filtered");
    glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)n, ext);
    double filtered_diff = 0.0, raw_diff = 0.0;
    for (int i = 0; i < W * H; ++i) {
        filtered_diff = fmax(filtered_diff, fabs(ext[i] - filtered[i]));
        raw_diff = fmax(raw_diff, fabs(ext[i] - raw[i]));
    }
    CHECK(filtered_diff == 0.0 && raw_diff > 0.0,
          "engine-texture filtered AO: %g from the pipeline's filtered AO (0 expected), %g from the raw", filtered_diff,
          raw_diff);
    free(filtered);
    glDeleteTextures(3, tex);
    free(depth);
    free(normal3);
    free(normal4);
    free(ext);
    free(ao);
    free(raw);
    free(raw2);
}

/* Every pixel of an image equal to 1 (float images only). */
static int count_not_one(ob_renderer *r, ob_image_kind kind)
{
    size_t n = ob_image_size(r, kind);
    float *v = malloc(n);
    ob_read_image(r, kind, v, n);
    int not_one = 0;
    for (size_t i = 0; i < n / sizeof(float); ++i) not_one += v[i] != 1.0f;
    free(v);
    return not_one;
}

/* none writes 1 with the fill pass and skips the full-size target while it still holds the last
 * none frame's 1 (frame.c run_without_ao): also after another method wrote it, a second none
 * frame in a row, and at another AO scale. */
static void test_none(ob_renderer *r)
{
    ob_settings s, ssao;
    ob_settings_init(&s, "none");
    ob_settings_init(&ssao, "ssao");
    const float scales[4] = {1.0f, 1.0f, 0.5f, 1.0f};
    const bool ssao_first[4] = {false, true, true, false};
    for (int i = 0; i < 4; ++i) {
        if (ssao_first[i]) {
            ob_settings_set_ao_scale(&ssao, scales[i]);
            CHECK(ob_render_frame(r, &test_cam, &ssao) == OB_OK, "frame ssao");
            CHECK(count_not_one(r, OB_IMAGE_AO_F32) > 0, "ssao occludes something (else the check below proves nothing)");
        }
        ob_settings_set_ao_scale(&s, scales[i]);
        CHECK(ob_render_frame(r, &test_cam, &s) == OB_OK, "frame none");
        CHECK(count_not_one(r, OB_IMAGE_AO_F32) == 0, "method none (frame %d, scale %.1f): AO != 1", i, scales[i]);
        CHECK(count_not_one(r, OB_IMAGE_AO_RAW_F32) == 0, "method none (frame %d, scale %.1f): raw AO != 1", i,
              scales[i]);
    }
}

static void test_shader_errors(void)
{
    /* A real driver log for an error on line 3 of a file we claim is ssao.glsl (#line ID*10000+3). */
    int id = 0;
    for (int i = 0; i < ob_shader_file_count; ++i)
        if (!strcmp(ob_shader_file_names[i], "ssao.glsl")) id = i + 1;
    char src[256];
    snprintf(src, sizeof src, "#version 450 core\nlayout(local_size_x = 1) in;\n#line %d\nvoid main() { undefined_thing = 1; }\n", id * 10000 + 3);
    GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
    const char *srcs[1] = {src};
    glShaderSource(sh, 1, srcs, NULL);
    glCompileShader(sh);
    GLint ok = 1;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    char log[2048] = "", line[512] = "";
    glGetShaderInfoLog(sh, sizeof log, NULL, log);
    glDeleteShader(sh);
    CHECK(!ok, "the broken shader fails");
    ob_format_shader_log(log, "x.glsl", line, sizeof line);
    CHECK(strncmp(line, "shaders/ssao.glsl:3: ", 21) == 0, "driver log mapped: '%s' (log: %s)", line, log);
    CHECK(ob_make_compute_program("no-such-shader.glsl", NULL) == 0, "missing shader fails");
    const char *msg = NULL;
    CHECK(ob_get_error(&msg) == OB_ERR_SHADER && strstr(msg, "no-such-shader.glsl"), "message: %s", msg);
}

int main(void)
{
    ob_context *ctx = ob_make_context(&(ob_context_desc){.gpu = OB_GPU_AUTO});
    if (!ctx) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "no context: %s\n", msg);
        return 1;
    }
    printf("renderer: %s (%s)\n", ob_query_renderer(ctx), ob_query_device(ctx));
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = "corner"});
    CHECK(scene != NULL, "corner loads");
    CHECK_NEAR(ob_query_scene_ao_radius(scene), 0.5, 1e-6, "corner's suggested radius");
    ob_renderer *r = make(ctx, scene);
    ob_settings s;
    ob_settings_init(&s, "ssao");
    ob_settings_set_filter(&s, "box4"); /* the tolerances below are the box blur's */
    if (r) {
        test_gbuffer(r, &s);
        test_ssao(r, &s);
        test_none(r);
    }
    test_shader_errors();
    ob_renderer *bad = ob_make_renderer(ctx, &(ob_renderer_desc){.width = ob_query_max_texture_size(ctx) + 1, .height = 4});
    CHECK(bad == NULL && ob_get_error(NULL) == OB_ERR_BAD_SIZE, "size above GL_MAX_TEXTURE_SIZE refused");
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_gpu");
}
