/* Depth MIP prefilter (issue 13). One test body, two implementations: every synthetic depth buffer
 * goes through the GPU pass (src/passes/depth_mips.c + shaders/depth_mips.glsl, tiles reduced in
 * shared memory) and through its CPU twin (ob_depth_mips_reference, level by level over the whole
 * image); the two must agree bit for bit on every level, and each must pass the same checks:
 *   - level 0 is the input; each texel of level L is the child in level L-1 that SAO's rotated grid
 *     picks, sky included (so every level holds only depths that some pixel under it has, and the
 *     one pixel its picks lead to has it: the readers reconstruct the tap there);
 *   - across a depth step, no level holds a depth strictly between the near and the far one;
 *   - a picked sky child gives 0 even beside geometry, a 2x2 of sky gives 0;
 *   - odd, tiny and partial-tile sizes (37x23, 33x17, 8x160, 1x1, 2x1, 160x120), and a run at a new
 *     size remakes the texture with that size's levels.
 * `test_depth_mips --bench` prints the pass's GPU time (median of 20) at 640x480 and 1280x720. */
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "depth_mips_params.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"
#include "passes/passes.h"
#include "sampling/sampling.h"

typedef struct chain {
    int width, height, levels;
    float *level[OB_DEPTH_MIPS_LEVELS];
} chain;

static void chain_alloc(chain *c, int width, int height)
{
    memset(c, 0, sizeof *c);
    c->width = width;
    c->height = height;
    for (int l = 0; l < OB_DEPTH_MIPS_LEVELS; ++l) {
        int w = 0, h = 0;
        ob_depth_mips_level_size(width, height, l, &w, &h);
        c->level[l] = calloc((size_t)w * (size_t)h, sizeof(float));
    }
}

static void chain_free(chain *c)
{
    for (int l = 0; l < OB_DEPTH_MIPS_LEVELS; ++l) free(c->level[l]);
    memset(c, 0, sizeof *c);
}

/* ---- the two implementations ----------------------------------------------------------------- */
static ob_depth_mips gpu; /* one pass for the whole run, so size changes remake its texture */

static void build_cpu(const float *depth, int width, int height, chain *out)
{
    chain_alloc(out, width, height);
    out->levels = ob_depth_mips_reference(depth, width, height, out->level);
}

static void build_gpu(const float *depth, int width, int height, chain *out)
{
    chain_alloc(out, width, height);
    GLuint input = ob_make_texture_2d(GL_R32F, width, height);
    glTextureSubImage2D(input, 0, 0, 0, width, height, GL_RED, GL_FLOAT, depth);
    CHECK(ob_depth_mips_run(&gpu, input, width, height) == OB_OK, "gpu run %dx%d", width, height);
    out->levels = gpu.levels;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (int l = 0; l < gpu.levels; ++l) {
        int w = 0, h = 0, gw = 0, gh = 0;
        ob_depth_mips_level_size(width, height, l, &w, &h);
        glGetTextureLevelParameteriv(gpu.texture, l, GL_TEXTURE_WIDTH, &gw);
        glGetTextureLevelParameteriv(gpu.texture, l, GL_TEXTURE_HEIGHT, &gh);
        CHECK(gw == w && gh == h, "gpu %dx%d level %d is %dx%d, want %dx%d (GL's rule)", width, height, l, gw, gh, w,
              h);
        glGetTextureImage(gpu.texture, l, GL_RED, GL_FLOAT, (GLsizei)((size_t)w * (size_t)h * sizeof(float)),
                          out->level[l]);
    }
    glDeleteTextures(1, &input);
    CHECK(glGetError() == GL_NO_ERROR, "gpu %dx%d: no GL error", width, height);
}

typedef void (*build_fn)(const float *depth, int width, int height, chain *out);
static const struct { const char *name; build_fn build; } impls[2] = {{"cpu", build_cpu}, {"gpu", build_gpu}};

/* ---- the one test body ----------------------------------------------------------------------- */
/* Checks every level of c (built from depth by `impl`); returns the number of failed texels. */
static int check_chain(const char *impl, const char *what, const float *depth, const chain *c)
{
    int bad = 0, want_levels = 1;
    while (want_levels < OB_DEPTH_MIPS_LEVELS && ((c->width > c->height ? c->width : c->height) >> want_levels) > 0)
        ++want_levels;
    CHECK(c->levels == want_levels, "%s %s: %d levels, want %d", impl, what, c->levels, want_levels);
    CHECK(!memcmp(c->level[0], depth, (size_t)c->width * (size_t)c->height * sizeof(float)),
          "%s %s: level 0 is not a copy of the input", impl, what);
    for (int l = 1; l < c->levels; ++l) {
        int bw = 0, bh = 0, w = 0, h = 0;
        ob_depth_mips_level_size(c->width, c->height, l - 1, &bw, &bh);
        ob_depth_mips_level_size(c->width, c->height, l, &w, &h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float v = c->level[l][y * w + x], d[4] = {0};
                for (int k = 0; k < 4; ++k) {
                    int cx = 2 * x + (k & 1), cy = 2 * y + (k >> 1);
                    d[k] = c->level[l - 1][(cy < bh ? cy : bh - 1) * bw + (cx < bw ? cx : bw - 1)];
                }
                /* The rotated grid's pick, child (y & 1, x & 1), sky or not; never a blend. */
                bool ok = v == d[(x & 1) * 2 + (y & 1)];
                if (!ok && bad++ < 3)
                    CHECK(ok, "%s %s: level %d texel (%d,%d) = %g from children %g %g %g %g", impl, what, l, x, y,
                          (double)v, (double)d[0], (double)d[1], (double)d[2], (double)d[3]);
            }
    }
    CHECK(bad == 0, "%s %s: %d texels are not a pick of their children", impl, what, bad);
    return bad;
}

/* Both implementations, the body on each, then bit-exact agreement on every level. */
static void run_both(const char *what, const float *depth, int width, int height, chain out[2])
{
    for (int i = 0; i < 2; ++i) {
        impls[i].build(depth, width, height, &out[i]);
        check_chain(impls[i].name, what, depth, &out[i]);
    }
    CHECK(out[0].levels == out[1].levels, "%s: cpu %d levels, gpu %d", what, out[0].levels, out[1].levels);
    for (int l = 0; l < out[0].levels && l < out[1].levels; ++l) {
        int w = 0, h = 0, differ = 0;
        ob_depth_mips_level_size(width, height, l, &w, &h);
        for (int i = 0; i < w * h; ++i) differ += out[0].level[l][i] != out[1].level[l][i];
        CHECK(differ == 0, "%s %dx%d level %d: %d of %d texels differ between cpu and gpu", what, width, height, l,
              differ, w * h);
    }
}

/* ---- synthetic depth buffers ----------------------------------------------------------------- */
/* Random view-facing and slanted planes (each pixel takes the plane of its nearest seed point), a
 * near disc in front of them (a silhouette), a block of sky and scattered sky pixels. */
static float *make_planes(int width, int height, uint64_t seed)
{
    float *depth = malloc((size_t)width * (size_t)height * sizeof(float));
    ob_rng rng;
    ob_rng_seed(&rng, seed, 13);
    enum { SEEDS = 5 };
    float sx[SEEDS], sy[SEEDS], a[SEEDS], bx[SEEDS], by[SEEDS];
    for (int s = 0; s < SEEDS; ++s) {
        sx[s] = ob_rng_float(&rng) * (float)width;
        sy[s] = ob_rng_float(&rng) * (float)height;
        a[s] = 4.0f + 40.0f * ob_rng_float(&rng);
        bx[s] = (ob_rng_float(&rng) - 0.5f) * 0.8f / (float)width; /* |slope| < 0.4 a across the image */
        by[s] = (ob_rng_float(&rng) - 0.5f) * 0.8f / (float)height;
    }
    float cx = 0.4f * (float)width, cy = 0.6f * (float)height, r = 0.25f * (float)(width < height ? width : height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int best = 0;
            float best_d2 = 1e30f;
            for (int s = 0; s < SEEDS; ++s) {
                float d2 = (x - sx[s]) * (x - sx[s]) + (y - sy[s]) * (y - sy[s]);
                if (d2 < best_d2) best_d2 = d2, best = s;
            }
            float z = a[best] * (1.0f + bx[best] * (float)x + by[best] * (float)y); /* > 0.2 a */
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r) z = 1.5f + 0.01f * (float)x; /* the near disc */
            if (x > width * 3 / 4 && y < height / 3) z = 0.0f;                                 /* a block of sky */
            if (ob_rng_float(&rng) < 0.1f) z = 0.0f;                                          /* scattered sky */
            depth[y * width + x] = z;
        }
    return depth;
}

static void test_random_planes(void)
{
    /* 37x23: odd at every level; 33x17: a column and a row of groups that only touch the edge;
     * 8x160: the narrow side is 1 texel from level 3 on, so children are clamped; 160x120: 10x7.5
     * work groups. */
    const int sizes[][2] = {{37, 23}, {33, 17}, {8, 160}, {160, 120}, {1, 1}, {2, 1}, {1, 2}, {3, 3}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; ++i) {
        int w = sizes[i][0], h = sizes[i][1];
        float *depth = make_planes(w, h, 100 + i);
        char what[64];
        snprintf(what, sizeof what, "planes %dx%d", w, h);
        chain out[2];
        run_both(what, depth, w, h, out);
        printf("  %-16s %d levels, cpu == gpu\n", what, out[1].levels);
        chain_free(&out[0]);
        chain_free(&out[1]);
        free(depth);
    }
}

static void test_step(void)
{
    /* Near 2 left of a slanted silhouette, far 10 right of it, sky in the bottom rows. */
    enum { W = 37, H = 23 };
    const float near = 2.0f, far = 10.0f;
    static float depth[W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) depth[y * W + x] = y >= H - 3 ? 0.0f : x < 11 + y / 3 ? near : far;
    chain out[2];
    run_both("step", depth, W, H, out);
    for (int i = 0; i < 2; ++i) {
        int between = 0, nears = 0, fars = 0;
        for (int l = 0; l < out[i].levels; ++l) {
            int w = 0, h = 0;
            ob_depth_mips_level_size(W, H, l, &w, &h);
            for (int k = 0; k < w * h; ++k) {
                float v = out[i].level[l][k];
                between += v > near && v < far;
                nears += l > 0 && v == near;
                fars += l > 0 && v == far;
            }
        }
        CHECK(between == 0, "%s step: %d texels between the near (%g) and the far (%g) depth", impls[i].name, between,
              (double)near, (double)far);
        CHECK(nears > 0 && fars > 0, "%s step: the coarse levels keep both sides (%d near, %d far)", impls[i].name,
              nears, fars);
    }
    chain_free(&out[0]);
    chain_free(&out[1]);
}

static void test_sky(void)
{
    /* 4x4, one 2x2 per level-1 texel. The rotated grid picks child (y & 1, x & 1) of texel (x, y):
     *   (0,0): all sky                                   -> 0
     *   (1,0): picks pixel (2,1) = sky; geometry 3 and 5 -> 0, the pick (no depth moves to a
     *          pixel that is not its own)
     *   (0,1): picks pixel (1,2) = 4; geometry 4 and 8   -> 4
     *   (1,1): all geometry, picks pixel (3,3)           -> 9
     * Level 2 (1x1) picks level-1 texel (0,0) = sky: 0, though 4 and 9 are geometry. */
    static const float depth[16] = {
        0.0f, 0.0f, 3.0f, 0.0f, /* y = 0 */
        0.0f, 0.0f, 0.0f, 5.0f, /* y = 1 */
        0.0f, 4.0f, 6.0f, 7.0f, /* y = 2 */
        8.0f, 0.0f, 8.5f, 9.0f, /* y = 3 */
    };
    const float want1[4] = {0.0f, 0.0f, 4.0f, 9.0f};
    chain out[2];
    run_both("sky 4x4", depth, 4, 4, out);
    for (int i = 0; i < 2; ++i) {
        CHECK(out[i].levels == 3, "%s sky: %d levels", impls[i].name, out[i].levels);
        for (int k = 0; k < 4; ++k)
            CHECK(out[i].level[1][k] == want1[k], "%s sky: level 1 texel %d = %g, want %g", impls[i].name, k,
                  (double)out[i].level[1][k], (double)want1[k]);
        CHECK(out[i].level[2][0] == 0.0f, "%s sky: level 2 = %g, want 0 (its pick is sky)",
              impls[i].name, (double)out[i].level[2][0]);
    }
    chain_free(&out[0]);
    chain_free(&out[1]);

    /* All sky: every level 0. */
    static float sky[20 * 18];
    run_both("all sky", sky, 20, 18, out);
    for (int i = 0; i < 2; ++i) {
        int nonzero = 0;
        for (int l = 0; l < out[i].levels; ++l) {
            int w = 0, h = 0;
            ob_depth_mips_level_size(20, 18, l, &w, &h);
            for (int k = 0; k < w * h; ++k) nonzero += out[i].level[l][k] != 0.0f;
        }
        CHECK(nonzero == 0, "%s all sky: %d texels are not 0", impls[i].name, nonzero);
    }
    chain_free(&out[0]);
    chain_free(&out[1]);
}

static void test_resize(void)
{
    float *depth = make_planes(160, 120, 7);
    GLuint input = ob_make_texture_2d(GL_R32F, 160, 120);
    glTextureSubImage2D(input, 0, 0, 0, 160, 120, GL_RED, GL_FLOAT, depth);
    const int sizes[][3] = {{160, 120, 5}, {160, 120, 5}, {37, 23, 5}, {2, 1, 2}, {1, 1, 1}, {160, 120, 5}};
    GLuint previous = 0;
    for (int i = 0; i < 6; ++i) {
        int w = sizes[i][0], h = sizes[i][1], levels = sizes[i][2];
        /* A smaller size reads the input's top-left corner: the pass only needs texels below w x h. */
        CHECK(ob_depth_mips_run(&gpu, input, w, h) == OB_OK, "run at %dx%d", w, h);
        GLint gw = 0, gh = 0, gl_levels = 0;
        glGetTextureLevelParameteriv(gpu.texture, 0, GL_TEXTURE_WIDTH, &gw);
        glGetTextureLevelParameteriv(gpu.texture, 0, GL_TEXTURE_HEIGHT, &gh);
        glGetTextureParameteriv(gpu.texture, GL_TEXTURE_IMMUTABLE_LEVELS, &gl_levels);
        CHECK(gpu.width == w && gpu.height == h && gpu.levels == levels && gw == w && gh == h && gl_levels == levels,
              "run at %dx%d: pass %dx%d %d levels, texture %dx%d %d levels, want %d", w, h, gpu.width, gpu.height,
              gpu.levels, gw, gh, gl_levels, levels);
        bool same_size = i > 0 && w == sizes[i - 1][0] && h == sizes[i - 1][1];
        CHECK(same_size == (gpu.texture == previous), "run at %dx%d: texture %s", w, h,
              same_size ? "remade at the same size" : "not remade at a new size");
        previous = gpu.texture;
    }
    CHECK(glGetError() == GL_NO_ERROR, "resize: no GL error");

    CHECK(ob_depth_mips_run(&gpu, input, 0, 4) == OB_ERR_BAD_SIZE, "0 x 4 is a bad size");
    CHECK(ob_depth_mips_run(&gpu, 0, 4, 4) == OB_ERR_INVALID_ARGUMENT, "no input texture");
    ob_depth_mips no_program;
    memset(&no_program, 0, sizeof no_program);
    CHECK(ob_depth_mips_run(&no_program, input, 4, 4) == OB_ERR_INVALID_ARGUMENT, "an uninitialised pass");
    CHECK(gpu.width == 160 && gpu.height == 120 && gpu.texture == previous, "a failed run leaves the pass as it was");
    ob_get_error(NULL);
    ob_depth_mips_destroy(&no_program);
    glDeleteTextures(1, &input);
    free(depth);
}

static void test_constants(void)
{
    ob_depth_mips_constants c;
    ob_depth_mips_fill(&c, 1280, 720);
    CHECK(c.size[0] == 1280 && c.size[1] == 720 && c.levels == 5, "1280x720: %dx%d, %d levels", c.size[0], c.size[1],
          c.levels);
    CHECK(ob_depth_mips_level_count(1, 1) == 1 && ob_depth_mips_level_count(2, 1) == 2 &&
              ob_depth_mips_level_count(1, 15) == 4 && ob_depth_mips_level_count(16, 1) == 5,
          "level counts: GL's 1 + floor(log2(max)), at most %d", OB_DEPTH_MIPS_LEVELS);
}

/* ---- cost (not a test) ----------------------------------------------------------------------- */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The prefilter, and in the same run the downsample pass at k = 1 (a plain per-pixel copy of depth
 * and normals, no shared memory) as the floor of the machine at hand. */
static void bench(void)
{
    const int sizes[2][2] = {{640, 480}, {1280, 720}};
    ob_timer_set timers;
    ob_timers_init(&timers);
    ob_compute_pass copy;
    if (ob_downsample_init(&copy) != OB_OK) return;
    for (int s = 0; s < 2; ++s) {
        int w = sizes[s][0], h = sizes[s][1];
        float *depth = make_planes(w, h, 3);
        GLuint input = ob_make_texture_2d(GL_R32F, w, h), normal = ob_make_texture_2d(GL_RGBA16F, w, h);
        GLuint depth_out = ob_make_texture_2d(GL_R32F, w, h), normal_out = ob_make_texture_2d(GL_RGBA16F, w, h);
        glTextureSubImage2D(input, 0, 0, 0, w, h, GL_RED, GL_FLOAT, depth);
        const ob_ao_grid grid = ob_ao_grid_make(w, h, 1);
        enum { WARM = 3, RUNS = 20 };
        double ms[2][RUNS];
        for (int r = 0; r < WARM + RUNS; ++r) {
            ob_timers_frame_begin(&timers);
            ob_timer_begin(&timers, "depth_mips");
            ob_depth_mips_run(&gpu, input, w, h);
            ob_timer_begin(&timers, "copy");
            ob_downsample_run(&copy, &grid, input, normal, depth_out, normal_out);
            ob_timer_end(&timers);
            ob_timers_frame_end(&timers);
            ob_timers_wait(&timers);
            if (r >= WARM) ms[0][r - WARM] = timers.ms[0], ms[1][r - WARM] = timers.ms[1];
        }
        for (int k = 0; k < 2; ++k) {
            qsort(ms[k], RUNS, sizeof ms[k][0], cmp_double);
            printf("%-10s %dx%d: median %.3f ms, min %.3f, max %.3f (%d runs)\n", k ? "copy" : "depth_mips", w, h,
                   0.5 * (ms[k][RUNS / 2 - 1] + ms[k][RUNS / 2]), ms[k][0], ms[k][RUNS - 1], RUNS);
        }
        GLuint t[4] = {input, normal, depth_out, normal_out};
        glDeleteTextures(4, t);
        free(depth);
    }
    ob_compute_pass_destroy(&copy);
    ob_timers_destroy(&timers);
}

int main(int argc, char **argv)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    if (ob_depth_mips_init(&gpu) != OB_OK) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "depth_mips init: %s\n", msg);
        ob_destroy_context(ctx);
        return 1;
    }
    printf("renderer: %s\n", ob_query_renderer(ctx));
    if (argc > 1 && !strcmp(argv[1], "--bench")) {
        bench();
    } else {
        test_constants();
        test_sky();
        test_step();
        test_random_planes();
        test_resize();
    }
    ob_depth_mips_destroy(&gpu);
    ob_destroy_context(ctx);
    return check_finish("test_depth_mips");
}
