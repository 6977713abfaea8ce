/* Presenting and the interactive viewer's entry points, on the real GL: ob_present's final frame
 * and debug views against ob_read_image and the CLI's mappings (app/render.c view_image), the GL
 * state it must leave alone, ob_renderer_resize, ob_set_shader_directory (the source tree's files
 * give the embedded bytes; a broken file names its line), and adopting the caller's context. */
#include <epoxy/gl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "gpu/gpu.h"
#include "gpu/shaders_embedded.h"
#include "methods/method.h"
#include "obscura/eval.h"

enum { W = 64, H = 48 };

static ob_camera cam;
static ob_scene *scene;

static const char *last_message(void)
{
    const char *msg = NULL;
    ob_get_error(&msg);
    return msg;
}

static ob_renderer *make(ob_context *ctx, int w, int h)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = w, .height = h});
    CHECK(r != NULL, "renderer %dx%d: %s", w, h, last_message());
    if (r) CHECK(ob_renderer_set_scene(r, scene) == OB_OK, "scene upload");
    return r;
}

static bool frame(ob_renderer *r, const ob_settings *s)
{
    ob_error e = ob_render_frame(r, &cam, s);
    CHECK(e == OB_OK, "%s frame: %s", ob_method_at(s->method)->name, last_message());
    return e == OB_OK;
}

/* An RGBA8 (or sRGB) texture of w x h behind a framebuffer, for ob_present to draw into. */
typedef struct target { GLuint fbo, tex; int w, h; } target;

static target make_target(GLenum format, int w, int h)
{
    target t = {0, 0, w, h};
    t.tex = ob_make_texture_2d(format, w, h);
    glCreateFramebuffers(1, &t.fbo);
    glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.tex, 0);
    const float magenta[4] = {1.0f, 0.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(t.fbo, GL_COLOR, 0, magenta);
    return t;
}

static void destroy_target(target *t)
{
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteTextures(1, &t->tex);
}

/* Raw bytes, bottom row first (GL order). */
static uint8_t *read_target(const target *t)
{
    size_t n = (size_t)t->w * (size_t)t->h * 4;
    uint8_t *px = malloc(n);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(t->tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)n, px);
    return px;
}

/* ob_read_image(FINAL) runs top row first: turned to GL order. */
static uint8_t *read_final_bottom_first(ob_renderer *r)
{
    size_t n = ob_image_size(r, OB_IMAGE_FINAL_RGBA8);
    uint8_t *top = malloc(n), *bottom = malloc(n);
    CHECK(ob_read_image(r, OB_IMAGE_FINAL_RGBA8, top, n) == OB_OK, "read final");
    int w = 0, h = 0;
    ob_query_renderer_size(r, &w, &h);
    size_t row = (size_t)w * 4;
    for (int y = 0; y < h; ++y) memcpy(bottom + (size_t)y * row, top + (size_t)(h - 1 - y) * row, row);
    free(top);
    return bottom;
}

/* ---- the CLI's mappings (app/render.c view_image), on the float images -------------------- */
static uint8_t to_byte(float v)
{
    v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    return (uint8_t)lrintf(v * 255.0f);
}

static float srgb(float c)
{
    c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

/* shaders/view.glsl's luminance ramp and legend, in C. */
static void luminance_ramp(float t, float rgb[3])
{
    static const float stops[6][3] = {{0, 0, 0.3f}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    float x = (t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t) * 5.0f;
    int i = (int)x < 4 ? (int)x : 4;
    for (int c = 0; c < 3; ++c) rgb[c] = stops[i][c] + (stops[i + 1][c] - stops[i][c]) * (x - (float)i);
}

static void luminance_pixel(const float *hdr, int x, int y, float rgb[3])
{
    const float lo = (float)OB_LUMINANCE_LOG2_LO, hi = (float)OB_LUMINANCE_LOG2_HI;
    int bar = H / 20 > 6 ? H / 20 : 6;
    if (y < bar) {
        float stops = hi - lo;
        float at = ((float)x + 0.5f) / (float)W * stops;
        int nearest = (int)floorf(at + 0.5f);
        bool on_tick = fabsf(at - (float)nearest) * (float)W / stops < 0.5f;
        int tall = nearest == (int)-lo ? bar : bar / 2;
        if (on_tick && y < tall) rgb[0] = rgb[1] = rgb[2] = 0.0f;
        else luminance_ramp(at / stops, rgb);
        return;
    }
    const float *p = &hdr[3 * ((size_t)y * W + (size_t)x)];
    float lum = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    if (lum <= 0.0f) rgb[0] = rgb[1] = rgb[2] = 0.0f;
    else if (log2f(lum) > hi) rgb[0] = rgb[1] = rgb[2] = 1.0f;
    else luminance_ramp((log2f(lum) - lo) / (hi - lo), rgb);
}

/* The expected RGBA bytes of a view (bottom row first) from ob_read_image. far and max_samples are
 * the GPU's scales (the CLI's are the image's maxima). */
static uint8_t *expected_view(ob_renderer *r, ob_view view, float far_z, float max_samples, const ob_settings *s)
{
    const ob_image_kind kinds[OB_VIEW_COUNT] = {
        [OB_VIEW_AO] = OB_IMAGE_AO_RGB_F32,     [OB_VIEW_NORMALS] = OB_IMAGE_NORMAL_F32,
        [OB_VIEW_DEPTH] = OB_IMAGE_DEPTH_F32,   [OB_VIEW_SHADOW] = OB_IMAGE_SHADOW_F32,
        [OB_VIEW_RADIANCE] = OB_IMAGE_RADIANCE_F32, [OB_VIEW_SAMPLES] = OB_IMAGE_SAMPLES_F32,
        [OB_VIEW_BOUNCE] = OB_IMAGE_BOUNCE_F32, [OB_VIEW_BENT_NORMALS] = OB_IMAGE_BENT_NORMAL_F32,
        [OB_VIEW_LUMINANCE] = OB_IMAGE_HDR_F32, [OB_VIEW_SECOND_DEPTH] = OB_IMAGE_SECOND_DEPTH_F32,
        [OB_VIEW_EXTRA] = OB_IMAGE_EXTRA_RADIANCE_F32, [OB_VIEW_HISTORY_AGE] = OB_IMAGE_HISTORY_AGE_F32};
    ob_image_kind kind = kinds[view];
    size_t px = (size_t)W * (size_t)H;
    if (view == OB_VIEW_HISTORY_AGE) {
        /* The AO grid's ages (k from the read-back's size) over the history length; 0 without. */
        size_t count = ob_image_size(r, kind) / sizeof(float);
        int k = 1;
        while (k < 4 && (size_t)((W + k - 1) / k) * (size_t)((H + k - 1) / k) != count) k *= 2;
        float *age = malloc(count * sizeof(float));
        uint8_t *out = malloc(px * 4);
        CHECK(ob_read_image(r, kind, age, count * sizeof(float)) == OB_OK, "read history_age");
        int n = s->temporal_frames > 0 ? s->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
        float frames = s->temporal ? (float)n : 0.0f;
        for (size_t i = 0; i < px; ++i) {
            int x = (int)(i % W) / k, y = (int)(i / W) / k;
            float v = frames > 0.0f ? age[(size_t)y * (size_t)((W + k - 1) / k) + (size_t)x] / frames : 0.0f;
            for (int c = 0; c < 3; ++c) out[4 * i + (size_t)c] = to_byte(v);
            out[4 * i + 3] = 255;
        }
        free(age);
        return out;
    }
    float *buf = malloc(ob_image_size(r, kind));
    uint8_t *out = malloc(px * 4);
    CHECK(ob_read_image(r, kind, buf, ob_image_size(r, kind)) == OB_OK, "read %s", ob_view_name(view));
    int channels = ob_image_size(r, kind) == px * 3 * sizeof(float) ? 3 : 1;
    for (size_t i = 0; i < px && view == OB_VIEW_LUMINANCE; ++i) {
        float rgb[3];
        luminance_pixel(buf, (int)(i % W), (int)(i / W), rgb);
        for (int c = 0; c < 3; ++c) out[4 * i + (size_t)c] = to_byte(rgb[c]);
        out[4 * i + 3] = 255;
    }
    for (size_t i = 0; i < px && view != OB_VIEW_LUMINANCE; ++i) {
        /* Bent normals: renormalised (filtering averages them), black where there is none. */
        float len = 0.0f;
        for (int c = 0; c < 3 && view == OB_VIEW_BENT_NORMALS; ++c) len += buf[i * 3 + (size_t)c] * buf[i * 3 + (size_t)c];
        len = sqrtf(len);
        for (int c = 0; c < 3; ++c) {
            float v = buf[i * (size_t)channels + (size_t)(channels == 3 ? c : 0)];
            if (view == OB_VIEW_BENT_NORMALS) v = len > 1e-4f ? v / len * 0.5f + 0.5f : 0.0f;
            if (view == OB_VIEW_NORMALS) v = v * 0.5f + 0.5f;
            else if (view == OB_VIEW_RADIANCE || view == OB_VIEW_BOUNCE || view == OB_VIEW_EXTRA) v = srgb(v);
            else if (view == OB_VIEW_DEPTH || view == OB_VIEW_SECOND_DEPTH) v = v > 0.0f ? 1.0f - v / far_z : 0.0f;
            else if (view == OB_VIEW_SAMPLES) v = max_samples > 0.0f ? v / max_samples : 0.0f;
            out[4 * i + (size_t)c] = to_byte(v);
        }
        out[4 * i + 3] = 255;
    }
    free(buf);
    return out;
}

static int max_byte_diff(const uint8_t *a, const uint8_t *b, size_t n)
{
    int worst = 0;
    for (size_t i = 0; i < n; ++i) {
        int d = abs((int)a[i] - (int)b[i]);
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* ---- tests ---------------------------------------------------------------------------------- */
static void test_view_names(void)
{
    const char *names[OB_VIEW_COUNT] = {"final",    "ao",      "normals", "depth",        "shadow",
                                        "radiance", "samples", "bounce",  "bent_normals", "luminance",
                                        "second_depth", "extra", "history_age"};
    for (int v = 0; v < OB_VIEW_COUNT; ++v) {
        CHECK(!strcmp(ob_view_name((ob_view)v), names[v]), "view %d is '%s'", v, ob_view_name((ob_view)v));
        int back = -1;
        for (int u = 0; u < OB_VIEW_COUNT; ++u)
            if (!strcmp(ob_view_name((ob_view)u), names[v])) back = u;
        CHECK(back == v, "'%s' names view %d only", names[v], v);
    }
    CHECK(!strcmp(ob_view_name(OB_VIEW_COUNT), ""), "out of range: ''");
    CHECK(!strcmp(ob_view_name((ob_view)-1), ""), "negative: ''");
}

static void test_present_refusals(ob_context *ctx)
{
    ob_renderer *r = make(ctx, W, H);
    if (!r) return;
    target t = make_target(GL_RGBA8, W, H);
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, W, H) == OB_ERR_INVALID_ARGUMENT &&
              strstr(last_message(), "no frame"),
          "present before any frame refused: %s", last_message());
    CHECK(ob_present(NULL, OB_VIEW_FINAL, t.fbo, 0, 0, W, H) == OB_ERR_INVALID_ARGUMENT, "NULL renderer");
    ob_settings s;
    ob_settings_init(&s, "ssao");
    frame(r, &s);
    CHECK(ob_present(r, OB_VIEW_COUNT, t.fbo, 0, 0, W, H) == OB_ERR_INVALID_ARGUMENT, "view out of range");
    CHECK(ob_present(r, (ob_view)-1, t.fbo, 0, 0, W, H) == OB_ERR_INVALID_ARGUMENT, "negative view");
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, 0, H) == OB_ERR_INVALID_ARGUMENT, "zero width");
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, W, -1) == OB_ERR_INVALID_ARGUMENT, "negative height");
    GLuint never_made = t.fbo + 1000;
    CHECK(ob_present(r, OB_VIEW_AO, never_made, 0, 0, W, H) == OB_ERR_GL, "no such framebuffer: %s", last_message());
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, W, H) == OB_OK, "and a good one still works: %s", last_message());
    CHECK(glGetError() == GL_NO_ERROR, "no GL error left behind");
    destroy_target(&t);
    ob_destroy_renderer(r);
}

static void test_present_final(ob_renderer *r, const ob_settings *s)
{
    if (!frame(r, s)) return;
    uint8_t *want = read_final_bottom_first(r);
    size_t n = (size_t)W * (size_t)H * 4;

    /* Same size: the bytes of ob_read_image. */
    target t = make_target(GL_RGBA8, W, H);
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, W, H) == OB_OK, "present final: %s", last_message());
    uint8_t *got = read_target(&t);
    CHECK(memcmp(got, want, n) == 0, "presented final == ob_read_image (max diff %d)", max_byte_diff(got, want, n));
    free(got);
    destroy_target(&t);

    /* An sRGB target with GL_FRAMEBUFFER_SRGB on, and a scissor box: neither may touch the bytes,
     * and both stay as they were. */
    t = make_target(GL_SRGB8_ALPHA8, W, H);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 4, 4);
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, W, H) == OB_OK, "present final into sRGB: %s", last_message());
    CHECK(glIsEnabled(GL_FRAMEBUFFER_SRGB) && glIsEnabled(GL_SCISSOR_TEST), "sRGB and scissor still enabled");
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_SCISSOR_TEST);
    got = read_target(&t);
    CHECK(memcmp(got, want, n) == 0, "no second sRGB encoding, no scissoring (max diff %d)",
          max_byte_diff(got, want, n));
    free(got);
    destroy_target(&t);

    /* Twice the size at an offset, nearest-neighbour: every pixel of the 2x2 block is the source's. */
    t = make_target(GL_RGBA8, 2 * W + 8, 2 * H + 6);
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 8, 6, 2 * W, 2 * H) == OB_OK, "present scaled");
    got = read_target(&t);
    int wrong = 0, outside = 0;
    for (int y = 0; y < t.h; ++y)
        for (int x = 0; x < t.w; ++x) {
            const uint8_t *p = got + 4 * ((size_t)y * (size_t)t.w + (size_t)x);
            if (x < 8 || y < 6) {
                outside += !(p[0] == 255 && p[1] == 0 && p[2] == 255); /* the clear colour, untouched */
                continue;
            }
            const uint8_t *q = want + 4 * ((size_t)((y - 6) / 2) * W + (size_t)((x - 8) / 2));
            wrong += memcmp(p, q, 4) != 0;
        }
    CHECK(wrong == 0, "%d scaled pixels differ from their source pixel", wrong);
    CHECK(outside == 0, "%d pixels outside the rectangle were drawn", outside);
    free(got);
    destroy_target(&t);
    free(want);
}

/* Every debug view against the CLI's mapping of ob_read_image, within one step of rounding, and
 * the compute pass's bindings put back. */
static void check_views(ob_renderer *r, const ob_settings *s, const char *label, float max_samples)
{
    size_t n = (size_t)W * (size_t)H * 4;
    target t = make_target(GL_RGBA8, W, H);
    for (int v = OB_VIEW_AO; v < OB_VIEW_COUNT; ++v) {
        /* Bindings a caller might have: a texture on unit 0, another unit active, a program. */
        GLuint mine = ob_make_texture_2d(GL_RGBA8, 4, 4);
        glBindTextureUnit(0, mine);
        glActiveTexture(GL_TEXTURE5);
        ob_error e = ob_present(r, (ob_view)v, t.fbo, 0, 0, W, H);
        CHECK(e == OB_OK, "%s: present %s: %s", label, ob_view_name((ob_view)v), last_message());
        GLint active = 0, bound = 0, program = -1, image = -1;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        glActiveTexture(GL_TEXTURE0);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, 0, &image);
        CHECK(active == GL_TEXTURE5 && bound == (GLint)mine, "%s: texture bindings restored", ob_view_name((ob_view)v));
        glBindTextureUnit(0, 0);
        glDeleteTextures(1, &mine);
        uint8_t *got = read_target(&t);
        uint8_t *want = expected_view(r, (ob_view)v, cam.far_z, max_samples, s);
        int diff = max_byte_diff(got, want, n);
        CHECK(diff <= 1, "%s: %s view within 1/255 of the CLI's mapping (max diff %d)", label,
              ob_view_name((ob_view)v), diff);
        free(got);
        free(want);
    }
    destroy_target(&t);
}

static void test_present_views(ob_renderer *r)
{
    ob_settings s;
    ob_settings_init(&s, "ssao");
    glUseProgram(0);
    if (frame(r, &s)) {
        int samples = (int)ob_settings_get(&s, "samples");
        check_views(r, &s, "ssao", (float)samples);
    }
    /* Adaptive: the counts over base x 3. */
    s.adaptive = true;
    if (frame(r, &s)) {
        int samples = (int)ob_settings_get(&s, "samples");
        check_views(r, &s, "ssao adaptive", (float)(3 * ob_adaptive_base(samples)));
    }
    /* A directional method: AO is M's RGB, and the bounce is there. */
    ob_settings d;
    ob_settings_init(&d, "ssdo");
    ob_settings_set(&d, "ssdo.extra_view=on"); /* and the extra view's light */
    if (frame(r, &d)) {
        int samples = (int)ob_settings_get(&d, "samples");
        check_views(r, &d, "ssdo", (float)samples);
    }
    /* A method that writes a bent normal: its view is the renormalised direction. */
    ob_settings g;
    ob_settings_init(&g, "gtao");
    ob_settings_set(&g, "gtao.bent_normals=on");
    /* and a second depth layer (depth peeling): its view is the depth view of that layer. */
    ob_settings_set(&g, "gtao.layers=2");
    if (frame(r, &g)) check_views(r, &g, "gtao with bent normals and two layers", 36.0f);
    /* Temporal accumulation: the history's age over its length, at half resolution for the scalar
     * history (age in .g) and for ssdo's RGB one (age in .a), three frames in. */
    ob_settings t = s;
    t.adaptive = false;
    t.temporal = true;
    t.temporal_frames = 5;
    ob_settings_set_ao_divisor(&t, 2);
    if (frame(r, &t) && frame(r, &t) && frame(r, &t))
        check_views(r, &t, "ssao temporal at 1/2", (float)(int)ob_settings_get(&t, "samples"));
    d.temporal = true;
    if (frame(r, &d) && frame(r, &d) && frame(r, &d))
        check_views(r, &d, "ssdo temporal", (float)(int)ob_settings_get(&d, "samples"));
}

static void test_resize(ob_context *ctx, const ob_settings *s)
{
    ob_renderer *r = make(ctx, W, H);
    if (!r) return;
    ob_settings half = *s;
    ob_settings_set_ao_scale(&half, 0.5f);
    ob_settings ssdo;
    ob_settings_init(&ssdo, "ssdo");
    /* Every lazily made target exists before the resize: both AO scales and SSDO's chains. */
    frame(r, s);
    frame(r, &half);
    frame(r, &ssdo);
    CHECK(ob_renderer_resize(r, W, H) == OB_OK, "same size: a no-op");
    CHECK(ob_renderer_resize(r, 40, 30) == OB_OK, "resize to 40x30: %s", last_message());
    int w = 0, h = 0;
    ob_query_renderer_size(r, &w, &h);
    CHECK(w == 40 && h == 30, "size now %dx%d", w, h);
    CHECK(ob_image_size(r, OB_IMAGE_FINAL_RGBA8) == 40 * 30 * 4, "final image size %zu",
          ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
    target t = make_target(GL_RGBA8, 40, 30);
    CHECK(ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, 40, 30) == OB_ERR_INVALID_ARGUMENT,
          "the old frame is gone after a resize");

    /* A resized renderer renders what a new one of that size does, byte for byte. */
    ob_renderer *fresh = make(ctx, 40, 30);
    const ob_settings *all[3] = {s, &half, &ssdo};
    for (int i = 0; i < 3 && fresh; ++i) {
        size_t n = ob_image_size(r, OB_IMAGE_FINAL_RGBA8);
        uint8_t *a = malloc(n), *b = malloc(n);
        frame(r, all[i]);
        frame(fresh, all[i]);
        CHECK(ob_read_image(r, OB_IMAGE_FINAL_RGBA8, a, n) == OB_OK, "read resized");
        CHECK(ob_read_image(fresh, OB_IMAGE_FINAL_RGBA8, b, n) == OB_OK, "read fresh");
        CHECK(memcmp(a, b, n) == 0, "%s (ao scale %g): resized == fresh 40x30 (max diff %d)",
              ob_method_at(all[i]->method)->name, 1.0 / (double)(all[i]->ao_divisor ? all[i]->ao_divisor : 1), max_byte_diff(a, b, n));
        int distinct = 0;
        for (size_t k = 4; k < n; k += 4) distinct += memcmp(a + k, a, 3) != 0;
        CHECK(distinct > 100, "the frame is a picture, not one colour (%d pixels differ from the first)", distinct);
        free(a);
        free(b);
    }
    ob_destroy_renderer(fresh);
    /* The destroyed renderer's program was the current one: nothing to restore, and no error. */
    CHECK(ob_present(r, OB_VIEW_AO, t.fbo, 0, 0, 40, 30) == OB_OK, "present after resize: %s", last_message());

    /* Bad sizes are refused and change nothing. */
    CHECK(ob_renderer_resize(r, 0, 30) == OB_ERR_BAD_SIZE, "width 0 refused");
    CHECK(ob_renderer_resize(r, 0, 0) == OB_ERR_BAD_SIZE, "0x0 refused (no default here)");
    CHECK(ob_renderer_resize(r, 40, -3) == OB_ERR_BAD_SIZE, "negative refused");
    CHECK(ob_renderer_resize(r, ob_query_max_texture_size(ctx) + 1, 30) == OB_ERR_BAD_SIZE &&
              strstr(last_message(), "GL_MAX_TEXTURE_SIZE"),
          "above GL_MAX_TEXTURE_SIZE refused: %s", last_message());
    CHECK(ob_renderer_resize(NULL, 40, 30) == OB_ERR_INVALID_ARGUMENT, "NULL renderer");
    ob_query_renderer_size(r, &w, &h);
    CHECK(w == 40 && h == 30, "still 40x30 after the refusals");
    CHECK(frame(r, s) && ob_present(r, OB_VIEW_FINAL, t.fbo, 0, 0, 40, 30) == OB_OK, "and it still renders");
    /* Back up to a larger size. */
    CHECK(ob_renderer_resize(r, 72, 50) == OB_OK && frame(r, &ssdo), "resize up to 72x50 and render");
    ob_query_renderer_size(NULL, &w, &h);
    CHECK(w == 0 && h == 0, "NULL renderer has size 0x0");
    destroy_target(&t);
    ob_destroy_renderer(r);
}

/* ---- ob_set_shader_directory ---------------------------------------------------------------- */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s) s[n] = '\0';
    fclose(f);
    *len = (size_t)n;
    return s;
}

static bool spit(const char *path, const char *s, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fwrite(s, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

/* The final frame and the raw AO of a new renderer (programs made with the current directory). */
static bool frame_bytes(ob_context *ctx, const ob_settings *s, uint8_t **final, float **raw)
{
    ob_renderer *r = make(ctx, W, H);
    bool ok = r && frame(r, s);
    if (ok) {
        *final = malloc(ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
        *raw = malloc(ob_image_size(r, OB_IMAGE_AO_RAW_F32));
        ob_read_image(r, OB_IMAGE_FINAL_RGBA8, *final, ob_image_size(r, OB_IMAGE_FINAL_RGBA8));
        ob_read_image(r, OB_IMAGE_AO_RAW_F32, *raw, ob_image_size(r, OB_IMAGE_AO_RAW_F32));
    }
    ob_destroy_renderer(r);
    return ok;
}

static void test_shader_directory(ob_context *ctx, const ob_settings *s)
{
    const size_t nf = (size_t)W * H * 4, na = (size_t)W * H * sizeof(float);
    uint8_t *final0 = NULL, *final1 = NULL;
    float *raw0 = NULL, *raw1 = NULL;
    if (!frame_bytes(ctx, s, &final0, &raw0)) return;

    /* The source tree's files: the same text as embedded, so the same bytes. */
    CHECK(ob_set_shader_directory(OB_SOURCE_DIR "/shaders") == OB_OK, "source shaders: %s", last_message());
    if (frame_bytes(ctx, s, &final1, &raw1)) {
        CHECK(memcmp(final0, final1, nf) == 0, "final frame from the source files == embedded");
        CHECK(memcmp(raw0, raw1, na) == 0, "raw AO from the source files == embedded");
    }
    free(final1);
    free(raw1);
    final1 = NULL;
    raw1 = NULL;
    CHECK(ob_make_compute_program("not-a-shader.glsl", NULL) == 0 && ob_get_error(NULL) == OB_ERR_SHADER &&
              strstr(last_message(), "not-a-shader.glsl"),
          "a file outside the build's list is named: %s", last_message());

    CHECK(ob_set_shader_directory("/nonexistent/obscura/shaders") == OB_ERR_IO, "missing dir: OB_ERR_IO");
    CHECK(strstr(last_message(), "/nonexistent/obscura/shaders") != NULL, "message names it: %s", last_message());

    /* A copy of the shaders with a syntax error in ssao.glsl, just above its main(). */
    char dir[] = "/tmp/obscura-shaders-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temp dir");
    int broken_line = 0;
    for (int i = 0; i < ob_shader_file_count; ++i) {
        char src[4096], dst[4096];
        snprintf(src, sizeof src, "%s/shaders/%s", OB_SOURCE_DIR, ob_shader_file_names[i]);
        snprintf(dst, sizeof dst, "%s/%s", dir, ob_shader_file_names[i]);
        size_t len = 0;
        char *text = slurp(src, &len);
        CHECK(text != NULL, "read %s", src);
        if (!text) continue;
        if (!strcmp(ob_shader_file_names[i], "ssao.glsl")) {
            char *at = strstr(text, "\nvoid main()");
            CHECK(at != NULL, "ssao.glsl has a main()");
            if (at) {
                broken_line = 2;
                for (const char *p = text; p < at; ++p) broken_line += *p == '\n';
                const char *bad = "int broken = ;\n";
                size_t head = (size_t)(at - text) + 1;
                char *edited = malloc(len + strlen(bad) + 1);
                memcpy(edited, text, head);
                memcpy(edited + head, bad, strlen(bad));
                memcpy(edited + head + strlen(bad), text + head, len - head + 1);
                free(text);
                text = edited;
                len += strlen(bad);
            }
        }
        CHECK(spit(dst, text, len), "write %s", dst);
        free(text);
    }
    CHECK(ob_set_shader_directory(dir) == OB_OK, "temp dir: %s", last_message());
    ob_renderer *r = make(ctx, W, H);
    if (r) {
        char want[64];
        snprintf(want, sizeof want, "shaders/ssao.glsl:%d:", broken_line);
        ob_error e = ob_render_frame(r, &cam, s);
        CHECK(e == OB_ERR_SHADER && strstr(last_message(), want), "broken ssao.glsl: %s, '%s' (want '%s')",
              ob_error_name(e), last_message(), want);
        printf("  broken ssao.glsl: %s\n", last_message());
        ob_settings none;
        ob_settings_init(&none, "none");
        CHECK(ob_render_frame(r, &cam, &none) == OB_OK, "the other programs still build: %s", last_message());
    }
    ob_destroy_renderer(r);
    for (int i = 0; i < ob_shader_file_count; ++i) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, ob_shader_file_names[i]);
        unlink(path);
    }
    rmdir(dir);

    /* NULL: back to the embedded copies (the temp dir is gone, so they must be). */
    CHECK(ob_set_shader_directory(NULL) == OB_OK, "back to embedded");
    if (frame_bytes(ctx, s, &final1, &raw1)) CHECK(memcmp(final0, final1, nf) == 0, "embedded again: same frame");
    free(final0);
    free(raw0);
    free(final1);
    free(raw1);
}

/* ---- adopting the caller's context ---------------------------------------------------------- */
/* A caller's stale GL error, left pending before each call that checks its own GL calls with
 * glGetError: the call works and does not report it as its own (ob_gl_drop_pending). Each call
 * once with GL_INVALID_VALUE pending; afterwards nothing is left pending either. */
static void test_stale_errors(ob_context *ctx, const ob_settings *s)
{
    glViewport(0, 0, -1, -1);
    ob_renderer *r = make(ctx, W, H);
    if (!r) return;
    glViewport(0, 0, -1, -1);
    bool rendered = frame(r, s);
    if (rendered) {
        size_t n = ob_image_size(r, OB_IMAGE_AO_F32);
        float *ao = malloc(n);
        glViewport(0, 0, -1, -1);
        CHECK(ao && ob_read_image(r, OB_IMAGE_AO_F32, ao, n) == OB_OK, "ob_read_image with a stale error: %s",
              last_message());
        free(ao);
        uint8_t *rgba = malloc((size_t)W * H * 4);
        glViewport(0, 0, -1, -1);
        CHECK(rgba && ob_read_view(r, OB_VIEW_AO, rgba, (size_t)W * H * 4) == OB_OK,
              "ob_read_view with a stale error: %s", last_message());
        free(rgba);
        glViewport(0, 0, -1, -1);
        CHECK(ob_wait_timings(r) == OB_OK, "ob_wait_timings with a stale error: %s", last_message());
    }
    CHECK(glGetError() == GL_NO_ERROR, "a stale error outlived the library's calls, or one raised its own");
    ob_destroy_renderer(r);
}

static void *make_without_context(void *result)
{
    /* A new thread has no current context. */
    ob_context *c = ob_make_context(&(ob_context_desc){.use_current = true});
    *(bool *)result = c == NULL && ob_get_error(NULL) == OB_ERR_NO_CONTEXT;
    ob_destroy_context(c);
    return NULL;
}

static void test_adopt(ob_context *ctx, const ob_settings *s)
{
    bool refused = false;
    pthread_t th;
    CHECK(pthread_create(&th, NULL, make_without_context, &refused) == 0, "thread");
    pthread_join(th, NULL);
    CHECK(refused, "use_current without a current context: NULL and OB_ERR_NO_CONTEXT");

    ob_context *adopted = ob_make_context(&(ob_context_desc){.use_current = true});
    CHECK(adopted != NULL, "adopt the headless context: %s", last_message());
    if (!adopted) return;
    CHECK(!strcmp(ob_query_device(adopted), "the caller's context"), "device '%s'", ob_query_device(adopted));
    CHECK(!strcmp(ob_query_renderer(adopted), ob_query_renderer(ctx)), "same renderer '%s'",
          ob_query_renderer(adopted));
    CHECK(!strcmp(ob_query_gl_version(adopted), ob_query_gl_version(ctx)), "same version");
    CHECK(ob_query_is_software(adopted) == ob_query_is_software(ctx), "software %d",
          (int)ob_query_is_software(adopted));
    CHECK(ob_query_max_texture_size(adopted) == ob_query_max_texture_size(ctx), "max texture size");
    uint8_t *a = NULL, *b = NULL;
    float *ra = NULL, *rb = NULL;
    CHECK(frame_bytes(adopted, s, &a, &ra), "render with the adopted context");
    ob_destroy_context(adopted);
    /* The original is untouched: still current, still renders, the same bytes. */
    CHECK(frame_bytes(ctx, s, &b, &rb), "the original still renders");
    if (a && b) CHECK(memcmp(a, b, (size_t)W * H * 4) == 0, "same frame on both");
    free(a);
    free(b);
    free(ra);
    free(rb);
}

int main(void)
{
    /* Before any context exists on this thread: refused, not a crash. */
    ob_context *none = ob_make_context(&(ob_context_desc){.use_current = true});
    CHECK(none == NULL && ob_get_error(NULL) == OB_ERR_NO_CONTEXT, "use_current with nothing current: %s",
          last_message());

    ob_context *ctx = ob_make_context(&(ob_context_desc){.gpu = OB_GPU_AUTO});
    if (!ctx) {
        fprintf(stderr, "no context: %s\n", last_message());
        return 1;
    }
    printf("renderer: %s (%s)\n", ob_query_renderer(ctx), ob_query_device(ctx));
    scene = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    CHECK(scene != NULL, "cornell loads");
    if (!scene) return check_finish("test_present");
    CHECK(ob_find_camera(scene, "front", &cam) == OB_OK, "camera front");
    /* Explicit planes: the depth view divides by the far plane. */
    cam.near_z = 0.05f;
    cam.far_z = 10.0f;
    ob_settings s;
    ob_settings_init(&s, "ssao");

    test_view_names();
    test_present_refusals(ctx);
    ob_renderer *r = make(ctx, W, H);
    if (r) {
        test_present_final(r, &s);
        test_present_views(r);
    }
    ob_destroy_renderer(r);
    test_resize(ctx, &s);
    test_shader_directory(ctx, &s);
    test_stale_errors(ctx, &s);
    test_adopt(ctx, &s);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_present");
}
