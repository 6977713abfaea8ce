/* obscura compare: every method on the same inputs against the ray-traced ground truth, written
 * as an HTML report (index.html), results.json and PNGs.
 *
 *   report/index.html                    per view: images, error maps, sortable table, chart
 *   report/results.json                  every number
 *   report/VIEW/reference_ao.png         AO_R from the Embree reference (docs/architecture.md)
 *   report/VIEW/METHOD_final.png, _ao.png, _error.png
 *   report/VIEW/mask_NAME.png            where each metric mask lies (ob_metric_masks)
 *   report/VIEW/chart.svg                quality (RMSE) against GPU time, made with gnuplot
 *
 * The reference is cached by (scene, camera, size, radius, spp) under $XDG_CACHE_HOME/obscura
 * (or ~/.cache/obscura): the report is re-run far more often than the geometry changes. */
#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli_options.h"
#include "flicker.h"
#include "graded_views.h"
#include "outputs.h"
#include "progress.h"
#include "reference_cache.h"
#include "run_program.h"

/* compare without --report writes here (in the current directory). */
#define CLI_DEFAULT_REPORT "obscura-report"

enum { MAX_VIEWS = 32, FRAMES = 5 }; /* 32 views: both sets of scenes/views.json fit one run each */

typedef struct compare_opts {
    cli_common common;
    const char *views[MAX_VIEWS]; /* "scene" or "scene:camera" */
    int view_count;
    const char *report;
    int spp;
    float radius;                 /* 0 = the scene's suggested radius */
    bool no_cache;
    double budget_ms;             /* --budget-ms: the equal-time shoot-out; 0 = none */
    /* --report is built in a temporary directory beside it (report then names that one) and
     * replaces it only when the whole report was written (outputs.h). */
    const char *final_report;
    cli_outputs *outs;
    int report_index;
    int argc;                     /* the command line as given: results.json records it */
    char **argv;
    ob_progress *bar;             /* the run's bar: one step per method of a view (and per flicker row) */
} compare_opts;

/* One row of a view's table: one combination of the lists. */
typedef struct method_result {
    char name[64];                /* the method */
    char label[CLI_MAX_LABEL];    /* "hbao · filter none · ao 0.5"; the method alone with single values */
    char stem[CLI_MAX_LABEL];     /* its images: STEM_final.png, STEM_ao.png, STEM_error.png */
    const cli_config *config;
    ob_metrics m;
    bool directional;
    ob_metrics rgb; /* directional methods: HDR radiance against the one-bounce reference */
    ob_metrics in_mask[OB_MASK_COUNT]; /* the AO inside each metric mask; count 0 = the mask is empty */
    double ao_ms, frame_ms;
    double chain_ms;              /* what the AO costs the frame: the AO pass, its depth MIPs, edges, filter and
                                     upsampling (medians of the per-frame sums) */
    bool pareto;                  /* no other row of the view is both as fast and more accurate */
} method_result;

static void compare_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura compare --scene S[:CAMERA] [--scene ...] [--report DIR] [options]\n"
          "\n"
          "Renders every method on the same inputs, ray-traces the ground truth AO_R from the very\n"
          "G-buffer points (Embree), and writes DIR/index.html, DIR/results.json and the images.\n"
          "Each combination of --methods, --filters, --ao-scales and --quality is one row.\n"
          "\n"
          "  --scene S[:CAMERA]    a scene (see `obscura list`) and optionally a camera preset\n"
          "                        (default --camera, else 'default'); repeatable up to 32 times, one\n"
          "                        report section each; --sidecar, --up, --eye/--target/--fov apply\n"
          "                        to every scene\n"
          "  --report DIR          where the report goes: built beside it and put in place only when\n"
          "                        whole; an existing DIR is replaced as a whole only when empty or\n"
          "                        when everything in it is listed in its .obscura-report (what this\n"
          "                        tool wrote); anything else in it is refused with exit 4 (default\n"
          "                        " CLI_DEFAULT_REPORT " in the current directory)\n"
          "  --spp N               reference rays per pixel (default 512: mean standard error < 0.01)\n"
          "  --radius R            AO radius R in world units for every method and the reference\n"
          "                        (default: each scene's suggested radius; a --set M.radius=... wins\n"
          "                        for method M, the reference keeps R)\n"
          "  --no-cache            recompute the reference even if a cached one exists\n"
          "  --budget-ms T         the equal-time shoot-out: every method at every --quality preset and\n"
          "                        --ao-scale (all of them unless the lists are given), and per view the\n"
          "                        best RMSE each method reaches within T ms of AO (pass + filter +\n"
          "                        upsampling); the chart marks the error/time Pareto front\n"
          "\n"
          "The one-bounce reference of the directional methods takes the lights of --light and a\n"
          "constant ambient (--ambient-color), so --ambient hemisphere|env is not taken here.\n",
          f);
    cli_common_usage(f, defaults);
}

static int parse(int argc, char **argv, compare_opts *o, cli_outputs *outs)
{
    *o = (compare_opts){.spp = 512, .outs = outs, .report_index = -1, .argc = argc, .argv = argv};
    cli_common_init(&o->common, "compare", CLI_TAKES_CAMERA | CLI_TAKES_LISTS | CLI_TAKES_GPU | CLI_TAKES_PATH);
    o->common.default_method = NULL; /* every method */
    o->common.width = 320;
    o->common.height = 240;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            compare_usage(stdout, &o->common);
            return -1;
        }
        if (!strcmp(a, "--no-cache")) {
            o->no_cache = true;
            continue;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        if (strcmp(a, "--scene") && strcmp(a, "--report") && strcmp(a, "--spp") && strcmp(a, "--radius") &&
            strcmp(a, "--budget-ms"))
            return cli_unknown_option("compare", a, compare_usage, &o->common);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura compare --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) {
            if (o->view_count >= MAX_VIEWS) return cli_fail(EXIT_USAGE, "--scene: at most %d", MAX_VIEWS);
            o->views[o->view_count++] = v;
        } else if (!strcmp(a, "--report")) {
            o->report = v;
        } else if (!strcmp(a, "--spp")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 2 || n > 1 << 20) return cli_fail(EXIT_USAGE, "--spp: expected 2..1048576, got '%s'", v);
            o->spp = (int)n;
        } else if (!strcmp(a, "--budget-ms")) {
            float b = 0.0f;
            if (!cli_parse_float(v, &b) || !(b > 0.0f) || !isfinite(b))
                return cli_fail(EXIT_USAGE, "--budget-ms: expected a positive number of milliseconds, got '%s'", v);
            o->budget_ms = b;
        } else {
            if (!cli_parse_float(v, &o->radius) || !(o->radius > 0.0f))
                return cli_fail(EXIT_USAGE, "--radius: expected a positive number, got '%s'", v);
        }
    }
    if (o->budget_ms > 0.0) {
        /* The shoot-out sweeps every preset and AO scale unless the lists say otherwise. */
        cli_common *c = &o->common;
        char q_opt[] = "--quality", q_val[] = "low,medium,high,ultra", s_opt[] = "--ao-scales", s_val[] = "1,0.5,0.25";
        char *q_argv[] = {q_opt, q_val}, *s_argv[] = {s_opt, s_val};
        int k = 0, code = EXIT_OK;
        if (c->by_quality_count == 0 && c->by_number_count == 0 && (code = cli_common_option(c, 2, q_argv, &k)) != CLI_TAKEN)
            return code;
        k = 0;
        if (c->ao_count == 0 && (code = cli_common_option(c, 2, s_argv, &k)) != CLI_TAKEN) return code;
    }
    if (!o->report) {
        /* No --report: a folder of the current directory, replaced next time as --report would
         * replace it (only what this tool wrote there), and named before anything runs. */
        o->report = CLI_DEFAULT_REPORT;
        printf("compare: no --report: the report goes to %s/ (--report DIR to choose)\n", o->report);
    }
    if (o->view_count == 0) return cli_fail(EXIT_USAGE, "--scene is required (see obscura compare --help)");
    if (!*o->report) return cli_fail(EXIT_USAGE, "--report: expected a directory, got ''");
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    if (o->common.ambient_mode != OB_AMBIENT_CONSTANT)
        return cli_fail(EXIT_USAGE, "--ambient: compare takes only 'constant' (the one-bounce reference has a constant ambient)");
    o->final_report = o->report;
    return cli_outputs_add(o->outs, "--report", o->report, CLI_FMT_DIR, &o->report_index);
}

/* ---- small helpers ------------------------------------------------------------------------- */

static void html_escape(FILE *f, const char *text)
{
    /* Names from models and sidecars are bytes: valid UTF-8 first (the page says utf-8). */
    char *valid = cli_utf8_valid(text);
    if (!valid) return;
    for (const char *s = valid; *s; ++s) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default: fputc(*s, f);
        }
    }
    free(valid);
}

/* A file-system-safe name for a view directory: letters, digits, '-' and '_' only. */
static void safe_name(char *out, size_t n, const char *in)
{
    size_t k = 0;
    for (; *in && k + 1 < n; ++in) {
        char c = *in;
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
        out[k++] = ok ? c : '_';
    }
    out[k] = '\0';
}

/* What this run wrote into the report's temporary directory, emptied again when a later step
 * fails. The temporary directory itself (cli_outputs_dir) is what keeps a failed run from touching
 * --report; this list only keeps the tree small for cli_outputs_abort to remove. */
typedef struct outputs {
    char **files, **dirs;
    int file_count, file_cap, dir_count, dir_cap;
} outputs;

static bool push_path(char ***list, int *count, int *cap, const char *path)
{
    if (*count == *cap) {
        int grown = *cap ? 2 * *cap : 32;
        char **p = realloc(*list, (size_t)grown * sizeof *p);
        if (!p) return false;
        *list = p;
        *cap = grown;
    }
    char *copy = strdup(path);
    if (!copy) return false;
    (*list)[(*count)++] = copy;
    return true;
}

/* A file of the report, written (or about to be: a failure in between still removes it). */
static bool track_file(outputs *out, const char *path)
{
    return push_path(&out->files, &out->file_count, &out->file_cap, path);
}

/* mkdir, remembering a directory this run made; fails on a path that exists but is no directory. */
static int make_report_dir(outputs *out, const char *path)
{
    struct stat st = {0};
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return EXIT_OK;
        return cli_fail(EXIT_OUTPUT, "cannot create %s: it exists and is not a directory", path);
    }
    if (mkdir(path, 0777) != 0) return cli_fail(EXIT_OUTPUT, "cannot create %s: %s", path, strerror(errno));
    if (!push_path(&out->dirs, &out->dir_count, &out->dir_cap, path)) {
        rmdir(path);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    return EXIT_OK;
}

static void outputs_finish(outputs *out, bool failed)
{
    for (int i = out->file_count - 1; i >= 0; --i) {
        if (failed) remove(out->files[i]);
        free(out->files[i]);
    }
    for (int i = out->dir_count - 1; i >= 0; --i) {
        if (failed) rmdir(out->dirs[i]);
        free(out->dirs[i]);
    }
    free(out->files);
    free(out->dirs);
    *out = (outputs){0};
}

/* Visibility (bottom row first) as an 8-bit grey PNG (top row first). */
static ob_error write_grey(const char *path, const float *v, int w, int h)
{
    uint8_t *g = malloc((size_t)w * (size_t)h);
    if (!g) return OB_ERR_OUT_OF_MEMORY;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float a = v[(size_t)(h - 1 - y) * (size_t)w + (size_t)x];
            a = a < 0.0f ? 0.0f : a > 1.0f ? 1.0f : a;
            g[(size_t)y * (size_t)w + (size_t)x] = (uint8_t)lrintf(a * 255.0f);
        }
    ob_error e = ob_write_png(path, w, h, 1, g);
    free(g);
    return e;
}

/* A metric mask (bottom row first) as an RGB PNG (top row first): white in the mask, over the
 * reference AO dimmed to a third so the scene stays readable, and sky dark blue so that it is not
 * taken for deep occlusion. rgb: w x h x 3 bytes of scratch. */
static ob_error write_mask(const char *path, const float *depth, const float *ref, const uint8_t *mask, int w, int h,
                           uint8_t *rgb)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t src = (size_t)(h - 1 - y) * (size_t)w + (size_t)x;
            uint8_t *p = rgb + ((size_t)y * (size_t)w + (size_t)x) * 3;
            if (mask[src]) {
                p[0] = p[1] = p[2] = 255;
            } else if (!(depth[src] > 0.0f)) {
                p[0] = 20;
                p[1] = 28;
                p[2] = 64;
            } else {
                float a = ref[src];
                a = a < 0.0f ? 0.0f : a > 1.0f ? 1.0f : a;
                p[0] = p[1] = p[2] = (uint8_t)lrintf(a * 85.0f);
            }
        }
    return ob_write_png(path, w, h, 3, rgb);
}

/* ---- one view ------------------------------------------------------------------------------ */

typedef struct view_result {
    char scene[128], camera[64], dir[192];
    float radius;
    double ref_seconds, ref_stderr_mean, bounce_seconds;
    bool ref_cached, has_bounce;
    ob_metric_mask_desc mask_desc;      /* as used: every default resolved */
    size_t mask_pixels[OB_MASK_COUNT];
    method_result *methods; /* one per configuration */
    int method_count;
    /* --path / --orbit: the flicker metrics (flicker.h), one row per configuration */
    cli_flicker_row *flicker;
    cli_flicker_reference flicker_ref;
    const char *set; /* "choose" or "check" when scenes/views.json lists SCENE:CAMERA, else NULL */
} view_result;

/* A --scene: loaded, with its camera, before anything is written. */
typedef struct view_input {
    char name[256]; /* as --scene named it: part of the reference cache key */
    ob_scene *scene;
    bool owns_scene; /* views of one scene share it: loaded once (--max-memory counted it once) */
    ob_camera cam;
} view_input;

/* earlier: the n views loaded before this one, whose scene it shares when it names the same. */
static int load_view(const compare_opts *o, const char *spec, view_input *in, const view_input *earlier, int n)
{
    const cli_common *c = &o->common;
    if (strlen(spec) >= sizeof in->name)
        return cli_fail(EXIT_USAGE, "--scene %.80s...: %zu bytes; expected SCENE[:CAMERA] of at most %zu", spec,
                        strlen(spec), sizeof in->name - 1);
    snprintf(in->name, sizeof in->name, "%s", spec);
    const char *camera = NULL;
    char *colon = strrchr(in->name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    if (camera && c->has_eye)
        return cli_fail(EXIT_USAGE, "--scene %s: a camera preset and --eye/--target exclude each other", spec);
    for (int k = 0; k < n && !in->scene; ++k)
        if (earlier[k].scene && !strcmp(earlier[k].name, in->name)) in->scene = earlier[k].scene;
    in->owns_scene = !in->scene;
    int code = in->scene ? EXIT_OK : cli_common_load_scene(c, in->name, &in->scene);
    if (code != EXIT_OK) return code;
    return cli_common_camera(c, in->scene, camera, &in->cam);
}

static int run_view(const compare_opts *o, ob_renderer *r, const view_input *in, const cli_config *configs, int count,
                    outputs *out, view_result *vr)
{
    const cli_common *c = &o->common;
    const ob_scene *scene = in->scene;
    const ob_camera cam = in->cam;
    int code = EXIT_OK;
    float *depth = NULL, *normals = NULL, *ref = NULL, *ao = NULL, *ref_rgb = NULL, *test_rgb = NULL;
    cli_exposure exposure = {0};
    uint8_t *rgba = NULL, *mask = NULL, *heat = NULL, *masks = NULL;
    snprintf(vr->scene, sizeof vr->scene, "%s", ob_query_scene_name(scene));
    snprintf(vr->camera, sizeof vr->camera, "%s", cam.name);
    char safe_scene[128], safe_cam[64];
    safe_name(safe_scene, sizeof safe_scene, vr->scene);
    safe_name(safe_cam, sizeof safe_cam, vr->camera);
    snprintf(vr->dir, sizeof vr->dir, "%s_%s", safe_scene, safe_cam);
    vr->radius = o->radius > 0.0f ? o->radius : ob_query_scene_ao_radius(scene);

    int w = c->width, h = c->height;
    size_t px = (size_t)w * (size_t)h;
    vr->methods = calloc((size_t)count, sizeof *vr->methods);
    if (!vr->methods) return cli_fail(EXIT_RUNTIME, "out of memory");
    if (ob_renderer_set_scene(r, scene) != OB_OK) return cli_fail_from_library();
    depth = malloc(px * sizeof(float));
    normals = malloc(px * 3 * sizeof(float));
    ref = malloc(px * sizeof(float));
    ao = malloc(px * 3 * sizeof(float));
    rgba = malloc(px * 4);
    mask = malloc(px);
    heat = malloc(px * 3);
    masks = malloc(px * OB_MASK_COUNT);
    if (!depth || !normals || !ref || !ao || !rgba || !mask || !heat || !masks) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto done;
    }
    char dir[700] = "";
    snprintf(dir, sizeof dir, "%s/%s", o->report, vr->dir);
    if ((code = make_report_dir(out, dir)) != EXIT_OK) goto done;

    /* The G-buffer is the same for every method: take it from a `none` frame. */
    ob_settings s = {0};
    ob_settings_init(&s, "none");
    if (ob_render_frame(r, &cam, &s) != OB_OK) {
        code = cli_fail_from_library();
        goto done;
    }
    ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, px * sizeof(float));
    ob_read_image(r, OB_IMAGE_NORMAL_F32, normals, px * 3 * sizeof(float));
    size_t covered = 0;
    for (size_t i = 0; i < px; ++i) covered += mask[i] = depth[i] > 0.0f;
    if (!covered && !c->allow_empty) {
        code = cli_fail(c->has_eye ? EXIT_USAGE : EXIT_INPUT, "nothing visible from this camera (%s:%s): the frame "
                        "covers no pixel; check the camera (or --allow-empty to report it anyway)", vr->scene, vr->camera);
        goto done;
    }

    /* The same camera matrices as the renderer (renderer.c): for the world points. */
    ob_camera cm = cam;
    if (cm.fov_y_deg <= 0.0f) cm.fov_y_deg = 60.0f;
    if (cm.up[0] == 0.0f && cm.up[1] == 0.0f && cm.up[2] == 0.0f) cm.up[1] = 1.0f;
    mat4 view, inv_view, proj;
    glm_lookat(cm.eye, cm.target, cm.up, view);
    glm_mat4_inv(view, inv_view);
    glm_perspective(glm_rad(cm.fov_y_deg), (float)w / (float)h, 1.0f, 2.0f, proj);
    proj[2][0] = cm.shift[0]; /* the lens shift, as ob_render_frame */
    proj[2][1] = cm.shift[1];
    const float proj_info[4] = {1.0f / proj[0][0], 1.0f / proj[1][1], proj[2][0], proj[2][1]};
    char key[900] = "";
    cli_reference_key(c, in->name, cam.name, key, sizeof key);
    const cli_view_frame frame = {.width = w, .height = h, .depth = depth, .normals = normals, .cam = cm,
                                  .proj_info = {proj_info[0], proj_info[1], proj_info[2], proj_info[3]}};
    memcpy((float *)frame.inv_view, inv_view, sizeof frame.inv_view);
    cli_reference_info info;
    code = cli_reference_ao(scene, &frame, key, vr->radius, o->spp, o->no_cache, c->verbose, ref, &info);
    vr->ref_cached = info.cached;
    vr->ref_seconds = info.seconds;
    vr->ref_stderr_mean = info.stderr_mean;
    if (code != EXIT_OK) goto done;
    char path[900] = "";
    snprintf(path, sizeof path, "%s/reference_ao.png", dir);
    if (!track_file(out, path)) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto done;
    }
    if (write_grey(path, ref, w, h) != OB_OK) {
        code = cli_fail_library_as(EXIT_OUTPUT);
        goto done;
    }

    /* Where the error matters (issue 15): the metric masks from the same depth and reference,
     * each measured again below and drawn for the report. */
    vr->mask_desc = ob_metric_mask_defaults(NULL, w);
    if (ob_metric_masks(depth, ref, w, h, vr->radius, &vr->mask_desc, masks) != OB_OK) {
        code = cli_fail_from_library();
        goto done;
    }
    for (int m = 0; m < OB_MASK_COUNT; ++m) {
        const uint8_t *plane = masks + (size_t)m * px;
        vr->mask_pixels[m] = 0;
        for (size_t i = 0; i < px; ++i) vr->mask_pixels[m] += plane[i] != 0;
        snprintf(path, sizeof path, "%s/mask_%s.png", dir, ob_metric_mask_name((ob_metric_mask)m));
        if (!track_file(out, path)) {
            code = cli_fail(EXIT_RUNTIME, "out of memory");
            goto done;
        }
        if (write_mask(path, depth, ref, plane, w, h, heat) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
    }

    /* The one-bounce reference, for directional methods only: their composed radiance (direct x M
     * + bounce) against shadow rays + one diffuse bounce + ambient x AO_R (ob_reference_bounce),
     * with the lights and the constant ambient the rows render with. It casts a shadow ray per
     * light at every bounce hit, so it takes a quarter of the AO rays. */
    bool any_directional = false;
    for (int k = 0; k < count; ++k) any_directional = any_directional || ob_method_at(configs[k].method)->directional;
    if (any_directional) {
        const ob_settings *lit = &configs[0].settings;
        ref_rgb = malloc(px * 3 * sizeof(float));
        test_rgb = malloc(px * 3 * sizeof(float));
        float *albedo = malloc(px * 3 * sizeof(float)), *pos = malloc(px * 3 * sizeof(float));
        float *nrm = malloc(px * 3 * sizeof(float));
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        bool ok = ref_rgb && test_rgb && albedo && pos && nrm &&
                  ob_read_image(r, OB_IMAGE_ALBEDO_F32, albedo, px * 3 * sizeof(float)) == OB_OK &&
                  ob_reference_points(depth, normals, w, h, proj_info, (const float *)inv_view, pos, nrm) == OB_OK &&
                  ob_reference_bounce(scene, lit->light_count > 0 ? lit->lights : NULL, lit->light_count, lit->ambient,
                                      pos, nrm, albedo, px,
                                      &(ob_reference_desc){.spp = o->spp / 4 > 16 ? o->spp / 4 : 16,
                                                           .radius = vr->radius, .progress = true},
                                      ref_rgb) == OB_OK;
        clock_gettime(CLOCK_MONOTONIC, &t1);
        vr->bounce_seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        free(albedo);
        free(pos);
        free(nrm);
        if (!ok) {
            code = ref_rgb && test_rgb ? cli_fail_from_library() : cli_fail(EXIT_RUNTIME, "out of memory");
            goto done;
        }
        vr->has_bounce = true;
    }
    /* One exposure for the view's final images: the view without AO's (cli_exposure_begin). */
    if ((code = cli_exposure_begin(&exposure, r, &cam, &configs[0].settings, px)) != EXIT_OK) goto done;
    char radius_set[64];
    snprintf(radius_set, sizeof radius_set, "radius=%.9g", (double)vr->radius);
    for (int k = 0; k < count; ++k) {
        const cli_config *cfg = &configs[k];
        const ob_method_info *mi = ob_method_at(cfg->method);
        method_result *mr = &vr->methods[vr->method_count++];
        snprintf(mr->name, sizeof mr->name, "%s", mi->name);
        snprintf(mr->label, sizeof mr->label, "%s", cfg->label);
        snprintf(mr->stem, sizeof mr->stem, "%s", cfg->stem);
        mr->config = cfg;
        s = cfg->settings;
        /* A still view is graded at the pixel centres, as its reference is traced: --jitter is for
         * the path rows (flicker.h). */
        s.jitter = 0;
        /* Every method at the reference's radius, unless a --set gave this one its own. */
        bool radius_given = false;
        for (int p = 0; p < mi->param_count; ++p)
            if (!strcmp(mi->params[p].name, "radius")) radius_given = (s.params_set >> p) & 1u;
        if (!radius_given && !isnan(ob_settings_get(&s, "radius"))) ob_settings_set(&s, radius_set);
        double ao_ms[FRAMES], frame_ms[FRAMES], chain_ms[FRAMES];
        for (int f = 0; f < FRAMES; ++f) {
            if (ob_render_frame(r, &cam, &s) != OB_OK || ob_wait_timings(r) != OB_OK) {
                code = cli_fail_from_library();
                goto done;
            }
            ob_pass_timing t[16];
            int tn = ob_query_timings(r, t, 16);
            ao_ms[f] = frame_ms[f] = chain_ms[f] = 0.0;
            for (int p = 0; p < tn; ++p) {
                if (!strcmp(t[p].name, "ao")) ao_ms[f] = t[p].ms;
                static const char *const chain[] = {"ao", "depth_mips", "edges", "filter", "upsample"};
                for (size_t q = 0; q < sizeof chain / sizeof chain[0]; ++q)
                    if (!strcmp(t[p].name, chain[q])) chain_ms[f] += t[p].ms;
                frame_ms[f] += t[p].ms;
            }
        }
        mr->ao_ms = cli_median(ao_ms, FRAMES);
        mr->chain_ms = cli_median(chain_ms, FRAMES);
        mr->frame_ms = cli_median(frame_ms, FRAMES);
        ob_read_image(r, OB_IMAGE_AO_F32, ao, px * sizeof(float));
        if (ob_compare_images(ao, ref, mask, w, h, 1, &mr->m) != OB_OK) {
            code = cli_fail_from_library();
            goto done;
        }
        for (int m = 0; m < OB_MASK_COUNT; ++m) {
            mr->in_mask[m] = (ob_metrics){0};
            if (vr->mask_pixels[m] > 0 &&
                ob_compare_images(ao, ref, masks + (size_t)m * px, w, h, 1, &mr->in_mask[m]) != OB_OK) {
                code = cli_fail_from_library();
                goto done;
            }
        }
        mr->directional = mi->directional;
        if (mi->directional &&
            (ob_read_image(r, OB_IMAGE_HDR_F32, test_rgb, px * 3 * sizeof(float)) != OB_OK ||
             ob_compare_images(test_rgb, ref_rgb, mask, w, h, 3, &mr->rgb) != OB_OK)) {
            code = cli_fail_from_library();
            goto done;
        }
        if ((code = cli_exposure_apply(&exposure, r, &cam, &s)) != EXIT_OK) goto done;
        ob_read_image(r, OB_IMAGE_FINAL_RGBA8, rgba, px * 4);
        static const char *const kinds[3] = {"final", "ao", "error"};
        ob_error e = OB_OK;
        for (int q = 0; q < 3 && e == OB_OK; ++q) {
            snprintf(path, sizeof path, "%s/%s_%s.png", dir, mr->stem, kinds[q]);
            if (!track_file(out, path)) {
                code = cli_fail(EXIT_RUNTIME, "out of memory");
                goto done;
            }
            if (q == 0) e = ob_write_png(path, w, h, 4, rgba);
            else if (q == 1) e = write_grey(path, ao, w, h);
            else {
                /* Error map: +-0.5 of visibility saturates. */
                e = ob_error_heatmap(ao, ref, mask, w, h, true, 0.5f, heat);
                if (e == OB_OK) e = ob_write_png(path, w, h, 3, heat);
            }
        }
        if (e != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
        if (c->verbose) {
            if (o->bar) ob_progress_break(o->bar);
            fprintf(stderr, "obscura: %s/%s %-12s RMSE %.4f bias %+.4f SSIM %.3f ao %.2f ms\n", vr->scene, vr->camera,
                    mr->label, mr->m.rmse, mr->m.bias, mr->m.ssim, mr->ao_ms);
        }
        if (o->bar) {
            char what[200];
            snprintf(what, sizeof what, "%.60s:%.40s %.60s (%d/%d)", vr->scene, vr->camera, mr->label, k + 1, count);
            ob_progress_advance(o->bar, 1, what);
        }
    }
done:
    free(depth);
    free(normals);
    free(ref);
    free(ao);
    free(ref_rgb);
    free(test_rgb);
    cli_exposure_free(&exposure);
    free(rgba);
    free(mask);
    free(heat);
    free(masks);
    return code;
}

/* ---- outputs ------------------------------------------------------------------------------- */

/* A float setting as the decimal it was written as (0.1, not 0.10000000149011612). */
static double json_float(float v)
{
    char text[32];
    snprintf(text, sizeof text, "%.7g", (double)v);
    return strtod(text, NULL);
}

/* The rows on the error/time Pareto front: no other row is at most as slow (AO chain ms) and
 * strictly more accurate, or as accurate and strictly faster. */
static void mark_pareto(view_result *vr)
{
    for (int k = 0; k < vr->method_count; ++k) {
        method_result *a = &vr->methods[k];
        a->pareto = true;
        for (int j = 0; j < vr->method_count && a->pareto; ++j) {
            const method_result *b = &vr->methods[j];
            if (j == k) continue;
            bool dominates = b->chain_ms <= a->chain_ms && b->m.rmse <= a->m.rmse &&
                             (b->chain_ms < a->chain_ms || b->m.rmse < a->m.rmse);
            if (dominates) a->pareto = false;
        }
    }
}

/* The shoot-out's answer for one method: its most accurate row within the budget (-1 = none),
 * and its fastest row (for "over budget by"). */
static void best_within(const view_result *vr, const char *method, double budget, int *best, int *fastest)
{
    *best = *fastest = -1;
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        if (strcmp(m->name, method)) continue;
        if (*fastest < 0 || m->chain_ms < vr->methods[*fastest].chain_ms) *fastest = k;
        if (m->chain_ms <= budget && (*best < 0 || m->m.rmse < vr->methods[*best].m.rmse)) *best = k;
    }
}

/* Each method once, in the order of its first row. */
static int method_names(const view_result *vr, const char **names, int max)
{
    int n = 0;
    for (int k = 0; k < vr->method_count; ++k) {
        bool seen = false;
        for (int j = 0; j < n; ++j) seen = seen || !strcmp(names[j], vr->methods[k].name);
        if (!seen && n < max) names[n++] = vr->methods[k].name;
    }
    return n;
}

/* The report's views of one set of scenes/views.json: how many, and each row's mean RMSE over them
 * into mean[0 .. rows) (every view has the same rows, in the same order). */
static const char *const view_set_names[2] = {"choose", "check"};
static int set_means(const view_result *views, int count, const char *set, double *mean, int rows)
{
    int n = 0;
    for (int k = 0; k < rows; ++k) mean[k] = 0.0;
    for (int v = 0; v < count; ++v) {
        if (!views[v].set || strcmp(views[v].set, set) || views[v].method_count != rows) continue;
        for (int k = 0; k < rows; ++k) mean[k] += views[v].methods[k].m.rmse;
        ++n;
    }
    for (int k = 0; k < rows && n; ++k) mean[k] /= n;
    return n;
}

/* The answer to "which method, at what cost?" across the report's views, one entry per row: mean
 * RMSE and bias, mean rank by RMSE (1 = the closest), wins (views where no row is closer), median
 * AO-pass ms, and whether the row is on the front (no other row is both as fast and closer, or
 * faster and as close). Every view has the same rows in the same order. */
typedef struct row_summary {
    double rmse, bias, rank, ao_ms;
    int wins;
    bool front;
} row_summary;

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static row_summary *summarise(const view_result *views, int count, int rows)
{
    row_summary *r = rows > 0 ? calloc((size_t)rows, sizeof *r) : NULL;
    double *ms = count > 0 ? calloc((size_t)count, sizeof *ms) : NULL;
    if (!r || !ms) {
        free(r);
        free(ms);
        return NULL;
    }
    int used = 0;
    for (int v = 0; v < count; ++v) {
        if (views[v].method_count != rows) continue;
        ++used;
        const method_result *m = views[v].methods;
        for (int k = 0; k < rows; ++k) {
            int better = 0;
            for (int j = 0; j < rows; ++j) better += m[j].m.rmse < m[k].m.rmse;
            r[k].rmse += m[k].m.rmse;
            r[k].bias += m[k].m.bias;
            r[k].rank += 1.0 + better;
            r[k].wins += better == 0;
        }
    }
    for (int k = 0; k < rows; ++k) {
        int n = 0;
        for (int v = 0; v < count; ++v)
            if (views[v].method_count == rows) ms[n++] = views[v].methods[k].ao_ms;
        qsort(ms, (size_t)n, sizeof *ms, compare_doubles);
        r[k].ao_ms = n ? (n & 1 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2])) : 0.0;
        if (used) r[k].rmse /= used, r[k].bias /= used, r[k].rank /= used;
    }
    for (int k = 0; k < rows; ++k) {
        r[k].front = true;
        for (int j = 0; j < rows && r[k].front; ++j)
            r[k].front = !(j != k && r[j].rmse <= r[k].rmse && r[j].ao_ms <= r[k].ao_ms &&
                           (r[j].rmse < r[k].rmse || r[j].ao_ms < r[k].ao_ms));
    }
    free(ms);
    return r;
}

static int write_json(const compare_opts *o, ob_context *ctx, const view_result *views, int count, outputs *out)
{
    cJSON *root = cJSON_CreateObject();
    /* What made the numbers: the tool, its commit, and the command line as given. */
    cJSON_AddStringToObject(root, "version", OB_VERSION_STRING);
    char commit[64];
    cli_git_commit(commit, sizeof commit);
    cJSON_AddStringToObject(root, "commit", commit);
    cJSON *cmd = cJSON_AddArrayToObject(root, "command_line");
    for (int i = 0; i < o->argc; ++i) cJSON_AddItemToArray(cmd, cJSON_CreateString(o->argv[i]));
    cJSON_AddStringToObject(root, "renderer", ob_query_renderer(ctx));
    cJSON_AddStringToObject(root, "gl_version", ob_query_gl_version(ctx));
    cJSON_AddNumberToObject(root, "width", o->common.width);
    cJSON_AddNumberToObject(root, "height", o->common.height);
    cJSON_AddNumberToObject(root, "reference_spp", o->spp);
    /* --guard as given, in pixels per side (the renderer rounds it up to 4 x the AO divisor). */
    cJSON_AddNumberToObject(root, "guard", o->common.guard_px);
    cJSON_AddBoolToObject(root, "temporal", o->common.temporal);
    cli_common_temporal_json(&o->common, root); /* the flicker rows' "on" too */
    time_t now = time(NULL);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    cJSON_AddStringToObject(root, "date", date);
    /* Per set of scenes/views.json that this report has views of: their count and each row's mean
     * RMSE over them (null when the report has none of the set's views). */
    cJSON *jsets = cJSON_AddObjectToObject(root, "sets");
    const int nrows = count > 0 ? views[0].method_count : 0;
    double *mean = nrows ? calloc((size_t)nrows, sizeof *mean) : NULL;
    for (int s = 0; s < 2; ++s) {
        int n = mean ? set_means(views, count, view_set_names[s], mean, nrows) : 0;
        if (!n) {
            cJSON_AddNullToObject(jsets, view_set_names[s]);
            continue;
        }
        cJSON *set = cJSON_AddObjectToObject(jsets, view_set_names[s]);
        cJSON_AddNumberToObject(set, "views", n);
        cJSON *means = cJSON_AddObjectToObject(set, "mean_rmse");
        for (int k = 0; k < nrows; ++k) cJSON_AddNumberToObject(means, views[0].methods[k].label, mean[k]);
    }
    free(mean);
    row_summary *sum = summarise(views, count, nrows);
    cJSON *jsum = cJSON_AddArrayToObject(root, "summary");
    for (int k = 0; sum && k < nrows; ++k) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "label", views[0].methods[k].label);
        cJSON_AddStringToObject(e, "method", views[0].methods[k].name);
        cJSON_AddNumberToObject(e, "mean_rmse", sum[k].rmse);
        cJSON_AddNumberToObject(e, "mean_bias", sum[k].bias);
        cJSON_AddNumberToObject(e, "mean_rank", sum[k].rank);
        cJSON_AddNumberToObject(e, "wins", sum[k].wins);
        cJSON_AddNumberToObject(e, "median_ao_ms", sum[k].ao_ms);
        cJSON_AddBoolToObject(e, "front", sum[k].front);
        cJSON_AddItemToArray(jsum, e);
    }
    free(sum);
    cJSON *jv = cJSON_AddArrayToObject(root, "views");
    for (int v = 0; v < count; ++v) {
        const view_result *vr = &views[v];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "scene", vr->scene);
        cJSON_AddStringToObject(j, "camera", vr->camera);
        cJSON_AddStringToObject(j, "dir", vr->dir);
        if (vr->set) cJSON_AddStringToObject(j, "set", vr->set);
        else cJSON_AddNullToObject(j, "set");
        cJSON_AddNumberToObject(j, "radius", vr->radius);
        cJSON *jr = cJSON_AddObjectToObject(j, "reference");
        cJSON_AddNumberToObject(jr, "seconds", vr->ref_seconds);
        cJSON_AddBoolToObject(jr, "cached", vr->ref_cached);
        cJSON_AddNumberToObject(jr, "mean_standard_error", vr->ref_stderr_mean);
        if (vr->has_bounce) cJSON_AddNumberToObject(jr, "bounce_seconds", vr->bounce_seconds);
        const ob_metric_mask_desc *md = &vr->mask_desc;
        cJSON *js = cJSON_AddObjectToObject(j, "mask_settings");
        cJSON_AddNumberToObject(js, "occluded_below", json_float(md->occluded_below));
        cJSON_AddNumberToObject(js, "edge_relative", json_float(md->edge_relative));
        cJSON_AddNumberToObject(js, "edge_band_px", md->edge_band);
        cJSON_AddNumberToObject(js, "thin_reach_px", md->thin_reach);
        cJSON_AddNumberToObject(js, "thin_depth", json_float(vr->radius));
        cJSON_AddNumberToObject(js, "border_fraction", json_float(md->border_fraction));
        cJSON *jmask = cJSON_AddObjectToObject(j, "masks");
        for (int q = 0; q < OB_MASK_COUNT; ++q) {
            const char *name = ob_metric_mask_name((ob_metric_mask)q);
            cJSON *e = cJSON_AddObjectToObject(jmask, name);
            cJSON_AddNumberToObject(e, "pixels", (double)vr->mask_pixels[q]);
            char image[300];
            snprintf(image, sizeof image, "%s/mask_%s.png", vr->dir, name);
            cJSON_AddStringToObject(e, "image", image);
        }
        cJSON *jm = cJSON_AddArrayToObject(j, "methods");
        for (int k = 0; k < vr->method_count; ++k) {
            const method_result *m = &vr->methods[k];
            cJSON *e = cJSON_CreateObject();
            cJSON_AddStringToObject(e, "method", m->name);
            /* The row's settings: the label names those that vary between rows. */
            cJSON_AddStringToObject(e, "label", m->label);
            cJSON_AddStringToObject(e, "filter", ob_filter_at(m->config->filter)->name);
            cJSON_AddNumberToObject(e, "ao_scale", 1.0 / m->config->ao_divisor);
            if (m->config->samples.quality) cJSON_AddStringToObject(e, "quality", m->config->samples.quality);
            if (m->config->samples.count > 0) cJSON_AddNumberToObject(e, "samples", m->config->samples.count);
            cJSON_AddNumberToObject(e, "rmse", m->m.rmse);
            cJSON_AddNumberToObject(e, "mae", m->m.mae);
            cJSON_AddNumberToObject(e, "bias", m->m.bias);
            /* JSON has no infinity: identical images report psnr null. */
            if (isfinite(m->m.psnr)) cJSON_AddNumberToObject(e, "psnr", m->m.psnr);
            else cJSON_AddNullToObject(e, "psnr");
            /* XeGTAO's measure: PSNR of the sRGB-encoded AO. */
            if (isfinite(m->m.psnr_srgb)) cJSON_AddNumberToObject(e, "psnr_srgb", m->m.psnr_srgb);
            else cJSON_AddNullToObject(e, "psnr_srgb");
            cJSON_AddNumberToObject(e, "ssim", m->m.ssim);
            cJSON_AddNumberToObject(e, "pixels", (double)m->m.count);
            /* The error inside each metric mask; an empty mask has no error to report (null). */
            cJSON *jin = cJSON_AddObjectToObject(e, "masks");
            for (int q = 0; q < OB_MASK_COUNT; ++q) {
                cJSON *x = cJSON_AddObjectToObject(jin, ob_metric_mask_name((ob_metric_mask)q));
                const ob_metrics *mm = &m->in_mask[q];
                if (mm->count > 0) {
                    cJSON_AddNumberToObject(x, "rmse", mm->rmse);
                    cJSON_AddNumberToObject(x, "bias", mm->bias);
                } else {
                    cJSON_AddNullToObject(x, "rmse");
                    cJSON_AddNullToObject(x, "bias");
                }
                cJSON_AddNumberToObject(x, "pixels", (double)mm->count);
            }
            if (m->directional) {
                cJSON *rgb = cJSON_AddObjectToObject(e, "radiance");
                cJSON_AddNumberToObject(rgb, "rmse", m->rgb.rmse);
                cJSON_AddNumberToObject(rgb, "bias", m->rgb.bias);
                cJSON_AddNumberToObject(rgb, "ssim", m->rgb.ssim);
            }
            cJSON_AddNumberToObject(e, "ao_ms", m->ao_ms);
            cJSON_AddNumberToObject(e, "chain_ms", m->chain_ms);
            cJSON_AddBoolToObject(e, "pareto", m->pareto);
            cJSON_AddNumberToObject(e, "frame_ms", m->frame_ms);
            cJSON_AddItemToArray(jm, e);
        }
        if (vr->flicker) {
            /* The flicker metrics (flicker.h): per configuration, temporal accumulation off (the
             * same moving noise, a one-frame history) and on. */
            cJSON *fl = cJSON_AddObjectToObject(j, "flicker");
            cJSON_AddStringToObject(fl, "path", o->common.path ? o->common.path : "orbit");
            if (o->common.has_orbit) cJSON_AddNumberToObject(fl, "orbit_degrees", o->common.orbit_deg);
            cJSON_AddNumberToObject(fl, "path_frames", vr->flicker_ref.frames);
            /* Frames that see nothing (--allow-empty): in no mean; their rmse_frames are null. */
            cJSON_AddNumberToObject(fl, "path_frames_empty", vr->flicker_ref.frames_empty);
            cJSON_AddNumberToObject(fl, "still_frames", FLICKER_STILL_FRAMES);
            /* Both variants' G-buffer jitter and the reference's footprint (0: pixel centres). */
            cJSON_AddNumberToObject(fl, "jitter_positions", vr->flicker_ref.jitter);
            cJSON_AddNumberToObject(fl, "reference_warped_error", vr->flicker_ref.warped);
            cJSON *rows = cJSON_AddArrayToObject(fl, "rows");
            for (int k = 0; k < vr->method_count; ++k) {
                const cli_flicker_row *row = &vr->flicker[k];
                cJSON *e = cJSON_CreateObject();
                cJSON_AddStringToObject(e, "label", vr->methods[k].label);
                cJSON_AddStringToObject(e, "method", vr->methods[k].name);
                const cli_flicker_variant *vs[2] = {&row->off, &row->on};
                for (int q = 0; q < 2; ++q) {
                    cJSON *x = cJSON_AddObjectToObject(e, q ? "temporal_on" : "temporal_off");
                    cJSON_AddNumberToObject(x, "static_noise", vs[q]->static_noise);
                    cJSON_AddNumberToObject(x, "warped_error", vs[q]->warped_excess);
                    cJSON_AddNumberToObject(x, "warped_error_raw", vs[q]->warped);
                    cJSON_AddNumberToObject(x, "rmse_last", vs[q]->rmse_last);
                    cJSON_AddNumberToObject(x, "rmse_worst", vs[q]->rmse_worst);
                    cJSON_AddNumberToObject(x, "worst_frame", vs[q]->worst_frame);
                    cJSON_AddNumberToObject(x, "rmse_mean", vs[q]->rmse_mean);
                    cJSON *curve = cJSON_AddArrayToObject(x, "rmse_frames");
                    for (int t = 0; vs[q]->rmse_frames && t < vr->flicker_ref.frames; ++t)
                        cJSON_AddItemToArray(curve, cJSON_CreateNumber(vs[q]->rmse_frames[t]));
                    cJSON_AddNumberToObject(x, "temporal_ms", vs[q]->temporal_ms);
                }
                cJSON_AddItemToArray(rows, e);
            }
        }
        if (o->budget_ms > 0.0) {
            cJSON *so = cJSON_AddObjectToObject(j, "shootout");
            cJSON_AddNumberToObject(so, "budget_ms", o->budget_ms);
            cJSON *arr = cJSON_AddArrayToObject(so, "methods");
            const char *names[CLI_MAX_CONFIGS];
            int n = method_names(vr, names, CLI_MAX_CONFIGS);
            for (int q = 0; q < n; ++q) {
                int best = -1, fastest = -1;
                best_within(vr, names[q], o->budget_ms, &best, &fastest);
                cJSON *e = cJSON_CreateObject();
                cJSON_AddStringToObject(e, "method", names[q]);
                cJSON_AddBoolToObject(e, "within_budget", best >= 0);
                if (best >= 0) {
                    cJSON_AddStringToObject(e, "label", vr->methods[best].label);
                    cJSON_AddNumberToObject(e, "rmse", vr->methods[best].m.rmse);
                    cJSON_AddNumberToObject(e, "chain_ms", vr->methods[best].chain_ms);
                }
                cJSON_AddNumberToObject(e, "fastest_ms", vr->methods[fastest].chain_ms);
                cJSON_AddItemToArray(arr, e);
            }
        }
        cJSON_AddItemToArray(jv, j);
    }
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text) return cli_fail(EXIT_RUNTIME, "out of memory writing results.json");
    char path[700];
    snprintf(path, sizeof path, "%s/results.json", o->report);
    if (!track_file(out, path)) {
        free(text);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    /* Scene and camera names are bytes from files: valid UTF-8 before any parser sees them. */
    char *valid = cli_utf8_valid(text);
    free(text);
    if (!valid) return cli_fail(EXIT_RUNTIME, "out of memory writing results.json");
    ob_error e = ob_write_text(path, valid);
    free(valid);
    return e == OB_OK ? EXIT_OK : cli_fail_library_as(EXIT_OUTPUT);
}

/* A row's label as one double-quoted field of gnuplot's inline data. gnuplot reads a quoted field
 * up to the next '"' with no escapes, and a line break would end the row (or spell the block's
 * closing "EOD"), so '"', '\\' and control bytes become '_'; invalid UTF-8 would make the whole
 * SVG unreadable to a browser, so it becomes U+FFFD first. Labels are registry names and numbers
 * today (cli_config_label): this keeps any later source of text from reaching gnuplot as syntax.
 * '`' and '@' stay: lines of a datablock are data, not commands, and gnuplot substitutes neither
 * backquotes nor macros in them. */
static void chart_label(char *out, size_t n, const char *label)
{
    char *valid = cli_utf8_valid(label);
    const char *src = valid ? valid : "";
    size_t k = 0;
    for (const unsigned char *p = (const unsigned char *)src; *p && k + 1 < n; ++p)
        out[k++] = *p == '"' || *p == '\\' || *p < 0x20 || *p == 0x7f ? '_' : (char)*p;
    out[k] = '\0';
    free(valid);
}

/* Quality against time for one view, as SVG through gnuplot (Debian's gnuplot-nox). No path and
 * no name the user gave reaches gnuplot or a shell (issue 44): gnuplot runs without one
 * (cli_spawn), reads the script on stdin from a file we opened, finds its data inline in the
 * script, and writes the SVG to its stdout, which we write into the report ourselves. The
 * script holds nothing but our own text and the sanitised labels (chart_label). */
static int write_chart(const compare_opts *o, const view_result *vr, outputs *out)
{
    const char *shown = o->final_report ? o->final_report : o->report; /* messages name --report */
    char svg_path[700], script[700];
    snprintf(svg_path, sizeof svg_path, "%s/%s/chart.svg", o->report, vr->dir);
    snprintf(script, sizeof script, "%s/%s/chart.gp", o->report, vr->dir);
    if (!track_file(out, script) || !track_file(out, svg_path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    /* w+: the same descriptor becomes gnuplot's stdin once rewound. */
    FILE *f = fopen(script, "w+");
    if (!f) return cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(errno));
    fprintf(f, "set encoding utf8\n"
               "set terminal svg size 560,360 font 'sans,11' background rgb 'white' noenhanced\n"
               "set xlabel 'AO ms: pass + depth MIPs + filter + upsampling (GPU timestamps)'\n"
               "set ylabel 'RMSE against the reference'\n"
               "set grid\n"
               "unset key\n"
               "set offsets graph 0.05, graph 0.15, graph 0.1, graph 0.1\n");
    /* Labels in double quotes: gnuplot reads "hbao · filter none" as one column. Past 16 rows the
     * labels would cover each other: only the front's are written. */
    fputs("$points << EOD\n", f);
    for (int k = 0; k < vr->method_count; ++k) {
        char label[CLI_MAX_LABEL] = "";
        if (vr->method_count <= 16 || vr->methods[k].pareto) chart_label(label, sizeof label, vr->methods[k].label);
        fprintf(f, "%.6f %.6f \"%s\"\n", vr->methods[k].chain_ms, vr->methods[k].m.rmse, label);
    }
    /* The Pareto front in order of time, drawn as a line. */
    fputs("EOD\n$front << EOD\n", f);
    double last = -1.0;
    for (;;) {
        int next = -1;
        for (int k = 0; k < vr->method_count; ++k) {
            const method_result *m = &vr->methods[k];
            if (m->pareto && m->chain_ms > last && (next < 0 || m->chain_ms < vr->methods[next].chain_ms)) next = k;
        }
        if (next < 0) break;
        last = vr->methods[next].chain_ms;
        fprintf(f, "%.6f %.6f\n", vr->methods[next].chain_ms, vr->methods[next].m.rmse);
    }
    fputs("EOD\n"
          "plot $points using 1:2 with points pt 7 ps 1.2 lc rgb '#3060a0', "
          "$points using 1:2:3 with labels offset 0.8,0.6 left font 'sans,10', "
          "$front using 1:2 with lines lw 1.5 lc rgb '#c05020' title 'Pareto front'\n",
          f);
    if (fflush(f) != 0 || ferror(f) || fseek(f, 0, SEEK_SET) != 0) {
        int e = errno;
        fclose(f);
        return cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(e));
    }
    /* A chart of 256 rows is about 100 KB of SVG; 16 MiB is far beyond any. */
    cli_spawn_output svg = {.limit = 16u << 20}, err = {.limit = 4096};
    const char *argv[] = {"gnuplot", NULL};
    int status = -1;
    int e = cli_spawn(argv, fileno(f), &svg, &err, &status);
    fclose(f);
    remove(script);
    int code = EXIT_OK;
    char why[256] = "";
    cli_spawn_last_line(&err, why, sizeof why);
    if (e == ENOENT) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: cannot draw %s/chart.svg: gnuplot is not installed (Debian: "
                                      "gnuplot-nox; scripts/install-deps.sh)",
                        shown, vr->dir);
    } else if (e != 0) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: cannot run gnuplot for %s/chart.svg: %s", shown, vr->dir, strerror(e));
    } else if (status != 0 || svg.len == 0 || svg.truncated) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: gnuplot failed to draw %s/chart.svg (%s%d): %s", shown, vr->dir,
                        status != 0 ? "exit status " : "no SVG, exit status ", status,
                        why[0] ? why : svg.truncated ? "more than 16 MiB of SVG" : "it said nothing");
    } else {
        FILE *s = fopen(svg_path, "wb");
        bool ok = s && fwrite(svg.data, 1, svg.len, s) == svg.len;
        int we = errno;
        if (s && fclose(s) != 0 && ok) {
            ok = false;
            we = errno;
        }
        if (!ok) code = cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.svg: %s", shown, vr->dir, strerror(we));
    }
    cli_spawn_output_free(&svg);
    cli_spawn_output_free(&err);
    return code;
}

/* The equal-time shoot-out: each method's most accurate row within the budget, best first. */
static void write_shootout_table(FILE *f, const view_result *vr, double budget)
{
    const char *names[CLI_MAX_CONFIGS];
    int n = method_names(vr, names, CLI_MAX_CONFIGS);
    int order[CLI_MAX_CONFIGS], best[CLI_MAX_CONFIGS], fastest[CLI_MAX_CONFIGS];
    for (int q = 0; q < n; ++q) {
        order[q] = q;
        best_within(vr, names[q], budget, &best[q], &fastest[q]);
    }
    /* Within the budget by RMSE, then the rest by how fast they can go. */
    for (int a = 1; a < n; ++a)
        for (int b = a; b > 0; --b) {
            int x = order[b - 1], y = order[b];
            double kx = best[x] >= 0 ? vr->methods[best[x]].m.rmse : 10.0 + vr->methods[fastest[x]].chain_ms;
            double ky = best[y] >= 0 ? vr->methods[best[y]].m.rmse : 10.0 + vr->methods[fastest[y]].chain_ms;
            if (ky < kx) {
                order[b - 1] = y;
                order[b] = x;
            }
        }
    fprintf(f, "<p class=\"note\">Equal-time shoot-out: the most accurate row of each method whose AO (pass + depth "
               "MIPs + filter + upsampling) took at most %.2f ms.</p>\n<table><thead><tr><th>method</th><th>best row "
               "within budget</th><th>RMSE</th><th>AO ms</th></tr></thead><tbody>\n",
            budget);
    for (int i = 0; i < n; ++i) {
        int q = order[i];
        fputs("<tr><td>", f);
        html_escape(f, names[q]);
        fputs("</td><td>", f);
        if (best[q] >= 0) {
            html_escape(f, vr->methods[best[q]].label);
            fprintf(f, "</td><td>%.4f</td><td>%.2f</td></tr>\n", vr->methods[best[q]].m.rmse, vr->methods[best[q]].chain_ms);
        } else {
            fprintf(f, "over budget (fastest %.2f ms)</td><td>&ndash;</td><td>&ndash;</td></tr>\n",
                    vr->methods[fastest[q]].chain_ms);
        }
    }
    fputs("</tbody></table>\n", f);
}

static void embed_file(FILE *out, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return;
    char buf[4096];
    /* Skip the XML prolog: inline SVG starts at <svg. */
    bool started = false;
    while (fgets(buf, sizeof buf, f)) {
        if (!started) {
            char *s = strstr(buf, "<svg");
            if (!s) continue;
            started = true;
            fputs(s, out);
            continue;
        }
        fputs(buf, out);
    }
    fclose(f);
}

/* The error where it matters: RMSE and bias inside each metric mask, and the masks themselves. */
static void write_mask_table(FILE *f, const view_result *vr, int w, int h)
{
    const ob_metric_mask_desc *md = &vr->mask_desc;
    const size_t *n = vr->mask_pixels;
    fprintf(f,
            "<p class=\"note\">Error where it matters, in pixels of geometry: <b>occluded</b> (reference &lt; %g) %zu; "
            "<b>silhouette</b> (within %d px of a depth step over %g%% or sky) %zu; <b>thin</b> (background over "
            "R = %g farther on both sides within %d px) %zu; <b>border</b> (outer %g%% of each side) %zu. "
            "n/a: the mask is empty. Mask images: white = in the mask, over the reference dimmed; sky dark blue.</p>\n",
            (double)md->occluded_below, n[OB_MASK_OCCLUDED], md->edge_band, 100.0 * (double)md->edge_relative,
            n[OB_MASK_SILHOUETTE], (double)vr->radius, md->thin_reach, n[OB_MASK_THIN],
            100.0 * (double)md->border_fraction, n[OB_MASK_BORDER]);
    fputs("<table class=\"sortable masks\"><thead><tr><th>method</th>", f);
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        const char *name = ob_metric_mask_name((ob_metric_mask)q);
        fprintf(f, "<th>%s RMSE</th><th>%s bias</th>", name, name);
    }
    fputs("</tr></thead><tbody>\n", f);
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        fputs("<tr><td>", f);
        html_escape(f, m->label);
        fputs("</td>", f);
        for (int q = 0; q < OB_MASK_COUNT; ++q) {
            if (m->in_mask[q].count > 0) fprintf(f, "<td>%.4f</td><td>%+.4f</td>", m->in_mask[q].rmse, m->in_mask[q].bias);
            else fputs("<td>n/a</td><td>n/a</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</tbody></table>\n<div class=\"grid\">", f);
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        const char *name = ob_metric_mask_name((ob_metric_mask)q);
        fprintf(f, "<div class=\"cell\"><img src=\"%s/mask_%s.png\" width=\"%d\" height=\"%d\" alt=\"%s mask\">"
                   "%s mask, %zu px</div>",
                vr->dir, name, w, h, name, name, n[q]);
    }
    fputs("</div>\n", f);
}

/* The flicker table (flicker.h) and each configuration's worst frame with temporal on. */
static void write_flicker_table(FILE *f, const compare_opts *o, const view_result *vr)
{
    const cli_common *c = &o->common;
    fprintf(f, "<h3>Flicker along ");
    if (c->path) {
        fputs("path ", f);
        html_escape(f, c->path);
    } else {
        fprintf(f, "an orbit of %g&deg;", (double)c->orbit_deg);
    }
    char jitter_note[200] = "Both variants sample the pixel centres, as does the reference (--jitter off).";
    if (vr->flicker_ref.jitter > 0)
        snprintf(jitter_note, sizeof jitter_note,
                 "Both variants jitter the G-buffer over %d sub-pixel points, and each frame's reference is "
                 "AO<sub>R</sub> averaged over the same %d points (--jitter).",
                 vr->flicker_ref.jitter, vr->flicker_ref.jitter);
    fprintf(f, " (%d frames)</h3>\n<p class=\"note\">off: the spatial filter alone with the same noise moving every "
               "frame; on: temporal accumulation (%s the filter, history %d frames, detail %g). Static noise: camera "
               "still for %d frames, mean per-pixel std-dev; "
               "warped error: mean |AO<sub>t</sub> &minus; reprojected AO<sub>t&minus;1</sub>| over pixels seen in both "
               "(the ratio is of these), and the same minus the reference's own (%.4f: AO<sub>R</sub> belongs to the "
               "surface point, so on a static scene the reference's change is its Monte Carlo noise and "
               "resampling); RMSE against the reference on the last and the worst frame, and its mean over the "
               "path's frames (a screen-space estimate depends on the view, and the accumulation averages the "
               "last views: the last frame alone can land where the single frame's error dips). %s</p>\n",
            vr->flicker_ref.frames, cli_common_temporal_at(c), cli_common_temporal_frames(c), (double)c->temporal_detail,
            FLICKER_STILL_FRAMES, vr->flicker_ref.warped, jitter_note);
    fputs("<table class=\"sortable\"><thead><tr><th>method</th><th>static noise off</th><th>on</th><th>ratio</th>"
          "<th>warped error off</th><th>on</th><th>ratio</th><th>minus reference off</th><th>on</th><th>RMSE last off</th><th>on</th>"
          "<th>RMSE worst off (frame)</th><th>on (frame)</th><th>RMSE mean off</th><th>on</th><th>temporal ms</th>"
          "</tr></thead><tbody>\n",
          f);
    for (int k = 0; k < vr->method_count; ++k) {
        const cli_flicker_variant *a = &vr->flicker[k].off, *b = &vr->flicker[k].on;
        fputs("<tr><td>", f);
        html_escape(f, vr->methods[k].label);
        fprintf(f, "</td><td>%.4f</td><td>%.4f</td><td>%.1fx</td><td>%.4f</td><td>%.4f</td><td>%.1fx</td>"
                   "<td>%+.4f</td><td>%+.4f</td><td>%.4f</td><td>%.4f</td><td>%.4f (%d)</td><td>%.4f (%d)</td><td>%.4f</td><td>%.4f</td>"
                   "<td>%.2f</td></tr>\n",
                a->static_noise, b->static_noise, b->static_noise > 0.0 ? a->static_noise / b->static_noise : 0.0,
                a->warped, b->warped, b->warped > 0.0 ? a->warped / b->warped : 0.0, a->warped_excess, b->warped_excess,
                a->rmse_last, b->rmse_last, a->rmse_worst, a->worst_frame, b->rmse_worst, b->worst_frame, a->rmse_mean,
                b->rmse_mean, b->temporal_ms);
    }
    fputs("</tbody></table>\n<div class=\"grid\">", f);
    for (int k = 0; k < vr->method_count; ++k) {
        fprintf(f, "<div class=\"cell\"><img src=\"%s/%s_temporal_worst.png\" width=\"%d\" height=\"%d\" alt=\"\">",
                vr->dir, vr->methods[k].stem, c->width, c->height);
        html_escape(f, vr->methods[k].label);
        fprintf(f, " temporal on, worst frame %d</div>", vr->flicker[k].on.worst_frame);
    }
    fputs("</div>\n", f);
}

static int write_html(const compare_opts *o, ob_context *ctx, const view_result *views, int count, outputs *out)
{
    char path[700], tmp[720];
    snprintf(path, sizeof path, "%s/index.html", o->report);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (!track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    FILE *f = fopen(tmp, "w");
    if (!f) return cli_fail(EXIT_OUTPUT, "cannot write %s: %s", path, strerror(errno));
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>Obscura: AO against ground truth</title>\n"
          "<style>body{font:14px sans-serif;margin:24px;color:#222}h2{margin-top:36px}"
          "table{border-collapse:collapse;margin:12px 0}th,td{padding:4px 10px;border-bottom:1px solid #ddd;text-align:right}"
          "th{cursor:pointer;background:#f2f2f2}td:first-child,th:first-child{text-align:left}"
          ".grid{display:flex;flex-wrap:wrap;gap:10px}.cell{font-size:12px}.cell img{display:block;border:1px solid #ccc}"
          ".note{color:#666}</style></head><body>\n<h1>Screen-space AO against the ray-traced ground truth</h1>\n<p class=\"note\">",
          f);
    fprintf(f, "%dx%d, reference %d rays per pixel (cosine-weighted, AO<sub>R</sub> as in docs/compare.md), GPU: ",
            o->common.width, o->common.height, o->spp);
    html_escape(f, ob_query_renderer(ctx));
    fputs(". Error maps: red = the method is brighter (misses occlusion), blue = darker; &plusmn;0.5 saturates. "
          "Click a column to sort.</p>\n",
          f);
    const int rows = count > 0 ? views[0].method_count : 0;
    /* Which method, at what cost: the summary across every view of the report. */
    row_summary *sum = summarise(views, count, rows);
    if (sum) {
        fprintf(f, "<h2>Summary over %d view%s</h2>\n<p class=\"note\">Mean RMSE and signed bias against "
                   "AO<sub>R</sub>, mean rank by RMSE (1 = the closest row of a view), wins (views no row is "
                   "closer on), median GPU time of the AO pass, and the front: rows no other row beats on both "
                   "error and time.</p>\n",
                count, count == 1 ? "" : "s");
        fputs("<table class=\"sortable\"><thead><tr><th>row</th><th>mean RMSE</th><th>mean bias</th>"
              "<th>mean rank</th><th>wins</th><th>AO ms (median)</th><th>front</th></tr></thead><tbody>\n",
              f);
        for (int k = 0; k < rows; ++k) {
            fputs("<tr><td>", f);
            html_escape(f, views[0].methods[k].label);
            fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.2f</td><td>%d</td><td>%.3f</td><td>%s</td></tr>\n",
                    sum[k].rmse, sum[k].bias, sum[k].rank, sum[k].wins, sum[k].ao_ms, sum[k].front ? "yes" : "");
        }
        fputs("</tbody></table>\n", f);
        free(sum);
    }
    /* The views' sets (scenes/views.json): the mean of each row over the choose views, the ones
     * the defaults were chosen on, and over the check views, never chosen on. */
    double *mean[2] = {NULL, NULL};
    int in_set[2] = {0, 0};
    for (int s = 0; s < 2 && rows; ++s) {
        mean[s] = calloc((size_t)rows, sizeof(double));
        if (mean[s]) in_set[s] = set_means(views, count, view_set_names[s], mean[s], rows);
    }
    if (in_set[0] || in_set[1]) {
        fputs("<h2>Choose and check views</h2>\n<p class=\"note\">The project's views in two sets "
              "(scenes/views.json, docs/methods.md): <em>choose</em> views, the ones the defaults were chosen on, "
              "and <em>check</em> views, never used for a choice. Mean RMSE of each row over this report's views of "
              "each set.</p>\n<table class=\"sortable\"><thead><tr><th>row</th>",
              f);
        for (int s = 0; s < 2; ++s)
            if (in_set[s]) fprintf(f, "<th>%s (%d view%s)</th>", view_set_names[s], in_set[s], in_set[s] == 1 ? "" : "s");
        fputs("</tr></thead><tbody>\n", f);
        for (int k = 0; k < rows; ++k) {
            fputs("<tr><td>", f);
            html_escape(f, views[0].methods[k].label);
            fputs("</td>", f);
            for (int s = 0; s < 2; ++s)
                if (in_set[s]) fprintf(f, "<td>%.4f</td>", mean[s][k]);
            fputs("</tr>\n", f);
        }
        fputs("</tbody></table>\n", f);
    }
    free(mean[0]);
    free(mean[1]);
    for (int v = 0; v < count; ++v) {
        const view_result *vr = &views[v];
        fputs("<section class=\"view\"><h2>", f);
        html_escape(f, vr->scene);
        fputs(" &mdash; ", f);
        html_escape(f, vr->camera);
        if (vr->set) fprintf(f, " <span class=\"note\">(a %s view)</span>", vr->set);
        fprintf(f, "</h2>\n<p class=\"note\">R = %g; reference: %.1f s%s, mean standard error %.4f</p>\n",
                (double)vr->radius, vr->ref_seconds, vr->ref_cached ? " (cached)" : "", vr->ref_stderr_mean);
        fputs("<table class=\"sortable\"><thead><tr><th>method</th><th>RMSE</th><th>bias</th><th>MAE</th><th>SSIM</th>"
              "<th>PSNR dB</th><th>sRGB PSNR dB</th><th>AO ms</th><th>frame ms</th></tr></thead><tbody>\n",
              f);
        for (int k = 0; k < vr->method_count; ++k) {
            const method_result *m = &vr->methods[k];
            fputs("<tr><td>", f);
            html_escape(f, m->label);
            fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.4f</td><td>%.3f</td>", m->m.rmse, m->m.bias, m->m.mae,
                    m->m.ssim);
            const double psnrs[2] = {m->m.psnr, m->m.psnr_srgb};
            for (int q = 0; q < 2; ++q) {
                if (isfinite(psnrs[q])) fprintf(f, "<td>%.2f</td>", psnrs[q]);
                else fputs("<td>&infin;</td>", f);
            }
            fprintf(f, "<td>%.2f</td><td>%.1f</td></tr>\n", m->ao_ms, m->frame_ms);
        }
        fputs("</tbody></table>\n", f);
        if (vr->has_bounce) {
            fprintf(f, "<p class=\"note\">Directional methods: composed HDR radiance against the one-bounce reference "
                       "(shadow rays, one diffuse bounce within R, ambient &times; AO<sub>R</sub>; %.1f s).</p>\n"
                       "<table class=\"sortable\"><thead><tr><th>method</th><th>radiance RMSE</th><th>bias</th>"
                       "<th>SSIM</th></tr></thead><tbody>\n",
                    vr->bounce_seconds);
            for (int k = 0; k < vr->method_count; ++k) {
                const method_result *m = &vr->methods[k];
                if (!m->directional) continue;
                fputs("<tr><td>", f);
                html_escape(f, m->label);
                fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.3f</td></tr>\n", m->rgb.rmse, m->rgb.bias, m->rgb.ssim);
            }
            fputs("</tbody></table>\n", f);
        }
        if (o->budget_ms > 0.0) write_shootout_table(f, vr, o->budget_ms);
        if (vr->flicker) write_flicker_table(f, o, vr);
        write_mask_table(f, vr, o->common.width, o->common.height);
        fputs("<div class=\"chart\">", f);
        char svg[700];
        snprintf(svg, sizeof svg, "%s/%s/chart.svg", o->report, vr->dir);
        embed_file(f, svg);
        fputs("</div>\n<div class=\"grid\">", f);
        fprintf(f, "<div class=\"cell\"><img src=\"%s/reference_ao.png\" width=\"%d\" height=\"%d\" alt=\"reference\">reference AO</div>",
                vr->dir, o->common.width, o->common.height);
        fputs("</div>\n", f);
        for (int k = 0; k < vr->method_count; ++k) {
            const method_result *m = &vr->methods[k];
            fputs("<div class=\"grid\">", f);
            const char *kinds[3] = {"final", "ao", "error"};
            for (int q = 0; q < 3; ++q) {
                fprintf(f, "<div class=\"cell\"><img src=\"%s/%s_%s.png\" width=\"%d\" height=\"%d\" alt=\"\">", vr->dir,
                        m->stem, kinds[q], o->common.width, o->common.height);
                html_escape(f, m->label);
                fprintf(f, " %s</div>", kinds[q]);
            }
            fputs("</div>\n", f);
        }
        fputs("</section>\n", f);
    }
    /* Sort a table by a column: numbers numerically, text alphabetically; click again to reverse.
     * The column is the header cell's index in its own row (forEach's index counts every table's). */
    fputs("<script>\n"
          "document.querySelectorAll('table.sortable th').forEach(function (th) {\n"
          "  th.addEventListener('click', function () {\n"
          "    var col = th.cellIndex;\n"
          "    var body = th.closest('table').tBodies[0];\n"
          "    var rows = Array.prototype.slice.call(body.rows);\n"
          "    var dir = th.dataset.dir === 'asc' ? -1 : 1;\n"
          "    th.dataset.dir = dir === 1 ? 'asc' : 'desc';\n"
          "    rows.sort(function (a, b) {\n"
          "      var x = a.cells[col].textContent, y = b.cells[col].textContent;\n"
          "      var nx = parseFloat(x), ny = parseFloat(y);\n"
          "      var c = isNaN(nx) || isNaN(ny) ? x.localeCompare(y) : nx - ny;\n"
          "      return dir * c;\n"
          "    });\n"
          "    rows.forEach(function (r) { body.appendChild(r); });\n"
          "  });\n"
          "});\n"
          "</script>\n</body></html>\n",
          f);
    bool ok = !ferror(f);
    if (fclose(f) != 0 || !ok || rename(tmp, path) != 0) {
        remove(tmp);
        return cli_fail(EXIT_OUTPUT, "cannot write %s", path);
    }
    return EXIT_OK;
}

/* --path / --orbit: the flicker metrics of every configuration (flicker.h), and each one's worst
 * frame with temporal on as STEM_temporal_worst.png. */
static int run_flicker(const compare_opts *o, ob_renderer *r, const view_input *in, const cli_config *configs, int count,
                       outputs *out, view_result *vr)
{
    vr->flicker = calloc((size_t)count, sizeof *vr->flicker);
    if (!vr->flicker) return cli_fail(EXIT_RUNTIME, "out of memory");
    const cli_flicker_desc d = {.common = &o->common, .renderer = r, .scene = in->scene, .scene_key = in->name,
                                .base = in->cam, .radius = vr->radius, .spp = o->spp, .no_cache = o->no_cache};
    int code = cli_flicker_run(&d, configs, count, vr->flicker, &vr->flicker_ref);
    for (int k = 0; k < count && code == EXIT_OK; ++k) {
        char path[900] = "";
        snprintf(path, sizeof path, "%s/%s/%s_temporal_worst.png", o->report, vr->dir, vr->methods[k].stem);
        if (!track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
        if (write_grey(path, vr->flicker[k].on.worst_ao, o->common.width, o->common.height) != OB_OK)
            return cli_fail_library_as(EXIT_OUTPUT);
    }
    return code;
}

static int compare_checked(const compare_opts *op);

int cmd_compare(int argc, char **argv)
{
    compare_opts o;
    cli_outputs outs = {0};
    int code = parse(argc, argv, &o, &outs);
    if (code == 0) code = compare_checked(&o);
    /* The report replaces --report only whole; a failure removes the temporary one. */
    code = cli_outputs_finish(&outs, code < 0 ? EXIT_OK : code);
    if (code == EXIT_OK && o.final_report) {
        int n = (int)strlen(o.final_report);
        while (n > 1 && o.final_report[n - 1] == '/') --n; /* "rep/" names rep/index.html */
        printf("report: %.*s/index.html\n", n, o.final_report);
    }
    return code;
}

static int compare_checked(const compare_opts *op)
{
    compare_opts o = *op;
    int code = EXIT_OK;
    const cli_common *c = &o.common;

    /* Everything is checked before the report directory is touched: the combinations and their
     * settings, every scene and camera, the context and the renderer's size. */
    cli_config *configs = NULL;
    int count = 0;
    if ((code = cli_common_configs(c, &configs, &count)) != EXIT_OK) return code;
    view_input inputs[MAX_VIEWS];
    memset(inputs, 0, sizeof inputs);
    view_result *views = calloc(MAX_VIEWS, sizeof *views);
    ob_context *ctx = NULL;
    ob_renderer *r = NULL;
    outputs out = {0};
    int done = 0;
    ob_progress bar = {0};
    if (!views) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }
    for (int v = 0; v < o.view_count && code == EXIT_OK; ++v) code = load_view(&o, o.views[v], &inputs[v], inputs, v);
    for (int v = 0; v < o.view_count && code == EXIT_OK && cli_common_moves(c); ++v) {
        ob_camera probe; /* --path names a path of every scene */
        code = cli_common_path_camera(c, inputs[v].scene, &inputs[v].cam, 0, &probe);
    }
    if (code != EXIT_OK) goto cleanup;
    ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!r) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    if ((code = cli_common_prepare(c, r)) != EXIT_OK) goto cleanup;

    /* The report is written into its temporary directory from here on. */
    if (!(o.report = cli_outputs_dir(o.outs, o.report_index))) {
        code = EXIT_OUTPUT;
        goto cleanup;
    }
    /* One step per method of each view, and per flicker row along a path (the reference inside
     * reports its own rays): the bar names the view and the method, and moves at every method, so
     * a run of ten methods never looks hung; in a log each step is a line. On a terminal it is held
     * (its line ended) before a view's references so that their bars draw on the lines below. */
    const int per_view = count * (cli_common_moves(c) ? 2 : 1);
    ob_progress_begin(&bar, "compare", (long long)o.view_count * per_view);
    bar.each = true;
    o.bar = &bar;
    for (int v = 0; v < o.view_count && code == EXIT_OK; ++v) {
        /* On a terminal the bar keeps its own line above the reference's bar (issue 48). */
        char step[320];
        snprintf(step, sizeof step, "%.60s:%.40s reference (view %d/%d)", inputs[v].name, inputs[v].cam.name, v + 1,
                 o.view_count);
        ob_progress_hold(&bar, step);
        code = run_view(&o, r, &inputs[v], configs, count, &out, &views[v]);
        if (code == EXIT_OK && cli_common_moves(c)) {
            snprintf(step, sizeof step, "%.60s:%.40s the path's references", inputs[v].name, inputs[v].cam.name);
            ob_progress_hold(&bar, step);
            code = run_flicker(&o, r, &inputs[v], configs, count, &out, &views[v]);
            char what[160];
            snprintf(what, sizeof what, "%.60s:%.40s flicker, %d rows", views[v].scene, views[v].camera, count);
            if (code == EXIT_OK) ob_progress_advance(&bar, count, what);
        }
        if (code == EXIT_OK) mark_pareto(&views[v]);
        if (code == EXIT_OK) code = write_chart(&o, &views[v], &out);
        if (code == EXIT_OK) ++done;
    }
    ob_progress_end(&bar);
    /* Each view's set, if scenes/views.json names it (as SCENE:CAMERA): labels, never a failure
     * when the file is missing; a malformed one is an error like any input. */
    cli_view_sets sets;
    if (code == EXIT_OK) code = cli_view_sets_load(&sets, false);
    for (int v = 0; v < done && code == EXIT_OK; ++v) {
        char spec[256];
        snprintf(spec, sizeof spec, "%s:%s", views[v].scene, views[v].camera);
        views[v].set = cli_view_set_of(&sets, spec);
    }
    if (code == EXIT_OK) code = write_json(&o, ctx, views, done, &out);
    if (code == EXIT_OK) code = write_html(&o, ctx, views, done, &out);
cleanup:
    ob_progress_end(&bar);
    outputs_finish(&out, code != EXIT_OK);
    for (int v = 0; v < MAX_VIEWS && views; ++v) {
        free(views[v].methods);
        cli_flicker_free(views[v].flicker, views[v].method_count);
        free(views[v].flicker);
    }
    free(views);
    for (int v = 0; v < MAX_VIEWS; ++v)
        if (inputs[v].owns_scene) ob_destroy_scene(inputs[v].scene);
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    free(configs);
    return code;
}
