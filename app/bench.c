/* obscura bench: GPU time per pass of every method over sample counts N and radii r (Belonogov 2018
 * §5.1 tables), against a no-AO frame, optionally in stereo against the 90 Hz budget (§5.2), as
 * a scaling study over resolution and triangle count, or (--host) the host path ob_host_ao beside
 * ob_render_frame's AO chain (issue 45). docs/architecture.md "Performance method": warm-up
 * frames first, then median/min/max over the measured frames, every ratio from the same run.
 *
 * This file parses the options and runs the sweep, the stereo run and the scaling study;
 * bench_host.c runs --host and bench_report.c prints and writes what they measured (bench.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"

/* --json and --csv (outputs.h): added while parsing, committed by cmd_bench. */
static cli_outputs bench_outs;
static int bench_json = -1, bench_csv = -1;

static const float QUICK_RADIUS = 4.0f;
static const int FULL_SAMPLES[] = {12, 24, 36, 64};
static const float FULL_RADII[] = {2.0f, 4.0f, 8.0f};

static void bench_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura bench [options]\n"
          "\n"
          "GPU time per pass (GL timestamp queries) of every AO method over sample counts N and\n"
          "radii r, after warm-up frames, as median/min/max over the measured frames, against a\n"
          "no-AO ('none') frame of the same camera, filter and AO scale: the tables of Belonogov 2018 §5.1-5.2.\n"
          "Each combination of --methods, --filters and --ao-scales is its own table.\n"
          "\n"
          "With no options it is a quick run (under 3 minutes on 2 cores with llvmpipe): every method\n"
          "once, first camera preset, N = 24, r = 4, 20 frames after 3, shadow maps rendered once.\n"
          "  --full                Belonogov 2018's whole table: every camera preset (identical presets\n"
          "                        once), N = 12,24,36,64, r = 2,4,8, 50 frames after 5, shadow maps\n"
          "                        rendered every frame; the options below still override it\n"
          "  --cameras A,B         camera presets by name or index (default: the first; --full every one)\n"
          "  --samples 12,24,36,64 the sweep's samples per pixel N (methods without a count run once);\n"
          "                        --quality low,high names them by preset instead (default 24)\n"
          "  --radius 2,4,8        r as a multiple of a quarter of the scene's suggested radius:\n"
          "                        radius = r x suggested / 4, so r = 4 is the suggested radius and\n"
          "                        2/4/8 are half/1x/2x (Belonogov 2018's r are metres on one scene); N and r\n"
          "                        are set after --set (default 4)\n"
          "  --frames N            measured frames per configuration (default 20; --full 50)\n"
          "  --warmup N            frames rendered first and not measured (default 3; --full 5)\n"
          "  --stereo              two eyes (one renderer each), eye offset +-ipd/2 along the\n"
          "                        camera's right vector, parallel views with off-axis frusta that\n"
          "                        converge at the camera's target (ob_stereo_cameras);\n"
          "                        frame = both eyes, against the 11.1 ms (90 Hz) budget; --size is\n"
          "                        per eye (default 1080x1200)\n"
          "  --ipd D               interpupillary distance in world units (default 0.064)\n"
          "  --scaling             instead of the sweep: AO-pass ms of each method against\n"
          "                        resolution and against triangles (scene tessellated 1x, 4x, 16x)\n"
          "                        at the first --samples and --radius values, first camera\n"
          "  --sizes WxH,WxH       --scaling's resolutions (default 640x480,1280x720,1920x1080,\n"
          "                        2560x1440,3840x2160)\n"
          "  --floor               also time a bare N-tap compute kernel (shaders/floor.glsl) at each\n"
          "                        configuration's N, radius and AO grid, one floor frame after each\n"
          "                        of the method's, and report AO pass / floor (the median of the\n"
          "                        frames' ratios: the floor of the machine at hand, at that moment)\n"
          "  --host                instead of the sweep: the host path (ob_host_ao) beside the frame's AO\n"
          "                        chain, per configuration (method, N, r, filter, AO scale, temporal),\n"
          "                        four paths in one run, alternated frame by frame:\n"
          "                          (a) frame: ob_render_frame, the sum of its chain passes (downsample,\n"
          "                              edges, depth_mips, second_back, ao, temporal, filter, upsample)\n"
          "                          (b) host_linear: ob_host_ao on that frame's G-buffer, read back and\n"
          "                              uploaded as R32F linear depth + RGBA16F view normals -> R32F\n"
          "                          (c) host_packed: as a D32F reversed-Z [0,1] depth buffer + octahedral\n"
          "                              RG16F world normals -> R8 (input pass + chain + output pass)\n"
          "                          (d) host_no_normals: (c) without normals (rebuilt from depth)\n"
          "                        each path's chain, input, output and total ms, total / (a) in the same\n"
          "                        frame, and (b)/(a) against issue 45's 1.05x; one renderer per path.\n"
          "                        Not with --stereo, --scaling, --floor or --guard\n"
          "  --host-rmse S[:C],... with --host, before the timing: on each view (at most 8) the RMSE and\n"
          "                        bias of (a)-(d) against the ray-traced AO_R (compare's reference and\n"
          "                        cache: 320x240, 512 rays/px), each view at its scene's suggested radius,\n"
          "                        N the first --samples/--quality if given, else the method's own, after\n"
          "                        5 calls of each path\n"
          "  --json FILE           every number, with GL renderer/version, CPU, commit and date\n"
          "  --csv FILE            one row per configuration and pass (--host: per configuration and path:\n"
          "                        scene, camera, method, samples, r, radius_world, filter, ao_scale,\n"
          "                        temporal, width, height, path, depth, normals, output, then median, min\n"
          "                        and max of chain_ms, input_ms, output_ms, total_ms and ratio_frame\n"
          "                        (total / (a) per frame), label; the RMSE is in the JSON only)\n"
          "\n"
          "stdout: per camera the none frames, then one table with a row per method when the run has\n"
          "one N and one r (the default), else one table per method (per combination), rows N, columns\n"
          "r; cells 'AO-pass ms / frame ms' (medians); --host: per configuration the four paths'\n"
          "'median (min-max)' and the (b)/(a) line, then the --host-rmse table; stderr: a progress bar\n"
          "with the configurations done and the time left.\n"
          "Every ms is GPU time from GL timestamp queries around each pass. frame ms is the sum of the\n"
          "frame's timed passes (stereo: both eyes'), not wall-clock time: the CPU's own work, gaps\n"
          "between passes and the present are not in it; FPS = 1000 / frame ms. Only --host's call cpu\n"
          "ms is wall-clock time, on the CPU.\n"
          "The methods' --methods default is every method but none, which is always measured\n"
          "(not with --host).\n",
          f);
    cli_common_usage(f, defaults);
}

static bool parse_int(const char *v, long lo, long hi, int *out)
{
    char *end = NULL;
    long n = strtol(v, &end, 10);
    if (end == v || *end || n < lo || n > hi) return false;
    *out = (int)n;
    return true;
}

/* Comma lists of positive numbers and sizes. */
static bool parse_float_list(const char *v, float *out, int *count)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", v);
    *count = 0;
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (*count >= MAX_LIST || !cli_parse_float(t, &out[*count]) || !(out[*count] > 0.0f)) return false;
        ++*count;
    }
    return *count > 0;
}

static bool parse_size_list(const char *v, int sizes[][2], int *count)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", v);
    *count = 0;
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (*count >= MAX_SIZES || !cli_parse_size(t, &sizes[*count][0], &sizes[*count][1])) return false;
        ++*count;
    }
    return *count > 0;
}

/* The options as given: 0, -1 after --help, or an exit code. */
static int parse_options(int argc, char **argv, bench_opts *o)
{
    /* frames, warmup and radii 0: not given (resolved after the loop, by --full). */
    *o = (bench_opts){.frames = 0, .warmup = -1, .ipd = 0.064f, .radius_count = 0,
                      .sizes = {{640, 480}, {1280, 720}, {1920, 1080}, {2560, 1440}, {3840, 2160}}, .size_count = 5,
                      .argc = argc, .argv = argv};
    cli_common *c = &o->common;
    cli_common_init(c, "bench", CLI_TAKES_SCENE | CLI_TAKES_LISTS | CLI_TAKES_GPU | CLI_TAKES_PATH);
    c->scene = "cornell";
    c->default_method = NULL; /* every method */
    c->width = 800;
    c->height = 600;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            bench_usage(stdout, c);
            return -1;
        }
        if (!strcmp(a, "--stereo")) { o->stereo = true; continue; }
        if (!strcmp(a, "--scaling")) { o->scaling = true; continue; }
        if (!strcmp(a, "--floor")) { o->floor = true; continue; }
        if (!strcmp(a, "--full")) { o->full = true; continue; }
        if (!strcmp(a, "--host")) { o->host = true; continue; }
        int taken = cli_common_option(c, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        const char *const own[] = {"--cameras", "--json", "--csv", "--radius", "--sizes", "--frames", "--warmup", "--ipd",
                                   "--host-rmse"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_unknown_option("bench", a, bench_usage, c);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura bench --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--cameras")) o->cameras = v;
        else if (!strcmp(a, "--json")) o->json = v;
        else if (!strcmp(a, "--csv")) o->csv = v;
        else if (!strcmp(a, "--host-rmse")) {
            int code = bench_host_views_check(v);
            if (code != EXIT_OK) return code;
            o->host_views = v;
        }
        else if (!strcmp(a, "--radius")) {
            if (!parse_float_list(v, o->radii, &o->radius_count))
                return cli_fail(EXIT_USAGE, "--radius: expected a comma list of positive numbers, got '%s'", v);
        } else if (!strcmp(a, "--sizes")) {
            if (!parse_size_list(v, o->sizes, &o->size_count))
                return cli_fail(EXIT_USAGE, "--sizes: expected a comma list of WIDTHxHEIGHT, got '%s'", v);
        } else if (!strcmp(a, "--frames")) {
            if (!parse_int(v, 1, 100000, &o->frames)) return cli_fail(EXIT_USAGE, "--frames: expected 1..100000, got '%s'", v);
        } else if (!strcmp(a, "--warmup")) {
            if (!parse_int(v, 0, 100000, &o->warmup)) return cli_fail(EXIT_USAGE, "--warmup: expected 0..100000, got '%s'", v);
        } else if (!strcmp(a, "--ipd")) {
            if (!cli_parse_float(v, &o->ipd) || !(o->ipd > 0.0f) || !isfinite(o->ipd))
                return cli_fail(EXIT_USAGE, "--ipd: expected a number > 0, got '%s'", v);
        }
    }
    return 0;
}

/* The options checked against each other and every default resolved (--full's among them); the
 * outputs added. 0 or an exit code. */
static int parse_finish(bench_opts *o)
{
    cli_common *c = &o->common;
    if (o->stereo && o->scaling) return cli_fail(EXIT_USAGE, "--stereo and --scaling exclude each other");
    if (o->host && (o->stereo || o->scaling || o->floor))
        return cli_fail(EXIT_USAGE, "--host and %s exclude each other", o->stereo ? "--stereo" : o->scaling ? "--scaling" : "--floor");
    if (o->host_views && !o->host) return cli_fail(EXIT_USAGE, "--host-rmse needs --host");
    if (o->stereo && (c->path || c->has_orbit)) return cli_fail(EXIT_USAGE, "--stereo and --path/--orbit exclude each other");
    /* The stereo size before cli_common_finish: its memory estimate is for the renderers made. */
    if (o->stereo && !c->has_size) {
        c->width = 1080;
        c->height = 1200;
    }
    /* --host: the frame's renderer and one per host path (HOST_PATHS). */
    c->renderers = o->stereo ? 2 : o->host ? 4 : 1;
    for (int z = 0; o->scaling && z < o->size_count; ++z)
        if ((long long)o->sizes[z][0] * o->sizes[z][1] > (long long)c->memory_width * c->memory_height) {
            c->memory_width = o->sizes[z][0];
            c->memory_height = o->sizes[z][1];
        }
    int code = cli_common_finish(c);
    if (code != EXIT_OK) return code;
    /* The CLI reads the frame's G-buffer back through the public API, which gives the visible frame
     * only: a host with a guard band renders the band itself (ob_host_input_size). */
    if (o->host && c->guard_px > 0)
        return cli_fail(EXIT_USAGE, "--host and --guard exclude each other: the frame's G-buffer is read back without "
                        "its band");
    o->samples_given = c->sample_count > 0;
    /* The sample counts are the sweep's rows (set per configuration by configure), not a list of
     * the combinations: they leave the common lists. */
    if (c->sample_count > 0) {
        o->sample_count = c->sample_count;
        for (int k = 0; k < o->sample_count; ++k) o->samples[k] = c->samples[k].count;
    } else if (o->full) {
        o->sample_count = (int)(sizeof FULL_SAMPLES / sizeof FULL_SAMPLES[0]);
        memcpy(o->samples, FULL_SAMPLES, sizeof FULL_SAMPLES);
    } else {
        o->sample_count = 1;
        o->samples[0] = QUICK_SAMPLES;
    }
    c->sample_count = 0;
    if (o->radius_count == 0) {
        o->radius_count = o->full ? (int)(sizeof FULL_RADII / sizeof FULL_RADII[0]) : 1;
        if (o->full) memcpy(o->radii, FULL_RADII, sizeof FULL_RADII);
        else o->radii[0] = QUICK_RADIUS;
    }
    if (o->frames == 0) o->frames = o->full ? FULL_FRAMES : QUICK_FRAMES;
    if (o->warmup < 0) o->warmup = o->full ? FULL_WARMUP : QUICK_WARMUP;
    o->keep_shadows = !o->full;
    /* none is always measured, as the baseline of each filter and AO scale. */
    int kept = 0;
    for (int k = 0; k < c->method_count; ++k)
        if (strcmp(ob_method_at(c->methods[k])->name, "none")) c->methods[kept++] = c->methods[k];
    c->method_count = kept;
    if (o->host && kept == 0)
        return cli_fail(EXIT_USAGE, "--host: no method to time ('none' runs no AO chain); name one with --methods");
    /* Both checked before anything is measured; written only as a pair (outputs.h). */
    if (o->json && (code = cli_outputs_add(&bench_outs, "--json", o->json, CLI_FMT_TEXT, &bench_json)) != EXIT_OK)
        return code;
    if (o->csv && (code = cli_outputs_add(&bench_outs, "--csv", o->csv, CLI_FMT_TEXT, &bench_csv)) != EXIT_OK) return code;
    return 0;
}

static int parse(int argc, char **argv, bench_opts *o)
{
    int code = parse_options(argc, argv, o);
    return code != 0 ? code : parse_finish(o);
}

/* ---- helpers --------------------------------------------------------------------------------- */

double bench_now_s(void)
{
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void bench_stats(double *v, int n, double *med, double *lo, double *hi)
{
    *med = cli_median(v, n);
    *lo = v[0];
    *hi = v[n - 1];
}

static bool method_has_param(int method, const char *name)
{
    const ob_method_info *m = ob_method_at(method);
    for (int i = 0; m && i < m->param_count; ++i)
        if (!strcmp(m->params[i].name, name)) return true;
    return false;
}

/* One configuration measured (app/progress.h: a bar on a terminal, lines at 0/25/50/75/100 % in a
 * log). */
void bench_progress(bench_state *st, const char *what)
{
    ++st->done;
    ob_progress_advance(&st->bar, 1, what);
}

void *bench_grow(void **items, int *count, int *cap, size_t size)
{
    if (*count == *cap) {
        int more = *cap ? 2 * *cap : 16;
        void *p = realloc(*items, (size_t)more * size);
        if (!p) return NULL;
        *items = p;
        *cap = more;
    }
    void *item = (char *)*items + (size_t)(*count)++ * size;
    memset(item, 0, size);
    return item;
}

static bench_row *new_row(bench_state *st)
{
    void *rows = st->rows;
    bench_row *r = bench_grow(&rows, &st->count, &st->cap, sizeof *r);
    st->rows = rows;
    if (r) r->baseline = -1;
    return r;
}

/* --floor: one frame of the bare kernel on eye e right after that eye's frame (whose depth and
 * normals it reads), waited for like the method's; its ms (0 when f is a warm-up frame). The floor
 * and the method alternate frame by frame, so both see the same machine: timed as a block after
 * the method's frames, the floor on the shared 2-core machine came out at ~13 or ~25 ms from one
 * configuration to the next (a core taken or not), and the ratio with it. */
static int floor_frame(ob_renderer *eye, const ob_settings *s, bool measured, bench_row *row, double *ms)
{
    ob_floor_info info = {0};
    *ms = 0.0;
    if (ob_render_floor(eye, s, &info) != OB_OK) return cli_fail_from_library();
    row->floor_taps = info.taps;
    row->floor_rays = info.rays;
    if (!measured) return EXIT_OK;
    if (ob_wait_timings(eye) != OB_OK) return cli_fail_from_library();
    ob_pass_timing t[MAX_PASSES];
    int n = ob_query_timings(eye, t, MAX_PASSES);
    for (int p = 0; p < n; ++p)
        if (!strcmp(t[p].name, "floor")) *ms += t[p].ms;
    return EXIT_OK;
}

/* Warm-up, then o->frames measured frames on every eye, each followed by a floor frame with
 * --floor (floor_frame). scratch holds frames x (MAX_PASSES + 3). */
static int measure(ob_renderer **eyes, const ob_camera *cams, int eye_count, const ob_settings *s, const bench_opts *o,
                   double *scratch, bench_row *row)
{
    int frames = o->frames;
    double *frame_ms = scratch + (size_t)MAX_PASSES * (size_t)frames;
    double *floor_ms = frame_ms + frames, *ratio = floor_ms + frames;
    const bool floor = o->floor && row->samples > 0;
    for (int f = 0; f < o->warmup + frames; ++f) {
        bool measured = f >= o->warmup;
        int m = f - o->warmup;
        if (measured) {
            frame_ms[m] = 0.0;
            floor_ms[m] = 0.0;
            for (int p = 0; p < MAX_PASSES; ++p) scratch[(size_t)p * (size_t)frames + (size_t)m] = 0.0;
        }
        for (int e = 0; e < eye_count; ++e) {
            ob_camera cam = cams[e];
            if (o->moving_scene && eye_count == 1) {
                int code = cli_common_path_camera(&o->common, o->moving_scene, &cams[e], f % o->common.path_frames, &cam);
                if (code != EXIT_OK) return code;
            }
            if (ob_render_frame(eyes[e], &cam, s) != OB_OK) return cli_fail_from_library();
            if (!measured) continue;
            /* Each measured frame's own timings (ob_wait_timings), not the ring's older frame. */
            if (ob_wait_timings(eyes[e]) != OB_OK) return cli_fail_from_library();
            ob_pass_timing t[MAX_PASSES];
            int n = ob_query_timings(eyes[e], t, MAX_PASSES);
            row->pass_count = n;
            for (int p = 0; p < n; ++p) {
                snprintf(row->pass[p], sizeof row->pass[p], "%s", t[p].name);
                scratch[(size_t)p * (size_t)frames + (size_t)m] += t[p].ms;
                frame_ms[m] += t[p].ms;
            }
        }
        /* Stereo sums both eyes' floors as the passes do. */
        for (int e = 0; floor && e < eye_count; ++e) {
            double ms;
            int code = floor_frame(eyes[e], s, measured, row, &ms);
            if (code != EXIT_OK) return code;
            if (measured) floor_ms[m] += ms;
        }
    }
    row->ao_ms = 0.0;
    int ao_pass = -1;
    for (int p = 0; p < row->pass_count; ++p) {
        bench_stats(scratch + (size_t)p * (size_t)frames, frames, &row->med[p], &row->min[p], &row->max[p]);
        if (!strcmp(row->pass[p], "ao")) {
            row->ao_ms = row->med[p];
            ao_pass = p;
        }
    }
    bench_stats(frame_ms, frames, &row->frame_med, &row->frame_min, &row->frame_max);
    if (floor) {
        /* The ratio is the median of each frame's AO pass over the floor frame beside it. */
        const double *ao = ao_pass >= 0 ? scratch + (size_t)ao_pass * (size_t)frames : NULL;
        for (int m = 0; m < frames; ++m) ratio[m] = ao && floor_ms[m] > 0.0 ? ao[m] / floor_ms[m] : 0.0;
        bench_stats(floor_ms, frames, &row->floor_med, &row->floor_min, &row->floor_max);
        double lo, hi;
        bench_stats(ratio, frames, &row->floor_ratio, &lo, &hi);
    }
    return EXIT_OK;
}

/* bench.h */
int bench_configure(const cli_config *cfg, int samples, float radius_world, ob_settings *s)
{
    *s = cfg->settings;
    if (samples > 0 && ob_settings_set_samples(s, samples) != OB_OK) return cli_fail_from_library();
    if (radius_world > 0.0f) {
        char buf[64];
        snprintf(buf, sizeof buf, "radius=%.9g", (double)radius_world);
        if (ob_settings_set(s, buf) != OB_OK) return cli_fail_from_library();
    }
    return EXIT_OK;
}

/* Whether the method takes a sample count: ob_settings_set_samples refuses with
 * OB_ERR_INVALID_ARGUMENT when it does not; any other refusal (N beyond its table) is the user's. */
static int takes_samples(const bench_opts *o, int method, bool *yes)
{
    ob_settings s;
    if (ob_settings_init(&s, ob_method_at(method)->name) != OB_OK) return cli_fail_from_library();
    *yes = true;
    for (int i = 0; i < o->sample_count; ++i) {
        ob_error err = ob_settings_set_samples(&s, o->samples[i]);
        if (err == OB_OK) continue;
        if (err == OB_ERR_INVALID_ARGUMENT) {
            *yes = false;
            ob_clear_error();
            return EXIT_OK;
        }
        return cli_fail_from_library();
    }
    return EXIT_OK;
}

static int camera_list(const bench_opts *o, const ob_scene *scene, int *idx, int *count)
{
    *count = 0;
    if (o->common.path) {
        /* The path is the camera: one measurement (the first preset's index only labels it). */
        if (o->cameras) return cli_fail(EXIT_USAGE, "--cameras and --path exclude each other (the path is the camera)");
        idx[(*count)++] = 0;
        return EXIT_OK;
    }
    if (!o->cameras && !o->full) {
        idx[(*count)++] = 0;
        return EXIT_OK;
    }
    if (!o->cameras) {
        /* Every preset, once per view: Cornell's "default" is its "front", timed twice before. */
        for (int i = 0; i < ob_query_camera_count(scene) && *count < MAX_CAMS; ++i) {
            ob_camera ci = ob_query_camera(scene, i);
            bool seen = false;
            for (int j = 0; j < *count && !seen; ++j) {
                ob_camera cj = ob_query_camera(scene, idx[j]);
                seen = !memcmp(ci.eye, cj.eye, sizeof ci.eye) && !memcmp(ci.target, cj.target, sizeof ci.target) &&
                       !memcmp(ci.up, cj.up, sizeof ci.up) && ci.fov_y_deg == cj.fov_y_deg &&
                       !memcmp(ci.shift, cj.shift, sizeof ci.shift);
            }
            if (!seen) idx[(*count)++] = i;
        }
        return EXIT_OK;
    }
    char buf[512];
    snprintf(buf, sizeof buf, "%s", o->cameras);
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        ob_camera c;
        if (ob_find_camera(scene, t, &c) != OB_OK) return cli_fail_from_library();
        for (int i = 0; i < ob_query_camera_count(scene); ++i)
            if (!strcmp(ob_query_camera(scene, i).name, c.name) && *count < MAX_CAMS) {
                idx[(*count)++] = i;
                break;
            }
    }
    return EXIT_OK;
}

/* The configurations of Belonogov 2018's whole table (--full) for this run's methods, for the
 * hint after a quick run. */
static int full_table_configs(const bench_opts *o, const ob_scene *scene, const bench_plan *p)
{
    bench_opts full = *o;
    full.full = true;
    full.cameras = NULL;
    int cams[MAX_CAMS], cam_count = 0;
    if (o->common.path || camera_list(&full, scene, cams, &cam_count) != EXIT_OK) cam_count = 1;
    const int ns = (int)(sizeof FULL_SAMPLES / sizeof FULL_SAMPLES[0]), rs = (int)(sizeof FULL_RADII / sizeof FULL_RADII[0]);
    int per_cam = p->base_count;
    for (int k = 0; k < p->count; ++k) per_cam += (p->has_samples[k] ? ns : 1) * (p->has_radius[k] ? rs : 1);
    return per_cam * cam_count;
}

/* ---- the plan ------------------------------------------------------------------------------- */

/* Everything that can be checked without a GPU first: the combinations of the lists with their
 * settings, the none frames and each method's N. */
static int plan_make(const bench_opts *o, bench_plan *p)
{
    const cli_common *c = &o->common;
    *p = (bench_plan){.base_count = c->filter_count * c->ao_count};
    int code = EXIT_OK;
    if (c->method_count > 0 && (code = cli_common_configs(c, &p->configs, &p->count)) != EXIT_OK) return code;
    /* The none frames, one per filter and AO scale: the same settings but the method. */
    p->bases = calloc((size_t)p->base_count, sizeof *p->bases);
    p->has_samples = calloc((size_t)p->count + 1, sizeof *p->has_samples);
    p->has_radius = calloc((size_t)p->count + 1, sizeof *p->has_radius);
    if (!p->bases || !p->has_samples || !p->has_radius) return cli_fail(EXIT_RUNTIME, "out of memory");
    for (int f = 0, b = 0; f < c->filter_count && code == EXIT_OK; ++f)
        for (int a = 0; a < c->ao_count && code == EXIT_OK; ++a, ++b) {
            p->bases[b] = (cli_config){.method = ob_find_method("none"), .filter = c->filters[f], .ao_divisor = c->ao_divisors[a]};
            code = cli_common_apply(c, &p->bases[b]);
        }
    for (int k = 0; k < p->count && code == EXIT_OK; ++k) {
        code = takes_samples(o, p->configs[k].method, &p->has_samples[k]);
        p->has_radius[k] = method_has_param(p->configs[k].method, "radius");
    }
    if (code != EXIT_OK) return code;
    /* The quick run renders the shadow maps once (see QUICK_*); --full every frame, as the
     * recorded tables do. */
    for (int b = 0; b < p->base_count; ++b) p->bases[b].settings.shadow.reuse = o->keep_shadows;
    for (int k = 0; k < p->count; ++k) p->configs[k].settings.shadow.reuse = o->keep_shadows;
    return EXIT_OK;
}

static void plan_free(bench_plan *p)
{
    free(p->has_samples);
    free(p->has_radius);
    free(p->bases);
    free(p->configs);
}

/* The scene and its cameras; an unknown --path fails here, before any GPU work. */
static int load_scene(bench_opts *o, ob_scene **scene, int *cams, int *cam_count)
{
    const cli_common *c = &o->common;
    int code = cli_common_load_scene(c, NULL, scene);
    if (code != EXIT_OK) return code;
    if (cli_common_moves(c)) {
        ob_camera probe = ob_query_camera(*scene, 0);
        if ((code = cli_common_path_camera(c, *scene, &probe, 0, &probe)) != EXIT_OK) return code;
        o->moving_scene = *scene;
    }
    return camera_list(o, *scene, cams, cam_count);
}

/* ---- the sweep (and stereo) ----------------------------------------------------------------- */

/* One camera of the sweep: its none frames, then each combination's grid of N x r, measured on
 * every eye. */
static int sweep_camera(const bench_opts *o, ob_renderer **eyes, const ob_scene *scene, int camera, const bench_plan *p,
                        bench_state *st, double *scratch)
{
    const cli_common *c = &o->common;
    const int eye_count = o->stereo ? 2 : 1;
    const float suggested = ob_query_scene_ao_radius(scene);
    ob_camera cam = ob_query_camera(scene, camera);
    ob_camera views[2];
    if (!o->stereo) views[0] = cam;
    else if (ob_stereo_cameras(&cam, &(ob_stereo_desc){.ipd = o->ipd, .aspect = (float)c->width / (float)c->height},
                               views) != OB_OK)
        return cli_fail_from_library();
    const int base = st->count; /* the none rows of this camera, in the order of bases */
    int code = EXIT_OK;
    for (int k = -p->base_count; k < p->count && code == EXIT_OK; ++k) {
        const bool is_base = k < 0;
        const cli_config *cfg = is_base ? &p->bases[k + p->base_count] : &p->configs[k];
        int nn = !is_base && p->has_samples[k] ? o->sample_count : 1;
        int rn = !is_base && p->has_radius[k] ? o->radius_count : 1;
        /* The none row of the same filter and AO scale. */
        int baseline = -1;
        for (int b = 0; b < p->base_count; ++b)
            if (p->bases[b].filter == cfg->filter && p->bases[b].ao_divisor == cfg->ao_divisor) baseline = base + b;
        for (int j = 0; j < nn && code == EXIT_OK; ++j)
            for (int q = 0; q < rn && code == EXIT_OK; ++q) {
                int n = !is_base && p->has_samples[k] ? o->samples[j] : 0;
                float r = !is_base && p->has_radius[k] ? o->radii[q] : 0.0f;
                float rw = r * suggested / 4.0f;
                ob_settings s = {0};
                if ((code = bench_configure(cfg, n, rw, &s)) != EXIT_OK) break;
                bench_row *row = new_row(st);
                if (!row) return cli_fail(EXIT_RUNTIME, "out of memory");
                /* A none row is its own baseline: its differences are 0 and ratios 1. */
                *row = (bench_row){.camera = camera, .method = cfg->method, .cfg = cfg, .samples = n, .r = r,
                                   .radius_world = rw, .width = c->width, .height = c->height,
                                   .triangles = ob_query_scene_stats(scene).triangles, .baseline = baseline};
                code = measure(eyes, views, eye_count, &s, o, scratch, row);
                /* Once per camera (its first row): timing an empty frame times nothing. */
                for (int e = 0; e < eye_count && code == EXIT_OK && row == &st->rows[base]; ++e)
                    code = cli_check_visible(eyes[e], c->width, c->height, ob_query_scene_name(scene), views[e].name,
                                             c->allow_empty, EXIT_INPUT);
                char what[512] = "";
                snprintf(what, sizeof what, "%s %s N=%d r=%g", cam.name, cfg->label, n, (double)r);
                if (code == EXIT_OK) bench_progress(st, what);
            }
    }
    return code;
}

/* Every camera's none frames and configurations, one renderer per eye. */
static int run_sweep(const bench_opts *o, ob_context *ctx, const ob_scene *scene, const int *cams, int cam_count,
                     const bench_plan *p, bench_state *st)
{
    const cli_common *c = &o->common;
    const int eye_count = o->stereo ? 2 : 1;
    /* Configurations per camera of the sweep: the none frames, then each combination's grid. */
    int per_cam = p->base_count;
    for (int k = 0; k < p->count; ++k)
        per_cam += (p->has_samples[k] ? o->sample_count : 1) * (p->has_radius[k] ? o->radius_count : 1);
    st->total = per_cam * cam_count;
    ob_progress_begin(&st->bar, "bench", st->total);
    ob_renderer *eyes[2] = {NULL, NULL};
    double *scratch = calloc((size_t)o->frames * (MAX_PASSES + 3), sizeof(double));
    int code = scratch ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
    for (int e = 0; e < eye_count && code == EXIT_OK; ++e) {
        eyes[e] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
        if (!eyes[e] || ob_renderer_set_scene(eyes[e], scene) != OB_OK) code = cli_fail_from_library();
        else code = cli_common_prepare(c, eyes[e]);
    }
    for (int ci = 0; ci < cam_count && code == EXIT_OK; ++ci) code = sweep_camera(o, eyes, scene, cams[ci], p, st, scratch);
    for (int e = 0; e < 2; ++e) ob_destroy_renderer(eyes[e]);
    free(scratch);
    return code;
}

/* ---- scaling ---------------------------------------------------------------------------------- */

/* One row of the scaling study: configuration k at the first N and r of the lists, rendered by r;
 * proto gives the camera, size, triangles and study. */
static int scaling_row(const bench_opts *o, ob_renderer *r, const ob_camera *cam, float suggested, const bench_plan *p,
                       int k, bench_row proto, bench_state *st, double *scratch)
{
    float rw = p->has_radius[k] ? o->radii[0] * suggested / 4.0f : 0.0f;
    ob_settings s = {0};
    int code = bench_configure(&p->configs[k], p->has_samples[k] ? o->samples[0] : 0, rw, &s);
    if (code != EXIT_OK) return code;
    bench_row *row = new_row(st);
    if (!row) return cli_fail(EXIT_RUNTIME, "out of memory");
    proto.method = p->configs[k].method;
    proto.cfg = &p->configs[k];
    proto.samples = p->has_samples[k] ? o->samples[0] : 0;
    proto.r = p->has_radius[k] ? o->radii[0] : 0.0f;
    proto.radius_world = rw;
    proto.baseline = -1;
    *row = proto;
    return measure(&r, cam, 1, &s, o, scratch, row);
}

/* Instead of the sweep: the first camera, the first N and r of the lists, every method at every
 * --sizes size, then on the scene tessellated 1x, 4x and 16x at --size. */
static int run_scaling(const bench_opts *o, ob_context *ctx, const ob_scene *scene, int camera, const bench_plan *p,
                       bench_state *st)
{
    const cli_common *c = &o->common;
    const ob_camera cam = ob_query_camera(scene, camera);
    const float suggested = ob_query_scene_ao_radius(scene);
    st->total = p->count * (o->size_count + 3);
    ob_progress_begin(&st->bar, "bench", st->total);
    double *scratch = calloc((size_t)o->frames * (MAX_PASSES + 3), sizeof(double));
    int code = scratch ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
    char what[512] = "";
    for (int z = 0; z < o->size_count && code == EXIT_OK; ++z) {
        ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = o->sizes[z][0], .height = o->sizes[z][1]});
        if (!r || ob_renderer_set_scene(r, scene) != OB_OK) code = cli_fail_from_library();
        else code = cli_common_prepare(c, r);
        for (int k = 0; k < p->count && code == EXIT_OK; ++k) {
            const bench_row proto = {.camera = camera, .width = o->sizes[z][0], .height = o->sizes[z][1],
                                     .triangles = ob_query_scene_stats(scene).triangles, .study = 1};
            code = scaling_row(o, r, &cam, suggested, p, k, proto, st, scratch);
            snprintf(what, sizeof what, "%dx%d %s", o->sizes[z][0], o->sizes[z][1], p->configs[k].label);
            if (code == EXIT_OK) bench_progress(st, what);
        }
        ob_destroy_renderer(r);
    }
    ob_renderer *eye = NULL;
    ob_scene *tess[3] = {NULL, NULL, NULL};
    if (code == EXIT_OK) {
        eye = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
        code = eye ? cli_common_prepare(c, eye) : cli_fail_from_library();
    }
    for (int l = 0; l < 3 && code == EXIT_OK; ++l) {
        tess[l] = ob_tessellate_scene(scene, l);
        if (!tess[l] || ob_renderer_set_scene(eye, tess[l]) != OB_OK) code = cli_fail_from_library();
        for (int k = 0; k < p->count && code == EXIT_OK; ++k) {
            const bench_row proto = {.camera = camera, .width = c->width, .height = c->height,
                                     .triangles = ob_query_scene_stats(tess[l]).triangles, .tess = l, .study = 2};
            code = scaling_row(o, eye, &cam, suggested, p, k, proto, st, scratch);
            snprintf(what, sizeof what, "%ux tris %s", 1u << (2 * l), p->configs[k].label);
            if (code == EXIT_OK) bench_progress(st, what);
        }
    }
    ob_destroy_renderer(eye);
    for (int l = 0; l < 3; ++l) ob_destroy_scene(tess[l]);
    free(scratch);
    return code;
}

/* ---- the command ----------------------------------------------------------------------------- */

static int bench_run(int argc, char **argv);

int cmd_bench(int argc, char **argv)
{
    int code = bench_run(argc, argv);
    /* --json and --csv both, or neither: a failure leaves the earlier files as they were. */
    return cli_outputs_finish(&bench_outs, code);
}

/* The mode asked for, measured and printed. */
static int run_mode(const bench_opts *o, ob_context *ctx, const ob_scene *scene, const int *cams, int cam_count,
                    const bench_plan *p, bench_state *st, host_state *hst)
{
    int code = EXIT_OK;
    if (o->host) {
        /* The accuracy first: a bad --host-rmse view fails before minutes of timing. */
        if (o->host_views) code = bench_host_rmse(o, ctx, p, hst);
        if (code == EXIT_OK) code = bench_host_run(o, ctx, scene, cams, cam_count, p, st, hst);
        if (code == EXIT_OK) bench_print_host_tables(o, scene, hst, cams, cam_count);
    } else if (!o->scaling) {
        code = run_sweep(o, ctx, scene, cams, cam_count, p, st);
        if (code == EXIT_OK) bench_print_tables(o, scene, st, cams, cam_count, p->configs, p->count);
    } else {
        code = run_scaling(o, ctx, scene, cams[0], p, st);
        const ob_camera cam = ob_query_camera(scene, cams[0]);
        if (code == EXIT_OK) bench_print_scaling(o, scene, &cam, st, p->configs, p->count);
    }
    return code;
}

static int bench_run(int argc, char **argv)
{
    bench_opts o;
    int code = parse(argc, argv, &o);
    if (code != 0) return code < 0 ? EXIT_OK : code;
    const cli_common *c = &o.common;
    bench_plan plan = {0};
    ob_scene *scene = NULL;
    ob_context *ctx = NULL;
    bench_state st = {0};
    host_state hst = {0};
    int cams[MAX_CAMS] = {0}, cam_count = 0;
    code = plan_make(&o, &plan);
    if (code == EXIT_OK) code = load_scene(&o, &scene, cams, &cam_count);
    if (code == EXIT_OK && !(ctx = cli_make_context(c->gpu, c->verbose))) code = cli_fail_from_library();
    const double t0 = bench_now_s();
    st.start = t0;
    if (code == EXIT_OK) code = run_mode(&o, ctx, scene, cams, cam_count, &plan, &st, &hst);
    ob_progress_end(&st.bar);
    if (code == EXIT_OK && !o.full && !o.scaling && !o.host)
        bench_print_full_hint(&o, st.count, full_table_configs(&o, scene, &plan), bench_now_s() - t0);
    const double seconds = bench_now_s() - t0;
    if (code == EXIT_OK)
        printf("\n%d configurations in %.0f s on %s\n", o.host ? hst.count : st.count, seconds, ob_query_renderer(ctx));
    /* Into temporary files, the CSV first: cmd_bench renames the pair only when both were
     * written, so a JSON that fails after it leaves neither. */
    if (code == EXIT_OK && o.csv)
        code = o.host ? bench_write_host_csv(&bench_outs, bench_csv, &hst, scene)
                      : bench_write_csv(&bench_outs, bench_csv, &st, scene, o.stereo ? 2 : 1);
    if (code == EXIT_OK && o.json) code = bench_write_json(&bench_outs, bench_json, &o, ctx, scene, &st, &hst, &plan, seconds);
    ob_progress_end(&st.bar); /* a failed run's bar line ends before the shell prompt */
    free(st.rows);
    free(hst.rows);
    free(hst.acc);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    plan_free(&plan);
    return code;
}
