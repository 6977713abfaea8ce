/* obscura bench: GPU time per pass of every method over sample counts N and radii r (seed 000
 * §5.1 tables), against a no-AO frame, optionally in stereo against the 90 Hz budget (§5.2) or as
 * a scaling study over resolution and triangle count. DESIGN.md "Performance method": warm-up
 * frames first, then median/min/max over the measured frames, every ratio from the same run. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli_options.h"
#include "outputs.h"
#include "progress.h"
#include "run_program.h"

/* --json and --csv (outputs.h): added while parsing, committed by cmd_bench. */
static cli_outputs bench_outs;
static int bench_json = -1, bench_csv = -1;

enum { MAX_PASSES = 20, MAX_LIST = CLI_MAX_LIST, MAX_CAMS = 32, MAX_SIZES = 16 };

static const double VR_BUDGET_MS = 1000.0 / 90.0;

/* What `obscura bench` with no options measures: every method once against none, on the first
 * camera preset, at N = 24 (seed 000's "medium") and r = 4 (the scene's suggested radius), 20
 * frames after 3, with the shadow maps rendered once (the scene and lights are static, as in the
 * viewer). On the 2-core llvmpipe machine an 800x600 Cornell frame took 0.5-0.9 s, 0.26 s of it
 * the point light's 2048^2 cube map: the old default, seed 000's table (both of Cornell's
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
          "no-AO ('none') frame of the same camera, filter and AO scale: the tables of seed 000 §5.1-5.2.\n"
          "Each combination of --methods, --filters and --ao-scales is its own table.\n"
          "\n"
          "With no options it is a quick run (under 3 minutes on 2 cores with llvmpipe): every method\n"
          "once, first camera preset, N = 24, r = 4, 20 frames after 3, shadow maps rendered once.\n"
          "  --full                seed 000's whole table: every camera preset (identical presets\n"
          "                        once), N = 12,24,36,64, r = 2,4,8, 50 frames after 5, shadow maps\n"
          "                        rendered every frame; the options below still override it\n"
          "  --cameras A,B         camera presets by name or index (default: the first; --full every one)\n"
          "  --samples 12,24,36,64 the sweep's samples per pixel N (methods without a count run once);\n"
          "                        --quality low,high names them by preset instead (default 24)\n"
          "  --radius 2,4,8        r as a multiple of a quarter of the scene's suggested radius:\n"
          "                        radius = r x suggested / 4, so r = 4 is the suggested radius and\n"
          "                        2/4/8 are half/1x/2x (seed 000's r are metres on one scene); N and r\n"
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
          "  --json FILE           every number, with GL renderer/version, CPU, commit and date\n"
          "  --csv FILE            one row per configuration and pass\n"
          "\n"
          "stdout: one table per method (per combination), rows N, columns r, cells 'AO-pass ms /\n"
          "frame ms' (medians); stderr: a progress bar with the configurations done and the time left.\n"
          "The methods' --methods default is every method but none, which is always measured.\n",
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
        int taken = cli_common_option(c, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        const char *const own[] = {"--cameras", "--json", "--csv", "--radius", "--sizes", "--frames", "--warmup", "--ipd"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura bench --help)", a);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura bench --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--cameras")) o->cameras = v;
        else if (!strcmp(a, "--json")) o->json = v;
        else if (!strcmp(a, "--csv")) o->csv = v;
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
    if (o->stereo && (c->path || c->has_orbit)) return cli_fail(EXIT_USAGE, "--stereo and --path/--orbit exclude each other");
    /* The stereo size before cli_common_finish: its memory estimate is for the renderers made. */
    if (o->stereo && !c->has_size) {
        c->width = 1080;
        c->height = 1200;
    }
    c->renderers = o->stereo ? 2 : 1;
    for (int z = 0; o->scaling && z < o->size_count; ++z)
        if ((long long)o->sizes[z][0] * o->sizes[z][1] > (long long)c->memory_width * c->memory_height) {
            c->memory_width = o->sizes[z][0];
            c->memory_height = o->sizes[z][1];
        }
    int code = cli_common_finish(c);
    if (code != EXIT_OK) return code;
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

static bench_row *new_row(bench_state *st)
{
    if (st->count == st->cap) {
        int cap = st->cap ? st->cap * 2 : 64;
        bench_row *p = realloc(st->rows, (size_t)cap * sizeof *p);
        if (!p) return NULL;
        st->rows = p;
        st->cap = cap;
    }
    bench_row *r = &st->rows[st->count++];
    memset(r, 0, sizeof *r);
    r->baseline = -1;
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

/* After a run without --full: how to run seed 000's whole table, and what it would cost at this
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
           "Seed 000's whole table: add --full (every camera preset, N = 12,24,36,64, r = 2,4,8, %d frames\n"
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

static void git_commit(char *out, size_t n)
{
    snprintf(out, n, "unknown");
    const char *dir = ob_data_dir();
    if (!dir) return;
    /* git gets the directory as one argument, with no shell (run_program.h): any name works, quotes
     * included, and none runs a command. No git, no repository: "unknown". */
    const char *argv[] = {"git", "-C", dir, "rev-parse", "--short", "HEAD", NULL};
    cli_spawn_output line = {.limit = 127};
    int status = -1;
    if (cli_spawn(argv, -1, &line, NULL, &status) == 0 && status == 0 && line.data && !line.truncated) {
        line.data[strcspn(line.data, "\r\n")] = '\0';
        if (line.data[0]) snprintf(out, n, "%s", line.data);
    }
    cli_spawn_output_free(&line);
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

static cJSON *row_json(const bench_row *r, const bench_row *none, const ob_scene *scene)
{
    cJSON *j = cJSON_CreateObject();
    char label[CLI_MAX_LABEL + 32] = "";
    row_label(r, label, sizeof label);
    cJSON_AddStringToObject(j, "method", method_name(r->method));
    cJSON_AddStringToObject(j, "label", label);
    cJSON_AddStringToObject(j, "filter", ob_filter_at(r->cfg->filter)->name);
    cJSON_AddNumberToObject(j, "ao_scale", 1.0 / r->cfg->ao_divisor);
    cJSON_AddStringToObject(j, "camera", ob_query_camera(scene, r->camera).name);
    if (r->samples > 0) cJSON_AddNumberToObject(j, "samples", r->samples);
    else cJSON_AddNullToObject(j, "samples");
    if (r->r > 0.0f) {
        cJSON_AddNumberToObject(j, "radius", r->r);
        cJSON_AddNumberToObject(j, "radius_world", r->radius_world);
    } else {
        cJSON_AddNullToObject(j, "radius");
        cJSON_AddNullToObject(j, "radius_world");
    }
    cJSON_AddNumberToObject(j, "width", r->width);
    cJSON_AddNumberToObject(j, "height", r->height);
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

    if (!o.scaling) {
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
    if (code == EXIT_OK && !o.full && !o.scaling) full_table_hint(&o, scene, has_samples, has_radius, count, base_count,
                                                                  st.count, now_s() - t0);
    const double seconds = now_s() - t0;
    if (code == EXIT_OK) printf("\n%d configurations in %.0f s on %s\n", st.count, seconds, ob_query_renderer(ctx));

    /* Into temporary files, the CSV first: cmd_bench renames the pair only when both were
     * written, so a JSON that fails after it leaves neither. */
    if (code == EXIT_OK && o.csv) code = write_csv(bench_csv, &st, scene, eye_count);
    if (code == EXIT_OK && o.json) {
        char cpu[256], commit[64], date[64];
        cpu_model(cpu, sizeof cpu);
        git_commit(commit, sizeof commit);
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
        cJSON_AddStringToObject(root, "mode", o.scaling ? "scaling" : o.stereo ? "stereo" : "sweep");
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
