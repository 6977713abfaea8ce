/* The options the rendering commands share: render, sheet, compare and bench (and the viewer
 * the viewer). One parser, one usage block, and one place that turns the options into
 * ob_settings and a camera, so that every command takes every option that applies to it and
 * spells, checks and applies it the same way.
 *
 *   cli_common c;
 *   cli_common_init(&c, "compare", CLI_TAKES_CAMERA | CLI_TAKES_LISTS);
 *   c.width = 320; ...                                 the command's own defaults
 *   for (int i = 1; i < argc; ++i) {
 *       int r = cli_common_option(&c, argc, argv, &i); CLI_TAKEN, CLI_NOT_MINE or an exit code
 *       ...                                            the command's own options
 *   }
 *   cli_common_finish(&c);                             defaults of the lists, cross-checks
 *   cli_common_configs(&c, &configs, &count);          every combination, as checked ob_settings
 *
 * Commands that take lists (CLI_TAKES_LISTS) run every combination of --methods x --filters x
 * --ao-scales x --quality (or --samples) as its own row, labelled with the settings that vary.
 * Everything is checked before a command writes anything: a bad value is one line naming the
 * option and the value, exit code EXIT_USAGE. */
#ifndef OB_CLI_OPTIONS_H
#define OB_CLI_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

#include "cli.h"
#include "settings_file.h"

enum {
    CLI_MAX_LIST = 32,      /* elements of one comma list (the method registry has fewer) */
    CLI_MAX_SETS = 64,      /* --set assignments */
    CLI_MAX_CONFIGS = 256,  /* combinations of the lists: beyond this a run takes hours on llvmpipe */
    CLI_MAX_LABEL = 160,
    CLI_PATH_FRAMES = 32,   /* --path-frames when not given */
    CLI_MAX_PATH_FRAMES = 10000,
};

/* What a command takes beyond the options every rendering command has. */
enum {
    CLI_TAKES_SCENE = 1u << 0,  /* --scene, one (compare has its own repeatable S[:CAMERA]) */
    CLI_TAKES_CAMERA = 1u << 1, /* --camera, --eye, --target, --fov */
    CLI_TAKES_LISTS = 1u << 2,  /* --methods, --filters, --ao-scales, and --quality/--samples as lists */
    CLI_TAKES_GPU = 1u << 3,    /* --gpu and -v: the command makes its own headless context (not view) */
    CLI_TAKES_PATH = 1u << 4,   /* --path NAME | --orbit DEG, --path-frames N (issue 17) */
};

/* cli_common_option's answers besides an exit code (which is never 0: EXIT_OK means nothing to
 * report, and a parser that fails always has something to report). */
enum { CLI_TAKEN = 0, CLI_NOT_MINE = -1 };

/* Which of the optional settings were given (the library's defaults stay otherwise). */
enum {
    CLI_GIVEN_SHADOW = 1u << 0,
    CLI_GIVEN_SHADOW_SIZE = 1u << 1,
    CLI_GIVEN_SHADOW_BIAS = 1u << 2,
    CLI_GIVEN_SLOPE_BIAS = 1u << 3,
    CLI_GIVEN_PCF_RADIUS = 1u << 4,
    CLI_GIVEN_VSM_BLUR = 1u << 5,
    CLI_GIVEN_VSM_BLEED = 1u << 6,
    CLI_GIVEN_EXPOSURE = 1u << 7,
    CLI_GIVEN_KEY = 1u << 8,
    CLI_GIVEN_WHITE = 1u << 9,
    CLI_GIVEN_BLOOM = 1u << 10,
    CLI_GIVEN_BLOOM_THRESHOLD = 1u << 11,
    CLI_GIVEN_AMBIENT_COLOR = 1u << 12,
    CLI_GIVEN_VSM_BITS = 1u << 13,
};

/* A sample count per pixel and the --quality preset that named it (NULL for --samples N). */
typedef struct cli_samples {
    int count;
    const char *quality;
} cli_samples;

typedef struct cli_common {
    const char *command;        /* "render": names the command in "see obscura render --help" */
    unsigned takes;             /* CLI_TAKES_* */
    const char *default_method; /* without --method(s): this method; NULL = every method */

    /* scene and camera */
    const char *scene, *sidecar;
    ob_up_axis up;
    bool allow_external_files; /* --allow-external-files */
    uint64_t max_memory;       /* --max-memory, bytes; 0 = the library's default */
    const char *max_memory_text; /* --max-memory as given, for messages (NULL: the default) */
    /* cli_common_finish: what the run takes besides the scene (render targets, shadow maps, the
     * command's image buffers, path frames kept), checked against --max-memory there and handed
     * to the import (ob_scene_desc.reserved_memory, reserved_what) with its largest items. */
    uint64_t run_memory;
    char run_memory_what[400];
    /* Set by the command before cli_common_finish, for that estimate: the renderers it holds at
     * once (stereo: 2, tune: one per view; 0 = 1), and the largest renderer's size when it is not
     * --size's (bench --scaling's largest --sizes; 0 = --size). */
    int renderers;
    int memory_width, memory_height;
    const char *camera;
    bool has_eye, has_target, has_fov;
    float eye[3], target[3], fov;
    int width, height;
    bool has_size;

    /* The lists: one element each for a command without CLI_TAKES_LISTS; cli_common_finish fills
     * in the defaults (default_method, geometry, 1, each method's own count). */
    int methods[CLI_MAX_LIST], method_count;  /* method registry indices */
    int filters[CLI_MAX_LIST], filter_count;  /* filter registry indices */
    int ao_divisors[3], ao_count;             /* 1, 2 or 4 (--ao-scale 1, 0.5, 0.25) */
    cli_samples samples[CLI_MAX_LIST];
    int sample_count;                         /* 0 = each method's own count */
    cli_samples by_quality[CLI_MAX_LIST], by_number[CLI_MAX_LIST];
    int by_quality_count, by_number_count;    /* --quality and --samples before finish */

    const char *sets[CLI_MAX_SETS];           /* --set, in order */
    int set_count;
    /* --settings FILE|DIR: tuned parameters per method (obscura tune). Commands with lists run each
     * tuned method twice, at its defaults and tuned; the others run it tuned. --set still wins. */
    const char *settings_path;
    cli_tuned tuned[CLI_MAX_TUNED_FILES];
    int tuned_count;
    bool adaptive;
    /* --guard PX or F%: the guard band per side (ob_settings.guard), in pixels or as a percentage of
     * the larger image dimension, resolved against --size by cli_common_finish into guard_px. */
    int guard_px;
    float guard_percent;
    bool guard_is_percent;
    /* --temporal on|off, --temporal-at before|after, --temporal-frames N, --temporal-detail A
     * (ob_settings.temporal*) */
    bool temporal;
    int temporal_at;
    int temporal_frames;
    float temporal_detail;
    /* --jitter J|on|off (ob_settings.jitter): -1 when not given (render and bench: off; compare's
     * path rows: OB_JITTER_POSITIONS_DEFAULT, cli_common_path_jitter) */
    int jitter;
    /* --upsample auto|plain|block (ob_settings.upsample) */
    int upsample;
    /* --path NAME (a sidecar path) or --orbit DEG (about the camera's target), over --path-frames
     * frames (default CLI_PATH_FRAMES) */
    const char *path;
    float orbit_deg;
    bool has_orbit;
    int path_frames;

    /* lighting, shadows, tone mapping */
    const char *lights[OB_MAX_LIGHTS];
    int light_count;
    const char *env;
    ob_ambient_mode ambient_mode;
    float ambient_color[3];
    bool ao_all_light, hdr_off, multibounce, textures_off;
    ob_shadow_method shadow;
    int shadow_size, pcf_radius, vsm_bits;
    float shadow_bias, slope_bias, vsm_blur, vsm_bleed, exposure, key, white, bloom, bloom_threshold;
    unsigned given;                           /* CLI_GIVEN_* */

    ob_gpu_kind gpu;
    bool verbose;
    bool allow_empty;                         /* --allow-empty: write a frame that covers no pixel */
} cli_common;

/* One combination of the lists, with its settings. */
typedef struct cli_config {
    int method, filter;         /* registry indices */
    int ao_divisor;             /* 1, 2 or 4 */
    cli_samples samples;        /* count 0: the method's own (it takes none, or none was asked for) */
    const cli_tuned *tuned;     /* --settings for this method, applied; NULL = its defaults */
    ob_settings settings;
    char label[CLI_MAX_LABEL];  /* "hbao · filter none · ao 0.5": the method, then each list that has
                                   more than one element, so a run with single values shows the method */
    char stem[CLI_MAX_LABEL];   /* the same as a file name: "hbao_filter-none_ao-0_5" */
} cli_config;

/* Zero values, no lists, scene "cornell" not set (each command sets its own defaults after). */
void cli_common_init(cli_common *c, const char *command, unsigned takes);
/* argv[*i] is a common option: take it (and its value, moving *i) -> CLI_TAKEN; not a common
 * option (or not one this command takes) -> CLI_NOT_MINE; a bad or missing value -> one line
 * on stderr and its exit code. */
int cli_common_option(cli_common *c, int argc, char **argv, int *i);
/* After the last option: the lists' defaults, and the checks that need every option
 * (--eye with --target, --camera against --eye, --ambient env with --env, --quality against
 * --samples for lists), last the memory the options make the run take (--size, --guard,
 * --ao-scale, --temporal, the methods' targets, --shadow-size, --path-frames) against
 * --max-memory, before anything is allocated. 0, or the exit code of the one line printed. */
int cli_common_finish(cli_common *c);
/* The usage lines of the common options this command takes, with its defaults from c (as set up
 * for parsing). */
void cli_common_usage(FILE *f, const cli_common *c);

/* Every combination of the lists, each as checked settings (methods outermost, then filters, AO
 * scales and sample counts; a method that takes no sample count runs once), in *configs
 * (malloc'd, free it). Also checks each --set against the combinations: one that names a method
 * or filter in none of them is an error. 0 or an exit code (nothing allocated then). */
int cli_common_configs(const cli_common *c, cli_config **configs, int *count);
/* The settings of one combination (method, filter, ao_divisor and samples filled in) into
 * cfg->settings, with its label and stem. 0 or an exit code. */
int cli_common_apply(const cli_common *c, cli_config *cfg);
/* The --settings entry for a method, or NULL. */
const cli_tuned *cli_common_tuned(const cli_common *c, int method);
/* cfg's label with another separator (the sheet's font has only ASCII: ", "). */
void cli_config_label(const cli_common *c, const cli_config *cfg, const char *sep, char *out, size_t n);

/* The scene named `name` (c->scene when NULL) with --sidecar, --up and --max-memory (less what
 * the rest of the run takes: c->run_memory) into *out; then, without --light, the shadow maps of
 * the scene's own lights beyond the key light (which the run's estimate counted) against
 * --max-memory too. 0, or the exit code of the one line printed (*out NULL). */
int cli_common_load_scene(const cli_common *c, const char *name, ob_scene **out);
/* The camera: --eye/--target/--fov, else the preset `preset` (c->camera when NULL, else
 * "default") with --fov. 0 or an exit code. */
int cli_common_camera(const cli_common *c, const ob_scene *scene, const char *preset, ob_camera *cam);
/* --path or --orbit given. */
bool cli_common_moves(const cli_common *c);
/* The jitter positions of compare's path rows (flicker.h): --jitter, else OB_JITTER_POSITIONS_DEFAULT. */
int cli_common_path_jitter(const cli_common *c);

/* --temporal-at's name ("before" or "after") and --temporal-frames with the default filled in. */
const char *cli_common_temporal_at(const cli_common *c);
int cli_common_temporal_frames(const cli_common *c);
struct cJSON;
/* The accumulation's settings (--temporal-at, --temporal-frames, --temporal-detail) as
 * root.temporal_settings: what a results.json's "temporal on" numbers were made with. */
void cli_common_temporal_json(const cli_common *c, struct cJSON *root);
/* The camera of frame f (0..path_frames-1) along --path (at f / (frames - 1) of its time span) or
 * --orbit (base turned by DEG x f / (frames - 1) about its target). 0 or an exit code (an unknown
 * path: one line naming the scene's paths). */
int cli_common_path_camera(const cli_common *c, const ob_scene *scene, const ob_camera *base, int f, ob_camera *out);
/* What a new renderer needs from the options (--env). 0 or an exit code. */
int cli_common_prepare(const cli_common *c, ob_renderer *r);

#endif
