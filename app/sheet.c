/* obscura sheet: a labelled contact sheet comparing AO methods on one scene view -> PNG.
 *
 * Layout (S = STRIP_H, P = PAD, TW x TH = --size, n = number of methods):
 *
 *   +------------------------------------------+  header strip (S): "final" above column 0,
 *   | final              ao                    |                   "ao" above column 1
 *   | ssao  ao 12.3 ms                         |  label strip (S) of row 0
 *   | [final  TW x TH]   [AO map  TW x TH]     |  tiles of row 0 (TH), P between and beside
 *   | none  ao 0.1 ms                          |  label strip of row 1, ...
 *   | [...]              [...]                 |
 *   +------------------------------------------+  P below the last row
 *
 *   width  = 2*TW + 3*P
 *   height = S + n*(S + TH) + P
 *
 * Text is stb_easy_font, each font pixel drawn as a TEXT_SCALE x TEXT_SCALE block, dark on the
 * light strip colour. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

/* Layout constants: tests/test_sheet.sh computes the expected sheet size from these. */
enum {
    PAD = 4,         /* pixels around and between the tiles */
    STRIP_H = 24,    /* header and label strips */
    TEXT_SCALE = 2,  /* each font pixel -> 2x2 */
    TEXT_INSET = 3,  /* text offset from a strip's top-left corner */
    MAX_METHODS = 32,
    MAX_SETS = 64,
    FRAMES = 3,      /* frames per method; the label shows the median AO pass time */
};
static const uint8_t STRIP_RGB[3] = {224, 224, 224};
static const uint8_t TEXT_RGB[3] = {16, 16, 16};

static void sheet_usage(FILE *f)
{
    fputs("usage: obscura sheet --scene NAME --out FILE.png [options]\n"
          "\n"
          "A contact sheet: one row per AO method, the final image and the AO map side by side,\n"
          "each row labelled with the method and the median GPU time of its AO pass (3 frames).\n"
          "\n"
          "  --scene NAME|PATH     built-in (cornell, corner, sphere-on-plane), a named scene from\n"
          "                        scenes/ (bunny, fzk-haus, cornell-obj) or any model Assimp reads\n"
          "  --out FILE.png        the sheet (required)\n"
          "  --camera NAME|INDEX   a camera preset of the scene (default: 'default')\n"
          "  --size WxH            size of each tile (default 320x240)\n"
          "  --methods A,B,...     methods, one row each (default: every method, see `obscura list`)\n"
          "  --quality Q           low, medium, high or ultra: 12, 24, 36 or 64 samples per pixel for\n"
          "                        every method that takes a sample count\n"
          "  --set M.P=V           set a parameter of method M, validated (repeatable; after --quality)\n"
          "  --gpu auto|hw|sw      hardware EGL device, Mesa llvmpipe, or hardware first (default auto)\n"
          "  -v                    print the GL renderer and device\n",
          f);
}

typedef struct sheet_opts {
    const char *scene, *camera, *out, *methods;
    const char *sets[MAX_SETS];
    int set_count;
    int width, height;
    int quality_samples; /* from --quality; 0 = not given */
    bool verbose;
    ob_gpu_kind gpu;
} sheet_opts;

static int parse(int argc, char **argv, sheet_opts *o)
{
    *o = (sheet_opts){.width = 320, .height = 240};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            sheet_usage(stdout);
            return -1;
        }
        if (!strcmp(a, "-v")) { o->verbose = true; continue; }
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura sheet --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) o->scene = v;
        else if (!strcmp(a, "--camera")) o->camera = v;
        else if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--methods")) o->methods = v;
        else if (!strcmp(a, "--set")) {
            if (o->set_count >= MAX_SETS) return cli_fail(EXIT_USAGE, "--set: too many");
            o->sets[o->set_count++] = v;
        } else if (!strcmp(a, "--size")) {
            if (!cli_parse_size(v, &o->width, &o->height))
                return cli_fail(EXIT_USAGE, "--size: expected WIDTHxHEIGHT with positive integers, got '%s'", v);
        } else if (!strcmp(a, "--quality")) {
            o->quality_samples = ob_quality_samples(v);
            if (o->quality_samples < 0)
                return cli_fail(EXIT_USAGE, "--quality: expected low, medium, high or ultra, got '%s'", v);
        } else if (!strcmp(a, "--gpu")) {
            if (!cli_parse_gpu(v, &o->gpu)) return cli_fail(EXIT_USAGE, "--gpu: expected auto, hw or sw, got '%s'", v);
        } else {
            return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura sheet --help)", a);
        }
    }
    if (!o->scene) return cli_fail(EXIT_USAGE, "--scene NAME is required (see obscura sheet --help)");
    if (!o->out) return cli_fail(EXIT_USAGE, "--out FILE.png is required (see obscura sheet --help)");
    if (!cli_output_writable(o->out))
        return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", o->out);
    return 0;
}

/* The --quality preset's sample count for one method. A method that takes no sample count
 * (none) is left as it is; a count beyond the method's range is an error. */
static ob_error apply_quality(ob_settings *s, int samples)
{
    if (samples <= 0) return OB_OK;
    ob_error err = ob_settings_set_samples(s, samples);
    return err == OB_ERR_INVALID_ARGUMENT ? OB_OK : err;
}

/* Settings for each method of --methods (default: the whole registry, in order), then --quality,
 * then each --set applied to the method its prefix names. */
static int make_settings(const sheet_opts *o, ob_settings *settings, int *count)
{
    *count = 0;
    if (!o->methods) {
        if (ob_method_count() > MAX_METHODS)
            return cli_fail(EXIT_USAGE, "more than %d methods: pick some with --methods", MAX_METHODS);
        for (int i = 0; i < ob_method_count(); ++i)
            if (ob_settings_init(&settings[(*count)++], ob_method_at(i)->name) != OB_OK) return cli_fail_from_library();
    } else {
        const char *p = o->methods;
        for (;;) {
            size_t len = strcspn(p, ",");
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)len, p);
            if (*count >= MAX_METHODS) return cli_fail(EXIT_USAGE, "--methods: more than %d methods", MAX_METHODS);
            if (ob_settings_init(&settings[*count], name) != OB_OK) return cli_fail_from_library();
            for (int i = 0; i < *count; ++i)
                if (settings[i].method == settings[*count].method)
                    return cli_fail(EXIT_USAGE, "--methods: '%s' is listed twice", name);
            ++*count;
            if (p[len] == '\0') break;
            p += len + 1;
        }
    }
    for (int i = 0; i < *count; ++i)
        if (apply_quality(&settings[i], o->quality_samples) != OB_OK) return cli_fail_from_library();
    for (int k = 0; k < o->set_count; ++k) {
        const char *a = o->sets[k];
        const char *dot = strchr(a, '.'), *eq = strchr(a, '=');
        if (!dot || !eq || dot > eq || dot == a)
            return cli_fail(EXIT_USAGE, "--set: expected METHOD.PARAM=VALUE, got '%s'", a);
        size_t mlen = (size_t)(dot - a);
        int target = -1;
        for (int i = 0; i < *count; ++i) {
            const char *name = ob_method_at(settings[i].method)->name;
            if (strlen(name) == mlen && !strncmp(name, a, mlen)) target = i;
        }
        if (target < 0) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)mlen, a);
            if (ob_find_method(name) < 0) return cli_fail(EXIT_USAGE, "--set %s: unknown method '%s'", a, name);
            return cli_fail(EXIT_USAGE, "--set %s: method '%s' is not in --methods", a, name);
        }
        if (ob_settings_set(&settings[target], a) != OB_OK) return cli_fail_from_library();
    }
    return 0;
}

/* ---- compositing ------------------------------------------------------------------------------ */
typedef struct sheet_image {
    int w, h;
    uint8_t *rgb; /* 3 bytes per pixel, top row first */
} sheet_image;

static void fill_rect(sheet_image *img, int x0, int y0, int x1, int y1, const uint8_t c[3])
{
    x0 = x0 < 0 ? 0 : x0;
    y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > img->w ? img->w : x1;
    y1 = y1 > img->h ? img->h : y1;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) memcpy(img->rgb + ((size_t)y * (size_t)img->w + (size_t)x) * 3, c, 3);
}

/* One line of text at (x, y), clipped to the columns [x, clip_x1): stb_easy_font's quads, each
 * font pixel scaled to TEXT_SCALE x TEXT_SCALE. */
static void draw_text(sheet_image *img, int x, int y, int clip_x1, const char *text)
{
    char line[128];
    size_t n = 0;
    for (; text[n] && n + 1 < sizeof line; ++n) /* stb_easy_font indexes its table by char - 32 */
        line[n] = text[n] >= 32 && text[n] < 127 ? text[n] : '?';
    line[n] = '\0';
    static float quads[128 * 80]; /* ~270 bytes per character; 4 vertices of x,y,z,colour per quad */
    int count = stb_easy_font_print(0.0f, 0.0f, line, NULL, quads, (int)sizeof quads);
    for (int q = 0; q < count; ++q) {
        const float *v = quads + (size_t)q * 16; /* vertex 0 = top left, vertex 2 = bottom right */
        int x0 = x + TEXT_SCALE * (int)lrintf(v[0]), y0 = y + TEXT_SCALE * (int)lrintf(v[1]);
        int x1 = x + TEXT_SCALE * (int)lrintf(v[8]), y1 = y + TEXT_SCALE * (int)lrintf(v[9]);
        fill_rect(img, x0, y0, x1 < clip_x1 ? x1 : clip_x1, y1, TEXT_RGB);
    }
}

static void put_final_tile(sheet_image *img, int x, int y, int tw, int th, const uint8_t *rgba)
{
    for (int j = 0; j < th; ++j)
        for (int i = 0; i < tw; ++i) {
            const uint8_t *s = rgba + ((size_t)j * (size_t)tw + (size_t)i) * 4;
            memcpy(img->rgb + ((size_t)(y + j) * (size_t)img->w + (size_t)(x + i)) * 3, s, 3);
        }
}

/* The AO map comes bottom row first; 1 = white. */
static void put_ao_tile(sheet_image *img, int x, int y, int tw, int th, const float *ao)
{
    for (int j = 0; j < th; ++j)
        for (int i = 0; i < tw; ++i) {
            float v = ao[(size_t)(th - 1 - j) * (size_t)tw + (size_t)i];
            v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
            uint8_t g = (uint8_t)lrintf(v * 255.0f);
            uint8_t *d = img->rgb + ((size_t)(y + j) * (size_t)img->w + (size_t)(x + i)) * 3;
            d[0] = d[1] = d[2] = g;
        }
}

static int row_y(int row, int th) { return STRIP_H + row * (STRIP_H + th); }

/* ---- rendering -------------------------------------------------------------------------------- */
/* FRAMES frames of one method; its row goes into the sheet, the median AO pass time into *ao_ms
 * (NaN when the renderer timed no "ao" pass). */
static int render_row(ob_renderer *r, const ob_camera *cam, const ob_settings *s, sheet_image *img, int row,
                      const sheet_opts *o, uint8_t *rgba, float *ao, double *ao_ms)
{
    double ms[FRAMES];
    int timed = 0;
    for (int f = 0; f < FRAMES; ++f) {
        if (ob_render_frame(r, cam, s) != OB_OK) return cli_fail_from_library();
        ob_pass_timing t[16];
        int n = ob_query_timings(r, t, 16);
        for (int p = 0; p < n; ++p)
            if (!strcmp(t[p].name, "ao")) {
                ms[timed++] = t[p].ms;
                break;
            }
    }
    *ao_ms = cli_median(ms, timed);

    size_t px = (size_t)o->width * (size_t)o->height;
    if (ob_read_image(r, OB_IMAGE_FINAL_RGBA8, rgba, px * 4) != OB_OK ||
        ob_read_image(r, OB_IMAGE_AO_F32, ao, px * sizeof(float)) != OB_OK)
        return cli_fail_from_library();
    int y = row_y(row, o->height);
    char label[128];
    const char *name = ob_method_at(s->method)->name;
    if (isnan(*ao_ms)) snprintf(label, sizeof label, "%s  ao -", name);
    else snprintf(label, sizeof label, "%s  ao %.1f ms", name, *ao_ms);
    draw_text(img, PAD + TEXT_INSET, y + TEXT_INSET, img->w - PAD, label);
    put_final_tile(img, PAD, y + STRIP_H, o->width, o->height, rgba);
    put_ao_tile(img, 2 * PAD + o->width, y + STRIP_H, o->width, o->height, ao);
    return EXIT_OK;
}

int cmd_sheet(int argc, char **argv)
{
    sheet_opts o;
    int code = parse(argc, argv, &o);
    if (code != 0) return code < 0 ? EXIT_OK : code;

    /* Everything that can be checked without a GPU is checked first. */
    ob_settings settings[MAX_METHODS];
    int count = 0;
    code = make_settings(&o, settings, &count);
    if (code != 0) return code;
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = o.scene});
    if (!scene) return cli_fail_from_library();
    ob_camera cam;
    if (ob_find_camera(scene, o.camera ? o.camera : "default", &cam) != OB_OK) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }

    ob_context *ctx = cli_make_context(o.gpu, o.verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }
    sheet_image img = {0};
    uint8_t *rgba = NULL;
    float *ao = NULL;
    double ao_ms[MAX_METHODS];
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = o.width, .height = o.height});
    if (!r || ob_renderer_set_scene(r, scene) != OB_OK) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    /* The renderer accepted the tile size (at most GL_MAX_TEXTURE_SIZE), so these sizes fit. */
    img.w = 2 * o.width + 3 * PAD;
    img.h = STRIP_H + count * (STRIP_H + o.height) + PAD;
    size_t px = (size_t)o.width * (size_t)o.height;
    img.rgb = malloc((size_t)img.w * (size_t)img.h * 3);
    rgba = malloc(px * 4);
    ao = malloc(px * sizeof(float));
    if (!img.rgb || !rgba || !ao) {
        code = cli_fail(EXIT_RUNTIME, "out of memory for a %dx%d sheet", img.w, img.h);
        goto cleanup;
    }
    fill_rect(&img, 0, 0, img.w, img.h, STRIP_RGB);
    draw_text(&img, PAD + TEXT_INSET, TEXT_INSET, PAD + o.width, "final");
    draw_text(&img, 2 * PAD + o.width + TEXT_INSET, TEXT_INSET, img.w - PAD, "ao");
    for (int i = 0; i < count && code == EXIT_OK; ++i)
        code = render_row(r, &cam, &settings[i], &img, i, &o, rgba, ao, &ao_ms[i]);
    if (code == EXIT_OK && ob_write_png(o.out, img.w, img.h, 3, img.rgb) != OB_OK)
        code = cli_fail_library_as(EXIT_OUTPUT);
    if (code == EXIT_OK)
        for (int i = 0; i < count; ++i) {
            const char *name = ob_method_at(settings[i].method)->name;
            if (isnan(ao_ms[i])) printf("%-10s ao        - ms\n", name);
            else printf("%-10s ao %8.3f ms\n", name, ao_ms[i]);
        }
cleanup:
    free(img.rgb);
    free(rgba);
    free(ao);
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    return code;
}
