/* Filters, subsampling and adaptive sample counts (issue 4), on synthetic textures where the
 * answer is known and on the demo scenes:
 *   - edge preservation across a depth step: the edge-aware filters do not leak, gaussian does;
 *   - noise reduction on a flat region under `geometry`;
 *   - bilateral_sep against the full bilateral;
 *   - half- and quarter-resolution AO + joint bilateral upsampling against full resolution, and
 *     silhouettes keeping their own side's AO;
 *   - adaptive counts: more samples at edges, fewer in total. */
#include <cglm/cglm.h>
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "filters/filter.h"
#include "obscura/obscura.h"
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
    const char *names[] = {"gaussian", "bilateral", "bilateral_sep", "geometry", "box4"};
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

/* Upsampling on synthetic textures: a depth step at full resolution, the AO grid at half. */
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
        ob_compute_pass pass;
        CHECK(ob_upsample_init(&pass) == OB_OK, "upsample program");
        ob_upsample_run(&pass, &g, fd, fn, ld, ln, la, out);
        float up[W * H];
        download(out, W, H, up);
        int wrong = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                float want = x <= edge ? 0.3f : 1.0f;
                wrong += fabsf(up[y * W + x] - want) > 1e-3f;
            }
        CHECK(wrong == 0, "k = %d: %d pixels took the other side's AO across the silhouette", k, wrong);
        ob_compute_pass_destroy(&pass);
        GLuint t[6] = {fd, fn, ld, ln, la, out};
        glDeleteTextures(6, t);
    }
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
        ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = scenes[sc][0]});
        CHECK(scene != NULL, "%s loads", scenes[sc][0]);
        if (!scene) continue;
        ob_camera cam;
        ob_find_camera(scene, scenes[sc][1], &cam);
        ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = SW, .height = SH});
        ob_renderer_set_scene(r, scene);
        size_t n = (size_t)SW * SH;
        float *depth = malloc(n * sizeof(float)), *ref = malloc(n * sizeof(float)), *got = malloc(n * sizeof(float));
        ob_settings s;
        ob_settings_init(&s, "ssao");

        /* bilateral_sep against the full 2D bilateral (seed 000 eq. 4.6-4.7 vs 4.5). */
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
         * fixed count at the same quality (seed 003 §4.1). */
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

int main(void)
{
    ob_context *ctx = ob_make_context(NULL);
    if (!ctx) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "no context: %s\n", msg);
        return 1;
    }
    test_edges();
    test_noise();
    test_upsample_silhouette();
    test_scenes(ctx);
    ob_destroy_context(ctx);
    return check_finish("test_filters");
}
