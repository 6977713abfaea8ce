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
 *   - with the two layers' planes, across an edge where the front is not one surface (a stair of
 *     one-pixel risers), the back where the ray through that edge leaves the back's plane, at most
 *     the centre's thickness deeper (perspective and orthographic); one front keeps the
 *     neighbours' rule;
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

/* A texture of two floats a pixel: the planes' octahedral pairs (the pass reads any format). */
static GLuint plane_texture(const float *oct, int w, int h)
{
    GLuint t = ob_make_texture_2d(GL_RG32F, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RG, GL_FLOAT, oct);
    return t;
}

/* Both implementations of front/second (w x h) and planes (or NULL), then agreement: bit for bit
 * without planes; with them within 1e-5 of the depth (the GPU's normalize and division round
 * differently from C's). The GPU's result in out. */
static void run_both(const char *what, const float *front, const float *second, int w, int h,
                     const ob_second_back_planes_data *planes, float *out)
{
    size_t n = (size_t)w * (size_t)h;
    float *cpu = malloc(n * sizeof(float));
    ob_second_back_reference(front, second, w, h, planes, cpu);
    GLuint f = ob_make_texture_2d(GL_R32F, w, h), s = ob_make_texture_2d(GL_R32F, w, h);
    glTextureSubImage2D(f, 0, 0, 0, w, h, GL_RED, GL_FLOAT, front);
    glTextureSubImage2D(s, 0, 0, 0, w, h, GL_RED, GL_FLOAT, second);
    ob_second_back_planes gpu_planes = {0};
    if (planes) {
        gpu_planes.front = plane_texture(planes->front, w, h);
        gpu_planes.back = plane_texture(planes->back, w, h);
        memcpy(gpu_planes.proj_info, planes->proj_info, sizeof gpu_planes.proj_info);
        gpu_planes.orthographic = planes->orthographic;
    }
    CHECK(ob_second_back_run(&gpu, f, s, planes ? &gpu_planes : NULL) == OB_OK, "%s: gpu run %dx%d", what, w, h);
    CHECK(gpu.width == w && gpu.height == h, "%s: the texture is %dx%d, want %dx%d", what, gpu.width, gpu.height, w, h);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(gpu.texture, 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), out);
    int differ = 0;
    for (size_t i = 0; i < n; ++i)
        differ += planes ? !(fabsf(cpu[i] - out[i]) <= 1e-5f * fabsf(cpu[i])) : memcmp(&cpu[i], &out[i], sizeof(float)) != 0;
    CHECK(differ == 0, "%s: %d of %zu texels differ between the GPU pass and its CPU twin", what, differ, n);
    CHECK(glGetError() == GL_NO_ERROR, "%s: no GL error", what);
    glDeleteTextures(1, &f);
    glDeleteTextures(1, &s);
    glDeleteTextures(1, &gpu_planes.front);
    glDeleteTextures(1, &gpu_planes.back);
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
    run_both("wedge", front, second, W, H, NULL, out);
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
    run_both("neighbours", front, second, W, H, NULL, out);
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
    run_both("open behind", front, second, W, H, NULL, out);
    CHECK(out[0] == -20.3f, "a riser's top row above its unknown lower row is flagged: %g", (double)out[0]);
    CHECK(out[1] == 0.0f && out[5] == 0.0f, "unknown stays unknown: %g, %g", (double)out[1], (double)out[5]);
    CHECK(out[2] == 19.3f,
          "a riser below an unknown row that lies behind its back, above a known one, keeps its own, unflagged: %g",
          (double)out[2]);
    CHECK(out[3] == 18.3f, "a riser above a sheet keeps its own, unflagged: %g", (double)out[3]);
    CHECK(out[4] == 17.5f, "a sheet beside an unknown row in front of it stays a sheet, unflagged: %g",
          (double)out[4]);
}

/* The two layers' planes over the footprint, under a camera of 60 degrees. A stair of risers one
 * pixel row tall facing the camera, each 0.5 nearer than the row above, each step leaving through
 * its horizontal tread 0.5 behind its riser on the ray through the pixel's centre (a back plane
 * y = const through that point). Across each row's upper and lower edges the front is another
 * riser, and the back is where the ray through that edge leaves the tread, 20.5 nc / ne deep for
 * the edge's and centre's ndc.y at depth 20: the edge nearer the horizon runs longer under the tread,
 * at most the centre's thickness deeper. One riser of the same tread planes (no step between the rows)
 * is one front, and keeps its neighbours' backs; so does a slab seen face-on (parallel planes). An
 * orthographic camera and a back tilted by 2 in y: the deeper edge lies 2 * 0.1 further. A sheet
 * stays a sheet. */
static void test_planes(void)
{
    enum { W = 4, H = 100 };
    const double f = 1.0 / tan(3.14159265358979323846 / 6.0), aspect = (double)W / (double)H;
    static float front[W * H], second[W * H], fo[2 * W * H], bo[2 * W * H], out[W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            front[i] = 20.0f + 0.5f * (float)(y % 2), second[i] = front[i] + 0.5f;
            fo[2 * i] = fo[2 * i + 1] = 0.0f;       /* (0, 0, 1): the riser faces the camera */
            bo[2 * i] = 0.0f, bo[2 * i + 1] = 1.0f; /* (0, 1, 0): the tread */
        }
    ob_second_back_planes_data pl = {fo, bo, {(float)(aspect / f), (float)(1.0 / f), 0.0f, 0.0f}, 0};
    run_both("planes: stair", front, second, W, H, &pl, out);
    int bad = 0, deeper = 0;
    for (int y = 0; y < H; ++y) {
        double z1 = front[y * W], z2 = second[y * W], nc = ((double)y + 0.5) * 2.0 / H - 1.0, want = z2;
        for (int k = -1; k <= 1; k += 2) {
            double ne = nc + k * 1.0 / H;
            if (fabs(ne) < 1e-9 || (ne > 0) != (nc > 0)) continue;
            want = fmax(want, fmin(z2 * nc / ne, 2.0 * z2 - z1));
        }
        /* The nearer row below (y % 2 == 0 lies in front of the odd rows' backs) is a neighbour of
         * the same solid: its back's mean with this one's is nearer than this one's, no deeper. */
        for (int x = 0; x < W; ++x) {
            bad += fabs(out[y * W + x] - want) > 2e-4 * want;
            deeper += out[y * W + x] > second[y * W + x] + 0.05f;
        }
    }
    CHECK(bad == 0, "planes: %d stair pixels not at the back of their deeper edge", bad);
    CHECK(deeper >= W * (H - 4), "planes: only %d of %d stair pixels deeper than their centre's back", deeper, W * H);

    for (int i = 0; i < W * H; ++i) front[i] = 20.0f, second[i] = 20.5f;
    run_both("planes: one riser", front, second, W, H, &pl, out);
    bad = 0;
    for (int i = 0; i < W * H; ++i) bad += fabsf(out[i] - 20.5f) > 1e-5f;
    CHECK(bad == 0, "planes: %d pixels of one riser (one front) moved from their neighbours' backs", bad);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) front[y * W + x] = 20.0f + 0.5f * (float)(y % 2), second[y * W + x] = front[y * W + x] + 0.5f;

    for (int i = 0; i < W * H; ++i) bo[2 * i] = bo[2 * i + 1] = 0.0f;
    run_both("planes: slab", front, second, W, H, &pl, out);
    bad = 0;
    for (int i = 0; i < W * H; ++i) bad += fabsf(out[i] - second[i]) > 1e-5f;
    CHECK(bad == 0, "planes: %d pixels of a slab seen face-on moved", bad);

    /* Orthographic: proj_info (1/P00, 1/P11, -P30, -P31), a view 10 units high; the back's normal
     * (0, 2, 1) / sqrt 5, octahedral (0, 2/3). Half a pixel is 0.1 view units. */
    for (int i = 0; i < W * H; ++i) bo[2 * i] = 0.0f, bo[2 * i + 1] = 2.0f / 3.0f;
    ob_second_back_planes_data ortho = {fo, bo, {10.0f * (float)aspect, 10.0f, 0.0f, 0.0f}, 1};
    run_both("planes: orthographic", front, second, W, H, &ortho, out);
    bad = 0;
    for (int i = 0; i < W * H; ++i) bad += fabsf(out[i] - (second[i] + 0.2f)) > 1e-4f;
    CHECK(bad == 0, "planes: %d pixels of a tilted back under an orthographic camera not 0.2 deeper (%g at 0)", bad,
          (double)out[0]);

    run_both("planes: sheet", front, front, W, H, &pl, out);
    CHECK(!memcmp(out, front, sizeof out), "planes: a sheet stays its own back");
}

/* A sheet seen at a slant, its own back (second = front), with holes (sky) in it: nothing changes. */
static void test_sheet(void)
{
    enum { W = 33, H = 17 };
    float front[W * H], out[W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) front[y * W + x] = (x % 5 == 2 && y % 5 == 2) ? 0.0f : 5.0f + 0.3f * (float)x;
    run_both("sheet", front, front, W, H, NULL, out);
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
        run_both(what, front, second, w, h, NULL, out);
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
    test_planes();
    test_sheet();
    test_random();
    ob_second_back_destroy(&gpu);
    ob_destroy_context(ctx);
    return check_finish("test_second_back");
}
