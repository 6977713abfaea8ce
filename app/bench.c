/* obscura bench: GPU time per pass of every method over sample counts N and radii r (Belonogov 2018
 * §5.1 tables), against a no-AO frame, optionally in stereo against the 90 Hz budget (§5.2), as
 * a scaling study over resolution and triangle count, or (--host) the host path ob_host_ao beside
 * ob_render_frame's AO chain (issue 45). docs/architecture.md "Performance method": warm-up
 * frames first, then median/min/max over the measured frames, every ratio from the same run. */
#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_options.h"
#include "outputs.h"
#include "progress.h"
#include "reference_cache.h"
#include "run_program.h"

/* --json and --csv (outputs.h): added while parsing, committed by cmd_bench. */
static cli_outputs bench_outs;
static int bench_json = -1, bench_csv = -1;

enum { MAX_PASSES = 20, MAX_LIST = CLI_MAX_LIST, MAX_CAMS = 32, MAX_SIZES = 16 };

static const double VR_BUDGET_MS = 1000.0 / 90.0;

/* What `obscura bench` with no options measures: every method once against none, on the first
 * camera preset, at N = 24 (Belonogov 2018's "medium") and r = 4 (the scene's suggested radius), 20
 * frames after 3, with the shadow maps rendered once (the scene and lights are static, as in the
 * viewer). On the 2-core llvmpipe machine an 800x600 Cornell frame took 0.5-0.9 s, 0.26 s of it
 * the point light's 2048^2 cube map: the old default, Belonogov 2018's table (both of Cornell's
 * identical presets x 4 N x 3 r x 10 methods x 55 frames, maps every frame), runs for hours
 * there; the quick run is 10 configurations of 23 frames. --full is the table. */
enum { QUICK_SAMPLES = 24, QUICK_FRAMES = 20, QUICK_WARMUP = 3, FULL_FRAMES = 50, FULL_WARMUP = 5 };
static const float QUICK_RADIUS = 4.0f;
static const int FULL_SAMPLES[] = {12, 24, 36, 64};
static const float FULL_RADII[] = {2.0f, 4.0f, 8.0f};

typedef struct bench_opts {
    cli_common common;            /* scene, methods, filters, AO scales, lighting, ... */
    const char *json, *csv, *cameras;
    int samples[CLI_MAX_LIST], sample_count; /* the sweep's N: --samples or --quality */
    float radii[MAX_LIST];
    int radius_count;
    int frames, warmup;
    bool stereo, scaling;
    bool floor;                   /* --floor: time the bare N-tap kernel beside each AO pass */
    bool full;                    /* --full: the whole seed table (see QUICK_* above) */
    bool host;                    /* --host: the host path (ob_host_ao) beside the frame's AO chain */
    bool samples_given;           /* --samples or --quality was given (--host-rmse: else each method's own) */
    const char *host_views;       /* --host-rmse SCENE[:CAMERA],...: the rebuilt normals' accuracy */
    bool keep_shadows;            /* render the shadow maps once, not every frame (the quick run) */
    float ipd;
    int sizes[MAX_SIZES][2], size_count;
} bench_opts;

/* One measured configuration: per pass and whole-frame statistics (stereo: both eyes summed). */
typedef struct bench_row {
    int camera;           /* index into the scene's presets */
    int method;           /* registry index */
    const cli_config *cfg; /* its combination of the lists (method, filter, AO scale) */
    int samples;          /* 0 = the method takes no sample count */
    float r;              /* the sweep's r (0 = the method takes no radius) */
    float radius_world;
    int width, height;    /* per eye */
    int tess;             /* scaling: subdivision levels; 0 otherwise */
    uint32_t triangles;
    int pass_count;
    char pass[MAX_PASSES][16];
    double med[MAX_PASSES], min[MAX_PASSES], max[MAX_PASSES];
    double frame_med, frame_min, frame_max, ao_ms;
    /* --floor: the bare N-tap kernel at this row's N, radius and AO grid (ob_render_floor), median,
     * min, max over the same number of measured frames after the same warm-up; floor_taps 0 = not
     * measured (the method takes no sample count, or no --floor). */
    double floor_med, floor_min, floor_max;
    double floor_ratio; /* the median over the measured frames of AO pass / the floor frame beside it */
    int floor_taps, floor_rays;
    int baseline;         /* index of this camera's none row, -1 when none */
    int study;            /* 0 the sweep, 1 scaling over resolution, 2 scaling over triangles */
} bench_row;

typedef struct bench_state {
    bench_row *rows;
    int count, cap;
    int done, total;      /* progress */
    double start;
    ob_progress bar;
} bench_state;

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
          "                              edges, depth_mips, ao, temporal, filter, upsample)\n"
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
          "stdout: one table per method (per combination), rows N, columns r, cells 'AO-pass ms /\n"
          "frame ms' (medians); --host: per configuration the four paths' 'median (min-max)' and the\n"
          "(b)/(a) line, then the --host-rmse table; stderr: a progress bar with the configurations\n"
          "done and the time left.\n"
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

static int host_views_check(const char *v);

static int parse(int argc, char **argv, bench_opts *o)
{
    /* frames, warmup and radii 0: not given (resolved after the loop, by --full). */
    *o = (bench_opts){.frames = 0, .warmup = -1, .ipd = 0.064f, .radius_count = 0,
                      .sizes = {{640, 480}, {1280, 720}, {1920, 1080}, {2560, 1440}, {3840, 2160}}, .size_count = 5};
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
            int code = host_views_check(v);
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

/* ---- helpers --------------------------------------------------------------------------------- */

static double now_s(void)
{
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Sorts v. */
static void stats(double *v, int n, double *med, double *lo, double *hi)
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
static void progress(bench_state *st, const char *what)
{
    ++st->done;
    ob_progress_advance(&st->bar, 1, what);
}

/* One more zeroed element of a growing array (*items, *count of *cap, `size` bytes each): its
 * address, or NULL when memory ran out (nothing changed then). */
static void *grow(void **items, int *count, int *cap, size_t size)
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
    bench_row *r = grow(&rows, &st->count, &st->cap, sizeof *r);
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

/* --path / --orbit: every frame of a measurement takes the next camera along it (warm-up frames
 * included, wrapping after --path-frames), so the timings include the history's reprojection under
 * motion; set once the scene is loaded. */
static struct {
    const cli_common *common;
    const ob_scene *scene;
} moving;

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
            if (moving.scene && eye_count == 1) {
                int code = cli_common_path_camera(moving.common, moving.scene, &cams[e], f % moving.common->path_frames, &cam);
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
        stats(scratch + (size_t)p * (size_t)frames, frames, &row->med[p], &row->min[p], &row->max[p]);
        if (!strcmp(row->pass[p], "ao")) {
            row->ao_ms = row->med[p];
            ao_pass = p;
        }
    }
    stats(frame_ms, frames, &row->frame_med, &row->frame_min, &row->frame_max);
    if (floor) {
        /* The ratio is the median of each frame's AO pass over the floor frame beside it. */
        const double *ao = ao_pass >= 0 ? scratch + (size_t)ao_pass * (size_t)frames : NULL;
        for (int m = 0; m < frames; ++m) ratio[m] = ao && floor_ms[m] > 0.0 ? ao[m] / floor_ms[m] : 0.0;
        stats(floor_ms, frames, &row->floor_med, &row->floor_min, &row->floor_max);
        double lo, hi;
        stats(ratio, frames, &row->floor_ratio, &lo, &hi);
    }
    return EXIT_OK;
}

/* The settings of one configuration: its combination's, then the sweep's N and r (samples 0 /
 * r 0 leave the method's own). */
static int configure(const cli_config *cfg, int samples, float radius_world, ob_settings *s)
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

/* After a run without --full: how to run Belonogov 2018's whole table, and what it would cost at this
 * run's pace per frame (a lower bound: the full table also renders the shadow maps every frame). */
static void full_table_hint(const bench_opts *o, const ob_scene *scene, const bool *has_samples, const bool *has_radius,
                            int count, int base_count, int measured, double seconds)
{
    bench_opts full = *o;
    full.full = true;
    full.cameras = NULL;
    int cams[MAX_CAMS], cam_count = 0;
    if (o->common.path || camera_list(&full, scene, cams, &cam_count) != EXIT_OK) cam_count = 1;
    const int ns = (int)(sizeof FULL_SAMPLES / sizeof FULL_SAMPLES[0]), rs = (int)(sizeof FULL_RADII / sizeof FULL_RADII[0]);
    int per_cam = base_count;
    for (int k = 0; k < count; ++k) per_cam += (has_samples[k] ? ns : 1) * (has_radius[k] ? rs : 1);
    const int configs = per_cam * cam_count;
    const double per_frame = measured > 0 ? seconds / ((double)measured * (o->frames + o->warmup)) : 0.0;
    const double minutes = per_frame * configs * (FULL_FRAMES + FULL_WARMUP) / 60.0;
    printf("\nThis was a quick run (%d configurations, %d frames each, shadow maps rendered once).\n"
           "Belonogov 2018's whole table: add --full (every camera preset, N = 12,24,36,64, r = 2,4,8, %d frames\n"
           "after %d, shadow maps every frame): %d configurations, over %.0f min at this run's pace.\n",
           measured, o->frames, FULL_FRAMES, FULL_WARMUP, configs, minutes);
}

/* ---- run info -------------------------------------------------------------------------------- */

static void cpu_model(char *out, size_t n)
{
    snprintf(out, n, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10)) continue;
        const char *c = strchr(line, ':');
        if (!c) break;
        for (++c; *c == ' ' || *c == '\t'; ++c) {}
        snprintf(out, n, "%s", c);
        out[strcspn(out, "\n")] = '\0';
        break;
    }
    fclose(f);
}

/* ---- output ---------------------------------------------------------------------------------- */

static const char *method_name(int m) { return ob_method_at(m)->name; }

/* A table's parts, shared by the AO-pass table and the floor table: the header of the radius
 * columns, a row's "N = ..." label, and the row measured at one cell. */
static void print_radius_header(const float *rs, int rn)
{
    printf("%-8s", "");
    for (int q = 0; q < rn; ++q) {
        char h[32];
        if (rs[q] > 0.0f) snprintf(h, sizeof h, "r = %g", (double)rs[q]);
        else snprintf(h, sizeof h, "r = -");
        printf(" %20s", h);
    }
    printf("\n");
}

static void print_samples_label(int n)
{
    char h[32];
    if (n > 0) snprintf(h, sizeof h, "N = %d", n);
    else snprintf(h, sizeof h, "N = -");
    printf("%-8s", h);
}

static const bench_row *table_cell(const bench_state *st, int camera, const cli_config *cfg, int samples, float r)
{
    const bench_row *hit = NULL;
    for (int i = 0; i < st->count; ++i) {
        const bench_row *row = &st->rows[i];
        if (row->camera == camera && row->cfg == cfg && row->samples == samples && row->r == r) hit = row;
    }
    return hit;
}

/* --floor: the method's table again, each cell AO pass / floor (the median over the frames of each
 * one's ratio; the floor's median ms, its taps), rows N as asked (the floor's N is the method's
 * actual sample count). */
static void print_floor_table(const bench_state *st, int camera, const cli_config *cfg, const int *ns, int nn,
                              const float *rs, int rn)
{
    printf("%s: AO pass / floor (floor ms, taps)\n", cfg->label);
    print_radius_header(rs, rn);
    for (int j = 0; j < nn; ++j) {
        print_samples_label(ns[j]);
        for (int q = 0; q < rn; ++q) {
            const bench_row *hit = table_cell(st, camera, cfg, ns[j], rs[q]);
            char cell[48] = "-";
            if (hit && hit->floor_taps > 0 && hit->floor_ratio > 0.0)
                snprintf(cell, sizeof cell, "%.2fx (%.3f, %d)", hit->floor_ratio, hit->floor_med,
                         hit->floor_taps);
            printf(" %20s", cell);
        }
        printf("\n");
    }
}

static void print_tables(const bench_opts *o, const ob_scene *scene, const bench_state *st, const int *cams, int cam_count,
                         const cli_config *configs, int config_count)
{
    const char *unit = o->stereo ? "both eyes" : "one view";
    for (int c = 0; c < cam_count; ++c) {
        const char *cname = ob_query_camera(scene, cams[c]).name;
        printf("\n== %s, camera %s, %dx%d%s, median of %d frames (%s) ==\n", ob_query_scene_name(scene), cname,
               o->common.width, o->common.height, o->stereo ? " per eye" : "", o->frames, unit);
        /* The none frames: one per filter and AO scale, each the baseline of its combinations. */
        for (int i = 0; i < st->count; ++i) {
            const bench_row *none = &st->rows[i];
            if (none->camera != cams[c] || none->baseline != i) continue;
            printf("%s: frame %.3f ms (%.1f FPS)%s\n", none->cfg->label, none->frame_med, 1000.0 / none->frame_med,
                   o->stereo ? (none->frame_med <= VR_BUDGET_MS ? ", within 11.1 ms" : ", over 11.1 ms") : "");
        }
        /* One sample count and one radius for every method (the default run): one table with a row
         * per method, not a one-cell table each. */
        bool one_cell = !o->floor && !o->stereo;
        for (int k = 0; k < config_count && one_cell; ++k) {
            int rows = 0;
            for (int i = 0; i < st->count; ++i) rows += st->rows[i].camera == cams[c] && st->rows[i].cfg == &configs[k];
            one_cell = rows == 1;
        }
        if (one_cell) {
            int width = 6;
            for (int k = 0; k < config_count; ++k) width = (int)strlen(configs[k].label) > width ? (int)strlen(configs[k].label) : width;
            printf("\n%-*s %6s %8s %22s %14s\n", width, "method", "N", "r", "AO-pass ms / frame ms", "frame / none");
            for (int k = 0; k < config_count; ++k)
                for (int i = 0; i < st->count; ++i) {
                    const bench_row *r = &st->rows[i];
                    if (r->camera != cams[c] || r->cfg != &configs[k]) continue;
                    const bench_row *none = r->baseline >= 0 ? &st->rows[r->baseline] : NULL;
                    char cell[48], ratio[16] = "-";
                    snprintf(cell, sizeof cell, "%.3f / %.3f", r->ao_ms, r->frame_med);
                    if (none && none->frame_med > 0.0) snprintf(ratio, sizeof ratio, "%.2fx", r->frame_med / none->frame_med);
                    printf("%-*s %6d %8g %22s %14s\n", width, configs[k].label, r->samples, (double)r->r, cell, ratio);
                    for (int p = 0; p < r->pass_count; ++p)
                        if (!strcmp(r->pass[p], "temporal") && r->ao_ms > 0.0)
                            printf("%-*s temporal accumulation %.3f ms = %.1f %% of the AO pass\n", width, "", r->med[p],
                                   100.0 * r->med[p] / r->ao_ms);
                }
            continue;
        }
        for (int k = 0; k < config_count; ++k) {
            const cli_config *cfg = &configs[k];
            printf("\n%s: AO-pass ms / frame ms", cfg->label);
            if (o->stereo) printf(" (frame budget 11.1 ms at 90 Hz; * = over)");
            printf("\n");
            float rs[MAX_LIST];
            int rn = 0;
            int ns[MAX_LIST];
            int nn = 0;
            for (int i = 0; i < st->count; ++i) {
                const bench_row *r = &st->rows[i];
                if (r->camera != cams[c] || r->cfg != cfg) continue;
                bool seen = false;
                for (int q = 0; q < rn; ++q) seen = seen || rs[q] == r->r;
                if (!seen && rn < MAX_LIST) rs[rn++] = r->r;
                seen = false;
                for (int q = 0; q < nn; ++q) seen = seen || ns[q] == r->samples;
                if (!seen && nn < MAX_LIST) ns[nn++] = r->samples;
            }
            print_radius_header(rs, rn);
            double sum_ratio = 0.0;
            int cells = 0;
            for (int j = 0; j < nn; ++j) {
                print_samples_label(ns[j]);
                for (int q = 0; q < rn; ++q) {
                    const bench_row *hit = table_cell(st, cams[c], cfg, ns[j], rs[q]);
                    char cell[48];
                    const bench_row *none = hit && hit->baseline >= 0 ? &st->rows[hit->baseline] : NULL;
                    if (hit) {
                        snprintf(cell, sizeof cell, "%.3f / %.3f%s", hit->ao_ms, hit->frame_med,
                                 o->stereo && hit->frame_med > VR_BUDGET_MS ? "*" : "");
                        if (none && none->frame_med > 0.0) {
                            sum_ratio += hit->frame_med / none->frame_med;
                            ++cells;
                        }
                    } else {
                        snprintf(cell, sizeof cell, "-");
                    }
                    printf(" %20s", cell);
                }
                printf("\n");
            }
            if (cells) printf("mean frame / none frame: %.2fx\n", sum_ratio / cells);
            if (o->floor) print_floor_table(st, cams[c], cfg, ns, nn, rs, rn);
            /* --temporal on: the accumulation pass against the method's AO pass, the same frames
             * (issue 17's budget: at most 15 % of gtao-high's). */
            for (int i = 0; i < st->count; ++i) {
                const bench_row *r = &st->rows[i];
                if (r->camera != cams[c] || r->cfg != cfg) continue;
                for (int p = 0; p < r->pass_count; ++p)
                    if (!strcmp(r->pass[p], "temporal") && r->ao_ms > 0.0)
                        printf("temporal accumulation N=%d r=%g: %.3f ms = %.1f %% of the AO pass (%.3f ms)\n", r->samples,
                               (double)r->r, r->med[p], 100.0 * r->med[p] / r->ao_ms, r->ao_ms);
            }
        }
    }
}

/* A row's label: its combination's, then the sweep's N and r where the method takes them. */
static void row_label(const bench_row *r, char *out, size_t n)
{
    int len = snprintf(out, n, "%s", r->cfg->label);
    if (r->samples > 0 && len >= 0 && (size_t)len < n) len += snprintf(out + len, n - (size_t)len, " \xc2\xb7 N %d", r->samples);
    if (r->r > 0.0f && len >= 0 && (size_t)len < n) snprintf(out + len, n - (size_t)len, " \xc2\xb7 r %g", (double)r->r);
}

/* The fields every row's JSON starts with: what was run, on which camera, at what size. */
static void config_json(cJSON *j, const char *label, int method, const cli_config *cfg, const ob_scene *scene,
                        int camera, int samples, float r, float radius_world, int width, int height)
{
    cJSON_AddStringToObject(j, "method", method_name(method));
    cJSON_AddStringToObject(j, "label", label);
    cJSON_AddStringToObject(j, "filter", ob_filter_at(cfg->filter)->name);
    cJSON_AddNumberToObject(j, "ao_scale", 1.0 / cfg->ao_divisor);
    cJSON_AddStringToObject(j, "camera", ob_query_camera(scene, camera).name);
    if (samples > 0) cJSON_AddNumberToObject(j, "samples", samples);
    else cJSON_AddNullToObject(j, "samples");
    if (r > 0.0f) {
        cJSON_AddNumberToObject(j, "radius", r);
        cJSON_AddNumberToObject(j, "radius_world", radius_world);
    } else {
        cJSON_AddNullToObject(j, "radius");
        cJSON_AddNullToObject(j, "radius_world");
    }
    cJSON_AddNumberToObject(j, "width", width);
    cJSON_AddNumberToObject(j, "height", height);
}

static cJSON *row_json(const bench_row *r, const bench_row *none, const ob_scene *scene)
{
    cJSON *j = cJSON_CreateObject();
    char label[CLI_MAX_LABEL + 32] = "";
    row_label(r, label, sizeof label);
    config_json(j, label, r->method, r->cfg, scene, r->camera, r->samples, r->r, r->radius_world, r->width, r->height);
    cJSON_AddNumberToObject(j, "triangles", r->triangles);
    cJSON_AddNumberToObject(j, "tessellation_levels", r->tess);
    cJSON *passes = cJSON_AddArrayToObject(j, "passes");
    for (int p = 0; p < r->pass_count; ++p) {
        cJSON *q = cJSON_CreateObject();
        cJSON_AddStringToObject(q, "name", r->pass[p]);
        cJSON_AddNumberToObject(q, "median", r->med[p]);
        cJSON_AddNumberToObject(q, "min", r->min[p]);
        cJSON_AddNumberToObject(q, "max", r->max[p]);
        cJSON_AddItemToArray(passes, q);
    }
    cJSON *fr = cJSON_AddObjectToObject(j, "frame_ms");
    cJSON_AddNumberToObject(fr, "median", r->frame_med);
    cJSON_AddNumberToObject(fr, "min", r->frame_min);
    cJSON_AddNumberToObject(fr, "max", r->frame_max);
    cJSON_AddNumberToObject(j, "fps", 1000.0 / r->frame_med);
    cJSON_AddNumberToObject(j, "ao_ms", r->ao_ms);
    if (r->floor_taps > 0) {
        cJSON *fl = cJSON_AddObjectToObject(j, "floor_ms");
        cJSON_AddNumberToObject(fl, "median", r->floor_med);
        cJSON_AddNumberToObject(fl, "min", r->floor_min);
        cJSON_AddNumberToObject(fl, "max", r->floor_max);
        if (r->floor_ratio > 0.0) cJSON_AddNumberToObject(j, "floor_ratio", r->floor_ratio);
        else cJSON_AddNullToObject(j, "floor_ratio");
        cJSON_AddNumberToObject(j, "floor_taps", r->floor_taps);
        cJSON_AddStringToObject(j, "floor_pattern", r->floor_rays > 0 ? "rays" : "disk");
        if (r->floor_rays > 0) cJSON_AddNumberToObject(j, "floor_rays", r->floor_rays);
    } else {
        cJSON_AddNullToObject(j, "floor_ms");
        cJSON_AddNullToObject(j, "floor_ratio");
    }
    if (none) {
        cJSON *v = cJSON_AddObjectToObject(j, "vs_none");
        cJSON_AddNumberToObject(v, "ao_minus_ms", r->ao_ms - none->ao_ms);
        if (none->ao_ms > 0.0) cJSON_AddNumberToObject(v, "ao_ratio", r->ao_ms / none->ao_ms);
        else cJSON_AddNullToObject(v, "ao_ratio");
        cJSON_AddNumberToObject(v, "frame_minus_ms", r->frame_med - none->frame_med);
        cJSON_AddNumberToObject(v, "frame_ratio", r->frame_med / none->frame_med);
    } else {
        cJSON_AddNullToObject(j, "vs_none");
    }
    return j;
}

static const bench_row *baseline_of(const bench_state *st, const bench_row *r)
{
    return r->baseline >= 0 ? &st->rows[r->baseline] : NULL;
}

static int write_csv(int index, const bench_state *st, const ob_scene *scene, int eyes)
{
    size_t cap = 4096 + (size_t)st->count * (MAX_PASSES + 1) * (300 + CLI_MAX_LABEL), len = 0;
    char *buf = malloc(cap);
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    len += (size_t)snprintf(buf + len, cap - len,
                            "scene,camera,method,samples,r,radius_world,filter,ao_scale,width,height,eyes,triangles,pass,"
                            "median_ms,min_ms,max_ms,fps,minus_none_ms,ratio_none,label,floor_ms,floor_ratio\n");
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        const bench_row *none = baseline_of(st, r);
        for (int p = 0; p <= r->pass_count; ++p) {
            bool frame = p == r->pass_count; /* the last row of a configuration: the whole frame */
            double med = frame ? r->frame_med : r->med[p], lo = frame ? r->frame_min : r->min[p],
                   hi = frame ? r->frame_max : r->max[p];
            double base = 0.0;
            bool has_base = false;
            if (none && frame) {
                base = none->frame_med;
                has_base = true;
            } else if (none && !strcmp(r->pass[p], "ao")) {
                base = none->ao_ms;
                has_base = true;
            }
            char samples[16] = "", rr[32] = "", rw[32] = "", fps[32] = "", minus[32] = "", ratio[32] = "";
            if (r->samples > 0) snprintf(samples, sizeof samples, "%d", r->samples);
            if (r->r > 0.0f) {
                snprintf(rr, sizeof rr, "%g", (double)r->r);
                snprintf(rw, sizeof rw, "%g", (double)r->radius_world);
            }
            if (frame) snprintf(fps, sizeof fps, "%.3f", 1000.0 / r->frame_med);
            if (has_base) {
                snprintf(minus, sizeof minus, "%.4f", med - base);
                if (base > 0.0) snprintf(ratio, sizeof ratio, "%.4f", med / base);
            }
            char label[CLI_MAX_LABEL + 32] = "";
            row_label(r, label, sizeof label);
            /* The floor on the ao row: its median and AO pass / floor. */
            char fms[32] = "", fratio[32] = "";
            if (!frame && r->floor_taps > 0 && !strcmp(r->pass[p], "ao")) {
                snprintf(fms, sizeof fms, "%.4f", r->floor_med);
                if (r->floor_ratio > 0.0) snprintf(fratio, sizeof fratio, "%.4f", r->floor_ratio);
            }
            len += (size_t)snprintf(buf + len, cap - len,
                                    "%s,%s,%s,%s,%s,%s,%s,%g,%d,%d,%d,%u,%s,%.4f,%.4f,%.4f,%s,%s,%s,%s,%s,%s\n",
                                    ob_query_scene_name(scene), ob_query_camera(scene, r->camera).name,
                                    method_name(r->method), samples, rr, rw, ob_filter_at(r->cfg->filter)->name,
                                    1.0 / r->cfg->ao_divisor, r->width, r->height, eyes, r->triangles,
                                    frame ? "frame" : r->pass[p], med, lo, hi, fps, minus, ratio, label, fms, fratio);
        }
    }
    int code = cli_outputs_write_text(&bench_outs, index, buf);
    free(buf);
    return code;
}

/* ---- scaling --------------------------------------------------------------------------------- */

typedef struct scaling_verdict {
    bool flat_in_triangles, linear_in_pixels;
    double tri_ratio, mpx_spread; /* max/min AO ms over tessellation; max |ms/MP / median - 1| */
} scaling_verdict;

static scaling_verdict verdict(const bench_state *st, const cli_config *cfg)
{
    scaling_verdict v = {false, false, 0.0, 0.0};
    double lo = INFINITY, hi = 0.0, per_mp[MAX_SIZES] = {0};
    int n = 0;
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        if (r->cfg != cfg) continue;
        if (r->study == 2) {
            lo = fmin(lo, r->ao_ms);
            hi = fmax(hi, r->ao_ms);
        } else if (r->study == 1 && n < MAX_SIZES) {
            per_mp[n++] = r->ao_ms / ((double)r->width * r->height * 1e-6);
        }
    }
    if (hi > 0.0 && lo > 0.0) {
        v.tri_ratio = hi / lo;
        v.flat_in_triangles = v.tri_ratio < 1.2;
    }
    if (n > 0) {
        double sorted[MAX_SIZES];
        memcpy(sorted, per_mp, sizeof sorted);
        double med = 0.0, a = 0.0, b = 0.0;
        stats(sorted, n, &med, &a, &b);
        for (int k = 0; k < n && med > 0.0; ++k) v.mpx_spread = fmax(v.mpx_spread, fabs(per_mp[k] / med - 1.0));
        v.linear_in_pixels = med > 0.0 && v.mpx_spread <= 0.3;
    }
    return v;
}

/* --floor in the scaling lines: ", 2.91x floor" (one static buffer: one call per printf). */
static const char *floor_note(const bench_row *r)
{
    static char note[48];
    note[0] = '\0';
    if (r->floor_taps > 0 && r->floor_ratio > 0.0) snprintf(note, sizeof note, ", %.2fx floor", r->floor_ratio);
    return note;
}

/* ---- --host: the host path beside the frame's AO chain (issue 45, item 7) ---------------------
 * For each configuration, four paths measured in one run, alternated frame by frame (the frame,
 * then each host call on that frame's G-buffer), so that a machine that slows down or speeds up
 * (a core taken on the shared 2-core machine) slows all four alike:
 *   (a) frame            ob_render_frame; the sum of its AO chain passes (CHAIN_PASSES)
 *   (b) host_linear      ob_host_ao on the frame's G-buffer read back (ob_read_image) and uploaded as
 *                        R32F linear depth and RGBA16F view normals, into an R32F output: the chain
 *                        alone, no input or output pass (a directional method's output still
 *                        needs the output pass: the chain writes its M as RGB)
 *   (c) host_packed      the same depth as a GL_DEPTH_COMPONENT32F reversed-Z [0,1] depth buffer
 *                        (window depth computed here from the linear depth with the frame's near
 *                        and far planes) and octahedral RG16F world-space normals, into an R8
 *                        output: input pass + chain + output pass
 *   (d) host_no_normals  (c) without normals: the input pass rebuilds them from the depth
 * Each host path has its own renderer (its own temporal history and targets). --host-rmse adds the
 * accuracy of those inputs against the ray-traced reference, on views of other scenes. */

enum { HOST_FRAME = 0, HOST_LINEAR, HOST_PACKED, HOST_NO_NORMALS, HOST_PATHS };
enum { HOST_MAX_VIEWS = 8, HOST_RMSE_W = 320, HOST_RMSE_H = 240, HOST_RMSE_SPP = 512, HOST_RMSE_FRAMES = 5 };
static const double HOST_TARGET = 1.05; /* issue 45: the host path at most 1.05x the frame's chain */

static const char *const host_path_names[HOST_PATHS] = {"frame", "host_linear", "host_packed", "host_no_normals"};
static const char *const host_path_depth[HOST_PATHS] = {"G-buffer", "R32F linear", "D32F reversed-Z 0-to-1",
                                                        "D32F reversed-Z 0-to-1"};
static const char *const host_path_normals[HOST_PATHS] = {"G-buffer", "RGBA16F view", "RG16F octahedral world",
                                                          "none (rebuilt from depth)"};
static const char *const host_path_output[HOST_PATHS] = {"renderer's own", "R32F", "R8", "R8"};
/* The passes of the AO chain (src/core/chain.c) that (a) sums; a host call's other passes are its
 * input and output passes. */
static const char *const CHAIN_PASSES[] = {"downsample", "edges", "depth_mips", "ao", "temporal", "filter", "upsample"};

static bool is_chain_pass(const char *name)
{
    for (size_t i = 0; i < sizeof CHAIN_PASSES / sizeof CHAIN_PASSES[0]; ++i)
        if (!strcmp(name, CHAIN_PASSES[i])) return true;
    return false;
}

/* The GL calls bench makes itself to hand the frame's G-buffer over as an engine would (epoxy, as
 * the viewer's; the library's context is current on this thread). */
static unsigned host_texture(unsigned format, int width, int height)
{
    unsigned t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, width, height);
    return t;
}

/* A host's textures for one size: the inputs of (b), (c), (d), each path's output, and the CPU
 * copies they are filled from (bottom row first, as ob_read_image and GL both have them). */
typedef struct host_inputs {
    int w, h;
    unsigned depth, normal, window, oct, radiance, albedo, out[HOST_PATHS];
    float *lin, *nrm, *win, *oct_px, *rad, *alb;
    float view[16], proj[16], reversed[16];
} host_inputs;

static void host_inputs_free(host_inputs *in)
{
    if (in->depth) {
        const unsigned t[] = {in->depth, in->normal, in->window, in->oct, in->radiance, in->albedo,
                              in->out[HOST_LINEAR], in->out[HOST_PACKED], in->out[HOST_NO_NORMALS]};
        glDeleteTextures((int)(sizeof t / sizeof t[0]), t);
    }
    free(in->lin);
    free(in->nrm);
    free(in->win);
    free(in->oct_px);
    free(in->rad);
    free(in->alb);
    memset(in, 0, sizeof *in);
}

static int host_inputs_make(host_inputs *in, int w, int h)
{
    memset(in, 0, sizeof *in);
    const size_t px = (size_t)w * (size_t)h;
    in->w = w;
    in->h = h;
    in->lin = malloc(px * sizeof(float));
    in->nrm = malloc(3 * px * sizeof(float));
    in->win = malloc(px * sizeof(float));
    in->oct_px = malloc(2 * px * sizeof(float));
    in->rad = malloc(3 * px * sizeof(float));
    in->alb = malloc(3 * px * sizeof(float));
    if (!in->lin || !in->nrm || !in->win || !in->oct_px || !in->rad || !in->alb) {
        host_inputs_free(in);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    in->depth = host_texture(GL_R32F, w, h);
    in->normal = host_texture(GL_RGBA16F, w, h);
    in->window = host_texture(GL_DEPTH_COMPONENT32F, w, h);
    in->oct = host_texture(GL_RG16F, w, h);
    in->radiance = host_texture(GL_RGBA16F, w, h);
    in->albedo = host_texture(GL_RGBA16F, w, h);
    in->out[HOST_LINEAR] = host_texture(GL_R32F, w, h);
    in->out[HOST_PACKED] = host_texture(GL_R8, w, h);
    in->out[HOST_NO_NORMALS] = host_texture(GL_R8, w, h);
    unsigned e = glGetError();
    if (e != 0) {
        host_inputs_free(in);
        return cli_fail(EXIT_RUNTIME, "--host: OpenGL error 0x%x making the host's %dx%d textures", e, w, h);
    }
    return EXIT_OK;
}

/* The camera's matrices as ob_render_frame makes them (src/core/frame.c): the renderer's defaults
 * filled in, near and far fitted to the scene's bounds as ob_camera_fit_planes does (and left in
 * *cam, so the frame uses the very planes the window depth is computed with), glm_lookat,
 * glm_perspective, the lens shift in P20 and P21; and the same projection reversed-Z with
 * glClipControl's [0, 1] range: window depth = n (f - d) / (d (f - n)), 1 at the near plane. */
static int host_matrices(const ob_scene *scene, ob_camera *cam, int w, int h, host_inputs *in)
{
    const ob_scene_stats st = ob_query_scene_stats(scene);
    if (ob_camera_matrices(cam, st.bounds_min, st.bounds_max, w, h, in->view, in->proj) != OB_OK)
        return cli_fail_from_library_in("--host: the camera");
    memcpy(in->reversed, in->proj, sizeof in->reversed);
    const double n = cam->near_z, f = cam->far_z;
    in->reversed[10] = (float)(n / (f - n));
    in->reversed[14] = (float)(f * n / (f - n));
    return EXIT_OK;
}

/* in->lin and in->nrm (and in->rad, in->alb with rgb) hold a G-buffer: the packed copies made
 * from them and everything uploaded. */
static void host_upload(host_inputs *in, bool rgb)
{
    const size_t px = (size_t)in->w * (size_t)in->h;
    const float *v = in->view, *p = in->reversed;
    for (size_t i = 0; i < px; ++i) {
        const double d = in->lin[i];
        /* ndc = -P22 + P32 / d; the far plane's 0 is sky. */
        in->win[i] = d > 0.0 ? (float)(-(double)p[10] + (double)p[14] / d) : 0.0f;
        /* World normal = the view's rotation transposed times the view normal (a rigid view). */
        const float *nv = in->nrm + 3 * i;
        float w[3];
        for (int r = 0; r < 3; ++r) w[r] = v[4 * r + 0] * nv[0] + v[4 * r + 1] * nv[1] + v[4 * r + 2] * nv[2];
        float l1 = fabsf(w[0]) + fabsf(w[1]) + fabsf(w[2]);
        float ex = l1 > 0.0f ? w[0] / l1 : 0.0f, ey = l1 > 0.0f ? w[1] / l1 : 0.0f;
        if (w[2] < 0.0f) { /* octahedral (Cigolle et al. 2014): the lower half folded over */
            float tx = (1.0f - fabsf(ey)) * (ex >= 0.0f ? 1.0f : -1.0f);
            float ty = (1.0f - fabsf(ex)) * (ey >= 0.0f ? 1.0f : -1.0f);
            ex = tx;
            ey = ty;
        }
        in->oct_px[2 * i] = ex;
        in->oct_px[2 * i + 1] = ey;
    }
    glTextureSubImage2D(in->depth, 0, 0, 0, in->w, in->h, GL_RED, GL_FLOAT, in->lin);
    glTextureSubImage2D(in->normal, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->nrm);
    glTextureSubImage2D(in->window, 0, 0, 0, in->w, in->h, GL_DEPTH_COMPONENT, GL_FLOAT, in->win);
    glTextureSubImage2D(in->oct, 0, 0, 0, in->w, in->h, GL_RG, GL_FLOAT, in->oct_px);
    if (rgb) {
        glTextureSubImage2D(in->radiance, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->rad);
        glTextureSubImage2D(in->albedo, 0, 0, 0, in->w, in->h, GL_RGB, GL_FLOAT, in->alb);
    }
}

/* The frame r just rendered, read back and uploaded. */
static int host_grab(ob_renderer *r, host_inputs *in, bool rgb)
{
    const size_t px = (size_t)in->w * (size_t)in->h;
    if (ob_read_image(r, OB_IMAGE_DEPTH_F32, in->lin, px * sizeof(float)) != OB_OK ||
        ob_read_image(r, OB_IMAGE_NORMAL_F32, in->nrm, 3 * px * sizeof(float)) != OB_OK ||
        (rgb && (ob_read_image(r, OB_IMAGE_RADIANCE_F32, in->rad, 3 * px * sizeof(float)) != OB_OK ||
                 ob_read_image(r, OB_IMAGE_ALBEDO_F32, in->alb, 3 * px * sizeof(float)) != OB_OK)))
        return cli_fail_from_library();
    host_upload(in, rgb);
    return EXIT_OK;
}

/* The host path calls no glGetError (obscura.h: a host's pending error stays the host's): bench,
 * the host here, reads it after each call, so that a call that went wrong in GL is not timed. */
static int host_gl_check(int p)
{
    unsigned e = glGetError();
    if (e == 0) return EXIT_OK;
    return cli_fail(EXIT_RUNTIME, "--host: OpenGL error 0x%x after ob_host_ao (%s)", e, host_path_names[p]);
}

/* Path p's frame and outputs over in's textures. */
static void host_call_args(const host_inputs *in, int p, bool rgb, ob_host_frame *f, ob_host_outputs *out)
{
    memset(f, 0, sizeof *f);
    memset(out, 0, sizeof *out);
    f->depth = p == HOST_LINEAR ? in->depth : in->window;
    f->normal = p == HOST_LINEAR ? in->normal : p == HOST_PACKED ? in->oct : 0;
    f->normal_space = p == HOST_PACKED ? OB_NORMALS_WORLD : OB_NORMALS_VIEW;
    f->depth_zero_to_one = p != HOST_LINEAR;
    memcpy(f->projection, p == HOST_LINEAR ? in->proj : in->reversed, sizeof f->projection);
    memcpy(f->view, in->view, sizeof f->view);
    if (rgb) {
        f->radiance = in->radiance;
        f->albedo = in->albedo;
    }
    out->ao = in->out[p];
}

/* The settings a host passes for the frame's: the same, with the scene's lights named (a host has
 * no scene; the indirect-light methods read them) and the radius the frame took from the scene
 * when the configuration left it to the scene. */
static int host_settings_of(const ob_settings *s, const ob_scene *scene, float scene_radius, ob_settings *hs)
{
    *hs = *s;
    if (hs->light_count == 0) {
        int n = ob_query_scene_light_count(scene);
        hs->light_count = n < OB_MAX_LIGHTS ? n : OB_MAX_LIGHTS;
        for (int i = 0; i < hs->light_count; ++i) hs->lights[i] = ob_query_scene_light(scene, i);
    }
    const ob_method_info *m = ob_method_at(hs->method);
    for (int i = 0; i < m->param_count; ++i)
        if (!strcmp(m->params[i].name, "radius") && !((hs->params_set >> i) & 1u)) {
            char set[64];
            snprintf(set, sizeof set, "radius=%.9g", (double)scene_radius);
            if (ob_settings_set(hs, set) != OB_OK) return cli_fail_from_library();
        }
    return EXIT_OK;
}

/* One path's numbers over the measured frames. */
typedef struct host_path_row {
    int pass_count;
    char pass[MAX_PASSES][16];
    double med[MAX_PASSES], min[MAX_PASSES], max[MAX_PASSES];
    /* median, min, max: its chain passes, its input and output passes, all of it, and all of it /
     * (a)'s chain in the same frame */
    double chain[3], input[3], output[3], total[3], ratio[3];
    /* the call's wall time on the CPU (ob_render_frame for (a), ob_host_ao for the others): its
     * checks, GL-state save and restore and command submission; the GPU runs on asynchronously */
    double call[3];
    bool has_input, has_output;
} host_path_row;

typedef struct host_row {
    int camera;
    const cli_config *cfg;
    int samples;
    float r, radius_world;
    int width, height;
    host_path_row path[HOST_PATHS];
} host_row;

/* --host-rmse: one view and configuration, RMSE and bias against AO_R over its geometry pixels. */
typedef struct host_acc_row {
    char scene[256], camera[64];
    const cli_config *cfg;
    int samples;           /* 0: the method's own */
    float radius;
    bool ref_cached;
    double ref_stderr;
    ob_metrics m[HOST_PATHS];
} host_acc_row;

typedef struct host_state {
    host_row *rows;
    int count, cap;
    host_acc_row *acc;
    int acc_count, acc_cap;
} host_state;

/* Per path: MAX_PASSES pass columns of `frames`, then chain, input, output, total, ratio. */
enum { HOST_COL_CHAIN = MAX_PASSES, HOST_COL_INPUT, HOST_COL_OUTPUT, HOST_COL_TOTAL, HOST_COL_RATIO, HOST_COL_CALL, HOST_COLS };

/* Path p's timings of frame m (its renderer's last frame, waited for). (a) keeps its chain passes. */
static int host_record(ob_renderer *r, int p, host_path_row *row, double *v, int frames, int m)
{
    if (ob_wait_timings(r) != OB_OK) return cli_fail_from_library();
    ob_pass_timing t[MAX_PASSES];
    int n = ob_query_timings(r, t, MAX_PASSES);
    for (int c = 0; c < HOST_COLS; ++c) v[(size_t)c * (size_t)frames + (size_t)m] = 0.0;
    for (int q = 0; q < n; ++q) {
        const bool chain = is_chain_pass(t[q].name), input = !strcmp(t[q].name, "input"),
                   output = !strcmp(t[q].name, "output");
        if (p == HOST_FRAME && !chain) continue;
        int k = 0;
        while (k < row->pass_count && strcmp(row->pass[k], t[q].name)) ++k;
        if (k == row->pass_count) {
            if (k == MAX_PASSES) continue;
            snprintf(row->pass[row->pass_count++], sizeof row->pass[0], "%s", t[q].name);
        }
        v[(size_t)k * (size_t)frames + (size_t)m] += t[q].ms;
        int col = chain ? HOST_COL_CHAIN : input ? HOST_COL_INPUT : output ? HOST_COL_OUTPUT : -1;
        if (col >= 0) v[(size_t)col * (size_t)frames + (size_t)m] += t[q].ms;
        v[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m] += t[q].ms;
        row->has_input = row->has_input || input;
        row->has_output = row->has_output || output;
    }
    return EXIT_OK;
}

/* Warm-up, then o->frames measured frames, each: the frame on eyes[0], its G-buffer handed to each
 * host path's renderer. scratch: HOST_PATHS x HOST_COLS x frames. */
static int host_measure(ob_renderer **rs, const ob_camera *base, const ob_scene *scene, const ob_settings *s,
                        const ob_settings *hs, const bench_opts *o, host_inputs *in, double *scratch, host_row *row)
{
    const int frames = o->frames;
    const bool rgb = ob_method_at(s->method)->directional;
    for (int p = 0; p < HOST_PATHS; ++p) ob_renderer_reset_history(rs[p]);
    for (int f = 0; f < o->warmup + frames; ++f) {
        const bool measured = f >= o->warmup;
        const int m = f - o->warmup;
        ob_camera cam = *base;
        if (moving.scene) {
            int code = cli_common_path_camera(moving.common, moving.scene, base, f % moving.common->path_frames, &cam);
            if (code != EXIT_OK) return code;
        }
        int code = host_matrices(scene, &cam, in->w, in->h, in);
        if (code != EXIT_OK) return code;
        double t0 = now_s();
        if (ob_render_frame(rs[HOST_FRAME], &cam, s) != OB_OK) return cli_fail_from_library();
        double call_ms = 1e3 * (now_s() - t0);
        if (measured) code = host_record(rs[HOST_FRAME], HOST_FRAME, &row->path[HOST_FRAME], scratch, frames, m);
        if (measured) scratch[(size_t)HOST_COL_CALL * (size_t)frames + (size_t)m] = call_ms;
        if (code == EXIT_OK) code = host_grab(rs[HOST_FRAME], in, rgb);
        for (int p = HOST_LINEAR; p < HOST_PATHS && code == EXIT_OK; ++p) {
            ob_host_frame hf;
            ob_host_outputs ho;
            host_call_args(in, p, rgb, &hf, &ho);
            t0 = now_s();
            if (ob_host_ao(rs[p], &hf, hs, &ho) != OB_OK) return cli_fail_from_library();
            call_ms = 1e3 * (now_s() - t0);
            if ((code = host_gl_check(p)) != EXIT_OK) return code;
            double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
            if (measured) code = host_record(rs[p], p, &row->path[p], v, frames, m);
            if (measured) v[(size_t)HOST_COL_CALL * (size_t)frames + (size_t)m] = call_ms;
        }
        if (code != EXIT_OK) return code;
        if (!measured) continue;
        const double base_ms = scratch[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m];
        for (int p = 0; p < HOST_PATHS; ++p) {
            double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
            v[(size_t)HOST_COL_RATIO * (size_t)frames + (size_t)m] =
                base_ms > 0.0 ? v[(size_t)HOST_COL_TOTAL * (size_t)frames + (size_t)m] / base_ms : 0.0;
        }
    }
    for (int p = 0; p < HOST_PATHS; ++p) {
        host_path_row *pr = &row->path[p];
        double *v = scratch + (size_t)p * HOST_COLS * (size_t)frames;
        for (int k = 0; k < pr->pass_count; ++k) stats(v + (size_t)k * (size_t)frames, frames, &pr->med[k], &pr->min[k], &pr->max[k]);
        double *cols[6] = {pr->chain, pr->input, pr->output, pr->total, pr->ratio, pr->call};
        for (int c = 0; c < 6; ++c)
            stats(v + (size_t)(HOST_COL_CHAIN + c) * (size_t)frames, frames, &cols[c][0], &cols[c][1], &cols[c][2]);
    }
    return EXIT_OK;
}

/* --host-rmse's list: SCENE[:CAMERA] elements, checked for shape while parsing (the scenes and
 * cameras themselves when they are loaded, before anything is timed). */
static int host_views_check(const char *v)
{
    if (!*v) return cli_fail(EXIT_USAGE, "--host-rmse: expected a comma list of SCENE[:CAMERA], got ''");
    if (strlen(v) >= 1024) return cli_fail(EXIT_USAGE, "--host-rmse: %zu bytes; at most 1023", strlen(v));
    int n = 1;
    for (const char *p = v; *p; ++p) n += *p == ',';
    if (n > HOST_MAX_VIEWS) return cli_fail(EXIT_USAGE, "--host-rmse: %d views; at most %d", n, HOST_MAX_VIEWS);
    for (const char *p = v;;) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == 0 || (len == 1 && *p == ':') || p[0] == ':' || p[len - 1] == ':')
            return cli_fail(EXIT_USAGE, "--host-rmse: empty scene or camera in '%s'", v);
        if (!end) break;
        p = end + 1;
    }
    return EXIT_OK;
}

static host_acc_row *new_acc_row(host_state *hst)
{
    void *acc = hst->acc;
    host_acc_row *a = grow(&acc, &hst->acc_count, &hst->acc_cap, sizeof *a);
    hst->acc = acc;
    return a;
}

/* One view of --host-rmse: its G-buffer and AO_R (the reference cache compare and tune use, at
 * compare's size and rays), then per configuration the frame's AO and each host path's after
 * HOST_RMSE_FRAMES calls (compare's frames per row), against AO_R over the geometry pixels. */
static int host_rmse_view(const bench_opts *o, const char *spec, ob_renderer *fr, ob_renderer *hr, host_inputs *in,
                          const cli_config *configs, int count, const bool *has_samples, const bool *has_radius,
                          host_state *hst)
{
    const cli_common *c = &o->common;
    const int w = HOST_RMSE_W, h = HOST_RMSE_H;
    const size_t px = (size_t)w * (size_t)h;
    char name[256];
    snprintf(name, sizeof name, "%s", spec);
    const char *camera = NULL;
    char *colon = strrchr(name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    ob_scene *scene = NULL;
    cli_view_frame vf = {0};
    float *ref = NULL, *ao = NULL;
    uint8_t *mask = NULL;
    int code = cli_common_load_scene(c, name, &scene);
    ob_camera cam = {0};
    if (code == EXIT_OK) code = cli_common_camera(c, scene, camera, &cam);
    if (code == EXIT_OK && ob_renderer_set_scene(fr, scene) != OB_OK) code = cli_fail_from_library();
    if (code == EXIT_OK) code = cli_common_prepare(c, fr);
    if (code == EXIT_OK) code = cli_view_frame_make(fr, &cam, w, h, &vf);
    if (code == EXIT_OK)
        code = cli_check_visible(fr, w, h, ob_query_scene_name(scene), cam.name, c->allow_empty, EXIT_USAGE);
    ref = malloc(px * sizeof(float));
    ao = malloc(px * sizeof(float));
    mask = malloc(px);
    if (code == EXIT_OK && (!ref || !ao || !mask)) code = cli_fail(EXIT_RUNTIME, "out of memory");
    const float radius = scene ? ob_query_scene_ao_radius(scene) : 0.0f;
    cli_reference_info info = {0};
    if (code == EXIT_OK) {
        char key[900] = "";
        cli_reference_key(c, name, cam.name, key, sizeof key);
        code = cli_reference_ao(scene, &vf, key, radius, HOST_RMSE_SPP, false, c->verbose, ref, &info);
    }
    bool rgb = false;
    for (int k = 0; k < count; ++k) rgb = rgb || ob_method_at(configs[k].method)->directional;
    if (code == EXIT_OK) {
        for (size_t i = 0; i < px; ++i) mask[i] = vf.depth[i] > 0.0f;
        memcpy(in->lin, vf.depth, px * sizeof(float));
        memcpy(in->nrm, vf.normals, 3 * px * sizeof(float));
        /* The direct light and albedo of the same (none) frame, for the indirect-light methods. */
        if (rgb && (ob_read_image(fr, OB_IMAGE_RADIANCE_F32, in->rad, 3 * px * sizeof(float)) != OB_OK ||
                    ob_read_image(fr, OB_IMAGE_ALBEDO_F32, in->alb, 3 * px * sizeof(float)) != OB_OK))
            code = cli_fail_from_library();
        cam = vf.cam;
        if (code == EXIT_OK) code = host_matrices(scene, &cam, w, h, in);
        if (code == EXIT_OK) host_upload(in, rgb);
    }
    for (int k = 0; k < count && code == EXIT_OK; ++k) {
        ob_settings s, hs;
        const int n = o->samples_given && has_samples[k] ? o->samples[0] : 0;
        if ((code = configure(&configs[k], n, has_radius[k] ? radius : 0.0f, &s)) != EXIT_OK) break;
        if ((code = host_settings_of(&s, scene, radius, &hs)) != EXIT_OK) break;
        const bool directional = ob_method_at(s.method)->directional;
        host_acc_row *a = new_acc_row(hst);
        if (!a) {
            code = cli_fail(EXIT_RUNTIME, "out of memory");
            break;
        }
        snprintf(a->scene, sizeof a->scene, "%s", name);
        snprintf(a->camera, sizeof a->camera, "%s", cam.name);
        a->cfg = &configs[k];
        a->samples = n;
        a->radius = radius;
        a->ref_cached = info.cached;
        a->ref_stderr = info.stderr_mean;
        for (int p = 0; p < HOST_PATHS && code == EXIT_OK; ++p) {
            ob_renderer *r = p == HOST_FRAME ? fr : hr;
            ob_renderer_reset_history(r);
            for (int f = 0; f < HOST_RMSE_FRAMES && code == EXIT_OK; ++f) {
                if (p == HOST_FRAME) {
                    if (ob_render_frame(fr, &cam, &s) != OB_OK) code = cli_fail_from_library();
                    continue;
                }
                ob_host_frame hf;
                ob_host_outputs ho;
                host_call_args(in, p, directional, &hf, &ho);
                if (ob_host_ao(hr, &hf, &hs, &ho) != OB_OK) code = cli_fail_from_library();
                else code = host_gl_check(p);
            }
            if (code != EXIT_OK) break;
            if (p == HOST_FRAME) {
                if (ob_read_image(fr, OB_IMAGE_AO_F32, ao, px * sizeof(float)) != OB_OK) code = cli_fail_from_library();
            } else {
                glGetTextureImage(in->out[p], 0, GL_RED, GL_FLOAT, (int)(px * sizeof(float)), ao);
            }
            if (code == EXIT_OK && ob_compare_images(ao, ref, mask, w, h, 1, &a->m[p]) != OB_OK) code = cli_fail_from_library();
        }
    }
    cli_view_frame_free(&vf);
    free(ref);
    free(ao);
    free(mask);
    ob_destroy_scene(scene);
    return code;
}

/* Every --host-rmse view, before anything is timed (a bad scene or camera fails first). */
static int host_rmse(const bench_opts *o, ob_context *ctx, const cli_config *configs, int count, const bool *has_samples,
                     const bool *has_radius, host_state *hst)
{
    ob_renderer *fr = ob_make_renderer(ctx, &(ob_renderer_desc){.width = HOST_RMSE_W, .height = HOST_RMSE_H});
    ob_renderer *hr = ob_make_renderer(ctx, &(ob_renderer_desc){.width = HOST_RMSE_W, .height = HOST_RMSE_H});
    host_inputs in = {0};
    int code = fr && hr ? host_inputs_make(&in, HOST_RMSE_W, HOST_RMSE_H) : cli_fail_from_library();
    char list[1024];
    snprintf(list, sizeof list, "%s", o->host_views);
    char *save = NULL;
    for (char *t = strtok_r(list, ",", &save); t && code == EXIT_OK; t = strtok_r(NULL, ",", &save))
        code = host_rmse_view(o, t, fr, hr, &in, configs, count, has_samples, has_radius, hst);
    host_inputs_free(&in);
    ob_destroy_renderer(fr);
    ob_destroy_renderer(hr);
    return code;
}

static host_row *new_host_row(host_state *hst)
{
    void *rows = hst->rows;
    host_row *r = grow(&rows, &hst->count, &hst->cap, sizeof *r);
    hst->rows = rows;
    return r;
}

/* The timing run: per camera, per configuration (the sweep's N and r), host_measure. */
static int host_bench(const bench_opts *o, ob_context *ctx, const ob_scene *scene, const int *cams, int cam_count,
                      const cli_config *configs, int count, const bool *has_samples, const bool *has_radius,
                      bench_state *st, host_state *hst)
{
    const cli_common *c = &o->common;
    const float suggested = ob_query_scene_ao_radius(scene);
    ob_renderer *rs[HOST_PATHS] = {NULL, NULL, NULL, NULL};
    host_inputs in = {0};
    double *scratch = calloc((size_t)HOST_PATHS * HOST_COLS * (size_t)o->frames, sizeof(double));
    int code = scratch ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
    for (int p = 0; p < HOST_PATHS && code == EXIT_OK; ++p) {
        rs[p] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
        if (!rs[p]) code = cli_fail_from_library();
    }
    if (code == EXIT_OK && ob_renderer_set_scene(rs[HOST_FRAME], scene) != OB_OK) code = cli_fail_from_library();
    if (code == EXIT_OK) code = cli_common_prepare(c, rs[HOST_FRAME]);
    if (code == EXIT_OK) code = host_inputs_make(&in, c->width, c->height);
    int per_cam = 0;
    for (int k = 0; k < count; ++k) per_cam += (has_samples[k] ? o->sample_count : 1) * (has_radius[k] ? o->radius_count : 1);
    st->total = per_cam * cam_count;
    if (code == EXIT_OK) ob_progress_begin(&st->bar, "bench --host", st->total);
    for (int ci = 0; ci < cam_count && code == EXIT_OK; ++ci) {
        const ob_camera cam = ob_query_camera(scene, cams[ci]);
        for (int k = 0; k < count && code == EXIT_OK; ++k) {
            const int nn = has_samples[k] ? o->sample_count : 1, rn = has_radius[k] ? o->radius_count : 1;
            for (int j = 0; j < nn && code == EXIT_OK; ++j)
                for (int q = 0; q < rn && code == EXIT_OK; ++q) {
                    const int n = has_samples[k] ? o->samples[j] : 0;
                    const float r = has_radius[k] ? o->radii[q] : 0.0f, rw = r * suggested / 4.0f;
                    ob_settings s, hs;
                    if ((code = configure(&configs[k], n, rw, &s)) != EXIT_OK) break;
                    if ((code = host_settings_of(&s, scene, suggested, &hs)) != EXIT_OK) break;
                    host_row *row = new_host_row(hst);
                    if (!row) {
                        code = cli_fail(EXIT_RUNTIME, "out of memory");
                        break;
                    }
                    *row = (host_row){.camera = cams[ci], .cfg = &configs[k], .samples = n, .r = r, .radius_world = rw,
                                      .width = c->width, .height = c->height};
                    code = host_measure(rs, &cam, scene, &s, &hs, o, &in, scratch, row);
                    /* Once per camera: timing an empty frame times nothing. */
                    if (code == EXIT_OK && k == 0 && j == 0 && q == 0)
                        code = cli_check_visible(rs[HOST_FRAME], c->width, c->height, ob_query_scene_name(scene), cam.name,
                                                 c->allow_empty, EXIT_INPUT);
                    char what[512] = "";
                    snprintf(what, sizeof what, "%s %s N=%d r=%g", cam.name, configs[k].label, n, (double)r);
                    if (code == EXIT_OK) progress(st, what);
                }
        }
    }
    host_inputs_free(&in);
    for (int p = 0; p < HOST_PATHS; ++p) ob_destroy_renderer(rs[p]);
    free(scratch);
    return code;
}

/* "12.345 (12.1-13.0)", or "-" for a pass the path did not run. */
static void host_cell(char *out, size_t n, const double *v, bool ran)
{
    if (!ran) snprintf(out, n, "-");
    else snprintf(out, n, "%.3f (%.3f-%.3f)", v[0], v[1], v[2]);
}

static void print_host_tables(const bench_opts *o, const ob_scene *scene, const host_state *hst, const int *cams,
                              int cam_count)
{
    static const char *const letter[HOST_PATHS] = {"(a)", "(b)", "(c)", "(d)"};
    for (int ci = 0; ci < cam_count; ++ci) {
        printf("\n== %s, camera %s, %dx%d%s: the host path (ob_host_ao) beside the frame's AO chain, ms median (min-max) "
               "of %d frames, the four alternated frame by frame ==\n",
               ob_query_scene_name(scene), ob_query_camera(scene, cams[ci]).name, o->common.width, o->common.height,
               o->common.temporal ? ", temporal on" : "", o->frames);
        printf("(a) frame            ob_render_frame, the sum of its chain passes (downsample, edges, depth_mips, ao, "
               "temporal, filter, upsample)\n"
               "(b) host_linear      ob_host_ao, R32F linear depth + RGBA16F view normals -> R32F\n"
               "(c) host_packed      ob_host_ao, D32F reversed-Z depth + octahedral RG16F world normals -> R8\n"
               "(d) host_no_normals  ob_host_ao, D32F reversed-Z depth, no normals (rebuilt by the input pass) -> R8\n"
               "x (a): the median over the frames of each frame's total / (a) in the same frame\n"
               "call cpu ms: the call's wall time on the CPU (checks, GL-state save and restore, submission; the "
               "GPU runs on asynchronously), with (a)'s G-buffer and lighting\n");
        for (int i = 0; i < hst->count; ++i) {
            const host_row *r = &hst->rows[i];
            if (r->camera != cams[ci]) continue;
            char label[CLI_MAX_LABEL + 32];
            snprintf(label, sizeof label, "%s", r->cfg->label);
            if (r->samples > 0) snprintf(label + strlen(label), sizeof label - strlen(label), " \xc2\xb7 N %d", r->samples);
            if (r->r > 0.0f) snprintf(label + strlen(label), sizeof label - strlen(label), " \xc2\xb7 r %g", (double)r->r);
            printf("\n%s\n  %-20s %-26s %-26s %-26s %-26s %-8s %s\n", label, "path", "chain ms", "input ms", "output ms",
                   "total ms", "x (a)", "call cpu ms");
            for (int p = 0; p < HOST_PATHS; ++p) {
                const host_path_row *pr = &r->path[p];
                char ch[64], inp[64], out[64], tot[64], cpu[64];
                host_cell(ch, sizeof ch, pr->chain, true);
                host_cell(inp, sizeof inp, pr->input, pr->has_input);
                host_cell(out, sizeof out, pr->output, pr->has_output);
                host_cell(tot, sizeof tot, pr->total, true);
                host_cell(cpu, sizeof cpu, pr->call, true);
                printf("  %s %-16s %-26s %-26s %-26s %-26s %.3fx   %s\n", letter[p], host_path_names[p], ch, inp, out, tot,
                       pr->ratio[0], cpu);
            }
            const double *q = r->path[HOST_LINEAR].ratio;
            printf("  (b)/(a) = %.3fx (frames' ratios: median, min %.3f, max %.3f): %s %.2fx\n", q[0], q[1], q[2],
                   q[0] <= HOST_TARGET ? "within" : "over", HOST_TARGET);
        }
    }
    if (hst->acc_count > 0) {
        printf("\n== host path accuracy: RMSE (bias) against the ray-traced AO_R (%d rays/px), %dx%d, each view's "
               "suggested radius, after %d calls ==\n",
               HOST_RMSE_SPP, HOST_RMSE_W, HOST_RMSE_H, HOST_RMSE_FRAMES);
        printf("  %-28s %-24s %-20s %-20s %-20s %-20s %s\n", "view", "configuration", "(a) frame", "(b) host_linear",
               "(c) host_packed", "(d) host_no_normals", "(d) - (b)");
        for (int i = 0; i < hst->acc_count; ++i) {
            const host_acc_row *a = &hst->acc[i];
            char view[330], cells[HOST_PATHS][48];
            snprintf(view, sizeof view, "%s:%s", a->scene, a->camera);
            for (int p = 0; p < HOST_PATHS; ++p)
                snprintf(cells[p], sizeof cells[p], "%.4f (%+.4f)", a->m[p].rmse, a->m[p].bias);
            printf("  %-28s %-24s %-20s %-20s %-20s %-20s %+.4f\n", view, a->cfg->label, cells[0], cells[1], cells[2],
                   cells[3], a->m[HOST_NO_NORMALS].rmse - a->m[HOST_LINEAR].rmse);
        }
    }
}

static void stat_json(cJSON *parent, const char *name, const double *v, bool ran)
{
    if (!ran) {
        cJSON_AddNullToObject(parent, name);
        return;
    }
    cJSON *j = cJSON_AddObjectToObject(parent, name);
    cJSON_AddNumberToObject(j, "median", v[0]);
    cJSON_AddNumberToObject(j, "min", v[1]);
    cJSON_AddNumberToObject(j, "max", v[2]);
}

static cJSON *host_row_json(const host_row *r, const ob_scene *scene)
{
    cJSON *j = cJSON_CreateObject();
    char label[CLI_MAX_LABEL + 32] = "";
    row_label(&(bench_row){.cfg = r->cfg, .samples = r->samples, .r = r->r}, label, sizeof label);
    config_json(j, label, r->cfg->method, r->cfg, scene, r->camera, r->samples, r->r, r->radius_world, r->width,
                r->height);
    cJSON_AddBoolToObject(j, "temporal", r->cfg->settings.temporal);
    cJSON *paths = cJSON_AddObjectToObject(j, "paths");
    for (int p = 0; p < HOST_PATHS; ++p) {
        const host_path_row *pr = &r->path[p];
        cJSON *x = cJSON_AddObjectToObject(paths, host_path_names[p]);
        cJSON_AddStringToObject(x, "depth", host_path_depth[p]);
        cJSON_AddStringToObject(x, "normals", host_path_normals[p]);
        cJSON_AddStringToObject(x, "output", host_path_output[p]);
        cJSON *passes = cJSON_AddArrayToObject(x, "passes");
        for (int k = 0; k < pr->pass_count; ++k) {
            cJSON *q = cJSON_CreateObject();
            cJSON_AddStringToObject(q, "name", pr->pass[k]);
            cJSON_AddNumberToObject(q, "median", pr->med[k]);
            cJSON_AddNumberToObject(q, "min", pr->min[k]);
            cJSON_AddNumberToObject(q, "max", pr->max[k]);
            cJSON_AddItemToArray(passes, q);
        }
        stat_json(x, "chain_ms", pr->chain, true);
        stat_json(x, "input_ms", pr->input, pr->has_input);
        stat_json(x, "output_ms", pr->output, pr->has_output);
        stat_json(x, "total_ms", pr->total, true);
        stat_json(x, "ratio_to_frame", pr->ratio, true);
        stat_json(x, "call_cpu_ms", pr->call, true);
    }
    const double *q = r->path[HOST_LINEAR].ratio;
    cJSON_AddNumberToObject(j, "host_ratio", q[0]);
    cJSON_AddBoolToObject(j, "host_within_target", q[0] <= HOST_TARGET);
    return j;
}

static cJSON *host_acc_json(const host_state *hst)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "width", HOST_RMSE_W);
    cJSON_AddNumberToObject(j, "height", HOST_RMSE_H);
    cJSON_AddNumberToObject(j, "reference_spp", HOST_RMSE_SPP);
    cJSON_AddNumberToObject(j, "calls", HOST_RMSE_FRAMES);
    cJSON *arr = cJSON_AddArrayToObject(j, "views");
    for (int i = 0; i < hst->acc_count; ++i) {
        const host_acc_row *a = &hst->acc[i];
        cJSON *x = cJSON_CreateObject();
        cJSON_AddStringToObject(x, "scene", a->scene);
        cJSON_AddStringToObject(x, "camera", a->camera);
        cJSON_AddStringToObject(x, "method", method_name(a->cfg->method));
        cJSON_AddStringToObject(x, "label", a->cfg->label);
        if (a->samples > 0) cJSON_AddNumberToObject(x, "samples", a->samples);
        else cJSON_AddNullToObject(x, "samples");
        cJSON_AddNumberToObject(x, "radius_world", a->radius);
        cJSON_AddBoolToObject(x, "reference_cached", a->ref_cached);
        cJSON_AddNumberToObject(x, "reference_stderr", a->ref_stderr);
        cJSON_AddNumberToObject(x, "pixels", (double)a->m[HOST_FRAME].count);
        for (int p = 0; p < HOST_PATHS; ++p) {
            cJSON *m = cJSON_AddObjectToObject(x, host_path_names[p]);
            cJSON_AddNumberToObject(m, "rmse", a->m[p].rmse);
            cJSON_AddNumberToObject(m, "bias", a->m[p].bias);
            cJSON_AddNumberToObject(m, "mae", a->m[p].mae);
            cJSON_AddNumberToObject(m, "ssim", a->m[p].ssim);
        }
        cJSON_AddNumberToObject(x, "no_normals_minus_linear_rmse", a->m[HOST_NO_NORMALS].rmse - a->m[HOST_LINEAR].rmse);
        cJSON_AddItemToArray(arr, x);
    }
    return j;
}

static int write_host_csv(int index, const host_state *hst, const ob_scene *scene)
{
    size_t cap = 4096 + (size_t)hst->count * HOST_PATHS * (700 + CLI_MAX_LABEL), len = 0;
    char *buf = malloc(cap);
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    len += (size_t)snprintf(buf + len, cap - len,
                            "scene,camera,method,samples,r,radius_world,filter,ao_scale,temporal,width,height,path,depth,"
                            "normals,output,chain_ms,chain_min_ms,chain_max_ms,input_ms,input_min_ms,input_max_ms,output_ms,"
                            "output_min_ms,output_max_ms,total_ms,total_min_ms,total_max_ms,ratio_frame,ratio_frame_min,"
                            "ratio_frame_max,call_cpu_ms,call_cpu_min_ms,call_cpu_max_ms,label\n");
    for (int i = 0; i < hst->count; ++i) {
        const host_row *r = &hst->rows[i];
        char label[CLI_MAX_LABEL + 32] = "", samples[16] = "", rr[32] = "", rw[32] = "";
        row_label(&(bench_row){.cfg = r->cfg, .samples = r->samples, .r = r->r}, label, sizeof label);
        if (r->samples > 0) snprintf(samples, sizeof samples, "%d", r->samples);
        if (r->r > 0.0f) {
            snprintf(rr, sizeof rr, "%g", (double)r->r);
            snprintf(rw, sizeof rw, "%g", (double)r->radius_world);
        }
        for (int p = 0; p < HOST_PATHS; ++p) {
            const host_path_row *pr = &r->path[p];
            char in[96] = ",,", out[96] = ",,";
            if (pr->has_input) snprintf(in, sizeof in, "%.4f,%.4f,%.4f", pr->input[0], pr->input[1], pr->input[2]);
            if (pr->has_output) snprintf(out, sizeof out, "%.4f,%.4f,%.4f", pr->output[0], pr->output[1], pr->output[2]);
            len += (size_t)snprintf(buf + len, cap - len,
                                    "%s,%s,%s,%s,%s,%s,%s,%g,%s,%d,%d,%s,%s,%s,%s,%.4f,%.4f,%.4f,%s,%s,%.4f,%.4f,%.4f,"
                                    "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s\n",
                                    ob_query_scene_name(scene), ob_query_camera(scene, r->camera).name,
                                    method_name(r->cfg->method), samples, rr, rw, ob_filter_at(r->cfg->filter)->name,
                                    1.0 / r->cfg->ao_divisor, r->cfg->settings.temporal ? "on" : "off", r->width, r->height,
                                    host_path_names[p], host_path_depth[p], host_path_normals[p], host_path_output[p],
                                    pr->chain[0], pr->chain[1], pr->chain[2], in, out, pr->total[0], pr->total[1],
                                    pr->total[2], pr->ratio[0], pr->ratio[1], pr->ratio[2], pr->call[0], pr->call[1],
                                    pr->call[2], label);
        }
    }
    int code = cli_outputs_write_text(&bench_outs, index, buf);
    free(buf);
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

static int bench_run(int argc, char **argv)
{
    bench_opts o;
    int code = parse(argc, argv, &o);
    if (code != 0) return code < 0 ? EXIT_OK : code;
    const cli_common *c = &o.common;

    /* Everything that can be checked without a GPU first: the combinations of the lists with
     * their settings, each method's N, the scene and the cameras. */
    cli_config *configs = NULL, *bases = NULL;
    int count = 0, base_count = c->filter_count * c->ao_count;
    bool *has_samples = NULL, *has_radius = NULL;
    ob_scene *scene = NULL;
    ob_context *ctx = NULL;
    bench_state st = {0};
    ob_renderer *eyes[2] = {NULL, NULL};
    ob_scene *tess[3] = {NULL, NULL, NULL};
    double *scratch = NULL;
    host_state hst = {0};
    if (c->method_count > 0 && (code = cli_common_configs(c, &configs, &count)) != EXIT_OK) return code;
    /* The none frames, one per filter and AO scale: the same settings but the method. */
    bases = calloc((size_t)base_count, sizeof *bases);
    has_samples = calloc((size_t)count + 1, sizeof *has_samples);
    has_radius = calloc((size_t)count + 1, sizeof *has_radius);
    if (!bases || !has_samples || !has_radius) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }
    for (int f = 0, b = 0; f < c->filter_count && code == EXIT_OK; ++f)
        for (int a = 0; a < c->ao_count && code == EXIT_OK; ++a, ++b) {
            bases[b] = (cli_config){.method = ob_find_method("none"), .filter = c->filters[f], .ao_divisor = c->ao_divisors[a]};
            code = cli_common_apply(c, &bases[b]);
        }
    for (int k = 0; k < count && code == EXIT_OK; ++k) {
        code = takes_samples(&o, configs[k].method, &has_samples[k]);
        has_radius[k] = method_has_param(configs[k].method, "radius");
    }
    if (code != EXIT_OK) goto cleanup;
    /* The quick run renders the shadow maps once (see QUICK_*); --full every frame, as the
     * recorded tables do. */
    for (int b = 0; b < base_count; ++b) bases[b].settings.shadow.reuse = o.keep_shadows;
    for (int k = 0; k < count; ++k) configs[k].settings.shadow.reuse = o.keep_shadows;

    if ((code = cli_common_load_scene(c, NULL, &scene)) != EXIT_OK) goto cleanup;
    if (cli_common_moves(c)) {
        /* An unknown path fails here, before any GPU work. */
        ob_camera probe = ob_query_camera(scene, 0);
        if ((code = cli_common_path_camera(c, scene, &probe, 0, &probe)) != EXIT_OK) goto cleanup;
        moving.common = c;
        moving.scene = scene;
    }
    int cams[MAX_CAMS] = {0}, cam_count = 0;
    if ((code = camera_list(&o, scene, cams, &cam_count)) != EXIT_OK) goto cleanup;
    const float suggested = ob_query_scene_ao_radius(scene);

    ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        goto cleanup;
    }

    scratch = calloc((size_t)o.frames * (MAX_PASSES + 3), sizeof(double));
    int eye_count = o.stereo ? 2 : 1;
    const double t0 = now_s();
    st.start = t0;
    if (!scratch) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }

    /* Configurations per camera of the sweep: the none frames, then each combination's grid. */
    int per_cam = base_count;
    for (int k = 0; k < count; ++k) per_cam += (has_samples[k] ? o.sample_count : 1) * (has_radius[k] ? o.radius_count : 1);

    if (o.host) {
        /* The accuracy first: a bad --host-rmse view fails before minutes of timing. */
        if (o.host_views) code = host_rmse(&o, ctx, configs, count, has_samples, has_radius, &hst);
        if (code == EXIT_OK)
            code = host_bench(&o, ctx, scene, cams, cam_count, configs, count, has_samples, has_radius, &st, &hst);
        if (code == EXIT_OK) print_host_tables(&o, scene, &hst, cams, cam_count);
    } else if (!o.scaling) {
        st.total = per_cam * cam_count;
        ob_progress_begin(&st.bar, "bench", st.total);
        for (int e = 0; e < eye_count && code == EXIT_OK; ++e) {
            eyes[e] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
            if (!eyes[e] || ob_renderer_set_scene(eyes[e], scene) != OB_OK) code = cli_fail_from_library();
            else code = cli_common_prepare(c, eyes[e]);
        }
        for (int ci = 0; ci < cam_count && code == EXIT_OK; ++ci) {
            ob_camera cam = ob_query_camera(scene, cams[ci]);
            ob_camera views[2];
            if (!o.stereo) views[0] = cam;
            else if (ob_stereo_cameras(&cam, &(ob_stereo_desc){.ipd = o.ipd, .aspect = (float)c->width / (float)c->height},
                                       views) != OB_OK)
                code = cli_fail_from_library();
            const int base = st.count; /* the none rows of this camera, in the order of bases */
            for (int k = -base_count; k < count && code == EXIT_OK; ++k) {
                const bool is_base = k < 0;
                const cli_config *cfg = is_base ? &bases[k + base_count] : &configs[k];
                int nn = !is_base && has_samples[k] ? o.sample_count : 1;
                int rn = !is_base && has_radius[k] ? o.radius_count : 1;
                /* The none row of the same filter and AO scale. */
                int baseline = -1;
                for (int b = 0; b < base_count; ++b)
                    if (bases[b].filter == cfg->filter && bases[b].ao_divisor == cfg->ao_divisor) baseline = base + b;
                for (int j = 0; j < nn && code == EXIT_OK; ++j)
                    for (int q = 0; q < rn && code == EXIT_OK; ++q) {
                        int n = !is_base && has_samples[k] ? o.samples[j] : 0;
                        float r = !is_base && has_radius[k] ? o.radii[q] : 0.0f;
                        float rw = r * suggested / 4.0f;
                        ob_settings s = {0};
                        if ((code = configure(cfg, n, rw, &s)) != EXIT_OK) break;
                        bench_row *row = new_row(&st);
                        if (!row) {
                            code = cli_fail(EXIT_RUNTIME, "out of memory");
                            break;
                        }
                        /* A none row is its own baseline: its differences are 0 and ratios 1. */
                        *row = (bench_row){.camera = cams[ci], .method = cfg->method, .cfg = cfg, .samples = n, .r = r,
                                           .radius_world = rw, .width = c->width, .height = c->height,
                                           .triangles = ob_query_scene_stats(scene).triangles, .baseline = baseline};
                        code = measure(eyes, views, eye_count, &s, &o, scratch, row);
                        /* Once per camera (its first row): timing an empty frame times nothing. */
                        for (int e = 0; e < eye_count && code == EXIT_OK && row == &st.rows[base]; ++e)
                            code = cli_check_visible(eyes[e], c->width, c->height, ob_query_scene_name(scene),
                                                     views[e].name, c->allow_empty, EXIT_INPUT);
                        char what[512] = "";
                        snprintf(what, sizeof what, "%s %s N=%d r=%g", cam.name, cfg->label, n, (double)r);
                        if (code == EXIT_OK) progress(&st, what);
                    }
            }
        }
        if (code == EXIT_OK) print_tables(&o, scene, &st, cams, cam_count, configs, count);
    } else {
        /* Scaling: the first camera, the first N and r of the lists. */
        ob_camera cam = ob_query_camera(scene, cams[0]);
        st.total = count * (o.size_count + 3);
        ob_progress_begin(&st.bar, "bench", st.total);
        for (int z = 0; z < o.size_count && code == EXIT_OK; ++z) {
            ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = o.sizes[z][0], .height = o.sizes[z][1]});
            if (!r || ob_renderer_set_scene(r, scene) != OB_OK) code = cli_fail_from_library();
            else code = cli_common_prepare(c, r);
            for (int k = 0; k < count && code == EXIT_OK; ++k) {
                float rw = has_radius[k] ? o.radii[0] * suggested / 4.0f : 0.0f;
                ob_settings s = {0};
                if ((code = configure(&configs[k], has_samples[k] ? o.samples[0] : 0, rw, &s)) != EXIT_OK) break;
                bench_row *row = new_row(&st);
                if (!row) {
                    code = cli_fail(EXIT_RUNTIME, "out of memory");
                    break;
                }
                *row = (bench_row){.camera = cams[0], .method = configs[k].method, .cfg = &configs[k],
                                   .samples = has_samples[k] ? o.samples[0] : 0, .r = has_radius[k] ? o.radii[0] : 0.0f,
                                   .radius_world = rw, .width = o.sizes[z][0], .height = o.sizes[z][1],
                                   .triangles = ob_query_scene_stats(scene).triangles, .baseline = -1, .study = 1};
                code = measure(&r, &cam, 1, &s, &o, scratch, row);
                char what[512] = "";
                snprintf(what, sizeof what, "%dx%d %s", o.sizes[z][0], o.sizes[z][1], configs[k].label);
                if (code == EXIT_OK) progress(&st, what);
            }
            ob_destroy_renderer(r);
        }
        if (code == EXIT_OK) {
            eyes[0] = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
            code = eyes[0] ? cli_common_prepare(c, eyes[0]) : cli_fail_from_library();
        }
        for (int l = 0; l < 3 && code == EXIT_OK; ++l) {
            tess[l] = ob_tessellate_scene(scene, l);
            if (!tess[l] || ob_renderer_set_scene(eyes[0], tess[l]) != OB_OK) {
                code = cli_fail_from_library();
                break;
            }
            for (int k = 0; k < count && code == EXIT_OK; ++k) {
                float rw = has_radius[k] ? o.radii[0] * suggested / 4.0f : 0.0f;
                ob_settings s = {0};
                if ((code = configure(&configs[k], has_samples[k] ? o.samples[0] : 0, rw, &s)) != EXIT_OK) break;
                bench_row *row = new_row(&st);
                if (!row) {
                    code = cli_fail(EXIT_RUNTIME, "out of memory");
                    break;
                }
                *row = (bench_row){.camera = cams[0], .method = configs[k].method, .cfg = &configs[k],
                                   .samples = has_samples[k] ? o.samples[0] : 0, .r = has_radius[k] ? o.radii[0] : 0.0f,
                                   .radius_world = rw, .width = c->width, .height = c->height,
                                   .triangles = ob_query_scene_stats(tess[l]).triangles, .tess = l, .baseline = -1,
                                   .study = 2};
                code = measure(eyes, &cam, 1, &s, &o, scratch, row);
                char what[512] = "";
                snprintf(what, sizeof what, "%ux tris %s", 1u << (2 * l), configs[k].label);
                if (code == EXIT_OK) progress(&st, what);
            }
        }
        if (code == EXIT_OK) {
            printf("\n== scaling: AO-pass median ms, %s camera %s, %d frames ==\n", ob_query_scene_name(scene), cam.name,
                   o.frames);
            for (int k = 0; k < count; ++k) {
                printf("\n%s\n  resolution:", configs[k].label);
                for (int i = 0; i < st.count; ++i)
                    if (st.rows[i].cfg == &configs[k] && st.rows[i].study == 1)
                        printf("  %dx%d %.3f ms (%.3f ms/MP%s)", st.rows[i].width, st.rows[i].height, st.rows[i].ao_ms,
                               st.rows[i].ao_ms / (st.rows[i].width * (double)st.rows[i].height * 1e-6),
                               floor_note(&st.rows[i]));
                printf("\n  triangles: ");
                for (int i = 0; i < st.count; ++i)
                    if (st.rows[i].cfg == &configs[k] && st.rows[i].study == 2)
                        printf("  %u tris %.3f ms%s", st.rows[i].triangles, st.rows[i].ao_ms, floor_note(&st.rows[i]));
                scaling_verdict v = verdict(&st, &configs[k]);
                printf("\n  flat in triangles: %s (max/min %.2f, < 1.2); linear in pixels: %s (ms/MP within %.0f%% of "
                       "the median, limit 30%%)\n",
                       v.flat_in_triangles ? "yes" : "no", v.tri_ratio, v.linear_in_pixels ? "yes" : "no",
                       100.0 * v.mpx_spread);
            }
        }
    }
    ob_progress_end(&st.bar);
    if (code == EXIT_OK && !o.full && !o.scaling && !o.host) full_table_hint(&o, scene, has_samples, has_radius, count, base_count,
                                                                  st.count, now_s() - t0);
    const double seconds = now_s() - t0;
    if (code == EXIT_OK)
        printf("\n%d configurations in %.0f s on %s\n", o.host ? hst.count : st.count, seconds, ob_query_renderer(ctx));

    /* Into temporary files, the CSV first: cmd_bench renames the pair only when both were
     * written, so a JSON that fails after it leaves neither. */
    if (code == EXIT_OK && o.csv)
        code = o.host ? write_host_csv(bench_csv, &hst, scene) : write_csv(bench_csv, &st, scene, eye_count);
    if (code == EXIT_OK && o.json) {
        char cpu[256], commit[64], date[64];
        cpu_model(cpu, sizeof cpu);
        cli_git_commit(commit, sizeof commit);
        time_t t = time(NULL);
        struct tm tm_utc;
        gmtime_r(&t, &tm_utc);
        strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tm_utc);
        /* The filters as one string: "geometry", or "none,geometry" for a list. */
        char filters[256] = "";
        for (int f = 0; f < c->filter_count; ++f) {
            size_t len = strlen(filters);
            snprintf(filters + len, sizeof filters - len, "%s%s", f ? "," : "", ob_filter_at(c->filters[f])->name);
        }
        cJSON *root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "tool", "obscura bench " OB_VERSION_STRING);
        cJSON_AddStringToObject(root, "date", date);
        cJSON_AddStringToObject(root, "commit", commit);
        /* Every option that shaped the run (--set, --settings, --shadow, --hdr included), as given. */
        cJSON *cmd = cJSON_AddArrayToObject(root, "command_line");
        for (int i = 0; i < argc; ++i) cJSON_AddItemToArray(cmd, cJSON_CreateString(argv[i]));
        cJSON_AddStringToObject(root, "renderer", ob_query_renderer(ctx));
        cJSON_AddStringToObject(root, "gl_version", ob_query_gl_version(ctx));
        cJSON_AddStringToObject(root, "device", ob_query_device(ctx));
        cJSON_AddBoolToObject(root, "software", ob_query_is_software(ctx));
        cJSON_AddStringToObject(root, "cpu", cpu);
        cJSON_AddNumberToObject(root, "cpu_cores", (double)sysconf(_SC_NPROCESSORS_ONLN));
        cJSON_AddStringToObject(root, "scene", ob_query_scene_name(scene));
        cJSON_AddNumberToObject(root, "triangles", ob_query_scene_stats(scene).triangles);
        cJSON_AddNumberToObject(root, "scene_radius", suggested);
        cJSON_AddStringToObject(root, "radius_rule", "radius_world = r x scene_radius / 4 (r = 4: the suggested radius)");
        cJSON_AddStringToObject(root, "mode", o.host ? "host" : o.scaling ? "scaling" : o.stereo ? "stereo" : "sweep");
        cJSON_AddNumberToObject(root, "width", c->width);
        cJSON_AddNumberToObject(root, "height", c->height);
        cJSON_AddNumberToObject(root, "eyes", eye_count);
        if (o.stereo) {
            cJSON_AddNumberToObject(root, "ipd", o.ipd);
            cJSON_AddNumberToObject(root, "budget_ms", VR_BUDGET_MS);
        }
        cJSON_AddNumberToObject(root, "frames", o.frames);
        /* Issue 17: the accumulation and the camera's motion change every pass's work. */
        cJSON_AddBoolToObject(root, "temporal", c->temporal);
        if (c->temporal) cli_common_temporal_json(c, root);
        if (c->path) cJSON_AddStringToObject(root, "path", c->path);
        if (c->has_orbit) cJSON_AddNumberToObject(root, "orbit_degrees", c->orbit_deg);
        if (cli_common_moves(c)) cJSON_AddNumberToObject(root, "path_frames", c->path_frames);
        cJSON_AddNumberToObject(root, "warmup", o.warmup);
        cJSON_AddBoolToObject(root, "floor", o.floor);
        cJSON_AddStringToObject(root, "filter", filters);
        cJSON_AddNumberToObject(root, "seconds", seconds);
        cJSON *arr = cJSON_AddArrayToObject(root, "configurations");
        if (o.host) {
            cJSON_AddNumberToObject(root, "host_target", HOST_TARGET);
            cJSON *hp = cJSON_AddArrayToObject(root, "host_paths");
            for (int p = 0; p < HOST_PATHS; ++p) {
                cJSON *x = cJSON_CreateObject();
                cJSON_AddStringToObject(x, "name", host_path_names[p]);
                cJSON_AddStringToObject(x, "depth", host_path_depth[p]);
                cJSON_AddStringToObject(x, "normals", host_path_normals[p]);
                cJSON_AddStringToObject(x, "output", host_path_output[p]);
                cJSON_AddItemToArray(hp, x);
            }
            for (int i = 0; i < hst.count; ++i) cJSON_AddItemToArray(arr, host_row_json(&hst.rows[i], scene));
            if (hst.acc_count > 0) cJSON_AddItemToObject(root, "host_rmse", host_acc_json(&hst));
            else cJSON_AddNullToObject(root, "host_rmse");
        }
        for (int i = 0; i < st.count; ++i) {
            cJSON *j = row_json(&st.rows[i], baseline_of(&st, &st.rows[i]), scene);
            if (o.stereo) cJSON_AddBoolToObject(j, "within_budget", st.rows[i].frame_med <= VR_BUDGET_MS);
            cJSON_AddItemToArray(arr, j);
        }
        if (o.scaling) {
            cJSON *sc = cJSON_AddArrayToObject(root, "scaling");
            for (int k = 0; k < count; ++k) {
                scaling_verdict v = verdict(&st, &configs[k]);
                cJSON *j = cJSON_CreateObject();
                cJSON_AddStringToObject(j, "method", method_name(configs[k].method));
                cJSON_AddStringToObject(j, "label", configs[k].label);
                cJSON_AddNumberToObject(j, "triangle_max_min_ratio", v.tri_ratio);
                cJSON_AddBoolToObject(j, "flat_in_triangles", v.flat_in_triangles);
                cJSON_AddNumberToObject(j, "ms_per_megapixel_spread", v.mpx_spread);
                cJSON_AddBoolToObject(j, "linear_in_pixels", v.linear_in_pixels);
                cJSON_AddItemToArray(sc, j);
            }
        }
        char *text = cJSON_Print(root);
        cJSON_Delete(root);
        if (!text) code = cli_fail(EXIT_RUNTIME, "out of memory");
        else code = cli_outputs_write_text(&bench_outs, bench_json, text);
        free(text);
    }

cleanup:
    ob_progress_end(&st.bar); /* a failed run's bar line ends before the shell prompt */
    free(scratch);
    free(st.rows);
    free(hst.rows);
    free(hst.acc);
    for (int e = 0; e < 2; ++e) ob_destroy_renderer(eyes[e]);
    for (int l = 0; l < 3; ++l) ob_destroy_scene(tess[l]);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    free(has_samples);
    free(has_radius);
    free(bases);
    free(configs);
    return code;
}
