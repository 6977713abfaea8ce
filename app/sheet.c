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

#include "cli_options.h"
#include "outputs.h"

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
    FRAMES = 3,      /* frames per method; the label shows the median AO pass time */
};
static const uint8_t STRIP_RGB[3] = {224, 224, 224};
static const uint8_t TEXT_RGB[3] = {16, 16, 16};

static void sheet_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura sheet --scene NAME --out FILE.png|.jpg|.pfm [options]\n"
          "\n"
          "A contact sheet: one row per AO method (per combination of the lists), the final image and\n"
          "the AO map side by side, each row labelled with its settings and the median GPU time of\n"
          "its AO pass (3 frames). --size is the size of each tile.\n"
          "\n"
          "  --out FILE            the sheet (required); the format follows the extension: .png, .jpg\n"
          "                        (.jpeg) or .pfm (the same pixels as floats, 0..1)\n",
          f);
    cli_common_usage(f, defaults);
}

typedef struct sheet_opts {
    cli_common common;
    const char *out;
    cli_outputs *outs; /* --out, checked before anything is rendered, written only whole */
    int out_index;
} sheet_opts;

static int parse(int argc, char **argv, sheet_opts *o, cli_outputs *outs)
{
    *o = (sheet_opts){.out = NULL, .outs = outs, .out_index = -1};
    cli_common_init(&o->common, "sheet", CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_LISTS | CLI_TAKES_GPU);
    o->common.default_method = NULL; /* every method */
    o->common.scene = "cornell";      /* every command's default scene */
    o->common.width = 320;
    o->common.height = 240;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            sheet_usage(stdout, &o->common);
            return -1;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        if (strcmp(a, "--out") != 0) return cli_unknown_option("sheet", a, sheet_usage, &o->common);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura sheet --help)", a);
        o->out = argv[++i];
    }
    if (!o->out) return cli_fail(EXIT_USAGE, "--out FILE is required (see obscura sheet --help)");
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    return cli_outputs_add(o->outs, "--out", o->out, CLI_FMT_IMAGE, &o->out_index);
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
/* FRAMES frames of one configuration; its row goes into the sheet, the median AO pass time into
 * *ao_ms (NaN when the renderer timed no "ao" pass). */
static int render_row(ob_renderer *r, const ob_camera *cam, const cli_config *cfg, const char *name, sheet_image *img,
                      int row, const cli_common *c, cli_exposure *exposure, uint8_t *rgba, float *ao, double *ao_ms)
{
    double ms[FRAMES];
    int timed = 0;
    for (int f = 0; f < FRAMES; ++f) {
        /* Wait: each frame's own timings, not a ring's older one. */
        if (ob_render_frame(r, cam, &cfg->settings) != OB_OK || ob_wait_timings(r) != OB_OK)
            return cli_fail_from_library();
        ob_pass_timing t[16];
        int n = ob_query_timings(r, t, 16);
        for (int p = 0; p < n; ++p)
            if (!strcmp(t[p].name, "ao")) {
                ms[timed++] = t[p].ms;
                break;
            }
    }
    *ao_ms = cli_median(ms, timed);
    /* Every row's final image at the exposure of the view without AO, so rows differ by the AO. */
    int code = cli_exposure_apply(exposure, r, cam, &cfg->settings);
    if (code != EXIT_OK) return code;

    size_t px = (size_t)c->width * (size_t)c->height;
    if (ob_read_image(r, OB_IMAGE_FINAL_RGBA8, rgba, px * 4) != OB_OK ||
        ob_read_image(r, OB_IMAGE_AO_F32, ao, px * sizeof(float)) != OB_OK)
        return cli_fail_from_library();
    int y = row_y(row, c->height);
    char label[CLI_MAX_LABEL + 32] = "";
    if (isnan(*ao_ms)) snprintf(label, sizeof label, "%s  ao -", name);
    else snprintf(label, sizeof label, "%s  ao %.1f ms", name, *ao_ms);
    draw_text(img, PAD + TEXT_INSET, y + TEXT_INSET, img->w - PAD, label);
    put_final_tile(img, PAD, y + STRIP_H, c->width, c->height, rgba);
    put_ao_tile(img, 2 * PAD + c->width, y + STRIP_H, c->width, c->height, ao);
    return EXIT_OK;
}

static int sheet_checked(const sheet_opts *op);

int cmd_sheet(int argc, char **argv)
{
    sheet_opts o;
    cli_outputs outs = {0};
    int code = parse(argc, argv, &o, &outs);
    if (code == 0) code = sheet_checked(&o);
    /* The sheet is written only whole (outputs.h). */
    return cli_outputs_finish(&outs, code < 0 ? EXIT_OK : code);
}

static int sheet_checked(const sheet_opts *op)
{
    const sheet_opts o = *op;
    int code = EXIT_OK;
    const cli_common *c = &o.common;

    /* Everything that can be checked without a GPU is checked first. */
    cli_config *configs = NULL;
    int count = 0;
    if ((code = cli_common_configs(c, &configs, &count)) != EXIT_OK) return code;
    ob_scene *scene = NULL;
    int loaded = cli_common_load_scene(c, NULL, &scene);
    if (loaded != EXIT_OK) {
        free(configs);
        return loaded;
    }
    ob_camera cam = {0};
    if ((code = cli_common_camera(c, scene, NULL, &cam)) != EXIT_OK) {
        free(configs);
        ob_destroy_scene(scene);
        return code;
    }

    ob_context *ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        free(configs);
        ob_destroy_scene(scene);
        return code;
    }
    sheet_image img = {0};
    cli_exposure exposure = {0};
    uint8_t *rgba = NULL;
    float *ao = NULL;
    double *ao_ms = calloc((size_t)count, sizeof *ao_ms);
    /* The sheet's font is ASCII only: its labels separate the settings with commas. */
    char(*names)[CLI_MAX_LABEL] = calloc((size_t)count, sizeof *names);
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!r || ob_renderer_set_scene(r, scene) != OB_OK) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    if ((code = cli_common_prepare(c, r)) != EXIT_OK) goto cleanup;
    /* The renderer accepted the tile size (at most GL_MAX_TEXTURE_SIZE), so these sizes fit. */
    img.w = 2 * c->width + 3 * PAD;
    img.h = STRIP_H + count * (STRIP_H + c->height) + PAD;
    size_t px = (size_t)c->width * (size_t)c->height;
    img.rgb = malloc((size_t)img.w * (size_t)img.h * 3);
    rgba = malloc(px * 4);
    ao = malloc(px * sizeof(float));
    if (!img.rgb || !rgba || !ao || !ao_ms || !names) {
        code = cli_fail(EXIT_RUNTIME, "out of memory for a %dx%d sheet", img.w, img.h);
        goto cleanup;
    }
    if ((code = cli_exposure_begin(&exposure, r, &cam, &configs[0].settings, px)) != EXIT_OK) goto cleanup;
    fill_rect(&img, 0, 0, img.w, img.h, STRIP_RGB);
    draw_text(&img, PAD + TEXT_INSET, TEXT_INSET, PAD + c->width, "final");
    draw_text(&img, 2 * PAD + c->width + TEXT_INSET, TEXT_INSET, img.w - PAD, "ao");
    for (int i = 0; i < count && code == EXIT_OK; ++i) {
        cli_config_label(c, &configs[i], ", ", names[i], sizeof names[i]);
        code = render_row(r, &cam, &configs[i], names[i], &img, i, c, &exposure, rgba, ao, &ao_ms[i]);
        /* Every row has the same camera: the first tells whether it sees anything. */
        if (code == EXIT_OK && i == 0)
            code = cli_check_visible(r, c->width, c->height, ob_query_scene_name(scene), cam.name, c->allow_empty,
                                     c->has_eye ? EXIT_USAGE : EXIT_INPUT);
    }
    if (code == EXIT_OK) code = cli_outputs_write_rgb8(o.outs, o.out_index, img.w, img.h, 3, img.rgb);
    if (code == EXIT_OK)
        for (int i = 0; i < count; ++i) {
            if (isnan(ao_ms[i])) printf("%-10s ao        - ms\n", names[i]);
            else printf("%-10s ao %8.3f ms\n", names[i], ao_ms[i]);
        }
cleanup:
    cli_exposure_free(&exposure);
    free(img.rgb);
    free(rgba);
    free(ao);
    free(ao_ms);
    free(names);
    free(configs);
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    return code;
}
