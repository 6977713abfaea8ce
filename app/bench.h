/* obscura bench in three files: bench.c parses the options and runs the sweep, the stereo run and
 * the scaling study; bench_host.c runs --host (the host path beside the frame's AO chain);
 * bench_report.c prints the tables and writes the CSV and the JSON. This header is what they
 * share: the options, the measured rows and the helpers both runners use. */
#ifndef OB_APP_BENCH_H
#define OB_APP_BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cli_options.h"
#include "outputs.h"
#include "progress.h"

enum { MAX_PASSES = 20, MAX_LIST = CLI_MAX_LIST, MAX_CAMS = 32, MAX_SIZES = 16 };

#define VR_BUDGET_MS (1000.0 / 90.0) /* stereo: one frame of both eyes at 90 Hz */

/* What `obscura bench` with no options measures: every method once against none, on the first
 * camera preset, at N = 24 (Belonogov 2018's "medium") and r = 4 (the scene's suggested radius), 20
 * frames after 3, with the shadow maps rendered once (the scene and lights are static, as in the
 * viewer). On the 2-core llvmpipe machine an 800x600 Cornell frame took 0.5-0.9 s, 0.26 s of it
 * the point light's 2048^2 cube map: the old default, Belonogov 2018's table (both of Cornell's
 * identical presets x 4 N x 3 r x 10 methods x 55 frames, maps every frame), runs for hours
 * there; the quick run is 10 configurations of 23 frames. --full is the table. */
enum { QUICK_SAMPLES = 24, QUICK_FRAMES = 20, QUICK_WARMUP = 3, FULL_FRAMES = 50, FULL_WARMUP = 5 };

typedef struct bench_opts {
    cli_common common;            /* scene, methods, filters, AO scales, lighting, ... */
    const char *json, *csv, *cameras;
    int samples[CLI_MAX_LIST], sample_count; /* the sweep's N: --samples or --quality */
    float radii[MAX_LIST];
    int radius_count;
    int frames, warmup;
    bool stereo, scaling;
    bool floor;                   /* --floor: time the bare N-tap kernel beside each AO pass */
    bool full;                    /* --full: Belonogov 2018's whole table (see QUICK_* above) */
    bool host;                    /* --host: the host path (ob_host_ao) beside the frame's AO chain */
    bool samples_given;           /* --samples or --quality was given (--host-rmse: else each method's own) */
    const char *host_views;       /* --host-rmse SCENE[:CAMERA],...: the rebuilt normals' accuracy */
    bool keep_shadows;            /* render the shadow maps once, not every frame (the quick run) */
    float ipd;
    int sizes[MAX_SIZES][2], size_count;
    int argc;                     /* the command line as given: --json records it */
    char **argv;
    /* --path / --orbit: every frame of a measurement takes the next camera along it (warm-up frames
     * included, wrapping after --path-frames), so the timings include the history's reprojection
     * under motion; the scene, set once it is loaded (NULL: a still camera). */
    const ob_scene *moving_scene;
} bench_opts;

/* One measured configuration: per pass and whole-frame statistics (stereo: both eyes summed).
 * Every time is GPU time from GL timestamps around each pass (ob_query_timings); the frame's is the
 * sum of its timed passes, not the wall-clock time of the frame. */
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

/* What a run measures: the combinations of the lists, the none frames (one per filter and AO
 * scale, each the baseline of its combinations), and whether each combination's method takes the
 * sweep's N and r. */
typedef struct bench_plan {
    cli_config *configs, *bases;
    int count, base_count;
    bool *has_samples, *has_radius;
} bench_plan;

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
#define HOST_TARGET 1.05 /* issue 45: the host path at most 1.05x the frame's chain */

/* Each path's name and what it hands ob_host_ao (bench_host.c). */
extern const char *const host_path_names[HOST_PATHS], *const host_path_depth[HOST_PATHS],
    *const host_path_normals[HOST_PATHS], *const host_path_output[HOST_PATHS];
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

/* ---- bench.c: what both runners use ---- */
double bench_now_s(void);
/* The median, min and max of v[0 .. n) (sorts v). */
void bench_stats(double *v, int n, double *med, double *lo, double *hi);
/* One more zeroed element of a growing array (*items, *count of *cap, `size` bytes each): its
 * address, or NULL when memory ran out (nothing changed then). */
void *bench_grow(void **items, int *count, int *cap, size_t size);
/* The settings of one configuration: its combination's, then the sweep's N and r (samples 0 /
 * radius_world 0 leave the method's own). */
int bench_configure(const cli_config *cfg, int samples, float radius_world, ob_settings *s);
/* One configuration measured: the bar moves on. */
void bench_progress(bench_state *st, const char *what);

/* ---- bench_host.c ---- */
/* --host-rmse's list checked for shape while parsing. */
int bench_host_views_check(const char *v);
/* --host-rmse: every view graded, before anything is timed. */
int bench_host_rmse(const bench_opts *o, ob_context *ctx, const bench_plan *p, host_state *hst);
/* --host: per camera and configuration, the four paths timed. */
int bench_host_run(const bench_opts *o, ob_context *ctx, const ob_scene *scene, const int *cams, int cam_count,
                   const bench_plan *p, bench_state *st, host_state *hst);

/* ---- bench_report.c ---- */
void bench_print_tables(const bench_opts *o, const ob_scene *scene, const bench_state *st, const int *cams, int cam_count,
                        const cli_config *configs, int config_count);
void bench_print_scaling(const bench_opts *o, const ob_scene *scene, const ob_camera *cam, const bench_state *st,
                         const cli_config *configs, int count);
void bench_print_host_tables(const bench_opts *o, const ob_scene *scene, const host_state *hst, const int *cams,
                             int cam_count);
/* After a quick run: how to run Belonogov 2018's whole table (full_configs configurations), and what
 * it would cost at this run's pace. */
void bench_print_full_hint(const bench_opts *o, int measured, int full_configs, double seconds);
/* --csv and --json into outs' output index (outputs.h). */
int bench_write_csv(cli_outputs *outs, int index, const bench_state *st, const ob_scene *scene, int eyes);
int bench_write_host_csv(cli_outputs *outs, int index, const host_state *hst, const ob_scene *scene);
int bench_write_json(cli_outputs *outs, int index, const bench_opts *o, ob_context *ctx, const ob_scene *scene,
                     const bench_state *st, const host_state *hst, const bench_plan *p, double seconds);

#endif
