/* Every texture argument of the host path checked, and every accepted input right (issue 45, item
 * 3; obscura.h, "the host path").
 *
 * Wrong inputs: a table of cases (formats, targets, sizes against ob_host_input_size, names that
 * are no texture, a missing radiance or albedo, projections that are orthographic, NaN or zero,
 * NULL arguments, ob_settings_from_host's refusals, and the old entry points' wrong inputs). Each
 * must return OB_ERR_INVALID_ARGUMENT (OB_ERR_UNKNOWN_METHOD for an unknown name) with one line
 * from ob_get_error that names the argument as a word ("normal", "ao", "second_depth", ...) and,
 * for formats and sizes, what it is; the output, filled with 0.25 first, must be unchanged; and
 * the call must leave no GL error of its own.
 *
 * Accepted inputs: the host rasterises one real scene (a sphere on a floor against a wall, a box in
 * the corner; ray-cast on the CPU) into every accepted depth format (GL_DEPTH_COMPONENT16/24/32F,
 * GL_DEPTH24_STENCIL8, GL_DEPTH32F_STENCIL8 with standard and reversed Z, [0,1] and [-1,1] depth
 * ranges, finite and infinite far planes; R16F and R32F linear depth), every normal encoding (view
 * and world space; RGBA16F/32F, RGB10_A2, RGBA8, octahedral RG16F, RG16_SNORM, RG8; none) and every
 * output format, and a TAA host's jittered reversed-Z frame. Each must give AO in [0, 1] that
 * matches the AO of R32F linear depth + RGBA32F view normals of the same geometry within a
 * tolerance stated per case with its reason (the storage's precision). */
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "obscura/eval.h"
#include "host_scene.h"

enum { W = 96, H = 72 };

/* ---- the host's frame in every encoding ------------------------------------------------------------ */
static const float cam_eye[3] = {0.6f, 2.3f, 4.6f}, cam_target[3] = {0.3f, 0.6f, -1.0f};
static const float fov_y = 0.87266f; /* 50 degrees */
#define NPX ((size_t)W * (size_t)H)

static host_view V;                                  /* the camera, projection standard, [-1, 1], 0.1..100 */
static float depth_px[NPX], vn_px[4 * NPX], wn_px[4 * NPX]; /* its linear depth, view and world normals */

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_NO_ERROR: return "none";
    case GL_INVALID_ENUM: return "INVALID_ENUM";
    case GL_INVALID_VALUE: return "INVALID_VALUE";
    case GL_INVALID_OPERATION: return "INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "OUT_OF_MEMORY";
    default: return "other";
    }
}

static GLuint upload(GLenum internal, int w, int h, GLenum format, const float *data)
{
    GLuint t = make_tex(internal, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, format, GL_FLOAT, data);
    return t;
}

/* A hardware depth texture of `format` holding the window depth of each pixel's linear depth
 * through `proj` (sky: the far plane's, 1, or 0 reversed). */
static GLuint depth_texture(GLenum format, const float proj[16], bool zero_to_one, bool reversed, const float *depth,
                            int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    float *win = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; ++i) win[i] = window_depth(proj, depth[i], zero_to_one, reversed ? 0.0f : 1.0f);
    GLuint t = make_tex(format, w, h);
    glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, win);
    free(win);
    return t;
}

/* A normal texture of `format` in its encoding (obscura.h, ob_host_frame.normal) from 4 floats
 * per pixel (xyz, zero for sky). */
static GLuint normal_texture(GLenum format, const float *n4, int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    float *px = malloc(4 * n * sizeof(float));
    bool oct = format == GL_RG16F || format == GL_RG16_SNORM || format == GL_RG8;
    bool unorm = format == GL_RGB10_A2 || format == GL_RGBA8 || format == GL_RG8;
    for (size_t i = 0; i < n; ++i) {
        const float *v = &n4[4 * i];
        bool sky = v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f;
        if (oct) {
            float e[2] = {0.0f, 0.0f};
            if (!sky) oct_encode(v, e);
            for (int k = 0; k < 2; ++k) px[2 * i + k] = unorm ? e[k] * 0.5f + 0.5f : e[k];
        } else {
            for (int k = 0; k < 3; ++k) px[4 * i + k] = unorm ? v[k] * 0.5f + 0.5f : v[k];
            px[4 * i + 3] = 1.0f;
        }
    }
    GLuint t = upload(format, w, h, oct ? GL_RG : GL_RGBA, px);
    free(px);
    return t;
}

static ob_host_frame frame_of(GLuint depth, GLuint normal, ob_normal_space space, const float proj[16], bool zero_to_one)
{
    ob_host_frame f = {.depth = depth, .normal = normal, .normal_space = space, .depth_zero_to_one = zero_to_one};
    memcpy(f.projection, proj, sizeof f.projection);
    memcpy(f.view, V.view, sizeof f.view);
    return f;
}

static bool is_integer_format(GLint format) { return format == GL_R32I || format == GL_R32UI || format == GL_RGBA8UI; }
static bool is_depth_format(GLint format)
{
    return format == GL_DEPTH_COMPONENT16 || format == GL_DEPTH_COMPONENT24 || format == GL_DEPTH_COMPONENT32F ||
           format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
}

static GLint texture_format(GLuint tex)
{
    GLint f = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &f);
    return f;
}

/* Level 0 as 4 floats (or ints) per pixel, 1 for a depth texture; *count gets the floats; NULL when
 * it has no level 0. */
static float *read_texture(GLuint tex, size_t *count)
{
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    const GLint format = texture_format(tex);
    *count = (size_t)w * (size_t)h * (is_depth_format(format) ? 1 : 4);
    if (w <= 0 || h <= 0) return NULL;
    float *px = calloc(*count, sizeof(float));
    GLsizei bytes = (GLsizei)(*count * sizeof(float));
    if (is_integer_format(format)) glGetTextureImage(tex, 0, GL_RGBA_INTEGER, GL_INT, bytes, px);
    else if (is_depth_format(format)) glGetTextureImage(tex, 0, GL_DEPTH_COMPONENT, GL_FLOAT, bytes, px);
    else glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, bytes, px);
    return px;
}

static void fill_sentinel(GLuint tex)
{
    GLint w = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    if (w <= 0) return;
    const float quarter = 0.25f;
    if (is_integer_format(texture_format(tex))) {
        const GLint v[4] = {25, 25, 25, 25};
        glClearTexImage(tex, 0, GL_RGBA_INTEGER, GL_INT, v);
    } else if (is_depth_format(texture_format(tex))) {
        glClearTexImage(tex, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &quarter);
    } else {
        const float v[4] = {0.25f, 0.25f, 0.25f, 0.25f};
        glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, v);
    }
}

/* `word` occurs in msg as a whole identifier (so "ao" is not found in "ob_host_ao", nor "depth" in
 * "second_depth"); alternatives separated by '|'. */
static bool names_word(const char *msg, const char *words)
{
    char buf[128];
    snprintf(buf, sizeof buf, "%s", words);
    for (char *w = strtok(buf, "|"); w; w = strtok(NULL, "|")) {
        size_t n = strlen(w);
        for (const char *p = msg; (p = strstr(p, w)) != NULL; ++p) {
            bool left = p == msg || !(isalnum((unsigned char)p[-1]) || p[-1] == '_');
            bool right = !(isalnum((unsigned char)p[n]) || p[n] == '_');
            if (left && right) return true;
        }
    }
    return false;
}

static bool contains_nocase(const char *msg, const char *what)
{
    size_t n = strlen(what);
    for (const char *p = msg; *p; ++p) {
        size_t k = 0;
        while (k < n && p[k] && tolower((unsigned char)p[k]) == tolower((unsigned char)what[k])) ++k;
        if (k == n) return true;
    }
    return false;
}

/* ---- the wrong-input table ------------------------------------------------------------------------ */
static int table_rows = 0;

static void table_header(const char *title)
{
    printf("\n%s\n%-58s %-24s %-9s %s\n", title, "case", "returned", "GL error", "message");
}

/* Checks one refused call: the code, one line naming `arg` (and holding also1, also2), no GL error of
 * its own, and the sentinel output (filled before the call; 0 = none) as it was. */
static void refused(const char *what, const char *arg, const char *also1, const char *also2, ob_error expect,
                    ob_error rc, const char *msg, GLuint sentinel, const float *sentinel_before, size_t sentinel_count)
{
    GLenum ge = glGetError();
    ++table_rows;
    printf("%-58s %-24s %-9s %s\n", what, ob_error_name(rc), gl_error_name(ge), rc == OB_OK ? "(none)" : msg);
    CHECK(rc == expect, "%s: returned %s, expected %s", what, ob_error_name(rc), ob_error_name(expect));
    CHECK(ge == GL_NO_ERROR, "%s: the call left GL error %s of its own", what, gl_error_name(ge));
    if (rc == OB_OK) return;
    CHECK(msg[0] && !strchr(msg, '\n'), "%s: one line of message, got \"%s\"", what, msg);
    if (arg) CHECK(names_word(msg, arg), "%s: the message names the argument \"%s\": \"%s\"", what, arg, msg);
    if (also1) CHECK(contains_nocase(msg, also1), "%s: the message says \"%s\": \"%s\"", what, also1, msg);
    if (also2) CHECK(contains_nocase(msg, also2), "%s: the message says \"%s\": \"%s\"", what, also2, msg);
    if (sentinel && sentinel_before) {
        size_t count = 0;
        float *after = read_texture(sentinel, &count);
        CHECK(after && count == sentinel_count && !memcmp(after, sentinel_before, count * sizeof(float)),
              "%s: the output texture %u was written by a refused call", what, sentinel);
        free(after);
    }
}

/* ob_host_ao with wrong inputs: `sentinel` is the output that must stay untouched. */
static void wrong(const char *what, const char *arg, const char *also1, const char *also2, ob_renderer *r,
                  const ob_host_frame *f, const ob_settings *s, const ob_host_outputs *o, GLuint sentinel)
{
    if (sentinel) fill_sentinel(sentinel);
    size_t count = 0;
    float *before = sentinel ? read_texture(sentinel, &count) : NULL;
    while (glGetError() != GL_NO_ERROR) {}
    ob_clear_error();
    ob_error rc = ob_host_ao(r, f, s, o);
    const char *msg = "";
    if (rc != OB_OK) ob_get_error(&msg);
    refused(what, arg, also1, also2, OB_ERR_INVALID_ARGUMENT, rc, msg, sentinel, before, count);
    free(before);
}

/* ---- comparing AO ----------------------------------------------------------------------------------- */
typedef struct ao_stats {
    double mean, p99, max;
    bool in_range, grey;
} ao_stats;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Channel 0 of `test` against channel 0 of `ref` (4 floats per pixel each) over every pixel. */
static ao_stats compare_ao(const float *test, const float *ref, bool rgba)
{
    ao_stats st = {.in_range = true, .grey = true};
    static double diff[NPX];
    for (size_t i = 0; i < NPX; ++i) {
        float a = test[4 * i];
        if (!(a >= 0.0f && a <= 1.0f)) st.in_range = false;
        if (rgba && (fabsf(test[4 * i + 1] - a) > 1e-6f || fabsf(test[4 * i + 2] - a) > 1e-6f)) st.grey = false;
        diff[i] = isfinite(a) ? fabs((double)a - (double)ref[4 * i]) : INFINITY;
        st.mean += diff[i];
        st.max = fmax(st.max, diff[i]);
    }
    st.mean /= (double)NPX;
    qsort(diff, NPX, sizeof diff[0], cmp_double);
    st.p99 = diff[(size_t)(0.99 * (double)(NPX - 1))];
    return st;
}

/* Runs ob_host_ao into `out` and reads it (4 floats per pixel); false (with a failure) on an error. */
static bool host_ao(ob_renderer *r, const ob_host_frame *f, const ob_settings *s, const ob_host_outputs *o, float *px,
                    const char *what)
{
    ob_renderer_reset_history(r); /* the same frame index, so the same noise, for every call */
    ob_clear_error();
    ob_error rc = ob_host_ao(r, f, s, o);
    const char *msg = "";
    if (rc != OB_OK) ob_get_error(&msg);
    GLenum ge = glGetError();
    CHECK(rc == OB_OK, "%s: ob_host_ao returned %s: %s", what, ob_error_name(rc), msg);
    CHECK(ge == GL_NO_ERROR, "%s: GL error %s", what, gl_error_name(ge));
    if (rc != OB_OK) return false;
    glGetTextureImage(o->ao, 0, GL_RGBA, GL_FLOAT, (GLsizei)(4 * NPX * sizeof(float)), px);
    return true;
}

typedef struct tolerance {
    double mean, p99;
    const char *why;
} tolerance;

static void print_stats_header(const char *title)
{
    printf("\n%s\n%-64s %8s %8s %8s %9s %9s  %s\n", title, "case", "mean", "p99", "max", "tol mean", "tol p99", "why");
}

static void check_stats(const char *what, const ao_stats *st, tolerance tol, bool rgba)
{
    printf("%-64s %8.5f %8.5f %8.5f %9.4f %9.4f  %s\n", what, st->mean, st->p99, st->max, tol.mean, tol.p99, tol.why);
    CHECK(st->in_range, "%s: AO outside [0, 1] or not finite", what);
    if (rgba) CHECK(st->grey, "%s: an AO method's RGBA output is grey (R = G = B)", what);
    CHECK(st->mean <= tol.mean, "%s: mean |AO - reference| %.5f above %.4f (%s)", what, st->mean, tol.mean, tol.why);
    CHECK(st->p99 <= tol.p99, "%s: 99th percentile |AO - reference| %.5f above %.4f (%s)", what, st->p99, tol.p99, tol.why);
}

/* ---- typed settings and the input size (no texture involved) ------------------------------------- */
static void test_settings(void)
{
    printf("\nob_settings_from_host:\n");
    ob_settings s, before;
    memset(&s, 0x5a, sizeof s);
    before = s;
    static const struct { const char *what, *arg; ob_host_settings h; ob_error expect; } bad[] = {
        {"radius 0", "radius", {.method = "vbao"}, OB_ERR_INVALID_ARGUMENT},
        {"radius -1", "radius", {.method = "vbao", .radius = -1.0f}, OB_ERR_INVALID_ARGUMENT},
        {"radius NaN", "radius", {.method = "vbao", .radius = NAN}, OB_ERR_INVALID_ARGUMENT},
        {"radius infinite", "radius", {.method = "vbao", .radius = INFINITY}, OB_ERR_INVALID_ARGUMENT},
        {"intensity for vbao (it has none)", "intensity", {.method = "vbao", .radius = 1.0f, .intensity = 2.0f},
         OB_ERR_INVALID_ARGUMENT},
        {"falloff for ssao (it has none)", "falloff", {.method = "ssao", .radius = 1.0f, .falloff = 0.5f},
         OB_ERR_INVALID_ARGUMENT},
        {"unknown method \"ssao2\"", "ssao2", {.method = "ssao2", .radius = 1.0f}, OB_ERR_UNKNOWN_METHOD},
        {"unknown filter \"median\"", "median", {.method = "vbao", .radius = 1.0f, .filter = "median"}, OB_ERR_UNKNOWN_METHOD},
        {"ao_divisor 3", "ao_divisor", {.method = "vbao", .radius = 1.0f, .ao_divisor = 3}, OB_ERR_OUT_OF_RANGE},
        {"quality 9", "quality", {.method = "vbao", .radius = 1.0f, .quality = (ob_quality)9}, OB_ERR_OUT_OF_RANGE},
        {"guard -4", "guard", {.method = "vbao", .radius = 1.0f, .guard = -4}, OB_ERR_OUT_OF_RANGE},
        {"temporal_frames 100000", "temporal_frames", {.method = "vbao", .radius = 1.0f, .temporal_frames = 100000},
         OB_ERR_OUT_OF_RANGE},
        {"intensity NaN for ssao", "intensity", {.method = "ssao", .radius = 1.0f, .intensity = NAN}, OB_ERR_INVALID_ARGUMENT},
    };
    table_header("ob_settings_from_host, wrong fields (settings must stay unchanged):");
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ob_clear_error();
        ob_error rc = ob_settings_from_host(&s, &bad[i].h);
        const char *msg = "";
        if (rc != OB_OK) ob_get_error(&msg);
        char what[96];
        snprintf(what, sizeof what, "ob_settings_from_host(%s)", bad[i].what);
        /* OUT_OF_RANGE is what obscura.h lists for ranges; INVALID_ARGUMENT is accepted there too. */
        ob_error expect = bad[i].expect == OB_ERR_OUT_OF_RANGE && rc == OB_ERR_INVALID_ARGUMENT ? rc : bad[i].expect;
        refused(what, bad[i].arg, NULL, NULL, expect, rc, msg, 0, NULL, 0);
        CHECK(!memcmp(&s, &before, sizeof s), "%s: settings changed by a refused call", what);
    }
    ob_clear_error();
    ob_error rc = ob_settings_from_host(NULL, &(ob_host_settings){.radius = 1.0f});
    const char *msg = "";
    if (rc != OB_OK) ob_get_error(&msg);
    refused("ob_settings_from_host(NULL settings)", "settings", NULL, NULL, OB_ERR_INVALID_ARGUMENT, rc, msg, 0, NULL, 0);
    ob_clear_error();
    rc = ob_settings_from_host(&s, NULL);
    if (rc != OB_OK) ob_get_error(&msg);
    refused("ob_settings_from_host(NULL host settings)", "host", NULL, NULL, OB_ERR_INVALID_ARGUMENT, rc, msg, 0, NULL, 0);

    /* What the typed fields become. */
    CHECK(ob_settings_from_host(&s, &(ob_host_settings){.radius = 0.25f}) == OB_OK, "defaults with a radius");
    CHECK(!strcmp(ob_method_at(s.method)->name, OB_DEFAULT_METHOD), "method NULL = %s", OB_DEFAULT_METHOD);
    CHECK(!strcmp(ob_filter_at(s.filter)->name, "crease"), "filter NULL = crease, got %s", ob_filter_at(s.filter)->name);
    CHECK_NEAR(ob_settings_get(&s, "radius"), 0.25, 1e-7, "radius taken as set");
    CHECK(ob_settings_from_host(&s, &(ob_host_settings){.method = "ssao", .radius = 2.0f, .quality = OB_QUALITY_HIGH,
                                                        .intensity = 1.5f, .ao_divisor = 2, .filter = "none",
                                                        .temporal = true, .temporal_frames = 8, .guard = 16}) == OB_OK,
          "ssao, every field");
    CHECK_NEAR(ob_settings_get(&s, "samples"), ob_quality_samples("high"), 0, "quality high = its samples");
    CHECK_NEAR(ob_settings_get(&s, "intensity"), 1.5, 1e-7, "ssao intensity");
    CHECK(s.ao_divisor == 2 && s.temporal && s.temporal_frames == 8 && s.guard == 16 &&
              !strcmp(ob_filter_at(s.filter)->name, "none"),
          "divisor, temporal, frames, guard, filter");
    CHECK(ob_settings_from_host(&s, &(ob_host_settings){.method = "gtao", .radius = 1.0f, .falloff = 0.3f,
                                                        .thickness = 0.2f}) == OB_OK,
          "gtao falloff, thickness");
    CHECK_NEAR(ob_settings_get(&s, "falloff"), 0.3, 1e-7, "gtao falloff");
    CHECK_NEAR(ob_settings_get(&s, "thickness"), 0.2, 1e-7, "gtao thickness (x R)");
    for (int m = 0; m < ob_method_count(); ++m) {
        const char *name = ob_method_at(m)->name;
        ob_clear_error();
        rc = ob_settings_from_host(&s, &(ob_host_settings){.method = name, .radius = 1.0f});
        msg = "";
        if (rc != OB_OK) ob_get_error(&msg);
        bool has_radius = !isnan(ob_settings_get(&(ob_settings){.method = m}, "radius"));
        printf("  ob_settings_from_host(%s, radius 1): %s%s%s\n", name, ob_error_name(rc), rc ? ": " : "", msg);
        if (has_radius) CHECK(rc == OB_OK && ob_settings_get(&s, "radius") == 1.0f, "%s takes radius 1: %s", name, msg);
    }

}

static void test_input_size(ob_renderer *r)
{
    static const struct { int guard, divisor, want; } cases[] = {
        {0, 1, 0}, {1, 1, 4}, {10, 1, 12}, {10, 2, 16}, {10, 4, 16}, {16, 4, 16}, {17, 4, 32}, {8, 2, 8}};
    printf("\nob_host_input_size of a %dx%d renderer:\n", W, H);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ob_settings s;
        ob_settings_init(&s, "vbao");
        s.guard = cases[i].guard;
        ob_settings_set_ao_divisor(&s, cases[i].divisor);
        int w = -1, h = -1, g = -1;
        ob_host_input_size(r, &s, &w, &h, &g);
        printf("  guard %2d, ao_divisor %d: %dx%d, %d px per side\n", cases[i].guard, cases[i].divisor, w, h, g);
        CHECK(g == cases[i].want && w == W + 2 * g && h == H + 2 * g, "guard %d at 1/%d: %dx%d, band %d (want %d)",
              cases[i].guard, cases[i].divisor, w, h, g, cases[i].want);
    }
    ob_settings s;
    ob_settings_init(&s, "vbao");
    ob_host_input_size(r, &s, NULL, NULL, NULL); /* every pointer may be NULL */
}

/* ---- the wrong inputs ----------------------------------------------------------------------------- */
static void test_wrong_inputs(ob_renderer *r, GLuint lin32, GLuint nrm32)
{
    ob_settings s, gi;
    ob_settings_from_host(&s, &(ob_host_settings){.method = "vbao", .radius = 1.0f});
    ob_settings_from_host(&gi, &(ob_host_settings){.method = "vbgi", .radius = 1.0f});
    const ob_host_frame good = frame_of(lin32, nrm32, OB_NORMALS_VIEW, V.proj, false);
    GLuint ao = make_tex(GL_R32F, W, H), rgba_ao = make_tex(GL_RGBA16F, W, H), indirect = make_tex(GL_RGBA16F, W, H);
    const ob_host_outputs out = {.ao = ao};
    GLuint rad = make_tex(GL_RGBA16F, W, H), alb = make_tex(GL_RGBA8, W, H);
    const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(rad, 0, GL_RGBA, GL_FLOAT, grey);
    glClearTexImage(alb, 0, GL_RGBA, GL_FLOAT, grey);
    ob_host_frame f;
    ob_host_outputs o;
    char what[128];

    table_header("ob_host_ao, wrong inputs (vbao unless said; the output filled with 0.25 first):");
    GLuint t;
#define WRONG_NORMAL(fmt, word)                                                  \
    t = make_tex(fmt, W, H), f = good, f.normal = t;                            \
    wrong("normal " #fmt, "normal", word, NULL, r, &f, &s, &out, ao);           \
    glDeleteTextures(1, &t)
    WRONG_NORMAL(GL_RGB8, "RGB8");
    WRONG_NORMAL(GL_R32F, "R32F");
    WRONG_NORMAL(GL_RGBA16UI, "RGBA16UI");
    WRONG_NORMAL(GL_SRGB8_ALPHA8, "SRGB8");
#define WRONG_DEPTH(fmt, word)                                                   \
    t = make_tex(fmt, W, H), f = good, f.depth = t;                             \
    wrong("depth " #fmt, "depth", word, NULL, r, &f, &s, &out, ao);             \
    glDeleteTextures(1, &t)
    WRONG_DEPTH(GL_R8, "R8");
    WRONG_DEPTH(GL_RGBA16F, "RGBA16F");
    WRONG_DEPTH(GL_RG32F, "RG32F");
    WRONG_DEPTH(GL_STENCIL_INDEX8, "STENCIL_INDEX8");
#define WRONG_AO(fmt, word)                                                      \
    t = make_tex(fmt, W, H), o = out, o.ao = t;                                 \
    wrong("ao " #fmt " (an AO method)", "ao", word, NULL, r, &good, &s, &o, t); \
    glDeleteTextures(1, &t)
    WRONG_AO(GL_RG8, "RG8");
    WRONG_AO(GL_R32I, "R32I");
    WRONG_AO(GL_RGB8, "RGB8");
    WRONG_AO(GL_DEPTH_COMPONENT32F, "DEPTH_COMPONENT32F");

    GLuint ms = 0;
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &ms);
    glTextureStorage2DMultisample(ms, 4, GL_DEPTH_COMPONENT32F, W, H, GL_TRUE);
    f = good, f.depth = ms, f.projection[10] = 0.0f, f.projection[14] = 0.1f, f.depth_zero_to_one = true;
    wrong("depth GL_TEXTURE_2D_MULTISAMPLE D32F", "depth", "MULTISAMPLE", NULL, r, &f, &s, &out, ao);
    GLuint arr = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &arr);
    glTextureStorage3D(arr, 1, GL_R32F, W, H, 2);
    f = good, f.depth = arr;
    wrong("depth a GL_TEXTURE_2D_ARRAY of R32F", "depth", "ARRAY", NULL, r, &f, &s, &out, ao);
    GLuint cube = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
    glTextureStorage2D(cube, 1, GL_RGBA16F, W, W);
    f = good, f.normal = cube;
    wrong("normal a GL_TEXTURE_CUBE_MAP of RGBA16F", "normal", "CUBE", NULL, r, &f, &s, &out, ao);
    f = good, f.depth = 12345;
    wrong("depth 12345 (no such texture)", "depth", "12345", NULL, r, &f, &s, &out, ao);
    GLuint gone = make_tex(GL_R32F, W, H);
    glDeleteTextures(1, &gone);
    f = good, f.normal = gone;
    snprintf(what, sizeof what, "normal %u (deleted)", gone);
    wrong(what, "normal", NULL, NULL, r, &f, &s, &out, ao);
    f = good, f.depth = 0;
    wrong("depth 0 (required)", "depth", NULL, NULL, r, &f, &s, &out, ao);
    o = out, o.ao = 0;
    wrong("ao 0 (required)", "ao", NULL, NULL, r, &good, &s, &o, 0);
    GLuint bare = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &bare);
    o = out, o.ao = bare;
    wrong("ao: a GL_TEXTURE_2D with no storage", "ao", NULL, NULL, r, &good, &s, &o, 0);
    GLuint half_n = make_tex(GL_RGBA16F, W / 2, H / 2), half_d = make_tex(GL_R32F, W / 2, H / 2),
           half_o = make_tex(GL_R32F, W / 2, H / 2);
    char big[16], small[16];
    snprintf(big, sizeof big, "%dx%d", W, H);
    snprintf(small, sizeof small, "%dx%d", W / 2, H / 2);
    f = good, f.normal = half_n;
    wrong("normal at half the input size", "normal", small, big, r, &f, &s, &out, ao);
    f = good, f.depth = half_d;
    wrong("depth at half the input size", "depth", small, big, r, &f, &s, &out, ao);
    o = out, o.ao = half_o;
    wrong("ao at half the renderer's size", "ao", small, big, r, &good, &s, &o, half_o);
    GLuint d32 = depth_texture(GL_DEPTH_COMPONENT32F, V.proj, false, false, depth_px, W, H);
    f = good, f.depth = d32, f.second_depth = lin32;
    wrong("second_depth R32F beside a D32F depth", "second_depth", "R32F", NULL, r, &f, &s, &out, ao);
    f = good, f.second_depth = half_d;
    wrong("second_depth at half size", "second_depth", small, NULL, r, &f, &s, &out, ao);

    /* The indirect-light methods. */
    f = good, f.radiance = 0, f.albedo = alb;
    o = (ob_host_outputs){.ao = rgba_ao, .indirect = indirect};
    wrong("vbgi without radiance", "radiance", NULL, NULL, r, &f, &gi, &o, rgba_ao);
    ob_settings ssdo;
    ob_settings_from_host(&ssdo, &(ob_host_settings){.method = "ssdo", .radius = 1.0f});
    wrong("ssdo without radiance", "radiance", NULL, NULL, r, &f, &ssdo, &o, rgba_ao);
    /* Without albedo: obscura.h says the indirect-light methods read radiance "and albedo", yet
     * says nothing of a missing one; either answer is taken here (printed for the record). */
    f.radiance = rad, f.albedo = 0;
    {
        ob_clear_error();
        ob_error rc = ob_host_ao(r, &f, &ssdo, &o);
        const char *msg = "";
        if (rc != OB_OK) ob_get_error(&msg);
        GLenum ge = glGetError();
        ++table_rows;
        printf("%-58s %-24s %-9s %s\n", "ssdo without albedo (either: obscura.h does not say)", ob_error_name(rc),
               gl_error_name(ge), rc == OB_OK ? "(accepted)" : msg);
        CHECK(rc == OB_OK || (rc == OB_ERR_INVALID_ARGUMENT && names_word(msg, "albedo")),
              "ssdo without albedo: accepted, or refused naming albedo: %s \"%s\"", ob_error_name(rc), msg);
        CHECK(ge == GL_NO_ERROR, "ssdo without albedo: GL error %s", gl_error_name(ge));
    }
    t = make_tex(GL_RGBA8, W, H);
    f = good, f.radiance = t, f.albedo = alb;
    wrong("radiance GL_RGBA8 (not linear HDR)", "radiance", "RGBA8", NULL, r, &f, &gi, &o, rgba_ao);
    glDeleteTextures(1, &t);
    t = make_tex(GL_R32F, W, H);
    f = good, f.radiance = rad, f.albedo = t;
    wrong("albedo GL_R32F", "albedo", "R32F", NULL, r, &f, &gi, &o, rgba_ao);
    glDeleteTextures(1, &t);
    f = good, f.radiance = half_n, f.albedo = alb;
    wrong("radiance at half size", "radiance", small, NULL, r, &f, &gi, &o, rgba_ao);
    t = make_tex(GL_R8, W, H);
    f = good, f.radiance = rad, f.albedo = alb;
    o = (ob_host_outputs){.ao = rgba_ao, .indirect = t};
    wrong("indirect GL_R8", "indirect", "R8", NULL, r, &f, &gi, &o, rgba_ao);
    o = (ob_host_outputs){.ao = ao, .bent_normal = t};
    ob_settings bent;
    ob_settings_from_host(&bent, &(ob_host_settings){.method = "gtao", .radius = 1.0f});
    ob_settings_set(&bent, "bent_normals=on");
    wrong("bent_normal GL_R8", "bent_normal", "R8", NULL, r, &good, &bent, &o, ao);
    glDeleteTextures(1, &t);
    t = make_tex(GL_RGBA8, W, H);
    f = good, f.motion = t;
    wrong("motion GL_RGBA8", "motion", "RGBA8", NULL, r, &f, &s, &out, ao);
    glDeleteTextures(1, &t);
    f = good, f.motion = half_n;
    wrong("motion at half size (RGBA16F)", "motion", NULL, NULL, r, &f, &s, &out, ao);

    /* The projection and the other numbers. */
    f = good;
    memset(f.projection, 0, sizeof f.projection);
    f.projection[0] = 2.0f / 8.0f, f.projection[5] = 2.0f / 6.0f, f.projection[10] = -2.0f / 99.9f;
    f.projection[14] = -100.1f / 99.9f, f.projection[15] = 1.0f;
    /* Orthographic projections are taken (test_host_ortho grades them); one whose z row cannot be
     * linearised (P22 = 0) is not. */
    f.projection[10] = 0.0f;
    wrong("an orthographic projection with P22 = 0", "projection", "orthographic", NULL, r, &f, &s, &out, ao);
    f = good, f.projection[5] = NAN;
    wrong("a NaN in the projection", "projection", NULL, NULL, r, &f, &s, &out, ao);
    f = good, f.projection[10] = INFINITY;
    wrong("an infinity in the projection", "projection", NULL, NULL, r, &f, &s, &out, ao);
    f = good, memset(f.projection, 0, sizeof f.projection);
    wrong("a zero projection", "projection", NULL, NULL, r, &f, &s, &out, ao);
    f = good, f.jitter[0] = NAN;
    wrong("a NaN jitter", "jitter", NULL, NULL, r, &f, &s, &out, ao);
    GLuint wn16 = normal_texture(GL_RGBA16F, wn_px, W, H);
    f = good, f.normal = wn16, f.normal_space = OB_NORMALS_WORLD;
    for (int i = 0; i < 16; ++i) f.view[i] = NAN;
    wrong("world normals with a NaN view matrix", "view", NULL, NULL, r, &f, &s, &out, ao);
    f = good, f.normal_space = (ob_normal_space)7;
    wrong("normal_space 7", "normal_space", NULL, NULL, r, &f, &s, &out, ao);
    wrong("NULL frame", "frame", NULL, NULL, r, NULL, &s, &out, ao);
    wrong("NULL settings", "settings", NULL, NULL, r, &good, NULL, &out, ao);
    wrong("NULL outputs", "outputs", NULL, NULL, r, &good, &s, NULL, ao);
    wrong("NULL renderer", NULL, NULL, NULL, NULL, &good, &s, &out, ao);
    ob_settings broken = s;
    broken.method = 99;
    wrong("settings.method 99", "settings|method", NULL, NULL, r, &good, &broken, &out, ao);

    /* A guard band: the inputs at ob_host_input_size, the output at the renderer's size. */
    ob_settings guarded = s;
    guarded.guard = 8;
    int gw = 0, gh = 0, g = 0;
    ob_host_input_size(r, &guarded, &gw, &gh, &g);
    GLuint gd = make_tex(GL_R32F, gw, gh), gn = make_tex(GL_RGBA16F, gw, gh), go = make_tex(GL_R32F, gw, gh);
    snprintf(big, sizeof big, "%dx%d", gw, gh);
    f = good, f.depth = gd;
    wrong("guard 8: depth at the visible size, normal at the input size", "normal|depth", NULL, NULL, r, &f, &guarded,
          &out, ao);
    f = good, f.depth = gd, f.normal = gn;
    o = out, o.ao = go;
    wrong("guard 8: ao at the input size (the output is cropped)", "ao", big, NULL, r, &f, &guarded, &o, go);
    f = good;
    wrong("guard 8: depth and normal at the visible size", "depth|normal", big, NULL, r, &f, &guarded, &out, ao);
    glDeleteTextures(1, &gd), glDeleteTextures(1, &gn), glDeleteTextures(1, &go);

    /* ssdo's extra view needs a second camera of the scene: a host has none. */
    ob_settings extra = ssdo;
    if (ob_settings_set(&extra, "extra_view=on") == OB_OK) {
        f = good, f.radiance = rad, f.albedo = alb;
        o = (ob_host_outputs){.ao = rgba_ao};
        wrong("ssdo extra_view=on (no scene to render a second camera)", "extra_view", NULL, NULL, r, &f, &extra, &o,
              rgba_ao);
    }
    GLuint dels[] = {ao, rgba_ao, indirect, rad, alb, ms, arr, cube, bare, half_n, half_d, half_o, d32, wn16};
    glDeleteTextures((GLsizei)(sizeof dels / sizeof dels[0]), dels);
}

/* ---- the old entry points: validated now too ------------------------------------------------------ */
static void test_old_entry_points(ob_renderer *r, GLuint lin32, GLuint nrm16)
{
    ob_settings s;
    ob_settings_init(&s, "vbao");
    ob_settings_set(&s, "radius=1");
    ob_settings_set_filter(&s, "crease");
    GLuint out = make_tex(GL_R32F, W, H);
    static float ref[4 * NPX], px[4 * NPX];
    ob_renderer_reset_history(r);
    ob_error rc = ob_compute_ao_filtered(r, lin32, nrm16, V.proj, &s, out);
    CHECK(rc == OB_OK, "ob_compute_ao_filtered on R32F + RGBA16F -> R32F as before");
    glGetTextureImage(out, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof ref, ref);

    size_t n = NPX;
    GLuint rgba8_n = normal_texture(GL_RGBA8, vn_px, W, H), rgb8_n = make_tex(GL_RGB8, W, H);
    GLuint half_n = make_tex(GL_RGBA16F, W / 2, H / 2), half_d = make_tex(GL_R32F, W / 2, H / 2);
    GLuint half_o = make_tex(GL_R32F, W / 2, H / 2), out_rgba8 = make_tex(GL_RGBA8, W, H), out_r16f = make_tex(GL_R16F, W, H);
    GLuint d32 = depth_texture(GL_DEPTH_COMPONENT32F, V.proj, false, false, depth_px, W, H);
    (void)n;
    static const struct { const char *what, *arg; int which; bool either; double tol; } cases[] = {
        /* vbao's default joining (connect=ends) reads every step's normal: 8-bit rounding (0.4 deg)
         * moves a sector here and there (worst 0.046, mean 0.0023 on llvmpipe). */
        {"normal GL_RGBA8 (n*0.5+0.5)", "normal|normal_tex", 0, true, 0.05},
        {"ao output GL_RGBA8", "ao|ao_out|ao_out_tex|output", 1, true, 1.0 / 255.0 + 1e-6},
        {"ao output GL_R16F", "ao|ao_out|ao_out_tex|output", 2, true, 1e-3},
        {"depth GL_DEPTH_COMPONENT32F (through proj, [-1,1])", "depth|linear_depth|linear_depth_tex", 3, true, 0.01},
        {"normal at half size", "normal|normal_tex", 4, false, 0},
        {"ao output at half size", "ao|ao_out|ao_out_tex|output", 5, false, 0},
        {"depth at half size", "depth|linear_depth|linear_depth_tex", 6, false, 0},
        {"normal GL_RGB8", "normal|normal_tex", 7, false, 0},
        {"depth 12345 (no such texture)", "depth|linear_depth|linear_depth_tex", 8, false, 0},
        {"depth 0", "depth|linear_depth|linear_depth_tex", 9, false, 0},
    };
    table_header("ob_compute_ao_filtered (the old entry point), wrong inputs (\"either\": refused, or right AO):");
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        GLuint depth = lin32, normal = nrm16, o = out;
        switch (cases[c].which) {
        case 0: normal = rgba8_n; break;
        case 1: o = out_rgba8; break;
        case 2: o = out_r16f; break;
        case 3: depth = d32; break;
        case 4: normal = half_n; break;
        case 5: o = half_o; break;
        case 6: depth = half_d; break;
        case 7: normal = rgb8_n; break;
        case 8: depth = 12345; break;
        case 9: depth = 0; break;
        }
        fill_sentinel(o);
        size_t count = 0;
        float *before = read_texture(o, &count);
        while (glGetError() != GL_NO_ERROR) {}
        ob_clear_error();
        ob_renderer_reset_history(r);
        rc = ob_compute_ao_filtered(r, depth, normal, V.proj, &s, o);
        const char *msg = "";
        if (rc != OB_OK) ob_get_error(&msg);
        char what[128];
        snprintf(what, sizeof what, "old: %s%s", cases[c].what, cases[c].either ? " (either)" : "");
        if (cases[c].either && rc == OB_OK) {
            GLenum ge = glGetError();
            glGetTextureImage(o, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof px, px);
            ao_stats st = compare_ao(px, ref, false);
            ++table_rows;
            printf("%-58s %-24s %-9s accepted: mean |AO - R32F/RGBA16F's| %.5f, worst %.5f (tol %.4g)\n", what,
                   ob_error_name(rc), gl_error_name(ge), st.mean, st.max, cases[c].tol);
            CHECK(ge == GL_NO_ERROR, "%s: GL error %s", what, gl_error_name(ge));
            CHECK(st.in_range && st.max <= cases[c].tol, "%s: accepted but the AO is not right: worst |diff| %.4f", what,
                  st.max);
        } else {
            refused(what, cases[c].arg, cases[c].which >= 4 && cases[c].which <= 6 ? "x" : NULL, NULL,
                    OB_ERR_INVALID_ARGUMENT, rc, msg, o, before, count);
        }
        free(before);
    }
    GLuint dels[] = {out, rgba8_n, rgb8_n, half_n, half_d, half_o, out_rgba8, out_r16f, d32};
    glDeleteTextures((GLsizei)(sizeof dels / sizeof dels[0]), dels);
}

/* ---- every accepted input gives the AO of the same geometry ---------------------------------------- */
typedef struct depth_case {
    const char *what;
    GLenum format;
    bool reversed, zero_to_one;
    double near_z, far_z; /* far 0: infinite */
    tolerance tol;
} depth_case;

static void test_accepted(ob_renderer *r)
{
    static float ref[4 * NPX], px[4 * NPX], px2[4 * NPX];
    GLuint lin32 = upload(GL_R32F, W, H, GL_RED, depth_px), n32 = normal_texture(GL_RGBA32F, vn_px, W, H);
    GLuint out32 = make_tex(GL_R32F, W, H);
    static const char *const methods[] = {"vbao", "ssao", "gtao"};
    const tolerance exact = {1e-6, 1e-6, "the same numbers"};
    /* The storage's precision in linear depth at the scene's distances (3..12 units, R = 1) and in
     * normal angle; a few per cent of pixels sit where a sample's test flips (a 1/16 step for
     * ssao), so the 99th percentile allows one such step and the mean a fraction of it. */
    const tolerance f32 = {0.001, 0.01, "D32F: window depth to 2^-24 relative, < 1e-4 units after linearising"};
    const tolerance d24 = {0.001, 0.01, "24-bit unorm window depth: steps of 6e-8, about 1e-4 units at 10"};
    const tolerance d16 = {0.01, 0.05, "16-bit unorm window depth (near 0.5): steps of 1.5e-5, about 3e-3 units at 10"};
    const tolerance r16f = {0.01, 0.05, "half float linear depth: 2^-11 relative, about 5e-3 units at 10"};
    static const depth_case depths[] = {
        {"D32F standard [-1,1] near 0.1 far 100", GL_DEPTH_COMPONENT32F, false, false, 0.1, 100.0, {0}},
        {"D32F standard [0,1] near 0.1 far 100", GL_DEPTH_COMPONENT32F, false, true, 0.1, 100.0, {0}},
        {"D32F standard [-1,1] near 0.1 infinite", GL_DEPTH_COMPONENT32F, false, false, 0.1, 0.0, {0}},
        {"D32F reversed [0,1] near 0.1 far 100", GL_DEPTH_COMPONENT32F, true, true, 0.1, 100.0, {0}},
        {"D32F reversed [0,1] near 0.1 infinite", GL_DEPTH_COMPONENT32F, true, true, 0.1, 0.0, {0}},
        {"D32F reversed [-1,1] near 0.1 far 100", GL_DEPTH_COMPONENT32F, true, false, 0.1, 100.0, {0}},
        {"D24 standard [-1,1] near 0.1 far 100", GL_DEPTH_COMPONENT24, false, false, 0.1, 100.0, {0}},
        {"D24 reversed [0,1] near 0.1 infinite", GL_DEPTH_COMPONENT24, true, true, 0.1, 0.0, {0}},
        {"D16 standard [-1,1] near 0.5 far 50", GL_DEPTH_COMPONENT16, false, false, 0.5, 50.0, {0}},
        {"D16 reversed [0,1] near 0.5 far 50", GL_DEPTH_COMPONENT16, true, true, 0.5, 50.0, {0}},
        {"D24S8 reversed [0,1] near 0.1 far 100", GL_DEPTH24_STENCIL8, true, true, 0.1, 100.0, {0}},
        {"D24S8 standard [-1,1] near 0.1 infinite", GL_DEPTH24_STENCIL8, false, false, 0.1, 0.0, {0}},
        {"D32F_S8 reversed [0,1] near 0.1 infinite", GL_DEPTH32F_STENCIL8, true, true, 0.1, 0.0, {0}},
        {"D32F_S8 standard [0,1] near 0.1 far 100", GL_DEPTH32F_STENCIL8, false, true, 0.1, 100.0, {0}},
    };
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; ++m) {
        ob_settings s;
        CHECK(ob_settings_from_host(&s, &(ob_host_settings){.method = methods[m], .radius = 1.0f, .filter = "none"}) ==
                  OB_OK,
              "%s settings", methods[m]);
        ob_host_frame f = frame_of(lin32, n32, OB_NORMALS_VIEW, V.proj, false);
        const ob_host_outputs o32 = {.ao = out32};
        char title[160], what[160];
        snprintf(title, sizeof title,
                 "%s (filter none), %dx%d: |AO - AO of R32F linear depth + RGBA32F view normals| over all pixels",
                 methods[m], W, H);
        print_stats_header(title);
        if (!host_ao(r, &f, &s, &o32, ref, "reference")) continue;
        double mean_ref = 0.0;
        for (size_t i = 0; i < NPX; ++i) mean_ref += ref[4 * i];
        printf("%-64s mean AO %.4f\n", "reference: R32F + RGBA32F view -> R32F", mean_ref / (double)NPX);
        CHECK(mean_ref / (double)NPX < 0.99 && mean_ref / (double)NPX > 0.3, "%s: the reference has AO in it", methods[m]);
        ao_stats st;
        /* Depth: every hardware format and convention, and R16F. */
        for (size_t d = 0; d < sizeof depths / sizeof depths[0]; ++d) {
            const depth_case *c = &depths[d];
            float proj[16];
            perspective(proj, fov_y, (float)W / (float)H, c->near_z, c->far_z, c->reversed, c->zero_to_one);
            GLuint t = depth_texture(c->format, proj, c->zero_to_one, c->reversed, depth_px, W, H);
            GLenum ge = glGetError();
            CHECK(ge == GL_NO_ERROR, "uploading %s: %s", c->what, gl_error_name(ge));
            f = frame_of(t, n32, OB_NORMALS_VIEW, proj, c->zero_to_one);
            if (host_ao(r, &f, &s, &o32, px, c->what)) {
                st = compare_ao(px, ref, false);
                tolerance tol = c->format == GL_DEPTH_COMPONENT16 ? d16
                                : c->format == GL_DEPTH_COMPONENT24 || c->format == GL_DEPTH24_STENCIL8 ? d24 : f32;
                snprintf(what, sizeof what, "depth %s", c->what);
                check_stats(what, &st, tol, false);
            }
            glDeleteTextures(1, &t);
        }
        GLuint t = upload(GL_R16F, W, H, GL_RED, depth_px);
        f = frame_of(t, n32, OB_NORMALS_VIEW, V.proj, false);
        if (host_ao(r, &f, &s, &o32, px, "R16F")) {
            st = compare_ao(px, ref, false);
            check_stats("depth R16F linear", &st, r16f, false);
        }
        glDeleteTextures(1, &t);

        /* Normals: every encoding, view and world space (depth R32F). */
        static const struct { GLenum format; const char *name; bool world; tolerance tol; } normals[] = {
            {GL_RGBA16F, "RGBA16F view", false, {0.001, 0.01, "half float xyz: 2^-11, 0.03 degrees"}},
            {GL_RGBA16F, "RGBA16F world", true, {0.001, 0.01, "half float xyz through the view matrix"}},
            {GL_RGBA32F, "RGBA32F world", true, {0.001, 0.01, "float xyz through the view matrix: rounding only"}},
            {GL_RGB10_A2, "RGB10_A2 view", false, {0.004, 0.02, "10-bit unorm n*0.5+0.5: 0.11 degrees"}},
            {GL_RGB10_A2, "RGB10_A2 world", true, {0.004, 0.02, "10-bit unorm n*0.5+0.5: 0.11 degrees"}},
            {GL_RGBA8, "RGBA8 view", false, {0.008, 0.05, "8-bit unorm n*0.5+0.5: 0.45 degrees, not unit"}},
            {GL_RGBA8, "RGBA8 world", true, {0.008, 0.05, "8-bit unorm n*0.5+0.5: 0.45 degrees, not unit"}},
            {GL_RG16F, "RG16F octahedral view", false, {0.001, 0.01, "half float octahedral: 0.05 degrees"}},
            {GL_RG16F, "RG16F octahedral world", true, {0.001, 0.01, "half float octahedral: 0.05 degrees"}},
            {GL_RG16_SNORM, "RG16_SNORM octahedral view", false, {0.001, 0.01, "16-bit snorm octahedral: 0.005 degrees"}},
            {GL_RG16_SNORM, "RG16_SNORM octahedral world", true, {0.001, 0.01, "16-bit snorm octahedral"}},
            {GL_RG8, "RG8 octahedral view", false, {0.008, 0.05, "8-bit unorm octahedral: about 1 degree"}},
            {GL_RG8, "RG8 octahedral world", true, {0.008, 0.05, "8-bit unorm octahedral: about 1 degree"}},
        };
        for (size_t k = 0; k < sizeof normals / sizeof normals[0]; ++k) {
            t = normal_texture(normals[k].format, normals[k].world ? wn_px : vn_px, W, H);
            f = frame_of(lin32, t, normals[k].world ? OB_NORMALS_WORLD : OB_NORMALS_VIEW, V.proj, false);
            snprintf(what, sizeof what, "normal %s", normals[k].name);
            if (host_ao(r, &f, &s, &o32, px, what)) {
                st = compare_ao(px, ref, false);
                check_stats(what, &st, normals[k].tol, false);
            }
            glDeleteTextures(1, &t);
        }
        f = frame_of(lin32, 0, OB_NORMALS_VIEW, V.proj, false);
        if (host_ao(r, &f, &s, &o32, px, "no normals")) {
            st = compare_ao(px, ref, false);
            check_stats("normal none (reconstructed from depth)", &st,
                        (tolerance){0.01, 0.15, "flat-shaded: wrong within a pixel of every depth edge"}, false);
        }

        /* Outputs: every accepted format, the same AO in its precision (grey for RGBA). An 8-bit
         * unorm store may take either of the two nearest codes (the GL specification's float to
         * normalized fixed-point conversion "should" round to nearest): a whole step, not half (an
         * NVIDIA H200 wrote values 0.0022 off, over half a step). */
        static const struct { GLenum format; const char *name; bool rgba; double max; } outs[] = {
            {GL_R8, "R8", false, 1.0 / 255.0 + 1e-6}, {GL_R16F, "R16F", false, 4.9e-4},
            {GL_RGBA8, "RGBA8", true, 1.0 / 255.0 + 1e-6}, {GL_RGBA16F, "RGBA16F", true, 4.9e-4},
            {GL_RGBA32F, "RGBA32F", true, 1e-6}};
        f = frame_of(lin32, n32, OB_NORMALS_VIEW, V.proj, false);
        for (size_t k = 0; k < sizeof outs / sizeof outs[0]; ++k) {
            t = make_tex(outs[k].format, W, H);
            fill_sentinel(t);
            snprintf(what, sizeof what, "output %s", outs[k].name);
            if (host_ao(r, &f, &s, &(ob_host_outputs){.ao = t}, px, what)) {
                st = compare_ao(px, ref, outs[k].rgba);
                check_stats(what, &st, (tolerance){outs[k].max, outs[k].max, "the format's rounding of [0, 1]"}, outs[k].rgba);
                CHECK(st.max <= outs[k].max, "%s: worst |AO - R32F's| %.6f above the format's rounding %.6f", what, st.max,
                      outs[k].max);
            }
            glDeleteTextures(1, &t);
        }
        (void)exact;
    }

    /* A TAA host: reversed-Z infinite D32F and octahedral world normals rasterised with a jittered
     * projection; the frame says the projection before the jitter and the jitter. Reference: R32F +
     * RGBA32F view normals of the jittered raster, with the jittered projection and no jitter. */
    {
        const float jitter[2] = {0.37f, -0.21f};
        float jittered[16];
        memcpy(jittered, V.proj, sizeof jittered);
        jittered[8] += 2.0f * jitter[0] / (float)W, jittered[9] += 2.0f * jitter[1] / (float)H;
        host_view jv;
        make_view(&jv, W, H, jittered, cam_eye, cam_target);
        static float jd[NPX], jvn[4 * NPX], jwn[4 * NPX];
        raycast(&jv, jd, jvn, jwn);
        float rz[16];
        perspective(rz, fov_y, (float)W / (float)H, 0.1, 0.0, true, true);
        rz[8] = jittered[8], rz[9] = jittered[9];
        GLuint jl = upload(GL_R32F, W, H, GL_RED, jd), jn = normal_texture(GL_RGBA32F, jvn, W, H);
        GLuint hd = depth_texture(GL_DEPTH_COMPONENT32F, rz, true, true, jd, W, H);
        GLuint on = normal_texture(GL_RG16F, jwn, W, H);
        for (int filtered = 0; filtered < 2; ++filtered) {
            ob_settings s;
            ob_settings_from_host(&s, &(ob_host_settings){.method = "vbao", .radius = 1.0f,
                                                          .filter = filtered ? "crease" : "none"});
            ob_host_frame f = frame_of(jl, jn, OB_NORMALS_VIEW, jittered, false);
            char what[160];
            snprintf(what, sizeof what, "TAA host: D32F reversed inf + RG16F oct world + jitter (%.2f, %.2f), %s", jitter[0],
                     jitter[1], filtered ? "crease" : "none");
            if (!filtered) print_stats_header("A TAA host's frame against the same raster as R32F + RGBA32F:");
            if (!host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32}, ref, "jittered reference")) continue;
            f = frame_of(hd, on, OB_NORMALS_WORLD, rz, true);
            f.projection[8] = V.proj[8], f.projection[9] = V.proj[9];
            f.jitter[0] = jitter[0], f.jitter[1] = jitter[1];
            if (host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32}, px, what)) {
                ao_stats st = compare_ao(px, ref, false);
                check_stats(what, &st, (tolerance){0.002, 0.02, "D32F + half float octahedral; jitter added by the library"}, false);
            }
            /* The same without saying the jitter: the AO must differ (the jitter is used). */
            f.jitter[0] = f.jitter[1] = 0.0f;
            if (!filtered && host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32}, px2, "jitter left out")) {
                ao_stats st = compare_ao(px2, ref, false);
                printf("%-64s %8.5f %8.5f %8.5f  (must be worse than with the jitter said)\n", "  the same, jitter not said",
                       st.mean, st.p99, st.max);
                ao_stats with = compare_ao(px, ref, false);
                CHECK(st.mean > with.mean, "the jitter changes the AO (%.5f without, %.5f with)", st.mean, with.mean);
            }
        }
        GLuint dels[] = {jl, jn, hd, on};
        glDeleteTextures(4, dels);
    }

    /* A directional method's mean of M into one channel, and the indirect light in R11F_G11F_B10F. */
    {
        ob_settings s;
        ob_settings_from_host(&s, &(ob_host_settings){.method = "ssdo", .radius = 1.0f, .filter = "none"});
        GLuint rad = make_tex(GL_RGBA16F, W, H), alb = make_tex(GL_RGBA8, W, H);
        static float lit[4 * NPX];
        for (size_t i = 0; i < NPX; ++i) {
            float l = depth_px[i] > 0.0f ? fmaxf(0.0f, 0.3f * wn_px[4 * i] + 0.9f * wn_px[4 * i + 1] + 0.3f * wn_px[4 * i + 2]) : 0.0f;
            lit[4 * i] = 2.0f * l, lit[4 * i + 1] = 1.5f * l, lit[4 * i + 2] = l, lit[4 * i + 3] = 1.0f;
        }
        glTextureSubImage2D(rad, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, lit);
        const float a[4] = {0.8f, 0.6f, 0.4f, 1.0f};
        glClearTexImage(alb, 0, GL_RGBA, GL_FLOAT, a);
        ob_host_frame f = frame_of(lin32, n32, OB_NORMALS_VIEW, V.proj, false);
        f.radiance = rad, f.albedo = alb;
        GLuint rgba = make_tex(GL_RGBA32F, W, H), r16 = make_tex(GL_R16F, W, H), ind16 = make_tex(GL_RGBA16F, W, H),
               ind11 = make_tex(GL_R11F_G11F_B10F, W, H);
        print_stats_header("Directional methods (ssdo) and the indirect output:");
        if (host_ao(r, &f, &s, &(ob_host_outputs){.ao = rgba, .indirect = ind16}, ref, "ssdo RGBA32F") &&
            host_ao(r, &f, &s, &(ob_host_outputs){.ao = r16, .indirect = ind11}, px, "ssdo R16F")) {
            static float mean_m[4 * NPX];
            for (size_t i = 0; i < NPX; ++i) mean_m[4 * i] = (ref[4 * i] + ref[4 * i + 1] + ref[4 * i + 2]) / 3.0f;
            ao_stats st = compare_ao(px, mean_m, false);
            check_stats("ssdo into R16F = the mean of its M (RGBA32F)", &st, (tolerance){1e-3, 1e-3, "half float"}, false);
            static float i16[4 * NPX], i11[4 * NPX];
            glGetTextureImage(ind16, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof i16, i16);
            glGetTextureImage(ind11, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof i11, i11);
            double worst = 0.0, peak = 0.0;
            for (size_t i = 0; i < NPX; ++i)
                for (int k = 0; k < 3; ++k) {
                    peak = fmax(peak, i16[4 * i + k]);
                    worst = fmax(worst, fabs((double)i16[4 * i + k] - i11[4 * i + k]) / fmax(1e-3, fabs(i16[4 * i + k])));
                }
            printf("%-64s worst relative %.4f (tol 0.035: 6 / 5 mantissa bits), peak %.3f\n",
                   "ssdo indirect R11F_G11F_B10F vs RGBA16F", worst, peak);
            CHECK(peak > 0.0, "ssdo writes an indirect light");
            CHECK(worst <= 0.035, "indirect in R11F_G11F_B10F = RGBA16F's within its precision (worst %.4f)", worst);
        }
        GLuint dels[] = {rad, alb, rgba, r16, ind16, ind11};
        glDeleteTextures(6, dels);
    }

    /* Bent normals come back in the space of the input normals (unit length on geometry). */
    {
        ob_settings s;
        ob_settings_from_host(&s, &(ob_host_settings){.method = "gtao", .radius = 1.0f, .filter = "none"});
        ob_settings_set(&s, "bent_normals=on");
        GLuint bent = make_tex(GL_RGBA16F, W, H), wn = normal_texture(GL_RGBA16F, wn_px, W, H);
        static float b[4 * NPX];
        for (int world = 0; world < 2; ++world) {
            ob_host_frame f = frame_of(lin32, world ? wn : n32, world ? OB_NORMALS_WORLD : OB_NORMALS_VIEW, V.proj, false);
            if (!host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32, .bent_normal = bent}, px, "bent normals")) continue;
            glGetTextureImage(bent, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof b, b);
            const float *n4 = world ? wn_px : vn_px;
            int geo = 0, unit = 0, facing = 0;
            for (size_t i = 0; i < NPX; ++i) {
                if (depth_px[i] <= 0.0f) continue;
                ++geo;
                float l = sqrtf(b[4 * i] * b[4 * i] + b[4 * i + 1] * b[4 * i + 1] + b[4 * i + 2] * b[4 * i + 2]);
                unit += fabsf(l - 1.0f) < 0.02f;
                facing += b[4 * i] * n4[4 * i] + b[4 * i + 1] * n4[4 * i + 1] + b[4 * i + 2] * n4[4 * i + 2] > 0.3f * l;
            }
            printf("gtao bent normals, %s normals in: %d of %d geometry px unit length, %d within 73 degrees of the normal\n",
                   world ? "world" : "view", unit, geo, facing);
            CHECK(unit >= geo * 99 / 100, "bent normals (%s) unit length: %d of %d", world ? "world" : "view", unit, geo);
            CHECK(facing >= geo * 95 / 100, "bent normals in the input normals' %s space: %d of %d near the normal",
                  world ? "world" : "view", facing, geo);
        }
        glDeleteTextures(1, &bent), glDeleteTextures(1, &wn);
    }

    /* The host's own texture state: one-level mutable textures with GL's default min filter
     * (GL_NEAREST_MIPMAP_LINEAR: incomplete as sampled by their own state), a depth texture with
     * compare mode on, and a depth-stencil texture set to read its stencil. obscura.h does not say;
     * the call must either refuse naming the texture or give the right AO, never wrong AO. */
    {
        ob_settings s;
        ob_settings_from_host(&s, &(ob_host_settings){.method = "vbao", .radius = 1.0f, .filter = "crease"});
        ob_host_frame f = frame_of(lin32, n32, OB_NORMALS_VIEW, V.proj, false);
        if (!host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32}, ref, "crease reference")) return;
        GLuint mut_d = 0, mut_n = 0;
        glGenTextures(1, &mut_d);
        glBindTexture(GL_TEXTURE_2D, mut_d);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, W, H, 0, GL_RED, GL_FLOAT, depth_px);
        glGenTextures(1, &mut_n);
        glBindTexture(GL_TEXTURE_2D, mut_n);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, W, H, 0, GL_RGBA, GL_FLOAT, vn_px);
        glBindTexture(GL_TEXTURE_2D, 0);
        float rz[16];
        perspective(rz, fov_y, (float)W / (float)H, 0.1, 0.0, true, true);
        GLuint cmp = depth_texture(GL_DEPTH_COMPONENT32F, rz, true, true, depth_px, W, H);
        glTextureParameteri(cmp, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(cmp, GL_TEXTURE_COMPARE_FUNC, GL_GREATER);
        GLuint sten = depth_texture(GL_DEPTH24_STENCIL8, rz, true, true, depth_px, W, H);
        glTextureParameteri(sten, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
        static const struct { const char *what, *arg; int which; } cases[] = {
            {"depth: mutable R32F, level 0 only, min filter NEAREST_MIPMAP_LINEAR", "depth", 0},
            {"normal: mutable RGBA32F, level 0 only, min filter NEAREST_MIPMAP_LINEAR", "normal", 1},
            {"depth: D32F with GL_TEXTURE_COMPARE_MODE = COMPARE_REF_TO_TEXTURE", "depth", 2},
            {"depth: D24S8 with GL_DEPTH_STENCIL_TEXTURE_MODE = GL_STENCIL_INDEX", "depth", 3}};
        printf("\nThe host's texture state (refused naming the texture, or the right AO):\n");
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
            f = frame_of(lin32, n32, OB_NORMALS_VIEW, V.proj, false);
            if (cases[c].which == 0) f.depth = mut_d;
            if (cases[c].which == 1) f.normal = mut_n;
            if (cases[c].which >= 2) f = frame_of(cases[c].which == 2 ? cmp : sten, n32, OB_NORMALS_VIEW, rz, true);
            fill_sentinel(out32);
            ob_renderer_reset_history(r);
            ob_clear_error();
            ob_error rc = ob_host_ao(r, &f, &s, &(ob_host_outputs){.ao = out32});
            const char *msg = "";
            if (rc != OB_OK) ob_get_error(&msg);
            GLenum ge = glGetError();
            if (rc == OB_OK) {
                glGetTextureImage(out32, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof px, px);
                ao_stats st = compare_ao(px, ref, false);
                printf("  %-74s handled: mean |AO - reference| %.5f, worst %.5f\n", cases[c].what, st.mean, st.max);
                CHECK(st.in_range && st.mean <= 0.001 && st.p99 <= 0.01,
                      "%s: accepted, so the AO must be right: mean %.5f, p99 %.5f", cases[c].what, st.mean, st.p99);
            } else {
                printf("  %-74s refused: %s \"%s\"\n", cases[c].what, ob_error_name(rc), msg);
                CHECK(rc == OB_ERR_INVALID_ARGUMENT && names_word(msg, cases[c].arg),
                      "%s: refused with %s naming \"%s\": \"%s\"", cases[c].what, ob_error_name(rc), cases[c].arg, msg);
            }
            CHECK(ge == GL_NO_ERROR, "%s: GL error %s", cases[c].what, gl_error_name(ge));
        }
        /* The host's parameters are its own: still as it set them. */
        GLint mode = 0, stencil_mode = 0, min_filter = 0;
        glGetTextureParameteriv(cmp, GL_TEXTURE_COMPARE_MODE, &mode);
        glGetTextureParameteriv(sten, GL_DEPTH_STENCIL_TEXTURE_MODE, &stencil_mode);
        glGetTextureParameteriv(mut_d, GL_TEXTURE_MIN_FILTER, &min_filter);
        CHECK(mode == GL_COMPARE_REF_TO_TEXTURE && stencil_mode == GL_STENCIL_INDEX && min_filter == GL_NEAREST_MIPMAP_LINEAR,
              "the host's texture parameters are left as the host set them (%#x, %#x, %#x)", mode, stencil_mode, min_filter);
        GLuint dels[] = {mut_d, mut_n, cmp, sten};
        glDeleteTextures(4, dels);
    }
    GLuint dels[] = {lin32, n32, out32};
    glDeleteTextures(3, dels);
}

int main(void)
{
    ob_context *ctx = NULL;
    ob_renderer *r = make_host_renderer(false, W, H, &ctx);
    if (!r) return 1;
    printf("host context: %s\n", (const char *)glGetString(GL_RENDERER));
    test_settings();
    float proj[16];
    perspective(proj, fov_y, (float)W / (float)H, 0.1, 100.0, false, false);
    make_view(&V, W, H, proj, cam_eye, cam_target);
    raycast(&V, depth_px, vn_px, wn_px);
    test_input_size(r);
    GLuint lin32 = upload(GL_R32F, W, H, GL_RED, depth_px), n16 = normal_texture(GL_RGBA16F, vn_px, W, H);
    test_wrong_inputs(r, lin32, n16);
    test_old_entry_points(r, lin32, n16);
    printf("\n%d wrong-input rows\n", table_rows);
    test_accepted(r);
    glDeleteTextures(1, &lin32), glDeleteTextures(1, &n16);
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    destroy_host_context();
    return check_finish("host_inputs");
}
