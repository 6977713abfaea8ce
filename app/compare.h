/* obscura compare in three files: compare.c runs the views (the reference, every row's frames,
 * metrics and images), compare_report.c writes what they found (results.json and index.html) and
 * compare_chart.c draws each view's error-against-time chart. This header is what they share: the
 * options, one row's and one view's results, and the list of files the report has written. */
#ifndef OB_APP_COMPARE_H
#define OB_APP_COMPARE_H

#include <stdbool.h>
#include <stddef.h>

#include "cli_options.h"
#include "flicker.h"
#include "outputs.h"
#include "progress.h"
#include "shard.h"

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
    /* The GL renderer the rows ran on, for the report's head (a merge takes its shards'). */
    char renderer[256], gl_version[256];
    /* --shard K/N: only the views owner[] gives this shard (shard.h); {0, 1} runs every view. */
    cli_shard shard;
    int owner[MAX_VIEWS];
    /* --shard-unit row: each row of each view is a unit of its own, row_owner[v * row_count + k]
     * (compare_assign_rows), and a shard runs the views it has a row of, with their references
     * from the shared cache (traced there first by --references-only). */
    bool by_row;
    int *row_owner, row_count;
    /* --references-only: trace (or find) each view's AO_R into the reference cache, and stop. */
    bool references_only;
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
    double ao_ms, frame_ms;       /* GPU ms, medians over FRAMES frames: the AO pass, and the sum of
                                     every timed pass of the frame (not wall-clock time) */
    double chain_ms;              /* what the AO costs the frame: the AO pass, its depth MIPs, edges, filter and
                                     upsampling (medians of the per-frame sums) */
    bool pareto;                  /* no other row of the view is both as fast and more accurate */
} method_result;

typedef struct view_result {
    int index;                          /* its --scene's position in the run */
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

/* What this run wrote into the report's temporary directory, emptied again when a later step
 * fails. The temporary directory itself (cli_outputs_dir) is what keeps a failed run from touching
 * --report; this list only keeps the tree small for cli_outputs_abort to remove. */
typedef struct report_files {
    char **files, **dirs;
    int file_count, file_cap, dir_count, dir_cap;
} report_files;

/* A file of the report, written (or about to be: a failure in between still removes it). False
 * when memory ran out. */
bool compare_track_file(report_files *out, const char *path);

/* compare.c: the parser (a merge re-reads its shards' command line with it), the views' sets
 * (choose/check, scenes/views.json), and the report's directories (made and tracked) and files
 * (removed again when the run fails). */
int compare_parse(int argc, char **argv, compare_opts *o, cli_outputs *outs);
/* o->owner for the run split over `shards` (compare_parse does it for --shard). */
void compare_assign_shards(compare_opts *o, int shards);
/* With --shard-unit row: o->row_owner over the count rows of every view, split over `shards`
 * (o->shard.count when it runs, the shards' N when merging). EXIT_OK or an exit code. */
int compare_assign_rows(compare_opts *o, const cli_config *configs, int count, int shards);
/* The shard that runs row k of view v (after compare_assign_shards, and compare_assign_rows with
 * --shard-unit row). Does this shard run view v (a row of it), and row k of it? */
int compare_row_owner(const compare_opts *o, int v, int k);
bool compare_view_is_mine(const compare_opts *o, int v);
bool compare_row_is_mine(const compare_opts *o, int v, int k);
int compare_label_sets(view_result *views, int count);
int compare_make_dir(report_files *out, const char *path);
void compare_files_finish(report_files *out, bool failed);

/* compare_merge.c: a shard's REPORT/shard.bin (every view it ran, for obscura merge). */
int compare_write_shard(const compare_opts *o, const cli_config *configs, const view_result *views, int count,
                        report_files *out);

/* compare_report.c */
/* Marks the rows on the view's error/time Pareto front (method_result.pareto). */
void compare_mark_pareto(view_result *vr);
/* REPORT/results.json and REPORT/index.html for the count views done: EXIT_OK or an exit code
 * after one line on stderr. */
int compare_write_json(const compare_opts *o, const view_result *views, int count, report_files *out);
int compare_write_html(const compare_opts *o, const view_result *views, int count, report_files *out);

/* compare_chart.c: REPORT/VIEW/chart.svg, drawn by gnuplot. */
int compare_write_chart(const compare_opts *o, const view_result *vr, report_files *out);

#endif
