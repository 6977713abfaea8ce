/* obscura render: one scene, one method, one camera -> PNG (+ AO as PFM/PNG). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_options.h"

static void render_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura render [options] --out FILE.png\n"
          "\n"
          "One scene, one AO method, one camera: the final image, and optionally the AO map, depth\n"
          "and normals.\n"
          "\n"
          "  --out FILE.png        the final image (required)\n"
          "  --view V              what --out shows: final (default), ao, normals, depth (grey, 1 - depth\n"
          "                        / far plane), shadow (the key light's visibility), radiance (direct\n"
          "                        light, tone mapped), samples (per pixel, grey, white = the most a\n"
          "                        pixel could take), bounce (SSDO's one-bounce indirect light, sRGB;\n"
          "                        black for AO methods), bent_normals (gtao with bent_normals=on),\n"
          "                        luminance (HDR luminance in false colour, 1/256..16, scale at the bottom),\n"
          "                        second_depth (the second depth layer as depth shows the first; a\n"
          "                        method with layers=2 makes one);\n"
          "                        for ssdo* ao shows the RGB modulation factor M\n"
          "  --ao-out FILE.pfm     the AO map as exact floats (PFM, bottom row first)\n"
          "  --ao-png FILE.png     the AO map as an 8-bit grey PNG\n"
          "  --depth-out FILE.pfm  linear view depth; --normal-out FILE.pfm view-space normals\n"
          "  --frames N            render N frames (timings are medians over them; default 1)\n"
          "  --timings             print GPU time per pass (GL timestamp queries)\n",
          f);
    cli_common_usage(f, defaults);
}

typedef struct render_opts {
    cli_common common;
    const char *out, *ao_out, *ao_png, *depth_out, *normal_out;
    ob_view view;
    int frames;
    bool timings;
} render_opts;

static void render_defaults(render_opts *o)
{
    *o = (render_opts){.view = OB_VIEW_FINAL, .frames = 1};
    cli_common_init(&o->common, "render", CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_GPU);
    o->common.scene = "cornell";
    /* The method closest to the ray-traced AO_R on every graded view (docs/compare.md). */
    o->common.default_method = "gtao";
    o->common.width = 640;
    o->common.height = 480;
}

static int parse(int argc, char **argv, render_opts *o)
{
    render_defaults(o);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            render_usage(stdout, &o->common);
            return -1;
        }
        if (!strcmp(a, "--timings")) {
            o->timings = true;
            continue;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        const char *const own[] = {"--out", "--ao-out", "--ao-png", "--depth-out", "--normal-out", "--view", "--frames"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura render --help)", a);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura render --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--ao-out")) o->ao_out = v;
        else if (!strcmp(a, "--ao-png")) o->ao_png = v;
        else if (!strcmp(a, "--depth-out")) o->depth_out = v;
        else if (!strcmp(a, "--normal-out")) o->normal_out = v;
        else if (!strcmp(a, "--view")) {
            int found = -1;
            for (int k = 0; k < OB_VIEW_COUNT; ++k)
                if (!strcmp(v, ob_view_name((ob_view)k))) found = k;
            if (found < 0)
                return cli_fail(EXIT_USAGE, "--view: expected final, ao, normals, depth, shadow, radiance, samples or bounce, got '%s'", v);
            o->view = (ob_view)found;
        } else if (!strcmp(a, "--frames")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > 100000) return cli_fail(EXIT_USAGE, "--frames: expected 1..100000, got '%s'", v);
            o->frames = (int)n;
        }
    }
    if (!o->out) return cli_fail(EXIT_USAGE, "--out FILE.png is required (see obscura render --help)");
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    const char *outs[5] = {o->out, o->ao_out, o->ao_png, o->depth_out, o->normal_out};
    for (int i = 0; i < 5; ++i)
        if (outs[i] && !cli_output_writable(outs[i]))
            return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", outs[i]);
    return 0;
}

static void flip_rows_to_grey(const float *ao, int w, int h, unsigned char *out)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float v = ao[(size_t)(h - 1 - y) * (size_t)w + (size_t)x];
            v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
            out[(size_t)y * (size_t)w + (size_t)x] = (unsigned char)lrintf(v * 255.0f);
        }
}

/* Outputs written so far in this run: removed again if a later one fails, so a failed run
 * leaves no partial set of files behind. */
static const char *written[8];
static int written_count;

static ob_error track(ob_error err, const char *path)
{
    if (err == OB_OK && written_count < 8) written[written_count++] = path;
    return err;
}

static int write_outputs_tracked(ob_renderer *r, const render_opts *o);

static int write_outputs(ob_renderer *r, const render_opts *o)
{
    written_count = 0;
    int code = write_outputs_tracked(r, o);
    if (code != EXIT_OK)
        for (int i = 0; i < written_count; ++i) remove(written[i]);
    return code;
}

static int write_outputs_tracked(ob_renderer *r, const render_opts *o)
{
    const int w = o->common.width, h = o->common.height;
    size_t px = (size_t)w * (size_t)h;
    int code = EXIT_OK;
    unsigned char *rgba = malloc(px * 4);
    float *buf = malloc(px * 3 * sizeof(float));
    unsigned char *grey = malloc(px);
    if (!rgba || !buf || !grey) {
        code = cli_fail(EXIT_RUNTIME, "out of memory for %dx%d outputs", w, h);
        goto done;
    }
    if (o->view == OB_VIEW_FINAL) {
        if (ob_read_image(r, OB_IMAGE_FINAL_RGBA8, rgba, px * 4) != OB_OK) {
            code = cli_fail_from_library();
            goto done;
        }
        if (track(ob_write_png(o->out, w, h, 4, rgba), o->out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
    } else {
        /* The library's view pass, the one the viewer shows (ob_present); the debug views are
         * written without alpha, as they always were. */
        if (ob_read_view(r, o->view, rgba, px * 4) != OB_OK) {
            code = cli_fail_from_library();
            goto done;
        }
        for (size_t i = 0; i < px; ++i) memmove(rgba + 3 * i, rgba + 4 * i, 3);
        if (track(ob_write_png(o->out, w, h, 3, rgba), o->out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
    }
    if (o->ao_out || o->ao_png) {
        if (ob_read_image(r, OB_IMAGE_AO_F32, buf, px * sizeof(float)) != OB_OK) {
            code = cli_fail_from_library();
            goto done;
        }
        if (o->ao_out && track(ob_write_pfm(o->ao_out, w, h, 1, buf), o->ao_out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
        if (o->ao_png) {
            flip_rows_to_grey(buf, w, h, grey);
            if (track(ob_write_png(o->ao_png, w, h, 1, grey), o->ao_png) != OB_OK) {
                code = cli_fail_library_as(EXIT_OUTPUT);
                goto done;
            }
        }
    }
    if (o->depth_out && (ob_read_image(r, OB_IMAGE_DEPTH_F32, buf, px * sizeof(float)) != OB_OK ||
                         track(ob_write_pfm(o->depth_out, w, h, 1, buf), o->depth_out) != OB_OK)) {
        code = cli_fail_library_as(EXIT_OUTPUT);
        goto done;
    }
    if (o->normal_out && (ob_read_image(r, OB_IMAGE_NORMAL_F32, buf, px * 3 * sizeof(float)) != OB_OK ||
                          track(ob_write_pfm(o->normal_out, w, h, 3, buf), o->normal_out) != OB_OK)) {
        code = cli_fail_library_as(EXIT_OUTPUT);
        goto done;
    }
done:
    free(rgba);
    free(buf);
    free(grey);
    return code;
}

int cmd_render(int argc, char **argv)
{
    render_opts o;
    int code = parse(argc, argv, &o);
    if (code != 0) return code < 0 ? EXIT_OK : code;
    const cli_common *c = &o.common;

    /* Everything that can be checked without a GPU is checked first. */
    cli_config *configs = NULL;
    int count = 0;
    if ((code = cli_common_configs(c, &configs, &count)) != EXIT_OK) return code;
    const ob_settings settings = configs[0].settings; /* no lists: one configuration */
    free(configs);

    ob_scene *scene = cli_common_load_scene(c, NULL);
    if (!scene) return cli_fail_from_library();
    ob_camera cam = {0};
    if ((code = cli_common_camera(c, scene, NULL, &cam)) != EXIT_OK) {
        ob_destroy_scene(scene);
        return code;
    }

    ob_context *ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!r || ob_renderer_set_scene(r, scene) != OB_OK) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    if ((code = cli_common_prepare(c, r)) != EXIT_OK) goto cleanup;
    enum { MAX_PASSES = 16 };
    double *samples = calloc((size_t)o.frames * MAX_PASSES, sizeof(double));
    const char *names[MAX_PASSES] = {0};
    int pass_count = 0;
    if (!samples) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }
    for (int f = 0; f < o.frames && code == EXIT_OK; ++f) {
        if (ob_render_frame(r, &cam, &settings) != OB_OK) {
            code = cli_fail_from_library();
            break;
        }
        ob_pass_timing t[MAX_PASSES];
        pass_count = ob_query_timings(r, t, MAX_PASSES);
        for (int p = 0; p < pass_count; ++p) {
            names[p] = t[p].name;
            samples[(size_t)p * (size_t)o.frames + (size_t)f] = t[p].ms;
        }
    }
    if (code == EXIT_OK && o.timings) {
        const ob_scene_stats st = ob_query_scene_stats(scene);
        printf("%s, %s, %dx%d, %u triangles, %d frame(s), %s\n", ob_query_scene_name(scene),
               ob_method_at(settings.method)->name, c->width, c->height, st.triangles, o.frames, ob_query_renderer(ctx));
        printf("%-10s %10s %10s %10s\n", "pass", "median ms", "min ms", "max ms");
        double total = 0.0;
        for (int p = 0; p < pass_count; ++p) {
            double *s = samples + (size_t)p * (size_t)o.frames;
            double med = cli_median(s, o.frames);
            total += med;
            printf("%-10s %10.3f %10.3f %10.3f\n", names[p], med, s[0], s[o.frames - 1]);
        }
        printf("%-10s %10.3f\n", "total", total);
    }
    free(samples);
    if (code == EXIT_OK) code = write_outputs(r, &o);
cleanup:
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    return code;
}
