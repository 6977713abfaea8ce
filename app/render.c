/* obscura render: one scene, one method, one camera -> PNG (+ AO as PFM/PNG).
 *
 * --stereo (Belonogov 2018 §5.2): the camera becomes the two eyes of a headset (ob_stereo_cameras), each
 * with its own renderer (its own G-buffer and AO, as a headset renders them); "mirror" writes both
 * side by side (Belonogov 2018's Mirror mode), "single" the left eye alone (its SinglePass mode). Both
 * eyes are rendered in either mode, so that the frame time and the left/right AO consistency
 * (ob_metric_stereo_consistency) are the stereo frame's. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_options.h"
#include "outputs.h"
#include "reference_cache.h"

static void render_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura render [options] --out FILE.png|.jpg|.pfm\n"
          "\n"
          "One scene, one AO method, one camera: the final image, and optionally the AO map, depth\n"
          "and normals.\n"
          "\n"
          "  --out FILE            the final image (required); the format follows the extension: .png,\n"
          "                        .jpg (.jpeg: no alpha) or .pfm (the same pixels as floats, 0..1)\n"
          "  --view V              what --out shows: final (default), ao, normals, depth (grey, 1 - depth\n"
          "                        / far plane), shadow (the key light's visibility), radiance (direct\n"
          "                        light, tone mapped), samples (per pixel, grey, white = the most a\n"
          "                        pixel could take), bounce (SSDO's one-bounce indirect light, sRGB;\n"
          "                        black for AO methods), bent_normals (gtao with bent_normals=on),\n"
          "                        luminance (HDR luminance in false colour, 1/256..16, scale at the bottom),\n"
          "                        second_depth (the second depth layer as depth shows the first; a\n"
          "                        method with layers=2 makes one), extra (the extra view's direct\n"
          "                        light, the camera turned 90 degrees around the target: ssdo with\n"
          "                        extra_view=on), history_age (--temporal on: frames in each pixel's\n"
          "                        history / --temporal-frames; black where reset);\n"
          "                        for ssdo* ao shows the RGB modulation factor M\n"
          "  --ao-out FILE.pfm     the AO map as exact floats (PFM, bottom row first; .png or .jpg: 8-bit)\n"
          "  --ao-png FILE.png     the AO map as an 8-bit grey PNG (or .jpg)\n"
          "  --depth-out FILE.pfm  linear view depth; --normal-out FILE.pfm view-space normals\n"
          "  --frames N            render N frames (timings are medians over them; default 1)\n"
          "  --timings             print GPU time per pass (GL timestamp queries) and the wall-clock\n"
          "                        frame, medians over the measured frames\n"
          "  --warmup N            frames rendered before the measured ones, untimed (shader\n"
          "                        compiles, first-use allocations, shadow maps); default 3 with\n"
          "                        --timings or --frames > 1, else 0\n"
          "  --stereo MODE         both eyes of a headset, each its own renderer: mirror (both side\n"
          "                        by side, every output 2W x H) or single (the left eye alone); prints\n"
          "                        per-eye and both-eye frame ms and the left/right AO consistency\n"
          "                        (mean |AO_right - AO_left reprojected| over pixels both eyes see);\n"
          "                        --size is per eye (default 1080x1200, the HTC Vive's)\n"
          "  --ipd D               --stereo: eye separation in world units (default 0.064)\n"
          "  --convergence D       --stereo: distance of the zero-parallax plane (default: the\n"
          "                        camera's eye-target distance); not with --headset\n"
          "  --headset NAME        --stereo: the headset's per-eye frustum, fov and size (vive)\n"
          "  --reference-spp N     --stereo: also ray trace AO_R for both eyes (N rays per pixel,\n"
          "                        cached) and print its left/right consistency: the noise floor\n",
          f);
    cli_common_usage(f, defaults);
}

typedef enum stereo_mode { STEREO_OFF = 0, STEREO_MIRROR, STEREO_SINGLE } stereo_mode;

typedef struct render_opts {
    cli_common common;
    const char *out, *ao_out, *ao_png, *depth_out, *normal_out;
    ob_view view;
    int frames;
    int warmup; /* -1 = the default: 3 when timing (--timings or --frames > 1), else 0 */
    bool timings;
    stereo_mode stereo;
    const char *headset;
    float ipd, convergence; /* 0 = default */
    int reference_spp;      /* 0 = no reference */
    /* Every output, checked before anything is rendered and written all or nothing: --out (each
     * frame's along a path, frame_outs[f]) and the others' indices in outs, -1 when not asked. */
    cli_outputs *outs;
    int out_index, ao_out_index, ao_png_index, depth_index, normal_index;
    int *frame_outs;
} render_opts;

static void render_defaults(render_opts *o)
{
    *o = (render_opts){.view = OB_VIEW_FINAL, .frames = 1, .warmup = -1, .out_index = -1, .ao_out_index = -1,
                       .ao_png_index = -1, .depth_index = -1, .normal_index = -1};
    cli_common_init(&o->common, "render", CLI_TAKES_SCENE | CLI_TAKES_CAMERA | CLI_TAKES_GPU | CLI_TAKES_PATH);
    o->common.scene = "cornell";
    o->common.default_method = OB_DEFAULT_METHOD;
    o->common.width = 640;
    o->common.height = 480;
}

static void numbered(const char *path, int f, char *out, size_t n);

/* Every output checked and added to o->outs (outputs.h): a bad one fails before the render. Along
 * a path --out is numbered per frame; the other outputs are the last frame's. */
static int add_outputs(render_opts *o)
{
    static const unsigned f32 = CLI_FMT_IMAGE, pfm = CLI_FMT_PFM;
    const struct { const char *option, *path; unsigned formats; int *index; } outs[] = {
        {"--ao-out", o->ao_out, f32, &o->ao_out_index},
        {"--ao-png", o->ao_png, CLI_FMT_PNG | CLI_FMT_JPG, &o->ao_png_index},
        /* Depth and normals are measurements: 8 bits would lose them. */
        {"--depth-out", o->depth_out, pfm, &o->depth_index},
        {"--normal-out", o->normal_out, pfm, &o->normal_index}};
    int code = EXIT_OK;
    if (cli_common_moves(&o->common)) {
        const int frames = o->common.path_frames;
        o->frame_outs = calloc((size_t)frames, sizeof *o->frame_outs);
        if (!o->frame_outs) return cli_fail(EXIT_RUNTIME, "out of memory");
        /* The extension first, once, before the numbered names repeat it. */
        if (!(cli_format_of(o->out) & CLI_FMT_IMAGE) || !*o->out)
            code = cli_outputs_add(o->outs, "--out", o->out, CLI_FMT_IMAGE, &o->out_index);
        for (int f = 0; f < frames && code == EXIT_OK; ++f) {
            char name[1100];
            numbered(o->out, f, name, sizeof name);
            code = cli_outputs_add(o->outs, "--out", name, CLI_FMT_IMAGE, &o->frame_outs[f]);
        }
    } else {
        code = cli_outputs_add(o->outs, "--out", o->out, CLI_FMT_IMAGE, &o->out_index);
    }
    for (size_t i = 0; i < sizeof outs / sizeof outs[0] && code == EXIT_OK; ++i)
        if (outs[i].path) code = cli_outputs_add(o->outs, outs[i].option, outs[i].path, outs[i].formats, outs[i].index);
    return code;
}

static int parse(int argc, char **argv, render_opts *o, cli_outputs *outs)
{
    render_defaults(o);
    o->outs = outs;
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
        const char *const own[] = {"--out",    "--ao-out", "--ao-png",      "--depth-out", "--normal-out",
                                   "--view",   "--frames", "--stereo",      "--ipd",       "--convergence",
                                   "--headset", "--reference-spp", "--warmup"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_unknown_option("render", a, render_usage, &o->common);
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
            if (found < 0) {
                /* From the library's own list, so a new view is named without touching this. */
                char names[512] = "";
                for (int k = 0; k < OB_VIEW_COUNT; ++k) {
                    size_t n = strlen(names);
                    snprintf(names + n, sizeof names - n, "%s%s", k ? ", " : "", ob_view_name((ob_view)k));
                }
                return cli_fail(EXIT_USAGE, "--view: unknown view '%s' (known: %s)", v, names);
            }
            o->view = (ob_view)found;
        } else if (!strcmp(a, "--frames")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > 100000) return cli_fail(EXIT_USAGE, "--frames: expected 1..100000, got '%s'", v);
            o->frames = (int)n;
        } else if (!strcmp(a, "--warmup")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 0 || n > 100000) return cli_fail(EXIT_USAGE, "--warmup: expected 0..100000, got '%s'", v);
            o->warmup = (int)n;
        } else if (!strcmp(a, "--stereo")) {
            if (!strcmp(v, "mirror")) o->stereo = STEREO_MIRROR;
            else if (!strcmp(v, "single")) o->stereo = STEREO_SINGLE;
            else return cli_fail(EXIT_USAGE, "--stereo: expected mirror or single, got '%s'", v);
        } else if (!strcmp(a, "--ipd") || !strcmp(a, "--convergence")) {
            float *dst = !strcmp(a, "--ipd") ? &o->ipd : &o->convergence;
            if (!cli_parse_float(v, dst) || !(*dst > 0.0f) || !isfinite(*dst))
                return cli_fail(EXIT_USAGE, "%s: expected a positive number, got '%s'", a, v);
        } else if (!strcmp(a, "--headset")) {
            ob_headset h;
            if (ob_find_headset(v, &h) != OB_OK) return cli_fail(EXIT_USAGE, "--headset: unknown headset '%s' (known: vive)", v);
            o->headset = v;
        } else if (!strcmp(a, "--reference-spp")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 2 || n > 1 << 20)
                return cli_fail(EXIT_USAGE, "--reference-spp: expected 2..1048576, got '%s'", v);
            o->reference_spp = (int)n;
        }
    }
    if (!o->out) return cli_fail(EXIT_USAGE, "--out FILE is required (see obscura render --help)");
    if (o->stereo && (o->common.path || o->common.has_orbit))
        return cli_fail(EXIT_USAGE, "--stereo and --path/--orbit exclude each other");
    if (o->frames != 1 && (o->common.path || o->common.has_orbit))
        return cli_fail(EXIT_USAGE, "--frames and --path/--orbit exclude each other (--path-frames counts the frames)");
    if (!o->stereo && (o->ipd > 0.0f || o->convergence > 0.0f || o->headset || o->reference_spp))
        return cli_fail(EXIT_USAGE, "--ipd, --convergence, --headset and --reference-spp need --stereo mirror|single");
    if (o->headset && o->convergence > 0.0f)
        return cli_fail(EXIT_USAGE, "--convergence and --headset exclude each other (the headset's frusta are fixed)");
    if (o->headset && o->common.has_fov)
        return cli_fail(EXIT_USAGE, "--fov and --headset exclude each other (the headset fixes the field of view)");
    if (o->stereo && !o->common.has_size) {
        /* Belonogov 2018's headset: 1080x1200 per eye (Belonogov 2018 §5.2). */
        ob_headset h = *ob_headset_at(0);
        if (o->headset) ob_find_headset(o->headset, &h);
        o->common.width = h.width;
        o->common.height = h.height;
    }
    o->common.renderers = o->stereo ? 2 : 1; /* one per eye, both held (--max-memory) */
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    if (o->warmup < 0) o->warmup = o->timings || o->frames > 1 ? 3 : 0;
    return add_outputs(o);
}

/* One image of each of the n eyes side by side, n W x H: each eye's rows are read whole and
 * interleaved, which keeps either row order (both eyes have the same). view >= 0: ob_read_view
 * of that view (4 bytes per pixel); else ob_read_image of kind. */
static ob_error read_side_by_side(ob_renderer *const *eyes, int n, int w, int h, int view, ob_image_kind kind,
                                  size_t pixel_bytes, void *dst, void *scratch)
{
    const size_t eye_bytes = (size_t)w * (size_t)h * pixel_bytes, row = (size_t)w * pixel_bytes;
    for (int e = 0; e < n; ++e) {
        void *to = n == 1 ? dst : scratch;
        ob_error err = view >= 0 ? ob_read_view(eyes[e], (ob_view)view, to, eye_bytes)
                                 : ob_read_image(eyes[e], kind, to, eye_bytes);
        if (err != OB_OK) return err;
        if (n == 1) break;
        for (int y = 0; y < h; ++y)
            memcpy((char *)dst + (size_t)y * row * (size_t)n + (size_t)e * row, (const char *)scratch + (size_t)y * row, row);
    }
    return OB_OK;
}

/* The outputs of the frame the eyes hold into o->outs' temporary files (committed by the caller):
 * what --view shows into out_index, the others when asked (with_rest). */
static int write_outputs(ob_renderer *const *eyes, int n, render_opts *o, int out_index, bool with_rest)
{
    /* Mirror: both eyes side by side in every output; single: the left eye's alone. */
    const int ew = o->common.width, h = o->common.height, w = ew * n;
    size_t px = (size_t)w * (size_t)h;
    int code = EXIT_OK;
    unsigned char *rgba = malloc(px * 4);
    float *buf = malloc(px * 3 * sizeof(float));
    void *scratch = malloc((size_t)ew * (size_t)h * 3 * sizeof(float) + (size_t)ew * (size_t)h * 4);
    if (!rgba || !buf || !scratch) {
        code = cli_fail(EXIT_RUNTIME, "out of memory for %dx%d outputs", w, h);
        goto done;
    }
    /* final: the library's own image; the others through its view pass, the one the viewer shows
     * (ob_present), written without alpha as they always were. */
    const bool final = o->view == OB_VIEW_FINAL;
    if (read_side_by_side(eyes, n, ew, h, final ? -1 : (int)o->view, OB_IMAGE_FINAL_RGBA8, 4, rgba, scratch) != OB_OK) {
        code = cli_fail_from_library();
        goto done;
    }
    if (!final)
        for (size_t i = 0; i < px; ++i) memmove(rgba + 3 * i, rgba + 4 * i, 3);
    if ((code = cli_outputs_write_rgb8(o->outs, out_index, w, h, final ? 4 : 3, rgba)) != EXIT_OK) goto done;
    if (!with_rest) goto done;
    const struct { int index; ob_image_kind kind; int channels; } rest[] = {
        {o->ao_out_index, OB_IMAGE_AO_F32, 1}, {o->ao_png_index, OB_IMAGE_AO_F32, 1},
        {o->depth_index, OB_IMAGE_DEPTH_F32, 1}, {o->normal_index, OB_IMAGE_NORMAL_F32, 3}};
    for (size_t k = 0; k < sizeof rest / sizeof rest[0] && code == EXIT_OK; ++k) {
        if (rest[k].index < 0) continue;
        if (read_side_by_side(eyes, n, ew, h, -1, rest[k].kind, (size_t)rest[k].channels * sizeof(float), buf, scratch) !=
            OB_OK)
            code = cli_fail_from_library();
        else
            code = cli_outputs_write_f32(o->outs, rest[k].index, w, h, rest[k].channels, buf);
    }
done:
    free(rgba);
    free(buf);
    free(scratch);
    return code;
}

/* -v: the last frame's exposure, so that another frame can be tone mapped at the same scale
 * (scripts/demo.sh shows the frame without AO at the with-AO frame's exposure): the scale is
 * exposure x key / L_avg, L_avg of the radiance before exposure, so a frame of log-average L2
 * rendered with --key K --exposure L2/L gets exactly the scale K / L of this one. The log-average
 * is the CPU formula the luminance pass is tested against, over the same composed radiance. */
static void print_exposure(ob_renderer *r, int w, int h, const ob_hdr_settings *hdr)
{
    size_t px = (size_t)w * (size_t)h;
    float *rgb = malloc(px * 3 * sizeof(float));
    double avg = rgb ? cli_frame_log_average(r, rgb, px) : NAN;
    free(rgb);
    if (isnan(avg)) {
        fprintf(stderr, "obscura: hdr: the frame's radiance could not be read back\n");
        return;
    }
    float key = hdr->key > 0.0f ? hdr->key : ob_hdr_auto_key((float)avg);
    fprintf(stderr, "obscura: hdr: log-average %.9g, key %.9g, exposure %.9g (scale exposure x key / log-average)\n", avg,
            (double)key, (double)hdr->exposure);
}

/* AO_R ray traced from each eye's own G-buffer points (a `none` frame of each eye, so before the
 * method's frames): *out gets left AO, right AO, left depth, right depth, W x H floats each. */
static int trace_references(ob_renderer *const *eyes, const ob_camera *cams, const render_opts *o,
                            const ob_scene *scene, float **out)
{
    const int w = o->common.width, h = o->common.height;
    const size_t px = (size_t)w * (size_t)h;
    float *buf = malloc(px * 4 * sizeof(float));
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    const float radius = ob_query_scene_ao_radius(scene);
    int code = EXIT_OK;
    for (int e = 0; e < 2 && code == EXIT_OK; ++e) {
        cli_view_frame f;
        if ((code = cli_view_frame_make(eyes[e], &cams[e], w, h, &f)) != EXIT_OK) break;
        char key[900] = "";
        cli_reference_key(&o->common, o->common.scene, cams[e].name, key, sizeof key);
        cli_reference_info info;
        code = cli_reference_ao(scene, &f, key, radius, o->reference_spp, false, o->common.verbose, buf + (size_t)e * px,
                                &info);
        memcpy(buf + (size_t)(2 + e) * px, f.depth, px * sizeof(float));
        cli_view_frame_free(&f);
    }
    if (code != EXIT_OK) {
        free(buf);
        return code;
    }
    *out = buf;
    return EXIT_OK;
}

/* The left/right consistency (ob_metric_stereo_consistency) of both eyes' AO, and of the
 * reference AO_R when traced: the floor (AO_R belongs to the surface point, so only its Monte
 * Carlo noise and the resampling remain). A pair with no pixel both eyes see is a note. */
static int report_consistency(ob_renderer *const *eyes, const ob_camera *cams, const render_opts *o, int method,
                              const float *reference, float reference_radius)
{
    const int w = o->common.width, h = o->common.height;
    const size_t px = (size_t)w * (size_t)h;
    float *buf = malloc(px * 4 * sizeof(float));
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    for (int e = 0; e < 2; ++e)
        if (ob_read_image(eyes[e], OB_IMAGE_AO_F32, buf + (size_t)e * px, px * sizeof(float)) != OB_OK ||
            ob_read_image(eyes[e], OB_IMAGE_DEPTH_F32, buf + (size_t)(2 + e) * px, px * sizeof(float)) != OB_OK) {
            free(buf);
            return cli_fail_from_library();
        }
    for (int k = 0; k < (reference ? 2 : 1); ++k) {
        const float *src = k == 0 ? buf : reference;
        ob_stereo_view views[2];
        for (int e = 0; e < 2; ++e)
            views[e] = (ob_stereo_view){.ao = src + (size_t)e * px, .linear_depth = src + (size_t)(2 + e) * px,
                                        .width = w, .height = h, .camera = cams[e]};
        char what[96];
        if (k == 0) snprintf(what, sizeof what, "%s", ob_method_at(method)->name);
        else snprintf(what, sizeof what, "reference AO_R, R %g, %d spp", (double)reference_radius, o->reference_spp);
        ob_stereo_consistency sc;
        const char *msg = "";
        if (ob_metric_stereo_consistency(&views[0], &views[1], 0.0f, &sc) == OB_OK)
            printf("stereo consistency (%s): mean |AO_right - AO_left reprojected| %.4f over %.1f %% of the right eye's "
                   "geometry pixels\n", what, sc.mean_abs, 100.0 * sc.fraction);
        else if (ob_get_error(&msg) != OB_OK)
            fprintf(stderr, "obscura render: note: no stereo consistency for %s: %s\n", what, msg);
    }
    free(buf);
    return EXIT_OK;
}

/* FILE.png -> FILE-0007.png (the number before the last extension, or at the end without one). */
static void numbered(const char *path, int f, char *out, size_t n)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) dot = path + strlen(path);
    snprintf(out, n, "%.*s-%04d%s", (int)(dot - path), path, f, dot);
}

/* --path / --orbit: the frames along it, --out numbered per frame (what --view shows), the other
 * outputs of the last frame; --timings as medians over the path. Written all or nothing by the
 * caller's commit. */
static int render_path(ob_renderer *r, const ob_camera *base, const ob_scene *scene, const ob_settings *settings,
                       render_opts *o)
{
    const cli_common *c = &o->common;
    const int frames = c->path_frames;
    double *ms = calloc((size_t)frames, sizeof(double));
    double *ao_ms = calloc((size_t)frames, sizeof(double));
    double *temporal_ms = calloc((size_t)frames, sizeof(double));
    if (!ms || !ao_ms || !temporal_ms) {
        free(ms);
        free(ao_ms);
        free(temporal_ms);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    int code = EXIT_OK;
    for (int f = 0; f < frames && code == EXIT_OK; ++f) {
        ob_camera cam;
        if ((code = cli_common_path_camera(c, scene, base, f, &cam)) != EXIT_OK) break;
        if (ob_render_frame(r, &cam, settings) != OB_OK) {
            code = cli_fail_from_library();
            break;
        }
        char which[96];
        snprintf(which, sizeof which, "%s frame %d", cam.name, f);
        if ((code = cli_check_visible(r, c->width, c->height, ob_query_scene_name(scene), which, c->allow_empty,
                                      EXIT_USAGE)) != EXIT_OK)
            break;
        ob_pass_timing t[20];
        int n = ob_query_timings(r, t, 20);
        for (int p = 0; p < n; ++p) {
            ms[f] += t[p].ms;
            if (!strcmp(t[p].name, "ao")) ao_ms[f] = t[p].ms;
            if (!strcmp(t[p].name, "temporal")) temporal_ms[f] = t[p].ms;
        }
        ob_renderer *one[1] = {r};
        code = write_outputs(one, 1, o, o->frame_outs[f], f == frames - 1);
    }
    if (code == EXIT_OK) {
        const char *first = o->outs->items[o->frame_outs[0]].path, *last = o->outs->items[o->frame_outs[frames - 1]].path;
        if (c->path) printf("%d frames along path %s: %s .. %s\n", frames, c->path, first, last);
        else printf("%d frames along an orbit of %g degrees: %s .. %s\n", frames, (double)c->orbit_deg, first, last);
        if (o->timings)
            printf("frame %.3f ms, ao %.3f ms, temporal %.3f ms (GPU medians over the path)\n", cli_median(ms, frames),
                   cli_median(ao_ms, frames), cli_median(temporal_ms, frames));
    }
    free(ms);
    free(ao_ms);
    free(temporal_ms);
    return code;
}

static int render_checked(render_opts *op);

int cmd_render(int argc, char **argv)
{
    render_opts o;
    cli_outputs outs = {0};
    int code = parse(argc, argv, &o, &outs);
    if (code == 0) code = render_checked(&o);
    /* Every output or none: the temporary files are renamed only when all were written. */
    code = cli_outputs_finish(&outs, code < 0 ? EXIT_OK : code);
    free(o.frame_outs);
    return code;
}

static int render_checked(render_opts *op)
{
    render_opts o = *op; /* o.outs is the caller's set */
    int code = EXIT_OK;
    const cli_common *c = &o.common;

    /* Everything that can be checked without a GPU is checked first. */
    cli_config *configs = NULL;
    int count = 0;
    if ((code = cli_common_configs(c, &configs, &count)) != EXIT_OK) return code;
    const ob_settings settings = configs[0].settings; /* no lists: one configuration */
    free(configs);

    ob_scene *scene = NULL;
    if ((code = cli_common_load_scene(c, NULL, &scene)) != EXIT_OK) return code;
    ob_camera cam = {0};
    if ((code = cli_common_camera(c, scene, NULL, &cam)) != EXIT_OK) {
        ob_destroy_scene(scene);
        return code;
    }
    /* Stereo: the eyes (left, right), each its own renderer (own G-buffer and AO). */
    const int eye_count = o.stereo ? 2 : 1;
    ob_camera cams[2] = {cam, cam};
    if (o.stereo && ob_stereo_cameras(&cam,
                                      &(ob_stereo_desc){.ipd = o.ipd, .convergence = o.convergence,
                                                        .aspect = (float)c->width / (float)c->height,
                                                        .headset = o.headset},
                                      cams) != OB_OK) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }

    ob_context *ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }
    ob_renderer *eyes[2] = {NULL, NULL};
    enum { MAX_PASSES = 16 };
    double *samples = NULL;
    float *reference = NULL;
    for (int e = 0; e < eye_count && code == EXIT_OK; ++e) {
        eyes[e] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
        if (!eyes[e] || ob_renderer_set_scene(eyes[e], scene) != OB_OK) code = cli_fail_from_library();
        else code = cli_common_prepare(c, eyes[e]);
    }
    if (code != EXIT_OK) goto cleanup;
    if (cli_common_moves(c)) {
        code = render_path(eyes[0], &cam, scene, &settings, &o);
        goto cleanup;
    }
    if (o.reference_spp > 0 && (code = trace_references(eyes, cams, &o, scene, &reference)) != EXIT_OK) goto cleanup;
    /* Per eye, pass, frame; the frame's total per eye after the passes. */
    samples = calloc((size_t)eye_count * (size_t)o.frames * (MAX_PASSES + 2), sizeof(double));
    double *wall = samples + (size_t)eye_count * (size_t)o.frames * (MAX_PASSES + 1); /* ms per frame, all eyes */
    const char *names[MAX_PASSES] = {0};
    int pass_count = 0;
    if (!samples) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }
    /* Warm-up frames first: the first frame pays for shader compiles, first-use allocations and
     * shadow maps (ssdo's upsample: 122 ms cold, 9 ms warm), which no later frame does. */
    for (int f = 0; f < o.warmup && code == EXIT_OK; ++f)
        for (int e = 0; e < eye_count && code == EXIT_OK; ++e)
            if (ob_render_frame(eyes[e], &cams[e], &settings) != OB_OK) code = cli_fail_from_library();
    for (int f = 0; f < o.frames && code == EXIT_OK; ++f) {
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (int e = 0; e < eye_count && code == EXIT_OK; ++e) {
            /* Wait: this frame's own timings (the ring would give an older frame's). */
            if (ob_render_frame(eyes[e], &cams[e], &settings) != OB_OK || ob_wait_timings(eyes[e]) != OB_OK) {
                code = cli_fail_from_library();
                break;
            }
            ob_pass_timing t[MAX_PASSES];
            int n = ob_query_timings(eyes[e], t, MAX_PASSES);
            double *es = samples + (size_t)e * (size_t)o.frames * (MAX_PASSES + 1);
            for (int i = 0; i < n; ++i) {
                /* By name: a pass that skips a frame (cached shadow maps) keeps its own column. */
                int p = 0;
                while (p < pass_count && strcmp(names[p], t[i].name) != 0) ++p;
                if (p == pass_count && pass_count < MAX_PASSES) names[pass_count++] = t[i].name;
                if (p == MAX_PASSES) continue;
                es[(size_t)p * (size_t)o.frames + (size_t)f] = t[i].ms;
                es[(size_t)MAX_PASSES * (size_t)o.frames + (size_t)f] += t[i].ms;
            }
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        wall[f] = 1e3 * (double)(t1.tv_sec - t0.tv_sec) + 1e-6 * (double)(t1.tv_nsec - t0.tv_nsec);
    }
    if (code == EXIT_OK && o.timings) {
        const ob_scene_stats st = ob_query_scene_stats(scene);
        printf("%s, %s, %dx%d%s, %u triangles, %d frame(s) after %d warm-up, %s\n", ob_query_scene_name(scene),
               ob_method_at(settings.method)->name, c->width, c->height, o.stereo ? " per eye" : "", st.triangles,
               o.frames, o.warmup, ob_query_renderer(ctx));
        printf("%-10s %10s %10s %10s%s\n", "pass", "median ms", "min ms", "max ms", o.stereo ? " (left eye)" : "");
        for (int p = 0; p < pass_count; ++p) {
            double *s = samples + (size_t)p * (size_t)o.frames;
            double med = cli_median(s, o.frames); /* sorts s: s[0] is the min */
            printf("%-10s %10.3f %10.3f %10.3f\n", names[p], med, s[0], s[o.frames - 1]);
        }
        /* The per-frame sum of passes (not the sum of per-pass medians), beside the wall-clock
         * frame that contains it (render + wait for the GPU, every eye). */
        double *sum = samples + (size_t)MAX_PASSES * (size_t)o.frames;
        double *total = calloc((size_t)o.frames, sizeof(double));
        if (total) {
            memcpy(total, sum, (size_t)o.frames * sizeof(double));
            double med = cli_median(total, o.frames);
            printf("%-10s %10.3f %10.3f %10.3f\n", "GPU sum", med, total[0], total[o.frames - 1]);
            free(total);
        }
        if (!o.stereo) {
            double med = cli_median(wall, o.frames);
            printf("%-10s %10.3f %10.3f %10.3f (wall clock)\n", "frame", med, wall[0], wall[o.frames - 1]);
        }
    }
    if (code == EXIT_OK && o.stereo) {
        /* The stereo frame against the headset's 90 Hz (Belonogov 2018 §5.2): medians of each eye's
         * per-frame sum of passes, and of both eyes' sum. */
        double *both = calloc((size_t)o.frames, sizeof(double));
        if (!both) code = cli_fail(EXIT_RUNTIME, "out of memory");
        double eye_ms[2] = {0.0, 0.0};
        for (int e = 0; e < 2 && both; ++e) {
            double *tot = samples + (size_t)e * (size_t)o.frames * (MAX_PASSES + 1) + (size_t)MAX_PASSES * (size_t)o.frames;
            for (int f = 0; f < o.frames; ++f) both[f] += tot[f];
            eye_ms[e] = cli_median(tot, o.frames);
        }
        if (both) {
            double both_ms = cli_median(both, o.frames);
            printf("stereo frame (%s, %dx%d per eye, %d frame(s), GPU ms): left %.3f, right %.3f, both %.3f (%s the "
                   "11.1 ms budget at 90 Hz)\n", o.stereo == STEREO_MIRROR ? "mirror" : "single", c->width, c->height,
                   o.frames, eye_ms[0], eye_ms[1], both_ms, both_ms <= 1000.0 / 90.0 ? "within" : "over");
            free(both);
        }
        if (code == EXIT_OK)
            code = report_consistency(eyes, cams, &o, settings.method, reference, ob_query_scene_ao_radius(scene));
    }
    for (int e = 0; e < eye_count && code == EXIT_OK; ++e)
        code = cli_check_visible(eyes[e], c->width, c->height, ob_query_scene_name(scene), cams[e].name, c->allow_empty,
                                 c->has_eye ? EXIT_USAGE : EXIT_INPUT);
    if (code == EXIT_OK && c->verbose && settings.hdr.enabled) print_exposure(eyes[0], c->width, c->height, &settings.hdr);
    if (code == EXIT_OK) code = write_outputs(eyes, o.stereo == STEREO_MIRROR ? 2 : 1, &o, o.out_index, true);
cleanup:
    free(samples);
    free(reference);
    for (int e = 0; e < 2; ++e) ob_destroy_renderer(eyes[e]);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    return code;
}
