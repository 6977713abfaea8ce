/* GPU tests of the HDR passes (SSDO thesis §2.2, §5.5, §6.5) on llvmpipe or a GPU: the reduction's
 * log-average (eq. 2.1) against the CPU formula on the very values the GPU stored, Reinhard's
 * L_white (eq. 2.4) mapping to 255, the automatic key rising with brightness, HDR off as a clamp,
 * and bloom spreading a single bright pixel. `test_hdr --bench` prints the passes' median times. */
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"
#include "passes/passes.h"

/* An odd size: partial 64x64 reduction blocks on both axes and an odd half-resolution bloom. */
enum { W = 257, H = 131 };

/* RGBA16F radiance from RGB floats (row 0 at the bottom, as GL stores it). */
static GLuint make_radiance(const float *rgb, int w, int h)
{
    float *rgba = calloc((size_t)w * (size_t)h * 4, sizeof(float));
    for (size_t i = 0; rgba && i < (size_t)w * (size_t)h; ++i) {
        memcpy(rgba + 4 * i, rgb + 3 * i, 3 * sizeof(float));
        rgba[4 * i + 3] = 1.0f;
    }
    GLuint tex = ob_make_texture_2d(GL_RGBA16F, w, h);
    if (rgba) glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, rgba);
    free(rgba);
    return tex;
}

static GLuint make_constant(float value, int w, int h)
{
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    for (size_t i = 0; rgb && i < (size_t)w * (size_t)h * 3; ++i) rgb[i] = value;
    GLuint tex = make_radiance(rgb, w, h);
    free(rgb);
    return tex;
}

/* Rec. 709 luminance of what the texture really holds (half floats), for the CPU reference. */
static float *stored_luminance(GLuint tex, int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    float *rgba = malloc(n * 4 * sizeof(float));
    float *l = malloc(n * sizeof(float));
    if (!rgba || !l) {
        free(rgba);
        free(l);
        return NULL;
    }
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    for (size_t i = 0; i < n; ++i)
        l[i] = 0.2126f * rgba[4 * i] + 0.7152f * rgba[4 * i + 1] + 0.0722f * rgba[4 * i + 2];
    free(rgba);
    return l;
}

/* One frame; returns the RGBA8 result (caller frees). */
static unsigned char *run(ob_hdr_pass *h, GLuint radiance, const ob_hdr_settings *s, int w, int h_px)
{
    GLuint final = ob_make_texture_2d(GL_RGBA8, w, h_px);
    ob_hdr_run(h, radiance, s, final, NULL);
    unsigned char *px = malloc((size_t)w * (size_t)h_px * 4);
    if (px) {
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureImage(final, 0, GL_RGBA, GL_UNSIGNED_BYTE, w * h_px * 4, px);
    }
    glDeleteTextures(1, &final);
    return px;
}

static double srgb(double c)
{
    c = c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

static const ob_hdr_settings plain = {.enabled = true, .exposure = 1.0f, .key = 0.0f, .l_white = 0.0f,
                                      .bloom_threshold = 1.0f, .bloom_strength = 0.0f};

/* (1) eq. 2.1 of a constant image is the constant; GPU and CPU agree on a mixed image too. */
static void test_log_average(ob_hdr_pass *h)
{
    const float constants[] = {0.01f, 0.18f, 1.0f, 50.0f};
    for (size_t c = 0; c < sizeof constants / sizeof constants[0]; ++c) {
        GLuint tex = make_constant(constants[c], W, H);
        float gpu = 0.0f, key = 0.0f;
        free(run(h, tex, &plain, W, H));
        ob_hdr_query(h, &gpu, &key);
        float *l = stored_luminance(tex, W, H);
        double cpu = l ? ob_hdr_log_average(l, (size_t)W * H) : 0.0;
        char what[96];
        snprintf(what, sizeof what, "GPU log-average of constant %g (relative)", constants[c]);
        CHECK_NEAR(gpu / constants[c], 1.0, 1e-3, what);
        snprintf(what, sizeof what, "CPU log-average of constant %g (relative)", constants[c]);
        CHECK_NEAR(cpu / constants[c], 1.0, 1e-3, what);
        /* Both on the same half floats: only float round-off in the GPU's sums remains. */
        snprintf(what, sizeof what, "GPU vs CPU log-average of constant %g (relative)", constants[c]);
        CHECK_NEAR(gpu / cpu, 1.0, 1e-5, what);
        free(l);
        glDeleteTextures(1, &tex);
    }

    /* A mixed image: black, dim, bright and coloured pixels, and a NaN the passes treat as black. */
    float *rgb = malloc((size_t)W * H * 3 * sizeof(float));
    if (!rgb) return;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float *p = rgb + 3 * ((size_t)y * W + (size_t)x);
            float v = (x + y) % 7 == 0 ? 0.0f : ((x / 5 + y / 3) % 2 ? 0.05f : 20.0f);
            p[0] = v * (x % 3 == 0 ? 2.0f : 1.0f);
            p[1] = v;
            p[2] = v * (y % 2 ? 0.5f : 1.0f);
        }
    rgb[3 * 77 + 1] = NAN;
    GLuint tex = make_radiance(rgb, W, H);
    free(rgb);
    float gpu = 0.0f;
    unsigned char *px = run(h, tex, &plain, W, H);
    ob_hdr_query(h, &gpu, NULL);
    float *l = stored_luminance(tex, W, H);
    double cpu = l ? ob_hdr_log_average(l, (size_t)W * H) : 0.0;
    CHECK(cpu > 0.05 && cpu < 20.0, "mixed image's log-average %g lies between its levels", cpu);
    CHECK_NEAR(gpu / cpu, 1.0, 1e-4, "GPU vs CPU log-average of a mixed image (relative)");
    CHECK(px && px[4 * 77] == 0 && px[4 * 77 + 1] == 0, "a NaN pixel comes out black");
    free(px);
    free(l);
    glDeleteTextures(1, &tex);

    const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    CHECK(ob_hdr_log_average(zeros, 4) < 1e-12, "black's log-average is 0 (eq. 2.1 less delta)");
    CHECK(ob_hdr_log_average(NULL, 0) == 0.0, "no pixels: 0");
}

/* (2) eq. 2.4 maps L_white to 1: on the CPU, and through the GPU to sRGB 255. */
static void test_reinhard(ob_hdr_pass *h)
{
    const float whites[] = {0.5f, 1.0f, 2.0f, 11.2f};
    for (size_t i = 0; i < sizeof whites / sizeof whites[0]; ++i)
        CHECK_NEAR(ob_hdr_reinhard(whites[i], whites[i]), 1.0, 1e-6, "ob_hdr_reinhard(L_white, L_white)");
    CHECK_NEAR(ob_hdr_reinhard(1.0f, 0.0f), 0.5, 1e-7, "eq. 2.3 without L_white: 1 -> 1/2");
    CHECK_NEAR(ob_hdr_reinhard(0.0f, 2.0f), 0.0, 0.0, "black stays black");
    CHECK(ob_hdr_reinhard(4.0f, 2.0f) > 1.0f, "beyond L_white eq. 2.4 exceeds 1 (clamped by sRGB)");

    /* A constant image c: L_avg = c, so eq. 2.2 gives L = key exactly; key = L_white -> white. */
    GLuint tex = make_constant(0.5f, W, H);
    ob_hdr_settings s = plain;
    s.key = 2.0f;
    s.l_white = 2.0f;
    unsigned char *px = run(h, tex, &s, W, H);
    float avg = 0.0f, key = 0.0f;
    ob_hdr_query(h, &avg, &key);
    CHECK_NEAR(key, 2.0, 0.0, "the explicit key is the key used");
    size_t centre = 4 * ((size_t)(H / 2) * W + W / 2);
    CHECK(px && px[centre] == 255 && px[centre + 1] == 255 && px[centre + 2] == 255 && px[centre + 3] == 255,
          "scaled L = L_white gives sRGB 255 (got %d %d %d)", px ? px[centre] : -1, px ? px[centre + 1] : -1,
          px ? px[centre + 2] : -1);
    free(px);

    /* Below white, the GPU matches the CPU formula: L = 1 with L_white 2 -> 0.625. */
    s.key = 1.0f;
    px = run(h, tex, &s, W, H);
    double want = 255.0 * srgb(ob_hdr_reinhard(1.0f, 2.0f));
    CHECK(px && fabs(px[centre] - want) <= 1.0, "eq. 2.4 at L = 1, L_white = 2: %d vs %.2f", px ? px[centre] : -1,
          want);
    free(px);
    /* And eq. 2.3 (l_white 0): 1 -> 0.5. */
    s.l_white = 0.0f;
    px = run(h, tex, &s, W, H);
    want = 255.0 * srgb(0.5);
    CHECK(px && fabs(px[centre] - want) <= 1.0, "eq. 2.3 at L = 1: %d vs %.2f", px ? px[centre] : -1, want);
    free(px);
    glDeleteTextures(1, &tex);
}

/* (3) §6.5: the automatic key rises with the log-average, on the GPU and the CPU. */
static void test_auto_key(ob_hdr_pass *h)
{
    const float levels[2] = {0.1f, 10.0f};
    float keys[2] = {0.0f, 0.0f};
    for (int i = 0; i < 2; ++i) {
        GLuint tex = make_constant(levels[i], W, H);
        free(run(h, tex, &plain, W, H));
        float avg = 0.0f;
        ob_hdr_query(h, &avg, &keys[i]);
        CHECK_NEAR(keys[i], ob_hdr_auto_key(avg), 1e-5, "GPU automatic key = ob_hdr_auto_key(log-average)");
        glDeleteTextures(1, &tex);
    }
    CHECK(keys[1] > keys[0], "a brighter image gets a higher key (%g for 0.1, %g for 10)", keys[0], keys[1]);
    bool monotone = true;
    float prev = ob_hdr_auto_key(0.0f);
    for (float l = 1e-3f; l < 1e5f; l *= 1.5f) {
        float k = ob_hdr_auto_key(l);
        if (!(k > prev)) monotone = false;
        prev = k;
    }
    CHECK(monotone, "ob_hdr_auto_key rises over 1e-3 .. 1e5");
    CHECK(ob_hdr_auto_key(0.0f) > 0.0f && ob_hdr_auto_key(1e6f) < 1.03f, "the key stays within (0, 1.03)");
}

/* (4) HDR off: exposure x radiance clamped to [0,1], then sRGB. */
static void test_disabled(ob_hdr_pass *h)
{
    float rgb[4 * 3] = {0.5f, 0.5f, 0.5f, 3.0f, 3.0f, 3.0f, 0.25f, 0.25f, 0.25f, 0.0f, 0.0f, 0.0f};
    GLuint tex = make_radiance(rgb, 4, 1);
    ob_hdr_pass small;
    CHECK(ob_hdr_init(&small, 4, 1) == OB_OK, "4x1 HDR pass");
    ob_hdr_settings s = plain;
    s.enabled = false;
    s.bloom_strength = 1.0f; /* ignored with HDR off */
    unsigned char *px = run(&small, tex, &s, 4, 1);
    CHECK(px && px[0] == 188 && px[1] == 188 && px[2] == 188, "radiance 0.5 -> sRGB 188 (got %d)", px ? px[0] : -1);
    CHECK(px && px[4] == 255 && px[5] == 255 && px[6] == 255, "radiance 3 -> 255 (got %d)", px ? px[4] : -1);
    CHECK(px && px[12] == 0, "black stays 0");
    free(px);
    float avg = -1.0f, key = -1.0f;
    ob_hdr_query(&small, &avg, &key);
    CHECK(avg == 0.0f && key == 0.0f, "HDR off: the query reads 0s (%g, %g)", avg, key);
    s.exposure = 2.0f;
    px = run(&small, tex, &s, 4, 1);
    CHECK(px && px[8] == 188, "exposure 2 x 0.25 -> 188 (got %d)", px ? px[8] : -1);
    free(px);
    ob_hdr_destroy(&small);
    (void)h;
    glDeleteTextures(1, &tex);
}

/* (5) bloom spreads a single bright pixel to its neighbours, and nothing when the strength is 0. */
static void test_bloom(void)
{
    enum { S = 64, CX = 32, CY = 32 };
    float *rgb = calloc((size_t)S * S * 3, sizeof(float));
    if (!rgb) return;
    for (int c = 0; c < 3; ++c) rgb[3 * (CY * S + CX) + c] = 100.0f;
    GLuint tex = make_radiance(rgb, S, S);
    free(rgb);
    ob_hdr_pass h;
    CHECK(ob_hdr_init(&h, S, S) == OB_OK, "64x64 HDR pass");
    ob_hdr_settings s = plain;
    s.key = 0.18f;
    s.l_white = 4.0f;
    s.bloom_threshold = 1.0f;
    const int near[4][2] = {{CX + 3, CY}, {CX - 3, CY}, {CX, CY + 4}, {CX + 2, CY - 2}};
    for (int pass = 0; pass < 2; ++pass) {
        s.bloom_strength = pass == 0 ? 0.0f : 0.5f;
        unsigned char *px = run(&h, tex, &s, S, S);
        if (!px) continue;
        CHECK(px[4 * (CY * S + CX)] == 255, "the bright pixel is white (strength %g)", s.bloom_strength);
        for (int i = 0; i < 4; ++i) {
            int v = px[4 * (near[i][1] * S + near[i][0])];
            if (pass == 0)
                CHECK(v == 0, "no bloom: neighbour (%d,%d) stays black (got %d)", near[i][0], near[i][1], v);
            else
                CHECK(v > 0, "bloom: neighbour (%d,%d) gets light (got %d)", near[i][0], near[i][1], v);
        }
        CHECK(px[0] == 0, "far corner stays black (strength %g, got %d)", s.bloom_strength, px[0]);
        free(px);
    }
    ob_hdr_destroy(&h);
    glDeleteTextures(1, &tex);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median GPU ms of each pass over `frames` frames after warm-up, at w x h. */
static void bench(int w, int h, int frames)
{
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    if (!rgb) return;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[3 * ((size_t)y * w + x) + c] = (x * 7 + y * 3) % 97 == 0 ? 40.0f : 0.02f + 0.5f * (float)x / (float)w;
    GLuint tex = make_radiance(rgb, w, h);
    free(rgb);
    GLuint final = ob_make_texture_2d(GL_RGBA8, w, h);
    ob_hdr_pass hp;
    if (ob_hdr_init(&hp, w, h) != OB_OK) return;
    ob_timer_set timers;
    ob_timers_init(&timers);
    ob_hdr_settings s = plain;
    s.l_white = 4.0f;
    s.bloom_threshold = 1.0f;
    s.bloom_strength = 0.25f;
    double *ms[3] = {calloc((size_t)frames, sizeof(double)), calloc((size_t)frames, sizeof(double)),
                     calloc((size_t)frames, sizeof(double))};
    for (int f = -3; f < frames && ms[0] && ms[1] && ms[2]; ++f) {
        ob_timers_frame_begin(&timers);
        ob_hdr_run(&hp, tex, &s, final, &timers);
        ob_timers_frame_end(&timers);
        ob_timers_wait(&timers);
        for (int i = 0; f >= 0 && i < timers.count && i < 3; ++i) ms[i][f] = timers.ms[i];
    }
    printf("bench %dx%d (%d frames, median ms):", w, h, frames);
    for (int i = 0; i < timers.count && i < 3 && ms[i]; ++i) {
        qsort(ms[i], (size_t)frames, sizeof(double), cmp_double);
        printf(" %s %.2f", timers.names[i], ms[i][frames / 2]);
    }
    printf("\n");
    for (int i = 0; i < 3; ++i) free(ms[i]);
    ob_timers_destroy(&timers);
    ob_hdr_destroy(&hp);
    glDeleteTextures(1, &final);
    glDeleteTextures(1, &tex);
}

int main(int argc, char **argv)
{
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    if (argc > 1 && strcmp(argv[1], "--bench") == 0) {
        int frames = argc > 2 ? atoi(argv[2]) : 50;
        printf("renderer: %s\n", ob_query_renderer(ctx));
        bench(800, 600, frames);
        bench(1280, 720, frames);
        bench(1920, 1080, frames);
        ob_destroy_context(ctx);
        return 0;
    }
    ob_hdr_pass h;
    ob_error err = ob_hdr_init(&h, W, H);
    CHECK(err == OB_OK, "ob_hdr_init %dx%d", W, H);
    if (err == OB_OK) {
        test_log_average(&h);
        test_reinhard(&h);
        test_auto_key(&h);
        test_disabled(&h);
        test_bloom();
        ob_hdr_destroy(&h);
    }
    ob_hdr_pass bad;
    CHECK(ob_hdr_init(&bad, 0, 4) == OB_ERR_BAD_SIZE, "a zero size is refused");
    ob_hdr_destroy(&bad);
    CHECK(glGetError() == GL_NO_ERROR, "no OpenGL error");
    ob_destroy_context(ctx);
    return check_finish("test_hdr");
}
