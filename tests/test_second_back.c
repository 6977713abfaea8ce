/* The second layer over each pixel's footprint (src/passes/second_back.c, shaders/second_back.glsl):
 * what vbao, vbgi and gtao read as their samples' backs. Every synthetic pair of layers goes through
 * the GPU pass and its CPU twin (ob_second_back_reference); the two must agree bit for bit, and the
 * result must do what the pass is for:
 *   - a pixel's back is the deepest of its own and the four footprint edges', an edge's back the
 *     mean of the pixel's and that neighbour's: a wedge whose back deepens by 1 per pixel gets 0.5
 *     deeper, and a pixel beside a much thicker neighbour of the same solid gets half way there;
 *   - a neighbour of another solid does not count: one whose front lies behind the pixel's back (the
 *     floor seen through a hole, a wall beyond a silhouette);
 *   - a neighbour of the same solid whose back is unknown flags the pixel (its back negated: at least
 *     the deepest known and at least the method's constant), a sheet excepted;
 *   - an unknown back (0) stays unknown, sky stays sky; a sheet (back = front) stays a sheet;
 *   - odd sizes and a size change (the texture is remade). */
#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"
#include "passes/passes.h"

static ob_second_back gpu; /* one pass for the whole run, so a size change remakes its texture */

/* Both implementations of front/second (w x h), then bit-exact agreement; the GPU's result in out. */
static void run_both(const char *what, const float *front, const float *second, int w, int h, float *out)
{
    size_t n = (size_t)w * (size_t)h;
    float *cpu = malloc(n * sizeof(float));
    ob_second_back_reference(front, second, w, h, cpu);
    GLuint f = ob_make_texture_2d(GL_R32F, w, h), s = ob_make_texture_2d(GL_R32F, w, h);
    glTextureSubImage2D(f, 0, 0, 0, w, h, GL_RED, GL_FLOAT, front);
    glTextureSubImage2D(s, 0, 0, 0, w, h, GL_RED, GL_FLOAT, second);
    CHECK(ob_second_back_run(&gpu, f, s) == OB_OK, "%s: gpu run %dx%d", what, w, h);
    CHECK(gpu.width == w && gpu.height == h, "%s: the texture is %dx%d, want %dx%d", what, gpu.width, gpu.height, w, h);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(gpu.texture, 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), out);
    int differ = 0;
    for (size_t i = 0; i < n; ++i) differ += memcmp(&cpu[i], &out[i], sizeof(float)) != 0;
    CHECK(differ == 0, "%s: %d of %zu texels differ between the GPU pass and its CPU twin", what, differ, n);
    CHECK(glGetError() == GL_NO_ERROR, "%s: no GL error", what);
    glDeleteTextures(1, &f);
    glDeleteTextures(1, &s);
    free(cpu);
}

/* A plane facing the camera at depth 10 with a back 0.5 behind, whose back deepens by `slope` per
 * pixel along x: the pixel's back becomes its deeper edge's, the mean with its right neighbour's. */
static void test_wedge(void)
{
    enum { W = 37, H = 23 };
    float front[W * H], second[W * H], out[W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) front[y * W + x] = 10.0f, second[y * W + x] = 10.5f + 0.01f * (float)x;
    run_both("wedge", front, second, W, H, out);
    int bad = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            float want = x + 1 < W ? 0.5f * (second[i] + second[i + 1]) : second[i];
            bad += out[i] != want;
        }
    CHECK(bad == 0, "wedge: %d pixels not at their deeper footprint edge's back", bad);
}

/* A thin part (back 0.1 behind its front) beside a thick one of the same solid (back 2 behind),
 * beside a floor seen through a hole (front 30, behind the part's back), beside a part whose back is
 * unknown, and sky. */
static void test_neighbours(void)
{
    enum { W = 8, H = 1 };
    /* x: 0 thin, 1 thin, 2 thick, 3 thin, 4 floor, 5 thin, 6 unknown, 7 sky */
    const float front[W] = {10.0f, 10.0f, 10.0f, 10.0f, 30.0f, 10.0f, 9.0f, 0.0f};
    const float second[W] = {10.1f, 10.1f, 12.0f, 10.1f, 31.0f, 10.1f, 0.0f, 0.0f};
    float out[W];
    run_both("neighbours", front, second, W, H, out);
    CHECK(out[0] == 10.1f, "a thin pixel between thin ones keeps its back: %g", (double)out[0]);
    CHECK(out[1] == 0.5f * (10.1f + 12.0f) && out[3] == out[1],
          "a thin pixel beside a thick one of the same solid reaches half way to its back: %g, %g", (double)out[1],
          (double)out[3]);
    CHECK(out[2] == 12.0f, "the thick pixel keeps its own, deeper back: %g", (double)out[2]);
    CHECK(out[4] == 31.0f, "the floor through a hole keeps its own back: %g", (double)out[4]);
    CHECK(out[5] == -10.1f,
          "a thin pixel beside the floor through a hole (not counted) and beside a part of its solid whose back is "
          "unknown (front 9, in front of its back) keeps its own back, flagged: %g",
          (double)out[5]);
    CHECK(out[6] == 0.0f && out[7] == 0.0f, "unknown stays unknown, sky stays sky: %g, %g", (double)out[6],
          (double)out[7]);
}

/* A column of risers, each nearer than the one above, as a Quake stair seen from below its treads.
 * The ray through a riser's top row clips the step's nose and leaves through the tread (a known back
 * 0.3 behind); the row under it runs into the solid below (unknown). The top row is flagged; a
 * riser one row tall, whose unknown neighbour above lies behind its back and whose neighbour below
 * is known, is not; a sheet beside an unknown row of a nearer solid stays an unflagged sheet. */
static void test_open_behind(void)
{
    enum { W = 1, H = 6 };
    /* y: 0 riser A's top (known), 1 its lower row (unknown), 2 riser B, 3 riser C, 4 sheet, 5 unknown */
    const float front[H] = {20.0f, 20.0f, 19.0f, 18.0f, 17.5f, 17.0f};
    const float second[H] = {20.3f, 0.0f, 19.3f, 18.3f, 17.5f, 0.0f};
    float out[H];
    run_both("open behind", front, second, W, H, out);
    CHECK(out[0] == -20.3f, "a riser's top row above its unknown lower row is flagged: %g", (double)out[0]);
    CHECK(out[1] == 0.0f && out[5] == 0.0f, "unknown stays unknown: %g, %g", (double)out[1], (double)out[5]);
    CHECK(out[2] == 19.3f,
          "a riser below an unknown row that lies behind its back, above a known one, keeps its own, unflagged: %g",
          (double)out[2]);
    CHECK(out[3] == 18.3f, "a riser above a sheet keeps its own, unflagged: %g", (double)out[3]);
    CHECK(out[4] == 17.5f, "a sheet beside an unknown row in front of it stays a sheet, unflagged: %g",
          (double)out[4]);
}

/* A sheet seen at a slant, its own back (second = front), with holes (sky) in it: nothing changes. */
static void test_sheet(void)
{
    enum { W = 33, H = 17 };
    float front[W * H], out[W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) front[y * W + x] = (x % 5 == 2 && y % 5 == 2) ? 0.0f : 5.0f + 0.3f * (float)x;
    run_both("sheet", front, front, W, H, out);
    CHECK(!memcmp(out, front, sizeof out), "a sheet stays its own back");
}

/* Random layers at two sizes in turn: the two implementations agree, no back is nearer than the
 * peel pass's, and a pixel whose back was unknown stays so. */
static void test_random(void)
{
    const int sizes[3][2] = {{160, 120}, {1, 1}, {61, 7}};
    unsigned seed = 12345u;
    for (int k = 0; k < 3; ++k) {
        int w = sizes[k][0], h = sizes[k][1];
        size_t n = (size_t)w * (size_t)h;
        float *front = malloc(n * sizeof(float)), *second = malloc(n * sizeof(float)), *out = malloc(n * sizeof(float));
        for (size_t i = 0; i < n; ++i) {
            seed = seed * 1664525u + 1013904223u;
            float u = (float)(seed >> 8) / 16777216.0f;
            seed = seed * 1664525u + 1013904223u;
            float v = (float)(seed >> 8) / 16777216.0f;
            front[i] = u < 0.05f ? 0.0f : 1.0f + 20.0f * u;
            second[i] = front[i] == 0.0f || v < 0.2f ? 0.0f : front[i] + 3.0f * v;
        }
        char what[32];
        snprintf(what, sizeof what, "random %dx%d", w, h);
        run_both(what, front, second, w, h, out);
        int nearer = 0, unknown = 0, flagged = 0;
        for (size_t i = 0; i < n; ++i) {
            nearer += fabsf(out[i]) < second[i];
            unknown += (second[i] == 0.0f) != (out[i] == 0.0f);
            flagged += out[i] < 0.0f;
        }
        CHECK(nearer == 0 && unknown == 0, "%s: %d backs nearer than the peel's, %d unknowns changed", what, nearer,
              unknown);
        /* A fifth of the backs is unknown: a 160x120 layer has flagged pixels beside them. */
        CHECK(n < 1000 || flagged > 0, "%s: no pixel flagged beside an unknown back", what);
        free(front), free(second), free(out);
    }
}

int main(void)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    if (ob_second_back_init(&gpu) != OB_OK) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "second_back init: %s\n", msg);
        ob_destroy_context(ctx);
        return 1;
    }
    test_wedge();
    test_neighbours();
    test_open_behind();
    test_sheet();
    test_random();
    ob_second_back_destroy(&gpu);
    ob_destroy_context(ctx);
    return check_finish("test_second_back");
}
