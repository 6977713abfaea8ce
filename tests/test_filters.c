/* Filters, subsampling and adaptive sample counts (issue 4), on synthetic textures where the
 * answer is known and on the demo scenes:
 *   - edge preservation across a depth step: the edge-aware filters do not leak, gaussian does;
 *   - noise reduction on a flat region under `geometry`;
 *   - bilateral_sep against the full bilateral;
 *   - half- and quarter-resolution AO + joint bilateral upsampling against full resolution, and
 *     silhouettes keeping their own side's AO;
 *   - adaptive counts: more samples at edges, fewer in total;
 *   - `crease` (issue 13): the 4x4 noise tile cancels exactly on a tilted plane, independent noise
 *     falls, no leak across a depth step, the RGB variant weighs like the R32F one, and the floor
 *     beside the corner's crease keeps its raw AO. */
#include <cglm/cglm.h>
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "filters/filter.h"
#include "frame_params.h"
#include "obscura/eval.h"
#include "passes/passes.h"
#include "sampling/sampling.h"

enum { W = 96, H = 64 };

static GLuint upload(GLenum format, int w, int h, GLenum channels, const float *data)
{
    GLuint t = ob_make_texture_2d(format, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, channels, GL_FLOAT, data);
    return t;
}

static void download(GLuint t, int w, int h, float *out)
{
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glGetTextureImage(t, 0, GL_RED, GL_FLOAT, (GLsizei)((size_t)w * (size_t)h * sizeof(float)), out);
}

/* A view-facing scene of two planes: x < W/2 at depth 2 with AO 0.3, the rest at depth 10 with
 * AO 1 (the far plane is open, the near one occluded), plus optional noise. */
typedef struct synthetic {
    GLuint depth, normal, ao, out, scratch;
    float ao_in[W * H];
} synthetic;

static void make_synthetic(synthetic *s, float noise, bool step)
{
    static float depth[W * H], normal[W * H * 4];
    ob_rng rng;
    ob_rng_seed(&rng, 99, 5);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            bool near = step && x < W / 2;
            depth[i] = near ? 2.0f : 10.0f;
            normal[4 * i + 0] = 0.0f;
            normal[4 * i + 1] = 0.0f;
            normal[4 * i + 2] = 1.0f;
            normal[4 * i + 3] = 1.0f;
            float base = step ? (near ? 0.3f : 1.0f) : 0.6f;
            s->ao_in[i] = base + noise * (ob_rng_float(&rng) * 2.0f - 1.0f);
        }
    s->depth = upload(GL_R32F, W, H, GL_RED, depth);
    s->normal = upload(GL_RGBA16F, W, H, GL_RGBA, normal);
    s->ao = upload(GL_R32F, W, H, GL_RED, s->ao_in);
    s->out = ob_make_texture_2d(GL_R32F, W, H);
    s->scratch = ob_make_texture_2d(GL_R32F, W, H);
}

static void free_synthetic(synthetic *s)
{
    GLuint t[5] = {s->depth, s->normal, s->ao, s->out, s->scratch};
    glDeleteTextures(5, t);
}

static bool run_filter(const char *name, synthetic *s, float *out)
{
    int fi = ob_find_filter(name);
    CHECK(fi >= 0, "filter %s registered", name);
    if (fi < 0) return false;
    const ob_filter_impl *f = ob_filter_impl_at(fi);
    float params[OB_MAX_PARAMS] = {0};
    for (int i = 0; i < f->info.param_count; ++i) params[i] = f->info.params[i].def;
    void *state = f->init ? f->init() : NULL;
    CHECK(!f->init || state, "%s init", name);
    const ob_filter_inputs in = {s->ao, s->out, s->scratch, s->depth, s->normal, W, H};
    CHECK(f->run(state, &in, params) == OB_OK, "%s run", name);
    download(s->out, W, H, out);
    if (f->destroy) f->destroy(state);
    return true;
}

static void test_edges(void)
{
    synthetic s;
    make_synthetic(&s, 0.0f, true);
    const char *names[] = {"gaussian", "bilateral", "bilateral_sep", "geometry", "box4", "crease"};
    for (size_t n = 0; n < sizeof names / sizeof names[0]; ++n) {
        float out[W * H];
        if (!run_filter(names[n], &s, out)) continue;
        /* The leak: mean change within 4 pixels on either side of the step. */
        double leak = 0.0;
        int count = 0;
        for (int y = 8; y < H - 8; ++y)
            for (int x = W / 2 - 4; x < W / 2 + 4; ++x) {
                leak += fabs(out[y * W + x] - s.ao_in[y * W + x]);
                ++count;
            }
        leak /= count;
        printf("  %-14s leak across the depth step %.4f\n", names[n], leak);
        if (!strcmp(names[n], "gaussian"))
            CHECK(leak > 0.05, "gaussian ignores geometry and should leak (%.4f)", leak);
        else if (strcmp(names[n], "box4") != 0)
            CHECK(leak < 0.005, "%s leaks %.4f across a 5x depth step", names[n], leak);
    }
    free_synthetic(&s);
}

static double variance(const float *v, int x0, int x1, int y0, int y1)
{
    double sum = 0.0, sq = 0.0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            sum += v[y * W + x];
            sq += (double)v[y * W + x] * v[y * W + x];
            ++n;
        }
    double mean = sum / n;
    return sq / n - mean * mean;
}

static void test_noise(void)
{
    synthetic s;
    make_synthetic(&s, 0.2f, false);
    float out[W * H];
    if (run_filter("geometry", &s, out)) {
        double raw = variance(s.ao_in, 16, W - 16, 16, H - 16), after = variance(out, 16, W - 16, 16, H - 16);
        printf("  geometry on a flat noisy region: variance %.5f -> %.5f (%.1f%%)\n", raw, after, 100.0 * after / raw);
        /* An 11x11 kernel with sigma 3 averages ~100 pixels with Gaussian weights: the variance
         * of independent noise falls to about 1/(4 pi sigma^2) = 0.9%; 5% leaves room. */
        CHECK(after <= 0.05 * raw, "geometry keeps %.1f%% of the variance (at most 5%%)", 100.0 * after / raw);
    }
    free_synthetic(&s);
}

/* ---- crease (src/filters/crease.c) ------------------------------------------------------------ */

/* The synthetic textures' camera: 60 deg vertical fov, square pixels, centred. `crease` rebuilds
 * view positions from the per-frame block as the methods do, so the tests bind one at
 * OB_BINDING_FRAME as the renderer would. */
static const float synthetic_ty = 0.57735027f; /* tan 30 deg */
static GLuint synthetic_frame_ubo;

static void bind_synthetic_frame(void)
{
    static ob_frame_constants f;
    memset(&f, 0, sizeof f);
    const float tx = synthetic_ty * (float)W / (float)H;
    /* proj_info = (1/P00, 1/P11, P20, P21) of a symmetric perspective (common.glsl). */
    f.proj_info[0] = f.ao_proj_info[0] = tx;
    f.proj_info[1] = f.ao_proj_info[1] = synthetic_ty;
    f.size[0] = f.ao_size[0] = (float)W;
    f.size[1] = f.ao_size[1] = (float)H;
    f.inv_size[0] = f.ao_inv_size[0] = 1.0f / (float)W;
    f.inv_size[1] = f.ao_inv_size[1] = 1.0f / (float)H;
    f.ao_k = 1;
    if (!synthetic_frame_ubo) {
        glCreateBuffers(1, &synthetic_frame_ubo);
        glNamedBufferStorage(synthetic_frame_ubo, sizeof f, &f, 0);
    }
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, synthetic_frame_ubo);
}

/* Eq. 1 of crease.glsl: with an even radius every residue mod 4 gets the same total weight, so a
 * 4x4-periodic pattern averages to its mean. Pure: no GL. */
static void test_crease_weights(void)
{
    const ob_filter_inputs in = {.width = W, .height = H};
    for (int r = 2; r <= 4; r += 2) {
        ob_filter_constants c;
        ob_crease_constants_init(&c, &in, r, 0.005f, 0.35f);
        float residue[4] = {0};
        for (int i = -r; i <= r; ++i) residue[((i % 4) + 4) % 4] += c.weights[abs(i)][0];
        for (int k = 1; k < 4; ++k)
            CHECK_NEAR(residue[k], residue[0], 1e-6, "crease: a residue mod 4 of the window weighs as much as the others");
        CHECK(c.radius == r && c.depth_falloff < 0.0f && c.normal_falloff < 0.0f, "crease constants for r = %d", r);
    }
}

/* A plane tilted 45 deg toward the camera (a floor seen from above, view-space normal
 * (0, 1, 1)/sqrt 2 at distance 1): its depth spans 0.9 .. 3.3 from the bottom row to the top, so
 * only exact view positions put every tap on p's plane. pattern: the 4x4 noise tile, else
 * independent noise 0.6 +- 0.2. */
static void make_tilted(synthetic *s, bool pattern)
{
    static float depth[W * H], normal[W * H * 4];
    const float c = 0.70710678f;
    ob_rng rng;
    ob_rng_seed(&rng, 7, 3);
    float tile[16];
    for (int k = 0; k < 16; ++k) tile[k] = 0.3f + 0.6f * ob_rng_float(&rng);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            /* P = d (ndc.x tx, ndc.y ty, -1) on n . P = -1 (common.glsl ob_view_position); n has
             * no x, so d depends on the row alone. */
            float ny = ((float)y + 0.5f) / (float)H * 2.0f - 1.0f;
            depth[i] = -1.0f / (c * ny * synthetic_ty - c);
            normal[4 * i + 0] = 0.0f;
            normal[4 * i + 1] = c;
            normal[4 * i + 2] = c;
            normal[4 * i + 3] = 1.0f;
            s->ao_in[i] = pattern ? tile[(y % 4) * 4 + x % 4] : 0.6f + 0.2f * (ob_rng_float(&rng) * 2.0f - 1.0f);
        }
    s->depth = upload(GL_R32F, W, H, GL_RED, depth);
    s->normal = upload(GL_RGBA16F, W, H, GL_RGBA, normal);
    s->ao = upload(GL_R32F, W, H, GL_RED, s->ao_in);
    s->out = ob_make_texture_2d(GL_R32F, W, H);
    s->scratch = ob_make_texture_2d(GL_R32F, W, H);
}

static void test_crease_plane(void)
{
    synthetic s;
    float out[W * H];
    make_tilted(&s, true);
    if (run_filter("crease", &s, out)) {
        double mean = 0.0, worst = 0.0;
        for (int k = 0; k < 16; ++k) mean += s.ao_in[(k / 4) * W + k % 4] / 16.0;
        for (int y = 2; y < H - 2; ++y)
            for (int x = 2; x < W - 2; ++x) worst = fmax(worst, fabs(out[y * W + x] - mean));
        printf("  crease on the 4x4 tile over a tilted plane: largest deviation from the tile mean %.2e\n", worst);
        /* 1e-4: float sums of 25 taps; a tap dropped by a wrong plane distance would leave ~0.1. */
        CHECK(worst < 1e-4, "crease leaves %.2e of the 4x4 tile on a tilted plane", worst);
    }
    free_synthetic(&s);

    make_tilted(&s, false);
    if (run_filter("crease", &s, out)) {
        double raw = variance(s.ao_in, 16, W - 16, 16, H - 16), after = variance(out, 16, W - 16, 16, H - 16);
        printf("  crease on independent noise over a tilted plane: variance %.5f -> %.5f (%.1f%%)\n", raw, after,
               100.0 * after / raw);
        /* Sum w^2 / (sum w)^2 of [1/2 1 1 1 1/2]^2 = (3.5/16)^2 = 4.8%; 10% leaves room. */
        CHECK(after <= 0.10 * raw, "crease keeps %.1f%% of the variance (at most 10%%)", 100.0 * after / raw);
    }
    free_synthetic(&s);
}

/* The RGB variant (SSDO's M and bounce): the same weights on every channel, the sky's value from
 * the CPU. A depth step with the sky in the last 8 columns; channel 0 against the R32F pass. */
static void test_crease_rgb(void)
{
    static float depth[W * H], normal[W * H * 4], rgb[W * H * 4], red[W * H], got[W * H * 4], ref[W * H];
    const float near_c[3] = {0.3f, 0.5f, 0.7f}, far_c[3] = {1.0f, 0.9f, 0.8f};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            bool sky = x >= W - 8, near = x < W / 2;
            depth[i] = sky ? 0.0f : near ? 2.0f : 10.0f;
            normal[4 * i + 2] = 1.0f;
            normal[4 * i + 3] = 1.0f;
            /* A 4-periodic pattern along y: beside the step only the pairs along y survive (eq. 4),
             * and they still cover its period, so the sides' values come back exactly. */
            float tile = 0.1f * (float)(y % 4) / 3.0f - 0.05f;
            for (int k = 0; k < 3; ++k) rgb[4 * i + k] = (near ? near_c[k] : far_c[k]) + tile;
            rgb[4 * i + 3] = 1.0f;
            red[i] = rgb[4 * i];
        }
    GLuint d = upload(GL_R32F, W, H, GL_RED, depth), n = upload(GL_RGBA16F, W, H, GL_RGBA, normal);
    GLuint src = upload(GL_RGBA16F, W, H, GL_RGBA, rgb), dst = ob_make_texture_2d(GL_RGBA16F, W, H);
    GLuint scratch = ob_make_texture_2d(GL_RGBA16F, W, H);
    GLuint src1 = upload(GL_R32F, W, H, GL_RED, red), dst1 = ob_make_texture_2d(GL_R32F, W, H);
    GLuint scratch1 = ob_make_texture_2d(GL_R32F, W, H);
    const ob_filter_impl *f = ob_filter_impl_at(ob_find_filter("crease"));
    CHECK(f && f->init_rgb, "crease has an RGB variant");
    if (f && f->init_rgb) {
        float params[OB_MAX_PARAMS] = {0};
        for (int i = 0; i < f->info.param_count; ++i) params[i] = f->info.params[i].def;
        void *st = f->init_rgb(), *st1 = f->init();
        CHECK(st && st1, "crease init (RGB and R32F)");
        if (st && st1) {
            const ob_filter_inputs in = {src, dst, scratch, d, n, W, H, true, 0.0f};
            const ob_filter_inputs in1 = {src1, dst1, scratch1, d, n, W, H, false, 1.0f};
            CHECK(f->run(st, &in, params) == OB_OK && f->run(st1, &in1, params) == OB_OK, "crease runs");
            glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glGetTextureImage(dst, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof got, got);
            download(dst1, W, H, ref);
            double worst = 0.0, sky_wrong = 0.0, leak = 0.0;
            for (int y = 2; y < H - 2; ++y)
                for (int x = 0; x < W; ++x) {
                    int i = y * W + x;
                    if (depth[i] <= 0.0f) {
                        for (int k = 0; k < 3; ++k) sky_wrong = fmax(sky_wrong, fabs(got[4 * i + k]));
                        continue;
                    }
                    worst = fmax(worst, fabs(got[4 * i] - ref[i]));
                    /* No channel takes the other side's value near the step. */
                    if (x >= W / 2 - 3 && x < W / 2 + 3) {
                        const float *want = x < W / 2 ? near_c : far_c;
                        for (int k = 0; k < 3; ++k) leak = fmax(leak, fabs(got[4 * i + k] - want[k]));
                    }
                }
            printf("  crease RGB: channel 0 vs R32F %.2e, off the side's value at the step %.4f\n", worst, leak);
            /* fp16 storage of values <= 1: 2^-11 each way. */
            CHECK(worst < 2e-3, "crease RGB channel 0 differs from the R32F pass by %.2e", worst);
            /* As the R32F edge test: 0.005; fp16 rounding is 5e-4. */
            CHECK(leak < 0.005, "crease RGB leaks %.4f across the step", leak);
            CHECK(sky_wrong == 0.0, "crease RGB: sky pixels hold %.3g instead of the sky value 0", sky_wrong);
        }
        if (st) f->destroy(st);
        if (st1) f->destroy(st1);
    }
    GLuint t[8] = {d, n, src, dst, scratch, src1, dst1, scratch1};
    glDeleteTextures(8, t);
}

/* Scene `name` seen from camera `camera` by a new w x h renderer; NULL after a failed CHECK
 * (then nothing is left to destroy). */
static ob_renderer *view_renderer(ob_context *ctx, const char *name, const char *camera, int w, int h, ob_scene **scene,
                                  ob_camera *cam)
{
    *scene = ob_load_scene(&(ob_scene_desc){.name = name});
    CHECK(*scene && ob_find_camera(*scene, camera, cam) == OB_OK, "%s:%s", name, camera);
    ob_renderer *r = *scene ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = w, .height = h}) : NULL;
    CHECK(!*scene || r, "a %dx%d renderer", w, h);
    if (!r) {
        ob_destroy_scene(*scene);
        *scene = NULL;
        return NULL;
    }
    ob_renderer_set_scene(r, *scene);
    return r;
}

/* Issue 13: on the corner scene the floor beside a wall keeps the method's own AO. Band: floor
 * (y = 0) pixels with h = min(x, z) < 0.05 R, found from the depth read-back; mean of the filtered
 * AO minus the raw AO over it, for each method. */
static void test_crease_corner(ob_context *ctx)
{
    enum { CW = 200, CH = 150 };
    ob_scene *scene;
    ob_camera cam;
    ob_renderer *r = view_renderer(ctx, "corner", "diagonal", CW, CH, &scene, &cam);
    if (!r) return;
    const float R = ob_query_scene_ao_radius(scene);
    size_t n = (size_t)CW * CH;
    float *depth = malloc(n * sizeof(float)), *raw = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    bool *band = calloc(n, sizeof(bool));
    mat4 view, inv;
    vec3 up = {0.0f, 1.0f, 0.0f};
    glm_lookat(cam.eye, cam.target, up, view);
    glm_mat4_inv(view, inv);
    const float ty = tanf(glm_rad(cam.fov_y_deg) * 0.5f), tx = ty * (float)CW / (float)CH;
    const char *methods[] = {"ssao", "hbao", "alchemy"};
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; ++m) {
        double shift[2] = {0.0, 0.0};
        int count = 0;
        const char *filters[2] = {"crease", "geometry"};
        for (int fi = 0; fi < 2; ++fi) {
            ob_settings s;
            ob_settings_init(&s, methods[m]);
            ob_settings_set_filter(&s, filters[fi]);
            CHECK(ob_render_frame(r, &cam, &s) == OB_OK, "corner frame, %s + %s", methods[m], filters[fi]);
            ob_read_image(r, OB_IMAGE_AO_RAW_F32, raw, n * sizeof(float));
            ob_read_image(r, OB_IMAGE_AO_F32, ao, n * sizeof(float));
            if (m == 0 && fi == 0) {
                ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, n * sizeof(float));
                for (int y = 0; y < CH; ++y)
                    for (int x = 0; x < CW; ++x) {
                        size_t i = (size_t)y * CW + (size_t)x;
                        float d = depth[i];
                        if (d <= 0.0f) continue;
                        vec4 pv = {((float)x + 0.5f) / CW * 2.0f - 1.0f, ((float)y + 0.5f) / CH * 2.0f - 1.0f, -1.0f, 1.0f}, pw;
                        pv[0] *= tx * d;
                        pv[1] *= ty * d;
                        pv[2] = -d;
                        glm_mat4_mulv(inv, pv, pw);
                        band[i] = fabsf(pw[1]) < 1e-3f * d && pw[0] > 0.0f && pw[2] > 0.0f && fminf(pw[0], pw[2]) < 0.05f * R;
                    }
            }
            count = 0;
            for (size_t i = 0; i < n; ++i) {
                if (!band[i]) continue;
                shift[fi] += ao[i] - raw[i];
                ++count;
            }
            shift[fi] /= count ? count : 1;
        }
        printf("  corner crease band (%d px, h < 0.05 R): %-8s crease %+.4f, geometry %+.4f against the raw AO\n", count,
               methods[m], shift[0], shift[1]);
        CHECK(count >= 20, "the crease band holds %d pixels", count);
        CHECK(fabs(shift[0]) <= 0.03, "%s: crease moves the AO beside the crease by %+.4f (at most 0.03)", methods[m],
              shift[0]);
    }
    free(depth);
    free(raw);
    free(ao);
    free(band);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

/* Upsampling on synthetic textures: a depth step at full resolution, the AO grid at half and a
 * quarter, through the plain and the block program (shaders/upsample.glsl), which must also agree
 * with each other. */
static void test_upsample_silhouette(void)
{
    static float fdepth[W * H], fnormal[W * H * 4];
    /* The step at x = 47.5 (odd), so a 2x grid does not line up with it. */
    const int edge = 47;
    for (int i = 0; i < W * H; ++i) {
        fdepth[i] = (i % W) <= edge ? 2.0f : 10.0f;
        fnormal[4 * i + 2] = 1.0f;
        fnormal[4 * i + 3] = 1.0f;
    }
    for (int k = 2; k <= 4; k *= 2) {
        ob_ao_grid g = ob_ao_grid_make(W, H, k);
        static float ldepth[W * H], lnormal[W * H * 4], lao[W * H];
        for (int y = 0; y < g.height; ++y)
            for (int x = 0; x < g.width; ++x) {
                int src = (y * k + g.o) * W + (x * k + g.o < W ? x * k + g.o : W - 1);
                int i = y * g.width + x;
                ldepth[i] = fdepth[src];
                lnormal[4 * i + 2] = 1.0f;
                lnormal[4 * i + 3] = 1.0f;
                lao[i] = fdepth[src] < 5.0f ? 0.3f : 1.0f;
            }
        GLuint fd = upload(GL_R32F, W, H, GL_RED, fdepth), fn = upload(GL_RGBA16F, W, H, GL_RGBA, fnormal);
        GLuint ld = upload(GL_R32F, g.width, g.height, GL_RED, ldepth);
        GLuint ln = upload(GL_RGBA16F, g.width, g.height, GL_RGBA, lnormal);
        GLuint la = upload(GL_R32F, g.width, g.height, GL_RED, lao);
        GLuint out = ob_make_texture_2d(GL_R32F, W, H);
        ob_upsample pass;
        CHECK(ob_upsample_init(&pass, false) == OB_OK, "upsample program");
        static float up[2][W * H];
        for (int program = 0; program < 2; ++program) {
            const char *name = program ? "block" : "plain";
            CHECK(ob_upsample_run(&pass, program ? OB_UPSAMPLE_BLOCK : OB_UPSAMPLE_PLAIN, &g, fd, fn, ld, ln, la, out,
                                  1.0f, 0, 0) == OB_OK,
                  "k = %d: the %s program runs", k, name);
            glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
            download(out, W, H, up[program]);
            int wrong = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    float want = x <= edge ? 0.3f : 1.0f;
                    wrong += fabsf(up[program][y * W + x] - want) > 1e-3f;
                }
            CHECK(wrong == 0, "k = %d, %s: %d pixels took the other side's AO across the silhouette", k, name, wrong);
        }
        /* The block program was made for this k and used (a fallback to the plain one would
         * pass the comparison below alone). */
        CHECK(pass.programs[0][k == 4 ? 2 : 1].program != 0, "k = %d: no block program was made", k);
        CHECK(!memcmp(up[0], up[1], sizeof up[0]), "k = %d: the block program differs from the plain one", k);

        /* A pair (frame.c: the bounce in the AO's dispatch): its second value, an RGBA16F texture
         * that varies across the image, is what the RGB program makes of it alone, and its AO
         * what the single program made, in either program. */
        static float lsecond[W * H * 4], alone[W * H * 4], second[W * H * 4], paired[W * H];
        for (int i = 0; i < g.width * g.height; ++i)
            for (int c = 0; c < 4; ++c) lsecond[4 * i + c] = lao[i] * (float)(c + 1) * 0.25f + (float)(i % 7) * 0.01f;
        GLuint ls = upload(GL_RGBA16F, g.width, g.height, GL_RGBA, lsecond);
        GLuint rgb_out = ob_make_texture_2d(GL_RGBA16F, W, H), second_out = ob_make_texture_2d(GL_RGBA16F, W, H);
        ob_upsample rgb;
        CHECK(ob_upsample_init(&rgb, true) == OB_OK, "RGB upsample program");
        CHECK(ob_upsample_run(&rgb, OB_UPSAMPLE_PLAIN, &g, fd, fn, ld, ln, ls, rgb_out, 0.0f, 0, 0) == OB_OK, "RGB alone");
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
        glGetTextureImage(rgb_out, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof alone, alone);
        for (int program = 0; program < 2; ++program) {
            CHECK(ob_upsample_run(&pass, program ? OB_UPSAMPLE_BLOCK : OB_UPSAMPLE_PLAIN, &g, fd, fn, ld, ln, la, out,
                                  1.0f, ls, second_out) == OB_OK,
                  "k = %d: a pair", k);
            glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
            download(out, W, H, paired);
            glGetTextureImage(second_out, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof second, second);
            CHECK(!memcmp(paired, up[0], sizeof paired), "k = %d, %s pair: its AO differs from the single pass's", k,
                  program ? "block" : "plain");
            CHECK(!memcmp(second, alone, sizeof second), "k = %d, %s pair: its second value differs from the RGB pass's",
                  k, program ? "block" : "plain");
        }
        CHECK(pass.programs[1][0].program != 0 && pass.programs[1][k == 4 ? 2 : 1].program != 0,
              "k = %d: the pair programs were made", k);
        ob_upsample_destroy(&rgb);
        ob_upsample_destroy(&pass);
        GLuint t[9] = {fd, fn, ld, ln, la, out, ls, rgb_out, second_out};
        glDeleteTextures(9, t);
    }
}

/* The two upsampling programs through the renderer (`upsample` plain and block), on a real view
 * at a size that is no multiple of 4 (a partial last block) at AO scale 1/2 and 1/4: the same
 * visibility, and for ssdo the same M and bounce (the RGB programs). */
static void test_upsample_programs(ob_context *ctx)
{
    enum { UW = 99, UH = 73 };
    ob_scene *scene;
    ob_camera cam;
    ob_renderer *r = view_renderer(ctx, "cornell", "front", UW, UH, &scene, &cam);
    if (!r) return;
    const char *methods[2] = {"vbao", "ssdo"};
    /* vbao's visibility (the R32F programs); ssdo's M and bounce (the RGBA16F ones). */
    const ob_image_kind kinds[2][2] = {{OB_IMAGE_AO_F32, OB_IMAGE_AO_F32}, {OB_IMAGE_AO_RGB_F32, OB_IMAGE_BOUNCE_F32}};
    float *a = malloc(ob_image_size(r, OB_IMAGE_AO_RGB_F32)), *b = malloc(ob_image_size(r, OB_IMAGE_AO_RGB_F32));
    for (int m = 0; m < 2; ++m)
        for (float scale = 0.5f; scale >= 0.25f; scale *= 0.5f) {
            ob_settings s[2];
            for (int program = 0; program < 2; ++program) {
                ob_settings_init(&s[program], methods[m]);
                ob_settings_set_ao_scale(&s[program], scale);
                CHECK(ob_settings_set(&s[program], program ? "upsample=block" : "upsample=plain") == OB_OK, "upsample=");
            }
            for (int kind = 0; kind < (m ? 2 : 1); ++kind) {
                const size_t bytes = ob_image_size(r, kinds[m][kind]);
                CHECK(ob_render_frame(r, &cam, &s[0]) == OB_OK && ob_read_image(r, kinds[m][kind], a, bytes) == OB_OK,
                      "%s plain", methods[m]);
                CHECK(ob_render_frame(r, &cam, &s[1]) == OB_OK && ob_read_image(r, kinds[m][kind], b, bytes) == OB_OK,
                      "%s block", methods[m]);
                double worst = 0.0, sum = 0.0;
                for (size_t i = 0; i < bytes / sizeof(float); ++i) {
                    worst = fmax(worst, fabs((double)a[i] - b[i]));
                    sum += a[i];
                }
                printf("  upsample %s at %g, %s: block against plain max |d| %.2g (mean %.4f)\n", methods[m],
                       (double)scale, kind ? "bounce" : "AO", worst, sum / (double)(bytes / sizeof(float)));
                CHECK(worst <= 1e-6, "%s at %g: the block upsampler differs from the plain one by %.2g", methods[m],
                      (double)scale, worst);
            }
        }
    ob_settings bad;
    ob_settings_init(&bad, "vbao");
    CHECK(ob_settings_set(&bad, "upsample=fast") == OB_ERR_INVALID_ARGUMENT, "upsample=fast is refused");
    /* Every program's name is what "upsample=" takes, and gives that program back. */
    for (int i = 0; i < OB_UPSAMPLE_PROGRAM_COUNT; ++i) {
        char set[32];
        snprintf(set, sizeof set, "upsample=%s", ob_upsample_program_name((ob_upsample_program)i));
        CHECK(ob_settings_set(&bad, set) == OB_OK && bad.upsample == i, "%s gives program %d", set, i);
    }
    CHECK(!strcmp(ob_upsample_program_name(OB_UPSAMPLE_PROGRAM_COUNT), ""), "an out-of-range program has no name");
    free(a);
    free(b);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

static double rmse_masked(const float *a, const float *b, const float *depth, int n)
{
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < n; ++i) {
        if (depth[i] <= 0.0f) continue;
        sum += (double)(a[i] - b[i]) * (a[i] - b[i]);
        ++count;
    }
    return count ? sqrt(sum / count) : 0.0;
}

static void test_scenes(ob_context *ctx)
{
    enum { SW = 160, SH = 120 };
    const char *scenes[2][2] = {{"cornell", "front"}, {"fzk-haus", "stair"}};
    for (int sc = 0; sc < 2; ++sc) {
        ob_scene *scene;
        ob_camera cam;
        ob_renderer *r = view_renderer(ctx, scenes[sc][0], scenes[sc][1], SW, SH, &scene, &cam);
        if (!r) continue;
        size_t n = (size_t)SW * SH;
        float *depth = malloc(n * sizeof(float)), *ref = malloc(n * sizeof(float)), *got = malloc(n * sizeof(float));
        ob_settings s;
        ob_settings_init(&s, "ssao");

        /* bilateral_sep against the full 2D bilateral (Belonogov 2018 eq. 4.6-4.7 vs 4.5). */
        ob_settings_set_filter(&s, "bilateral");
        ob_render_frame(r, &cam, &s);
        ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, n * sizeof(float));
        ob_read_image(r, OB_IMAGE_AO_F32, ref, n * sizeof(float));
        ob_settings_set_filter(&s, "bilateral_sep");
        ob_render_frame(r, &cam, &s);
        ob_read_image(r, OB_IMAGE_AO_F32, got, n * sizeof(float));
        double sep = rmse_masked(ref, got, depth, (int)n);
        printf("  %-8s bilateral_sep vs bilateral RMSE %.4f\n", scenes[sc][0], sep);
        CHECK(sep < 0.02, "%s: bilateral_sep RMSE %.4f against the full bilateral (at most 0.02)", scenes[sc][0], sep);

        /* Half and quarter resolution + joint bilateral upsampling against full resolution, all
         * with the default geometry filter. */
        ob_settings_set_filter(&s, "geometry");
        ob_render_frame(r, &cam, &s);
        ob_read_image(r, OB_IMAGE_AO_F32, ref, n * sizeof(float));
        const float scales[2] = {0.5f, 0.25f};
        const double limits[2] = {0.03, 0.05};
        for (int k = 0; k < 2; ++k) {
            CHECK(ob_settings_set_ao_scale(&s, scales[k]) == OB_OK, "scale");
            CHECK(ob_render_frame(r, &cam, &s) == OB_OK, "frame at %g", (double)scales[k]);
            ob_read_image(r, OB_IMAGE_AO_F32, got, n * sizeof(float));
            double e = rmse_masked(ref, got, depth, (int)n);
            int sky_wrong = 0;
            for (size_t i = 0; i < n; ++i) sky_wrong += depth[i] <= 0.0f && got[i] != 1.0f;
            printf("  %-8s ao-scale %.2f RMSE against full resolution %.4f\n", scenes[sc][0], (double)scales[k], e);
            CHECK(e < limits[k], "%s: scale %g RMSE %.4f (at most %.2f)", scenes[sc][0], (double)scales[k], e, limits[k]);
            CHECK(sky_wrong == 0, "%d sky pixels got AO", sky_wrong);
        }
        ob_settings_set_ao_scale(&s, 1.0f);

        /* Adaptive: edge pixels take more samples than plane pixels, and fewer in total than the
         * fixed count at the same quality (SSDO thesis §4.1). */
        ob_settings_set_samples(&s, 30);
        s.adaptive = true;
        CHECK(ob_render_frame(r, &cam, &s) == OB_OK, "adaptive frame");
        ob_read_image(r, OB_IMAGE_SAMPLES_F32, got, n * sizeof(float));
        double total = 0.0;
        float lo = 1e9f, hi = 0.0f;
        for (size_t i = 0; i < n; ++i) {
            if (depth[i] <= 0.0f) continue;
            total += got[i];
            lo = fminf(lo, got[i]);
            hi = fmaxf(hi, got[i]);
        }
        int geometry = 0;
        for (size_t i = 0; i < n; ++i) geometry += depth[i] > 0.0f;
        printf("  %-8s adaptive: %g..%g samples, mean %.1f against 30 fixed\n", scenes[sc][0], (double)lo, (double)hi,
               total / geometry);
        CHECK(lo == 10.0f && hi == 30.0f, "adaptive counts span 10..30 (got %g..%g)", (double)lo, (double)hi);
        CHECK(total < 30.0 * geometry, "adaptive total %.0f not below the fixed %d", total, 30 * geometry);
        /* Pixels at a depth discontinuity (a 10% step to a neighbour) against all pixels. */
        double edge_sum = 0.0;
        int edges = 0;
        for (int y = 1; y < SH - 1; ++y)
            for (int x = 1; x < SW - 1; ++x) {
                size_t i = (size_t)y * SW + (size_t)x;
                float d = depth[i];
                if (d <= 0.0f) continue;
                float step = fmaxf(fmaxf(fabsf(depth[i + 1] - d), fabsf(depth[i - 1] - d)),
                                   fmaxf(fabsf(depth[i + SW] - d), fabsf(depth[i - SW] - d)));
                if (step < 0.1f * d) continue;
                edge_sum += got[i];
                ++edges;
            }
        printf("  %-8s adaptive: %d edge pixels average %.1f samples\n", scenes[sc][0], edges, edge_sum / edges);
        CHECK(edges > 20 && edge_sum / edges > total / geometry + 5.0, "edge pixels average %.1f samples, all %.1f",
              edge_sum / (edges ? edges : 1), total / geometry);
        s.adaptive = false;
        free(depth);
        free(ref);
        free(got);
        ob_destroy_renderer(r);
        ob_destroy_scene(scene);
    }
}

/* crease's tiled and block programs against the plain one they replace: the same output (only acos
 * and exp are approximated: weights move by < 1e-3 of themselves) on a frame whose size is no
 * multiple of the 8x8 work group nor of the 4x4 block (partial tiles and blocks at the right and
 * top), at full and half AO resolution, for AO (R32F) and SSDO's M (RGBA16F), and at radii the
 * block (3: the tiled program) and the tiles (6: the plain one) do not hold. */
static void test_crease_tiled(ob_context *ctx)
{
    enum { TW = 101, TH = 77 };
    ob_scene *scene;
    ob_camera cam;
    ob_renderer *r = view_renderer(ctx, "cornell", "front", TW, TH, &scene, &cam);
    if (!r) return;
    size_t n = (size_t)TW * TH * 3;
    float *plain = malloc(n * sizeof(float)), *other = malloc(n * sizeof(float));
    const char *const programs[] = {"crease.tiled=off", "crease.tiled=on", "crease.tiled=block"};
    const struct {
        const char *method;
        float scale;
        const char *radius;
    } cases[] = {{"ssao", 1.0f, "crease.radius=2"}, {"ssao", 0.5f, "crease.radius=2"}, {"ssao", 0.5f, "crease.radius=3"},
                 {"ssdo", 1.0f, "crease.radius=2"}, {"hbao", 1.0f, "crease.radius=6"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        for (int t = 0; t < 3; ++t) {
            ob_settings s;
            ob_settings_init(&s, cases[c].method);
            ob_settings_set_filter(&s, "crease");
            ob_settings_set_ao_scale(&s, cases[c].scale);
            ob_settings_set(&s, cases[c].radius);
            ob_settings_set(&s, programs[t]);
            CHECK(ob_render_frame(r, &cam, &s) == OB_OK, "%s frame", cases[c].method);
            ob_read_image(r, OB_IMAGE_AO_RGB_F32, t ? other : plain, n * sizeof(float));
            if (!t) continue;
            double worst = 0.0;
            for (size_t i = 0; i < n; ++i) worst = fmax(worst, fabs((double)plain[i] - other[i]));
            /* RGBA16F M: one half-float step near 1 is 4.9e-4. */
            double tol = !strcmp(cases[c].method, "ssdo") ? 1e-3 : 1e-4;
            printf("  crease %s vs off, %s at %.1f, %s: max difference %.2g\n", programs[t], cases[c].method,
                   cases[c].scale, cases[c].radius, worst);
            CHECK(worst <= tol, "%s at %.1f, %s: %s within %.0e of plain (%.2g)", cases[c].method, cases[c].scale,
                  cases[c].radius, programs[t], tol, worst);
        }
    }
    free(plain);
    free(other);
    ob_destroy_renderer(r);
    ob_destroy_scene(scene);
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    bind_synthetic_frame(); /* crease reads the camera from the frame's block */
    test_edges();
    test_noise();
    test_crease_weights();
    test_crease_plane();
    test_crease_rgb();
    test_upsample_silhouette();
    test_upsample_programs(ctx);
    test_scenes(ctx);
    test_crease_corner(ctx);
    test_crease_tiled(ctx);
    if (synthetic_frame_ubo) glDeleteBuffers(1, &synthetic_frame_ubo);
    ob_destroy_context(ctx);
    return check_finish("test_filters");
}
