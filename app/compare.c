/* obscura compare: every method on the same inputs against the ray-traced ground truth, written
 * as an HTML report (index.html), results.json and PNGs.
 *
 *   report/index.html                    per view: images, error maps, sortable table, chart
 *   report/results.json                  every number
 *   report/VIEW/reference_ao.png         AO_R from the Embree reference (docs/architecture.md)
 *   report/VIEW/METHOD_final.png, _ao.png, _error.png
 *   report/VIEW/mask_NAME.png            where each metric mask lies (ob_metric_masks)
 *   report/VIEW/chart.svg                quality (RMSE) against GPU time, made with gnuplot
 *   report/VIEW/chart.gp                 the gnuplot script it was drawn from
 *
 * The reference is cached by (scene, camera, size, radius, spp) under $XDG_CACHE_HOME/obscura
 * (or ~/.cache/obscura): the report is re-run far more often than the geometry changes.
 *
 * This file runs the views: the options, the reference, each row's frames, metrics and images.
 * What they found is written by compare_report.c (results.json, index.html) and compare_chart.c
 * (the chart); compare.h is what the three share. */
#include <cglm/cglm.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "compare.h"
#include "graded_views.h"
#include "reference_cache.h"

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
          "  --shard K/N           run only this process's share of the views (K = 0..N-1, as a Slurm\n"
          "                        array's SLURM_ARRAY_TASK_ID), each shard with its own --report;\n"
          "                        obscura merge puts the N reports together (docs/scale.md)\n"
          "  --shard-unit view|row what a shard takes: whole views, each with its reference and every\n"
          "                        row (default), or single rows of views, balanced by their samples\n"
          "                        per pixel, for more shards than views; a row's view takes its\n"
          "                        reference from the cache, so run --references-only first\n"
          "  --references-only     trace (or find) each view's AO_R in the reference cache (with\n"
          "                        --path/--orbit, every frame's too) and stop: no report (with\n"
          "                        --shard K/N, this shard's views)\n"
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

/* A row's expected cost beside the others of its view: its samples per pixel (16 where the
 * method takes its own count) over the pixels its AO scale leaves, as the frames it times cost. */
static double row_cost(const cli_config *cfg)
{
    double taps = cfg->samples.count > 0 ? (double)cfg->samples.count : 16.0;
    return taps / ((double)cfg->ao_divisor * (double)cfg->ao_divisor);
}

int compare_assign_rows(compare_opts *o, const cli_config *configs, int count, int shards)
{
    const int units = o->view_count * count;
    double *cost = malloc((size_t)units * sizeof *cost + 1);
    free(o->row_owner);
    o->row_owner = malloc((size_t)units * sizeof *o->row_owner + 1);
    if (!cost || !o->row_owner) {
        free(cost);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    for (int v = 0; v < o->view_count; ++v)
        for (int k = 0; k < count; ++k)
            cost[v * count + k] = (double)o->common.width * (double)o->common.height * row_cost(&configs[k]);
    cli_shard_assign(cost, units, shards, o->row_owner);
    o->row_count = count;
    free(cost);
    return EXIT_OK;
}

int compare_row_owner(const compare_opts *o, int v, int k)
{
    return o->by_row ? o->row_owner[v * o->row_count + k] : o->owner[v];
}

bool compare_row_is_mine(const compare_opts *o, int v, int k)
{
    return compare_row_owner(o, v, k) == o->shard.index;
}

bool compare_view_is_mine(const compare_opts *o, int v)
{
    if (!o->by_row) return o->owner[v] == o->shard.index;
    for (int k = 0; k < o->row_count; ++k)
        if (compare_row_is_mine(o, v, k)) return true;
    return false;
}

void compare_assign_shards(compare_opts *o, int shards)
{
    /* Every view costs pixels x rays (one size and spp a run; its rows are the same for every
     * view): balanced by that, the same on every machine (shard.h). */
    double cost[MAX_VIEWS];
    for (int v = 0; v < o->view_count; ++v) cost[v] = (double)o->common.width * (double)o->common.height * (double)o->spp;
    cli_shard_assign(cost, o->view_count, shards, o->owner);
}

int compare_parse(int argc, char **argv, compare_opts *o, cli_outputs *outs)
{
    *o = (compare_opts){.spp = 512, .outs = outs, .report_index = -1, .argc = argc, .argv = argv, .shard = {0, 1}};
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
        if (!strcmp(a, "--references-only")) {
            o->references_only = true;
            continue;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        if (strcmp(a, "--scene") && strcmp(a, "--report") && strcmp(a, "--spp") && strcmp(a, "--radius") &&
            strcmp(a, "--budget-ms") && strcmp(a, "--shard") && strcmp(a, "--shard-unit"))
            return cli_unknown_option("compare", a, compare_usage, &o->common);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura compare --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) {
            if (o->view_count >= MAX_VIEWS) return cli_fail(EXIT_USAGE, "--scene: at most %d", MAX_VIEWS);
            o->views[o->view_count++] = v;
        } else if (!strcmp(a, "--report")) {
            o->report = v;
        } else if (!strcmp(a, "--shard")) {
            int code = cli_shard_parse("--shard", v, &o->shard);
            if (code != EXIT_OK) return code;
        } else if (!strcmp(a, "--shard-unit")) {
            if (strcmp(v, "view") && strcmp(v, "row"))
                return cli_fail(EXIT_USAGE, "--shard-unit: expected view or row, got '%s'", v);
            o->by_row = !strcmp(v, "row");
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
    if (o->references_only && (o->report || o->by_row || o->budget_ms > 0.0))
        return cli_fail(EXIT_USAGE, "--references-only writes no report: it takes no --report, --shard-unit or --budget-ms");
    if (!o->report && !o->references_only) {
        /* No --report: a folder of the current directory, replaced next time as --report would
         * replace it (only what this tool wrote there), and named before anything runs. */
        o->report = CLI_DEFAULT_REPORT;
        printf("compare: no --report: the report goes to %s/ (--report DIR to choose)\n", o->report);
    }
    if (o->view_count == 0) return cli_fail(EXIT_USAGE, "--scene is required (see obscura compare --help)");
    if (o->report && !*o->report) return cli_fail(EXIT_USAGE, "--report: expected a directory, got ''");
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    compare_assign_shards(o, o->shard.count);
    if (o->common.ambient_mode != OB_AMBIENT_CONSTANT)
        return cli_fail(EXIT_USAGE, "--ambient: compare takes only 'constant' (the one-bounce reference has a constant ambient)");
    if (o->references_only) return EXIT_OK;
    o->final_report = o->report;
    return cli_outputs_add(o->outs, "--report", o->report, CLI_FMT_DIR, &o->report_index);
}

/* ---- the report's files ---------------------------------------------------------------------- */

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
bool compare_track_file(report_files *out, const char *path)
{
    return push_path(&out->files, &out->file_count, &out->file_cap, path);
}

/* mkdir, remembering a directory this run made; fails on a path that exists but is no directory. */
int compare_make_dir(report_files *out, const char *path)
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

void compare_files_finish(report_files *out, bool failed)
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
    *out = (report_files){0};
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

/* A view's images and scratch (W x H, bottom row first, as ob_read_image gives them), its
 * G-buffer with the camera's matrices (frame: what the reference reads) and the exposure of its
 * final images. */
typedef struct view_buffers {
    int w, h;
    size_t px;
    float *depth, *normals, *ref, *ao, *ref_rgb, *test_rgb;
    uint8_t *rgba, *mask, *heat, *masks;
    cli_view_frame frame; /* depth and normals point into the two above */
    cli_exposure exposure;
    char dir[700];        /* REPORT/VIEW */
} view_buffers;

static int buffers_make(view_buffers *b, int w, int h)
{
    const size_t px = (size_t)w * (size_t)h;
    *b = (view_buffers){.w = w, .h = h, .px = px};
    b->depth = malloc(px * sizeof(float));
    b->normals = malloc(px * 3 * sizeof(float));
    b->ref = malloc(px * sizeof(float));
    b->ao = malloc(px * 3 * sizeof(float));
    b->rgba = malloc(px * 4);
    b->mask = malloc(px);
    b->heat = malloc(px * 3);
    b->masks = malloc(px * OB_MASK_COUNT);
    if (!b->depth || !b->normals || !b->ref || !b->ao || !b->rgba || !b->mask || !b->heat || !b->masks)
        return cli_fail(EXIT_RUNTIME, "out of memory");
    return EXIT_OK;
}

static void buffers_free(view_buffers *b)
{
    free(b->depth);
    free(b->normals);
    free(b->ref);
    free(b->ao);
    free(b->ref_rgb);
    free(b->test_rgb);
    cli_exposure_free(&b->exposure);
    free(b->rgba);
    free(b->mask);
    free(b->heat);
    free(b->masks);
}

/* The G-buffer is the same for every method: taken from a `none` frame, with the camera matrices
 * the renderer makes (renderer.c), from which the reference computes the world points. */
static int view_gbuffer(const compare_opts *o, ob_renderer *r, const ob_camera *cam, const view_result *vr,
                        view_buffers *b)
{
    const cli_common *c = &o->common;
    ob_settings s = {0};
    ob_settings_init(&s, "none");
    if (ob_render_frame(r, cam, &s) != OB_OK) return cli_fail_from_library();
    ob_read_image(r, OB_IMAGE_DEPTH_F32, b->depth, b->px * sizeof(float));
    ob_read_image(r, OB_IMAGE_NORMAL_F32, b->normals, b->px * 3 * sizeof(float));
    size_t covered = 0;
    for (size_t i = 0; i < b->px; ++i) covered += b->mask[i] = b->depth[i] > 0.0f;
    if (!covered && !c->allow_empty)
        return cli_fail(c->has_eye ? EXIT_USAGE : EXIT_INPUT, "nothing visible from this camera (%s:%s): the frame "
                        "covers no pixel; check the camera (or --allow-empty to report it anyway)", vr->scene, vr->camera);

    /* The same camera matrices as the renderer (renderer.c): for the world points. */
    ob_camera cm = *cam;
    if (cm.fov_y_deg <= 0.0f) cm.fov_y_deg = 60.0f;
    if (cm.up[0] == 0.0f && cm.up[1] == 0.0f && cm.up[2] == 0.0f) cm.up[1] = 1.0f;
    mat4 view, inv_view, proj;
    glm_lookat(cm.eye, cm.target, cm.up, view);
    glm_mat4_inv(view, inv_view);
    glm_perspective(glm_rad(cm.fov_y_deg), (float)b->w / (float)b->h, 1.0f, 2.0f, proj);
    proj[2][0] = cm.shift[0]; /* the lens shift, as ob_render_frame */
    proj[2][1] = cm.shift[1];
    b->frame = (cli_view_frame){.width = b->w, .height = b->h, .depth = b->depth, .normals = b->normals, .cam = cm,
                                .proj_info = {1.0f / proj[0][0], 1.0f / proj[1][1], proj[2][0], proj[2][1]}};
    memcpy(b->frame.inv_view, inv_view, sizeof b->frame.inv_view);
    return EXIT_OK;
}

/* AO_R at the G-buffer's points, from the reference cache or traced into it (reference_cache.h). */
static int view_trace(const compare_opts *o, const view_input *in, view_result *vr, view_buffers *b)
{
    const cli_common *c = &o->common;
    char key[900] = "";
    cli_reference_key(c, in->name, in->cam.name, key, sizeof key);
    cli_reference_info info;
    int code = cli_reference_ao(in->scene, &b->frame, key, vr->radius, o->spp, o->no_cache, c->verbose, b->ref, &info);
    vr->ref_cached = info.cached;
    vr->ref_seconds = info.seconds;
    vr->ref_stderr_mean = info.stderr_mean;
    return code;
}

/* AO_R (view_trace), written as reference_ao.png. */
static int view_reference(const compare_opts *o, const view_input *in, view_result *vr, view_buffers *b,
                          report_files *out)
{
    int code = view_trace(o, in, vr, b);
    if (code != EXIT_OK) return code;
    char path[900] = "";
    snprintf(path, sizeof path, "%s/reference_ao.png", b->dir);
    if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    if (write_grey(path, b->ref, b->w, b->h) != OB_OK) return cli_fail_library_as(EXIT_OUTPUT);
    return EXIT_OK;
}

/* Where the error matters (issue 15): the metric masks from the same depth and reference, each
 * measured again for every row and drawn for the report. */
static int view_masks(view_result *vr, view_buffers *b, report_files *out)
{
    vr->mask_desc = ob_metric_mask_defaults(NULL, b->w);
    if (ob_metric_masks(b->depth, b->ref, b->w, b->h, vr->radius, &vr->mask_desc, b->masks) != OB_OK)
        return cli_fail_from_library();
    for (int m = 0; m < OB_MASK_COUNT; ++m) {
        const uint8_t *plane = b->masks + (size_t)m * b->px;
        vr->mask_pixels[m] = 0;
        for (size_t i = 0; i < b->px; ++i) vr->mask_pixels[m] += plane[i] != 0;
        char path[900] = "";
        snprintf(path, sizeof path, "%s/mask_%s.png", b->dir, ob_metric_mask_name((ob_metric_mask)m));
        if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
        if (write_mask(path, b->depth, b->ref, plane, b->w, b->h, b->heat) != OB_OK) return cli_fail_library_as(EXIT_OUTPUT);
    }
    return EXIT_OK;
}

/* The one-bounce reference, for directional methods only: their composed radiance (direct x M
 * + bounce) against shadow rays + one diffuse bounce + ambient x AO_R (ob_reference_bounce),
 * with the lights and the constant ambient the rows render with. It casts a shadow ray per
 * light at every bounce hit, so it takes a quarter of the AO rays. */
static int view_bounce(const compare_opts *o, ob_renderer *r, const ob_scene *scene, const cli_config *configs,
                       view_result *vr, view_buffers *b)
{
    const size_t px = b->px;
    const ob_settings *lit = &configs[0].settings;
    b->ref_rgb = malloc(px * 3 * sizeof(float));
    b->test_rgb = malloc(px * 3 * sizeof(float));
    float *albedo = malloc(px * 3 * sizeof(float)), *pos = malloc(px * 3 * sizeof(float));
    float *nrm = malloc(px * 3 * sizeof(float));
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    bool ok = b->ref_rgb && b->test_rgb && albedo && pos && nrm &&
              ob_read_image(r, OB_IMAGE_ALBEDO_F32, albedo, px * 3 * sizeof(float)) == OB_OK &&
              ob_reference_points(b->depth, b->normals, b->w, b->h, b->frame.proj_info, b->frame.inv_view, pos, nrm) ==
                  OB_OK &&
              ob_reference_bounce(scene, lit->light_count > 0 ? lit->lights : NULL, lit->light_count, lit->ambient, pos,
                                  nrm, albedo, px,
                                  &(ob_reference_desc){.spp = o->spp / 4 > 16 ? o->spp / 4 : 16, .radius = vr->radius,
                                                       .progress = true},
                                  b->ref_rgb) == OB_OK;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    vr->bounce_seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    free(albedo);
    free(pos);
    free(nrm);
    if (!ok) return b->ref_rgb && b->test_rgb ? cli_fail_from_library() : cli_fail(EXIT_RUNTIME, "out of memory");
    vr->has_bounce = true;
    return EXIT_OK;
}

/* A row's settings: its combination's, graded at the pixel centres, at the reference's radius. */
static ob_settings row_settings(const cli_config *cfg, const ob_method_info *mi, float radius)
{
    ob_settings s = cfg->settings;
    /* A still view is graded at the pixel centres, as its reference is traced: --jitter is for
     * the path rows (flicker.h). */
    s.jitter = 0;
    /* Every method at the reference's radius, unless a --set gave this one its own. */
    bool radius_given = false;
    for (int p = 0; p < mi->param_count; ++p)
        if (!strcmp(mi->params[p].name, "radius")) radius_given = (s.params_set >> p) & 1u;
    char radius_set[64];
    snprintf(radius_set, sizeof radius_set, "radius=%.9g", (double)radius);
    if (!radius_given && !isnan(ob_settings_get(&s, "radius"))) ob_settings_set(&s, radius_set);
    return s;
}

/* FRAMES frames of a row, each waited for: the medians of its GPU pass times (GL timestamps around
 * each pass). frame_ms is the sum of every timed pass of a frame, not the wall-clock time. */
static int time_row(ob_renderer *r, const ob_camera *cam, const ob_settings *s, method_result *mr)
{
    double ao_ms[FRAMES], frame_ms[FRAMES], chain_ms[FRAMES];
    for (int f = 0; f < FRAMES; ++f) {
        if (ob_render_frame(r, cam, s) != OB_OK || ob_wait_timings(r) != OB_OK) return cli_fail_from_library();
        ob_pass_timing t[16];
        int tn = ob_query_timings(r, t, 16);
        ao_ms[f] = frame_ms[f] = chain_ms[f] = 0.0;
        for (int p = 0; p < tn; ++p) {
            if (!strcmp(t[p].name, "ao")) ao_ms[f] = t[p].ms;
            static const char *const chain[] = {"ao", "depth_mips", "second_back", "edges", "filter", "upsample"};
            for (size_t q = 0; q < sizeof chain / sizeof chain[0]; ++q)
                if (!strcmp(t[p].name, chain[q])) chain_ms[f] += t[p].ms;
            frame_ms[f] += t[p].ms;
        }
    }
    mr->ao_ms = cli_median(ao_ms, FRAMES);
    mr->chain_ms = cli_median(chain_ms, FRAMES);
    mr->frame_ms = cli_median(frame_ms, FRAMES);
    return EXIT_OK;
}

/* The row's AO (just rendered) against the reference: over the view, inside each metric mask, and
 * for a directional method its composed radiance against the one-bounce reference. */
static int grade_row(ob_renderer *r, const view_result *vr, view_buffers *b, method_result *mr)
{
    const int w = b->w, h = b->h;
    ob_read_image(r, OB_IMAGE_AO_F32, b->ao, b->px * sizeof(float));
    if (ob_compare_images(b->ao, b->ref, b->mask, w, h, 1, &mr->m) != OB_OK) return cli_fail_from_library();
    for (int m = 0; m < OB_MASK_COUNT; ++m) {
        mr->in_mask[m] = (ob_metrics){0};
        if (vr->mask_pixels[m] > 0 &&
            ob_compare_images(b->ao, b->ref, b->masks + (size_t)m * b->px, w, h, 1, &mr->in_mask[m]) != OB_OK)
            return cli_fail_from_library();
    }
    if (mr->directional &&
        (ob_read_image(r, OB_IMAGE_HDR_F32, b->test_rgb, b->px * 3 * sizeof(float)) != OB_OK ||
         ob_compare_images(b->test_rgb, b->ref_rgb, b->mask, w, h, 3, &mr->rgb) != OB_OK))
        return cli_fail_from_library();
    return EXIT_OK;
}

/* STEM_final.png (at the view's one exposure), STEM_ao.png and STEM_error.png. */
static int write_row_images(ob_renderer *r, const ob_camera *cam, const ob_settings *s, view_buffers *b,
                            const method_result *mr, report_files *out)
{
    const int w = b->w, h = b->h;
    int code = cli_exposure_apply(&b->exposure, r, cam, s);
    if (code != EXIT_OK) return code;
    ob_read_image(r, OB_IMAGE_FINAL_RGBA8, b->rgba, b->px * 4);
    static const char *const kinds[3] = {"final", "ao", "error"};
    ob_error e = OB_OK;
    for (int q = 0; q < 3 && e == OB_OK; ++q) {
        char path[900] = "";
        snprintf(path, sizeof path, "%s/%s_%s.png", b->dir, mr->stem, kinds[q]);
        if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
        if (q == 0) e = ob_write_png(path, w, h, 4, b->rgba);
        else if (q == 1) e = write_grey(path, b->ao, w, h);
        else {
            /* Error map: +-0.5 of visibility saturates. */
            e = ob_error_heatmap(b->ao, b->ref, b->mask, w, h, true, 0.5f, b->heat);
            if (e == OB_OK) e = ob_write_png(path, w, h, 3, b->heat);
        }
    }
    return e == OB_OK ? EXIT_OK : cli_fail_library_as(EXIT_OUTPUT);
}

/* Row k of count: timed, graded, its images written, and the bar moved on. */
static int run_row(const compare_opts *o, ob_renderer *r, const ob_camera *cam, const cli_config *cfg, int k, int count,
                   view_result *vr, view_buffers *b, report_files *out)
{
    const ob_method_info *mi = ob_method_at(cfg->method);
    method_result *mr = &vr->methods[vr->method_count++];
    snprintf(mr->name, sizeof mr->name, "%s", mi->name);
    snprintf(mr->label, sizeof mr->label, "%s", cfg->label);
    snprintf(mr->stem, sizeof mr->stem, "%s", cfg->stem);
    mr->config = cfg;
    mr->directional = mi->directional;
    const ob_settings s = row_settings(cfg, mi, vr->radius);
    int code = time_row(r, cam, &s, mr);
    if (code == EXIT_OK) code = grade_row(r, vr, b, mr);
    if (code == EXIT_OK) code = write_row_images(r, cam, &s, b, mr, out);
    if (code != EXIT_OK) return code;
    if (o->common.verbose) {
        if (o->bar) ob_progress_break(o->bar);
        fprintf(stderr, "obscura: %s/%s %-12s RMSE %.4f bias %+.4f SSIM %.3f ao %.2f ms\n", vr->scene, vr->camera,
                mr->label, mr->m.rmse, mr->m.bias, mr->m.ssim, mr->ao_ms);
    }
    if (o->bar) {
        char what[200];
        snprintf(what, sizeof what, "%.60s:%.40s %.60s (%d/%d)", vr->scene, vr->camera, mr->label, k + 1, count);
        ob_progress_advance(o->bar, 1, what);
    }
    return EXIT_OK;
}

/* The view's scene, camera, directory name and radius. */
static void view_name(const compare_opts *o, const view_input *in, view_result *vr)
{
    snprintf(vr->scene, sizeof vr->scene, "%s", ob_query_scene_name(in->scene));
    snprintf(vr->camera, sizeof vr->camera, "%s", in->cam.name);
    char safe_scene[128], safe_cam[64];
    cli_safe_name(safe_scene, sizeof safe_scene, vr->scene);
    cli_safe_name(safe_cam, sizeof safe_cam, vr->camera);
    snprintf(vr->dir, sizeof vr->dir, "%s_%s", safe_scene, safe_cam);
    vr->radius = o->radius > 0.0f ? o->radius : ob_query_scene_ao_radius(in->scene);
}

/* --references-only: this shard's views' AO_R into the reference cache (found there or traced),
 * a line each, and no report: the first stage of a run split by rows (docs/scale.md). */
static int run_references(const compare_opts *o, ob_renderer *r, const view_input *inputs)
{
    int code = EXIT_OK;
    for (int v = 0; v < o->view_count && code == EXIT_OK; ++v) {
        if (!compare_view_is_mine(o, v)) continue;
        view_result vr = {.index = v};
        view_name(o, &inputs[v], &vr);
        if (ob_renderer_set_scene(r, inputs[v].scene) != OB_OK) return cli_fail_from_library();
        view_buffers b;
        code = buffers_make(&b, o->common.width, o->common.height);
        if (code == EXIT_OK) code = view_gbuffer(o, r, &inputs[v].cam, &vr, &b);
        if (code == EXIT_OK) code = view_trace(o, &inputs[v], &vr, &b);
        if (code == EXIT_OK)
            printf("reference: %s:%s %s (%.1f s, mean standard error %.4f)\n", vr.scene, vr.camera,
                   vr.ref_cached ? "was in the cache" : "traced into the cache", vr.ref_seconds, vr.ref_stderr_mean);
        buffers_free(&b);
        if (code == EXIT_OK && cli_common_moves(&o->common)) {
            /* Along --path/--orbit: every frame's reference, as the flicker rows take them (no row). */
            const cli_flicker_desc d = {.common = &o->common, .renderer = r, .scene = inputs[v].scene,
                                        .scene_key = inputs[v].name, .base = inputs[v].cam, .radius = vr.radius,
                                        .spp = o->spp, .no_cache = o->no_cache};
            cli_flicker_row none;
            cli_flicker_reference ref;
            code = cli_flicker_run(&d, NULL, 0, &none, &ref);
            if (code == EXIT_OK)
                printf("reference: %s:%s along the %s, %d frames, in the cache\n", vr.scene, vr.camera,
                       o->common.path ? "path" : "orbit", ref.frames);
        }
    }
    return code;
}

/* One view: its directory, G-buffer, reference, masks (and one-bounce reference), then every row. */
static int run_view(const compare_opts *o, ob_renderer *r, const view_input *in, const cli_config *configs, int count,
                    report_files *out, view_result *vr)
{
    const cli_common *c = &o->common;
    view_name(o, in, vr);

    vr->methods = calloc((size_t)count, sizeof *vr->methods);
    if (!vr->methods) return cli_fail(EXIT_RUNTIME, "out of memory");
    if (ob_renderer_set_scene(r, in->scene) != OB_OK) return cli_fail_from_library();
    view_buffers b;
    int code = buffers_make(&b, c->width, c->height);
    snprintf(b.dir, sizeof b.dir, "%s/%s", o->report, vr->dir);
    if (code == EXIT_OK) code = compare_make_dir(out, b.dir);
    if (code == EXIT_OK) code = view_gbuffer(o, r, &in->cam, vr, &b);
    if (code == EXIT_OK) code = view_reference(o, in, vr, &b, out);
    if (code == EXIT_OK) code = view_masks(vr, &b, out);
    bool any_directional = false;
    for (int k = 0; k < count; ++k)
        any_directional = any_directional || (compare_row_is_mine(o, vr->index, k) && ob_method_at(configs[k].method)->directional);
    if (code == EXIT_OK && any_directional) code = view_bounce(o, r, in->scene, configs, vr, &b);
    /* One exposure for the view's final images: the view without AO's (cli_exposure_begin). */
    if (code == EXIT_OK) code = cli_exposure_begin(&b.exposure, r, &in->cam, &configs[0].settings, b.px);
    for (int k = 0; k < count && code == EXIT_OK; ++k)
        if (compare_row_is_mine(o, vr->index, k)) code = run_row(o, r, &in->cam, &configs[k], k, count, vr, &b, out);
    buffers_free(&b);
    return code;
}

/* --path / --orbit: the flicker metrics of every configuration (flicker.h), and each one's worst
 * frame with temporal on as STEM_temporal_worst.png. */
static int run_flicker(const compare_opts *o, ob_renderer *r, const view_input *in, const cli_config *configs, int count,
                       report_files *out, view_result *vr)
{
    /* The view's rows this shard ran (every row but with --shard-unit row), in their order. */
    cli_config *mine = malloc((size_t)count * sizeof *mine);
    int *index = malloc((size_t)count * sizeof *index), n = 0;
    vr->flicker = calloc((size_t)count, sizeof *vr->flicker);
    if (!vr->flicker || !mine || !index) {
        free(mine);
        free(index);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    for (int k = 0; k < count; ++k)
        if (compare_row_is_mine(o, vr->index, k)) mine[n] = configs[k], index[n++] = k;
    const cli_flicker_desc d = {.common = &o->common, .renderer = r, .scene = in->scene, .scene_key = in->name,
                                .base = in->cam, .radius = vr->radius, .spp = o->spp, .no_cache = o->no_cache};
    int code = cli_flicker_run(&d, mine, n, vr->flicker, &vr->flicker_ref);
    for (int k = 0; k < n; ++k) vr->flicker[k].config = &configs[index[k]];
    free(mine);
    free(index);
    for (int k = 0; k < n && code == EXIT_OK; ++k) {
        char path[900] = "";
        snprintf(path, sizeof path, "%s/%s/%s_temporal_worst.png", o->report, vr->dir, vr->methods[k].stem);
        if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
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
    int code = compare_parse(argc, argv, &o, &outs);
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

/* What one run holds from the checks to the report. */
typedef struct compare_run {
    cli_config *configs;
    int count;
    view_input inputs[MAX_VIEWS];
    view_result *views;
    ob_context *ctx;
    ob_renderer *r;
    report_files out;
    int done;                     /* views run */
    ob_progress bar;
} compare_run;

/* Everything is checked before the report directory is touched: the combinations and their
 * settings, every scene and camera, the context and the renderer's size. */
static int compare_prepare(compare_opts *o, compare_run *run)
{
    const cli_common *c = &o->common;
    int code = cli_common_configs(c, &run->configs, &run->count);
    if (code == EXIT_OK && o->by_row) code = compare_assign_rows(o, run->configs, run->count, o->shard.count);
    if (code != EXIT_OK) return code;
    run->views = calloc(MAX_VIEWS, sizeof *run->views);
    if (!run->views) return cli_fail(EXIT_RUNTIME, "out of memory");
    for (int v = 0; v < o->view_count && code == EXIT_OK; ++v)
        if (compare_view_is_mine(o, v)) code = load_view(o, o->views[v], &run->inputs[v], run->inputs, v);
    for (int v = 0; v < o->view_count && code == EXIT_OK && cli_common_moves(c); ++v) {
        ob_camera probe; /* --path names a path of every scene */
        code = cli_common_path_camera(c, run->inputs[v].scene, &run->inputs[v].cam, 0, &probe);
    }
    if (code != EXIT_OK) return code;
    run->ctx = cli_make_context(c->gpu, c->verbose);
    if (!run->ctx) return cli_fail_from_library();
    snprintf(o->renderer, sizeof o->renderer, "%s", ob_query_renderer(run->ctx));
    snprintf(o->gl_version, sizeof o->gl_version, "%s", ob_query_gl_version(run->ctx));
    run->r = ob_make_renderer(run->ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!run->r) return cli_fail_from_library();
    return cli_common_prepare(c, run->r);
}

/* Every view (and its flicker rows and chart), into the report's temporary directory. */
static int run_views(compare_opts *o, compare_run *run)
{
    const cli_common *c = &o->common;
    /* The report is written into its temporary directory from here on. */
    if (!(o->report = cli_outputs_dir(o->outs, o->report_index))) return EXIT_OUTPUT;
    /* One step per method of each view, and per flicker row along a path (the reference inside
     * reports its own rays): the bar names the view and the method, and moves at every method, so
     * a run of ten methods never looks hung; in a log each step is a line. On a terminal it is held
     * (its line ended) before a view's references so that their bars draw on the lines below. */
    const int count = run->count;
    int mine = 0; /* rows of this shard */
    for (int v = 0; v < o->view_count; ++v)
        for (int k = 0; k < count; ++k) mine += compare_row_is_mine(o, v, k);
    ob_progress_begin(&run->bar, "compare", (long long)mine * (cli_common_moves(c) ? 2 : 1));
    run->bar.each = true;
    o->bar = &run->bar;
    int code = EXIT_OK;
    for (int v = 0; v < o->view_count && code == EXIT_OK; ++v) {
        if (!compare_view_is_mine(o, v)) continue; /* another shard's view */
        view_result *vr = &run->views[run->done];
        vr->index = v;
        /* On a terminal the bar keeps its own line above the reference's bar (issue 48). */
        char step[320];
        snprintf(step, sizeof step, "%.60s:%.40s reference (view %d/%d)", run->inputs[v].name,
                 run->inputs[v].cam.name, v + 1, o->view_count);
        ob_progress_hold(&run->bar, step);
        code = run_view(o, run->r, &run->inputs[v], run->configs, count, &run->out, vr);
        if (code == EXIT_OK && cli_common_moves(c)) {
            snprintf(step, sizeof step, "%.60s:%.40s the path's references", run->inputs[v].name,
                     run->inputs[v].cam.name);
            ob_progress_hold(&run->bar, step);
            code = run_flicker(o, run->r, &run->inputs[v], run->configs, count, &run->out, vr);
            char what[160];
            snprintf(what, sizeof what, "%.60s:%.40s flicker, %d rows", vr->scene, vr->camera, vr->method_count);
            if (code == EXIT_OK) ob_progress_advance(&run->bar, vr->method_count, what);
        }
        if (code == EXIT_OK) compare_mark_pareto(vr);
        if (code == EXIT_OK) code = compare_write_chart(o, vr, &run->out);
        if (code == EXIT_OK) ++run->done;
    }
    ob_progress_end(&run->bar);
    return code;
}

/* Each view's set, if scenes/views.json names it (as SCENE:CAMERA): labels, never a failure
 * when the file is missing; a malformed one is an error like any input. */
int compare_label_sets(view_result *views, int count)
{
    cli_view_sets sets;
    int code = cli_view_sets_load(&sets, false);
    for (int v = 0; v < count && code == EXIT_OK; ++v) {
        char spec[256];
        snprintf(spec, sizeof spec, "%s:%s", views[v].scene, views[v].camera);
        views[v].set = cli_view_set_of(&sets, spec);
    }
    return code;
}

static void compare_run_free(compare_run *run, bool failed)
{
    ob_progress_end(&run->bar);
    compare_files_finish(&run->out, failed);
    for (int v = 0; v < MAX_VIEWS && run->views; ++v) {
        free(run->views[v].methods);
        cli_flicker_free(run->views[v].flicker, run->views[v].method_count);
        free(run->views[v].flicker);
    }
    free(run->views);
    for (int v = 0; v < MAX_VIEWS; ++v)
        if (run->inputs[v].owns_scene) ob_destroy_scene(run->inputs[v].scene);
    ob_destroy_renderer(run->r);
    ob_destroy_context(run->ctx);
    free(run->configs);
}

/* The report of the views run: results.json, index.html and, for a shard, shard.bin. */
static int write_report(const compare_opts *o, compare_run *run)
{
    int code = compare_label_sets(run->views, run->done);
    if (code == EXIT_OK) code = compare_write_json(o, run->views, run->done, &run->out);
    if (code == EXIT_OK) code = compare_write_html(o, run->views, run->done, &run->out);
    if (code == EXIT_OK && o->shard.count > 1) code = compare_write_shard(o, run->configs, run->views, run->done, &run->out);
    return code;
}

static int compare_checked(const compare_opts *op)
{
    compare_opts o = *op;
    compare_run *run = calloc(1, sizeof *run);
    if (!run) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = compare_prepare(&o, run);
    if (code == EXIT_OK) code = o.references_only ? run_references(&o, run->r, run->inputs) : run_views(&o, run);
    if (code == EXIT_OK && !o.references_only) code = write_report(&o, run);
    compare_run_free(run, code != EXIT_OK);
    free(run);
    free(o.row_owner);
    return code;
}
