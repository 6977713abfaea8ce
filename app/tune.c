/* `obscura tune`: the parameters of one method that minimise its error against the ray-traced
 * AO_R on training views, checked on validation views it never saw, written as a settings file
 * that --settings loads everywhere (settings_file.h).
 *
 * The search is coordinate descent over a narrowing grid: each pass sweeps every named parameter
 * in turn over `steps` values of its current range (every option of an enum) with the others held,
 * keeps the best, and halves the range around it. Coordinate descent costs passes x parameters x
 * steps evaluations where a full grid costs steps^parameters; the repeated passes pick up what the
 * parameters do to each other. The starting point (the defaults, or --settings) is always one of
 * the candidates, so the tuned error on the training views is never above the default's. The
 * objective is the mean over training views of the MSE over geometry pixels of the filtered AO.
 *
 * --shard K/N --exchange DIR splits the views over N processes run at once, which exchange each
 * evaluation's per-view errors (tune_exchange.h) and so make the unsharded run's choices. */
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
#include "reference_cache.h"
#include "settings_file.h"
#include "graded_views.h"
#include "shard.h"
#include "tune_exchange.h"

/* 32 views a list: every check view of scenes/views.json in one --check. */
enum { MAX_VIEWS = 32, MAX_UNITS = 3 * MAX_VIEWS, MAX_TUNE = 8, MAX_CANDIDATES = 64 };

/* The run's views are its units: the training views, then the validation and the check views, in
 * the command line's order; an evaluation is the mean over one set of them. */
enum { SET_TRAIN, SET_VALIDATE, SET_CHECK, SETS };
static const char *const set_names[SETS] = {"training", "validation", "check"};

typedef struct tune_param {
    char name[64];           /* without the method's prefix; "radius_scale" for every method's */
    ob_param_type type;
    float lo, hi;            /* the search range (the registry's unless given) */
    const char *const *options;
    float value;             /* current best */
} tune_param;

typedef struct tune_view {
    char spec[256], name[200];
    ob_scene *scene;
    bool owns_scene; /* views of one scene share it: loaded once, destroyed by its first view */
    ob_camera cam;
    ob_renderer *r;
    cli_view_frame frame;
    float *ref;
    size_t pixels;           /* geometry pixels */
} tune_view;

typedef struct tune_opts {
    cli_common common;
    const char *params_text, *out;
    cli_outputs *outs; /* --out, checked before the search and written only at its end */
    int out_index;
    const char *train[MAX_VIEWS], *validate[MAX_VIEWS], *check[MAX_VIEWS];
    int train_count, validate_count, check_count;
    int passes, steps, spp;
    bool no_cache;
    const char *units[MAX_UNITS]; /* every view, as SCENE:CAMERA */
    int unit_count, first[SETS], count[SETS];
    /* --shard K/N: which shard loads and renders each view (cli_shard_assign); all 0 unsharded. */
    cli_shard shard;
    bool shard_given;
    int owner[MAX_UNITS];
    const char *exchange;
    float exchange_timeout;
    int argc;
    char **argv;                  /* the command line: the run id hashes it (tune_run_id) */
} tune_opts;

static void tune_usage(FILE *f, const cli_common *c)
{
    fputs("usage: obscura tune --method M --params LIST --train S:C[,S:C] [--validate S:C[,S:C]] [--check S:C[,S:C]]\n"
          "                   --out FILE.json [--shard K/N --exchange DIR]\n"
          "\n"
          "The values of M's parameters that minimise the mean MSE of its (filtered) AO against the\n"
          "ray-traced AO_R over the training views, by coordinate descent over a narrowing grid;\n"
          "the error on the validation views before and after; the tuned values as a settings file\n"
          "for --settings (render, view, compare, bench, sheet). References come from compare's cache.\n"
          "\n"
          "  --params LIST         M.P or M.P=LO:HI, comma-separated: numeric (float, int) or enum\n"
          "                        parameters of M, and M.radius_scale (every method's: occluder\n"
          "                        radius = scale x R); the range defaults to the registry's and must\n"
          "                        lie inside it\n"
          "  --train S:C           a training view, scene:camera (repeatable or comma-separated)\n"
          "  --validate S:C        a validation view, never a training one (repeatable or comma-separated)\n"
          "  --check S:C           a check view, reported before and after like a validation view; the\n"
          "                        project's check views (scenes/views.json, \"check\") are refused in\n"
          "                        --train: no choice is made on them (docs/methods.md, choose and check)\n"
          "  --out FILE.json       the tuned settings, written whole at the end (nothing on failure)\n"
          "  --passes N            passes over the parameters (default 3); each halves the ranges\n"
          "  --steps N             values per parameter per pass (default 9)\n"
          "  --spp N               reference rays per pixel (default 512, as compare: cache hits)\n"
          "  --no-cache            recompute the references\n"
          "  --shard K/N           shard K (0..N-1) of one run over N processes that run at once, on one\n"
          "                        machine or many: each loads and renders only its share of the views,\n"
          "                        and every evaluation's errors are exchanged through --exchange, so\n"
          "                        that each shard makes the unsharded run's choices; shard 0 writes\n"
          "                        --out (the others take it and write nothing). 0/1: the whole run\n"
          "  --exchange DIR        the folder the N shards share (one file system every machine sees);\n"
          "                        the run's records go to DIR/RUN (RUN: a hash of the command line),\n"
          "                        which must hold no earlier run's: remove it before a rerun\n"
          "  --exchange-timeout S  the longest wait for the other shards at one evaluation, the first\n"
          "                        (their loading) included: seconds (default 3600); then one line names\n"
          "                        the missing shards, exit 3. A shard that fails stops the others at once\n"
          "                        (docs/tuning.md, \"Tuning on many machines\")\n",
          f);
    cli_common_usage(f, c);
}

static int parse_int(const char *opt, const char *v, int lo, int hi, int *out)
{
    char *end = NULL;
    long n = strtol(v, &end, 10);
    if (end == v || *end || n < lo || n > hi) return cli_fail(EXIT_USAGE, "%s: expected %d..%d, got '%s'", opt, lo, hi, v);
    *out = (int)n;
    return EXIT_OK;
}

/* "a,b" after --train/--validate/--check: each element a view. */
static int add_views(const char *opt, char *v, const char **list, int *count)
{
    for (char *save = NULL, *tok = strtok_r(v, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (*count >= MAX_VIEWS) return cli_fail(EXIT_USAGE, "%s: at most %d views", opt, MAX_VIEWS);
        list[(*count)++] = tok;
    }
    return EXIT_OK;
}

/* The lists: no view twice, no check view of the project's in --train. */
static int check_lists(const tune_opts *o)
{
    for (int i = 0; i < o->validate_count; ++i)
        for (int j = 0; j < o->train_count; ++j)
            if (!strcmp(o->validate[i], o->train[j]))
                return cli_fail(EXIT_USAGE, "--validate %s is also a training view: validation must be unseen", o->validate[i]);
    for (int i = 0; i < o->check_count; ++i) {
        for (int j = 0; j < o->train_count; ++j)
            if (!strcmp(o->check[i], o->train[j]))
                return cli_fail(EXIT_USAGE, "--check %s is also a training view: check views choose nothing", o->check[i]);
        for (int j = 0; j < o->validate_count; ++j)
            if (!strcmp(o->check[i], o->validate[j]))
                return cli_fail(EXIT_USAGE, "--check %s is also a validation view: give it once", o->check[i]);
    }
    for (int i = 0; i < o->train_count; ++i)
        for (int j = 0; j < i; ++j)
            if (!strcmp(o->train[i], o->train[j])) return cli_fail(EXIT_USAGE, "--train %s is given twice", o->train[i]);
    /* The project's check views choose nothing: not even through a training set given by hand. */
    cli_view_sets sets;
    int sets_code = cli_view_sets_load(&sets, true);
    if (sets_code != EXIT_OK) return sets_code;
    for (int i = 0; i < o->train_count; ++i)
        if (cli_view_set_of(&sets, o->train[i]) && !strcmp(cli_view_set_of(&sets, o->train[i]), "check"))
            return cli_fail(EXIT_USAGE, "--train %s is a check view (%s): check views are never chosen on; give it "
                            "to --check", o->train[i], sets.path);
    return EXIT_OK;
}

/* --shard and --exchange, and the views' shards: every view costs pixels x reference rays (one size
 * and spp a run), balanced by that as compare balances its views, the same on every shard. */
static int plan_shards(tune_opts *o)
{
    if (o->shard.count > 1 && !o->exchange)
        return cli_fail(EXIT_USAGE, "--shard %d/%d: the shards exchange every evaluation's errors: give --exchange DIR, "
                        "a folder all %d see (see obscura tune --help)", o->shard.index, o->shard.count, o->shard.count);
    if (o->exchange && !o->shard_given)
        return cli_fail(EXIT_USAGE, "--exchange: without --shard K/N there is nothing to exchange");
    if (o->exchange && !*o->exchange) return cli_fail(EXIT_USAGE, "--exchange: expected a folder, got ''");
    const char *const *lists[SETS] = {o->train, o->validate, o->check};
    const int counts[SETS] = {o->train_count, o->validate_count, o->check_count};
    double cost[MAX_UNITS];
    for (int set = 0; set < SETS; ++set) {
        o->first[set] = o->unit_count;
        o->count[set] = counts[set];
        for (int i = 0; i < counts[set]; ++i) {
            cost[o->unit_count] = (double)o->common.width * (double)o->common.height * (double)o->spp;
            o->units[o->unit_count++] = lists[set][i];
        }
    }
    cli_shard_assign(cost, o->unit_count, o->shard.count, o->owner);
    return EXIT_OK;
}

static int parse(int argc, char **argv, tune_opts *o, cli_outputs *outs)
{
    *o = (tune_opts){.passes = 3, .steps = 9, .spp = 512, .outs = outs, .out_index = -1, .shard = {0, 1},
                     .exchange_timeout = 3600.0f, .argc = argc, .argv = argv};
    cli_common_init(&o->common, "tune", CLI_TAKES_GPU);
    o->common.width = 320;
    o->common.height = 240;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            tune_usage(stdout, &o->common);
            return -1;
        }
        if (!strcmp(a, "--no-cache")) {
            o->no_cache = true;
            continue;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        static const char *const own[] = {"--params", "--train", "--validate", "--check", "--out", "--passes", "--steps",
                                          "--spp", "--shard", "--exchange", "--exchange-timeout"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_unknown_option("tune", a, tune_usage, &o->common);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura tune --help)", a);
        char *v = argv[++i];
        int code = EXIT_OK;
        if (!strcmp(a, "--params")) o->params_text = v;
        else if (!strcmp(a, "--train")) code = add_views(a, v, o->train, &o->train_count);
        else if (!strcmp(a, "--validate")) code = add_views(a, v, o->validate, &o->validate_count);
        else if (!strcmp(a, "--check")) code = add_views(a, v, o->check, &o->check_count);
        else if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--passes")) code = parse_int(a, v, 1, 20, &o->passes);
        else if (!strcmp(a, "--steps")) code = parse_int(a, v, 2, MAX_CANDIDATES - 1, &o->steps);
        else if (!strcmp(a, "--shard")) code = cli_shard_parse(a, v, &o->shard), o->shard_given = true;
        else if (!strcmp(a, "--exchange")) o->exchange = v;
        else if (!strcmp(a, "--exchange-timeout")) {
            if (!cli_parse_float(v, &o->exchange_timeout) || !(o->exchange_timeout > 0.0f) || !isfinite(o->exchange_timeout))
                code = cli_fail(EXIT_USAGE, "--exchange-timeout: expected a positive number of seconds, got '%s'", v);
        } else code = parse_int(a, v, 2, 1 << 20, &o->spp);
        if (code != EXIT_OK) return code;
    }
    if (!o->common.method_count) return cli_fail(EXIT_USAGE, "--method is required (see obscura tune --help)");
    if (!o->params_text) return cli_fail(EXIT_USAGE, "--params is required (see obscura tune --help)");
    if (o->train_count == 0) return cli_fail(EXIT_USAGE, "--train: no training view (see obscura tune --help)");
    /* Shard 0 writes the settings; the others may be given the same --out (one command line for
     * every task of a Slurm step) and leave it alone. */
    if (o->shard.index == 0 && (!o->out || !*o->out))
        return cli_fail(EXIT_USAGE, "--out FILE.json is required (see obscura tune --help)");
    int code = check_lists(o);
    if (code == EXIT_OK) code = plan_shards(o);
    if (code != EXIT_OK) return code;
    o->common.renderers = 0; /* every view of this shard keeps its renderer */
    for (int u = 0; u < o->unit_count; ++u) o->common.renderers += o->owner[u] == o->shard.index;
    if ((code = cli_common_finish(&o->common)) != EXIT_OK) return code;
    if (o->shard.index != 0) return EXIT_OK;
    return cli_outputs_add(o->outs, "--out", o->out, CLI_FMT_TEXT, &o->out_index);
}

/* "M.P" or "M.P=LO:HI" -> p, checked against the method's table. */
static int parse_param(const char *method, const char *text, tune_param *p)
{
    memset(p, 0, sizeof *p);
    const char *dot = strchr(text, '.');
    const char *eq = strchr(text, '=');
    size_t mlen = dot ? (size_t)(dot - text) : 0;
    if (!dot || (eq && eq < dot) || strlen(method) != mlen || strncmp(text, method, mlen) != 0)
        return cli_fail(EXIT_USAGE, "--params %s: expected %s.PARAM or %s.PARAM=LO:HI", text, method, method);
    size_t nlen = eq ? (size_t)(eq - dot - 1) : strlen(dot + 1);
    /* Cut to fit, a long name could become a real one: refused whole instead. */
    if (nlen >= sizeof p->name)
        return cli_fail(EXIT_USAGE, "--params %.80s...: a parameter name of %zu characters; %s has none longer than %zu "
                        "(see obscura list)", text, nlen, method, sizeof p->name - 1);
    snprintf(p->name, sizeof p->name, "%.*s", (int)nlen, dot + 1);
    const ob_method_info *m = ob_method_at(ob_find_method(method));
    float min = 0.0f, max = 0.0f;
    if (!strcmp(p->name, "radius_scale")) {
        p->type = OB_PARAM_FLOAT;
        min = OB_RADIUS_SCALE_MIN;
        max = OB_RADIUS_SCALE_MAX;
    } else {
        int pi = -1;
        for (int i = 0; i < m->param_count; ++i)
            if (!strcmp(m->params[i].name, p->name)) pi = i;
        if (pi < 0) return cli_fail(EXIT_USAGE, "--params %s: %s has no parameter '%s' (see obscura list)", text, method, p->name);
        const ob_param_info *pi_info = &m->params[pi];
        if (pi_info->type != OB_PARAM_FLOAT && pi_info->type != OB_PARAM_INT && pi_info->type != OB_PARAM_ENUM)
            return cli_fail(EXIT_USAGE, "--params %s: %s.%s is on/off; tune searches numeric and enum parameters", text,
                            method, p->name);
        p->type = pi_info->type;
        p->options = pi_info->options;
        min = pi_info->min;
        max = pi_info->max;
    }
    p->lo = min;
    p->hi = max;
    if (eq) {
        if (p->type == OB_PARAM_ENUM)
            return cli_fail(EXIT_USAGE, "--params %s: %s.%s is an enum: every option is tried, no range", text, method,
                            p->name);
        char range[64];
        if (strlen(eq + 1) >= sizeof range)
            return cli_fail(EXIT_USAGE, "--params %.80s...: a range of %zu characters; expected LO:HI (at most %zu "
                            "characters)", text, strlen(eq + 1), sizeof range - 1);
        snprintf(range, sizeof range, "%s", eq + 1);
        char *colon = strchr(range, ':');
        if (!colon) return cli_fail(EXIT_USAGE, "--params %s: expected LO:HI after '='", text);
        *colon = '\0';
        if (!cli_parse_float(range, &p->lo) || !cli_parse_float(colon + 1, &p->hi) || !(p->lo < p->hi))
            return cli_fail(EXIT_USAGE, "--params %s: expected numbers LO < HI", text);
        if (p->lo < min || p->hi > max)
            return cli_fail(EXIT_USAGE, "--params %s: the range [%g, %g] leaves the registry's [%g, %g]", text,
                            (double)p->lo, (double)p->hi, (double)min, (double)max);
    }
    return EXIT_OK;
}

/* The value as ob_settings_set takes it. */
static void value_text(const tune_param *p, float v, char *out, size_t n)
{
    if (p->type == OB_PARAM_ENUM) snprintf(out, n, "%s", p->options[(int)v]);
    else if (p->type == OB_PARAM_INT) snprintf(out, n, "%d", (int)lroundf(v));
    else snprintf(out, n, "%.6g", (double)v);
}

static int settings_with(const tune_opts *o, const tune_param *ps, int count, ob_settings *s)
{
    const cli_common *c = &o->common;
    cli_config cfg = {.method = c->methods[0], .filter = c->filters[0], .ao_divisor = c->ao_divisors[0],
                      .samples = c->sample_count > 0 ? c->samples[0] : (cli_samples){0, NULL},
                      .tuned = cli_common_tuned(c, c->methods[0])};
    int code = cli_common_apply(c, &cfg);
    if (code != EXIT_OK) return code;
    *s = cfg.settings;
    const char *method = ob_method_at(c->methods[0])->name;
    for (int k = 0; k < count; ++k) {
        char v[64], a[160];
        value_text(&ps[k], ps[k].value, v, sizeof v);
        snprintf(a, sizeof a, "%s.%s=%s", method, ps[k].name, v);
        if (ob_settings_set(s, a) != OB_OK) return cli_fail_from_library();
    }
    return EXIT_OK;
}

/* MSE of the method's filtered AO against AO_R over the view's geometry pixels. */
static int view_mse(tune_view *v, const ob_settings *s, float *ao, double *mse)
{
    if (ob_render_frame(v->r, &v->cam, s) != OB_OK) return cli_fail_from_library();
    size_t px = (size_t)v->frame.width * (size_t)v->frame.height;
    if (ob_read_image(v->r, OB_IMAGE_AO_F32, ao, px * sizeof(float)) != OB_OK) return cli_fail_from_library();
    double sum = 0.0;
    for (size_t i = 0; i < px; ++i)
        if (v->frame.depth[i] > 0.0f) {
            double d = (double)ao[i] - (double)v->ref[i];
            sum += d * d;
        }
    *mse = v->pixels ? sum / (double)v->pixels : 0.0;
    return EXIT_OK;
}

/* One run, from the views' loading to the settings file. */
typedef struct tune_run {
    const tune_opts *o;
    ob_context *ctx;
    tune_view views[MAX_UNITS];   /* this shard's loaded; every view's spec */
    float radius[MAX_UNITS];      /* each view's AO radius R (another shard's from its records) */
    double before[MAX_UNITS], after[MAX_UNITS]; /* each view's RMSE at the start and tuned */
    double mean_before[SETS], mean_after[SETS];   /* each set's mean MSE */
    tune_param ps[MAX_TUNE], best[MAX_TUNE];      /* the start, and the best so far */
    int pcount;
    double best_mse;              /* the training views' mean MSE at best */
    float *ao;
    int evaluations, total;
    double start, seconds;
    ob_progress bar;
    tune_exchange x;              /* with more than one shard */
    bool sharded;
} tune_run;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One evaluation done (app/progress.h). The total counts every candidate a pass may try, and a pass
 * whose range has shrunk tries fewer: the last evaluation completes the job. */
static void progress(tune_run *t, const char *what, double best, bool last)
{
    ++t->evaluations;
    char text[200];
    snprintf(text, sizeof text, "%s, best RMSE %.4f", what, sqrt(best));
    ob_progress_advance(&t->bar, last ? t->bar.total - t->bar.done : 1, text);
}

/* Mean MSE over one set of views, and each view's RMSE into rmse (indexed by unit; may be NULL).
 * This shard renders its own views; with shards, the others' MSEs come from the exchange, and the
 * sum runs over every view in the set's order, as the unsharded run's does: the same double. */
static int mean_mse(tune_run *t, int set, const tune_param *ps, double *mean, double *rmse)
{
    const tune_opts *o = t->o;
    ob_settings s;
    int code = settings_with(o, ps, t->pcount, &s);
    if (code != EXIT_OK) return code;
    const int first = o->first[set], count = o->count[set];
    double mse[MAX_VIEWS] = {0};
    float radius[MAX_VIEWS];
    for (int i = 0; i < count; ++i) {
        radius[i] = t->radius[first + i];
        if (o->owner[first + i] == o->shard.index && (code = view_mse(&t->views[first + i], &s, t->ao, &mse[i])) != EXIT_OK)
            return code;
    }
    if (t->sharded && (code = tune_exchange_share(&t->x, set_names[set], first, count, mse, radius)) != EXIT_OK)
        return code;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        sum += mse[i];
        t->radius[first + i] = radius[i];
        if (rmse) rmse[first + i] = sqrt(mse[i]);
    }
    *mean = sum / count;
    return EXIT_OK;
}

/* The scene a view loaded earlier under the same name, or NULL. */
static ob_scene *loaded_scene(const tune_view *views, int n, const char *name)
{
    for (int i = 0; i < n; ++i)
        if (views[i].scene && !strcmp(views[i].name, name)) return views[i].scene;
    return NULL;
}

/* View u: its scene (shared with an earlier view of this shard that names the same one: each copy
 * of a scene is memory that --max-memory counted once), camera, renderer, G-buffer and reference. */
static int load_view(tune_run *t, int u, size_t *max_px)
{
    const cli_common *c = &t->o->common;
    tune_view *v = &t->views[u];
    const char *camera = NULL;
    char *colon = strrchr(v->name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    v->scene = loaded_scene(t->views, u, v->name);
    v->owns_scene = !v->scene;
    int code = v->scene ? EXIT_OK : cli_common_load_scene(c, v->name, &v->scene);
    if (code != EXIT_OK) return code;
    code = cli_common_camera(c, v->scene, camera, &v->cam);
    if (code != EXIT_OK) return code;
    v->r = ob_make_renderer(t->ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!v->r || ob_renderer_set_scene(v->r, v->scene) != OB_OK) return cli_fail_from_library();
    if ((code = cli_common_prepare(c, v->r)) != EXIT_OK) return code;
    if ((code = cli_view_frame_make(v->r, &v->cam, c->width, c->height, &v->frame)) != EXIT_OK) return code;
    size_t px = (size_t)c->width * (size_t)c->height;
    v->ref = malloc(px * sizeof(float));
    if (!v->ref) return cli_fail(EXIT_RUNTIME, "out of memory");
    t->radius[u] = ob_query_scene_ao_radius(v->scene);
    /* Before the reference is traced: a view with nothing in it has no error to tune against
     * (--allow-empty does not apply). */
    for (size_t i = 0; i < px; ++i) v->pixels += v->frame.depth[i] > 0.0f;
    if (v->pixels == 0)
        return cli_fail(c->has_eye ? EXIT_USAGE : EXIT_INPUT, "%s: nothing visible from this camera (%s:%s)", v->spec,
                        ob_query_scene_name(v->scene), v->cam.name);
    char key[900];
    cli_reference_key(c, v->name, v->cam.name, key, sizeof key);
    cli_reference_info info;
    code = cli_reference_ao(v->scene, &v->frame, key, t->radius[u], t->o->spp, t->o->no_cache, c->verbose, v->ref, &info);
    if (code != EXIT_OK) return code;
    if (px > *max_px) *max_px = px;
    return EXIT_OK;
}

/* Every view's name; this shard's views loaded, in order, and the frame buffer for the largest. */
static int load_views(tune_run *t)
{
    const tune_opts *o = t->o;
    for (int u = 0; u < o->unit_count; ++u) {
        const char *spec = o->units[u];
        if (strlen(spec) >= sizeof t->views[u].name)
            return cli_fail(EXIT_USAGE, "%.80s...: a view of %zu bytes; expected SCENE:CAMERA of at most %zu", spec,
                            strlen(spec), sizeof t->views[u].name - 1);
        snprintf(t->views[u].spec, sizeof t->views[u].spec, "%s", spec);
        snprintf(t->views[u].name, sizeof t->views[u].name, "%s", spec);
    }
    t->ctx = cli_make_context(o->common.gpu, o->common.verbose);
    if (!t->ctx) return cli_fail_library_as(EXIT_NO_GPU);
    size_t max_px = 1; /* a shard may own no view */
    for (int u = 0; u < o->unit_count; ++u) {
        if (o->owner[u] != o->shard.index) continue; /* another shard's view */
        int code = load_view(t, u, &max_px);
        if (code != EXIT_OK) return code;
    }
    t->ao = malloc(max_px * sizeof(float));
    return t->ao ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
}

/* The renderers, then the scenes (each by the view that loaded it), then the context. */
static void free_views(tune_run *t)
{
    for (int u = 0; u < MAX_UNITS; ++u) {
        cli_view_frame_free(&t->views[u].frame);
        free(t->views[u].ref);
        if (t->views[u].r) ob_destroy_renderer(t->views[u].r);
    }
    for (int u = 0; u < MAX_UNITS; ++u)
        if (t->views[u].scene && t->views[u].owns_scene) ob_destroy_scene(t->views[u].scene);
    if (t->ctx) ob_destroy_context(t->ctx);
}

/* One coordinate's candidates over [lo, hi] (every option of an enum), the current value among
 * them. */
static int candidates(const tune_param *p, int steps, float *out)
{
    int n = 0;
    if (p->type == OB_PARAM_ENUM) {
        for (int k = (int)p->lo; k <= (int)p->hi && n < MAX_CANDIDATES; ++k) out[n++] = (float)k;
        return n;
    }
    out[n++] = p->value;
    for (int k = 0; k < steps && n < MAX_CANDIDATES; ++k) {
        float v = p->lo + (p->hi - p->lo) * (float)k / (float)(steps - 1);
        if (p->type == OB_PARAM_INT) v = roundf(v);
        bool seen = false;
        for (int j = 0; j < n; ++j) seen = seen || fabsf(out[j] - v) <= 1e-6f * fmaxf(1.0f, fabsf(v));
        if (!seen) out[n++] = v;
    }
    return n;
}

/* Parameter k's candidates with the others held at their best, then its range halved around the
 * best value (inside the registry's). */
static int search_param(tune_run *t, int pass, int k)
{
    const tune_opts *o = t->o;
    tune_param *best = t->best;
    float cand[MAX_CANDIDATES];
    int n = candidates(&best[k], o->steps, cand);
    tune_param trial[MAX_TUNE];
    memcpy(trial, best, sizeof trial);
    float chosen = best[k].value;
    for (int j = 0; j < n; ++j) {
        trial[k].value = cand[j];
        double m = 0.0;
        int code = mean_mse(t, SET_TRAIN, trial, &m, NULL);
        if (code != EXIT_OK) return code;
        /* Strictly better only: on a tie the earlier candidate (the current value first) stays. */
        if (m < t->best_mse) {
            t->best_mse = m;
            chosen = cand[j];
        }
        char what[160], v[32];
        value_text(&best[k], cand[j], v, sizeof v);
        snprintf(what, sizeof what, "pass %d %.60s=%.30s", pass + 1, best[k].name, v);
        progress(t, what, t->best_mse, false);
    }
    best[k].value = chosen;
    if (best[k].type != OB_PARAM_ENUM) {
        float half = 0.25f * (best[k].hi - best[k].lo);
        best[k].lo = fmaxf(t->ps[k].lo, chosen - half);
        best[k].hi = fminf(t->ps[k].hi, chosen + half);
    }
    return EXIT_OK;
}

/* Every evaluation, in the one order every shard makes them: the start on each set, the search
 * (per pass and parameter its candidates: at most steps + 1, or the enum's options), then the
 * result on each set. */
static int search(tune_run *t)
{
    const tune_opts *o = t->o;
    t->total = o->check_count ? 4 : 2;
    for (int pass = 0; pass < o->passes; ++pass)
        for (int k = 0; k < t->pcount; ++k)
            t->total += t->ps[k].type == OB_PARAM_ENUM ? (int)(t->ps[k].hi - t->ps[k].lo) + 1 : o->steps + 1;
    t->start = now_s();
    ob_progress_begin(&t->bar, "tune", t->total);
    int code = mean_mse(t, SET_TRAIN, t->ps, &t->best_mse, t->before);
    if (code != EXIT_OK) return code;
    progress(t, "defaults, training views", t->best_mse, false);
    if (o->validate_count && (code = mean_mse(t, SET_VALIDATE, t->ps, &t->mean_before[SET_VALIDATE], t->before)) != EXIT_OK)
        return code;
    progress(t, "defaults, validation views", t->best_mse, false);
    if (o->check_count) {
        if ((code = mean_mse(t, SET_CHECK, t->ps, &t->mean_before[SET_CHECK], t->before)) != EXIT_OK) return code;
        progress(t, "defaults, check views", t->best_mse, false);
    }
    memcpy(t->best, t->ps, sizeof t->best);
    for (int pass = 0; pass < o->passes; ++pass)
        for (int k = 0; k < t->pcount; ++k)
            if ((code = search_param(t, pass, k)) != EXIT_OK) return code;
    if ((code = mean_mse(t, SET_TRAIN, t->best, &t->mean_after[SET_TRAIN], t->after)) != EXIT_OK) return code;
    if (o->validate_count && (code = mean_mse(t, SET_VALIDATE, t->best, &t->mean_after[SET_VALIDATE], t->after)) != EXIT_OK)
        return code;
    if (o->check_count) {
        progress(t, "tuned, validation views", t->best_mse, false);
        if ((code = mean_mse(t, SET_CHECK, t->best, &t->mean_after[SET_CHECK], t->after)) != EXIT_OK) return code;
        progress(t, "tuned, check views", t->best_mse, true);
    } else {
        progress(t, "tuned, validation views", t->best_mse, true);
    }
    ob_progress_end(&t->bar);
    t->seconds = now_s() - t->start;
    return EXIT_OK;
}

static double mean_of(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += v[i];
    return n ? s / n : 0.0;
}

/* The table on stdout: the values, then each view's RMSE and each set's mean. */
static void print_table(const tune_run *t, const char *method)
{
    const tune_opts *o = t->o;
    printf("\n%s tuned over %d training view(s), %d evaluations in %.0f s:\n", method, o->train_count, t->evaluations,
           t->seconds);
    for (int k = 0; k < t->pcount; ++k) {
        char a[32], b[32];
        value_text(&t->ps[k], t->ps[k].value, a, sizeof a);
        value_text(&t->best[k], t->best[k].value, b, sizeof b);
        printf("  %-16s %s -> %s\n", t->ps[k].name, a, b);
    }
    printf("\n  %-40s %-10s %10s %10s\n", "view", "role", "default", "tuned");
    for (int u = 0; u < o->unit_count; ++u) {
        const char *role = u < o->first[SET_VALIDATE] ? "training" : u < o->first[SET_CHECK] ? "validation" : "check";
        printf("  %-40s %-10s %10.4f %10.4f\n", t->views[u].spec, role, t->before[u], t->after[u]);
    }
    for (int set = 0; set < SETS; ++set)
        if (set == SET_TRAIN || o->count[set])
            printf("  %-40s %-10s %10.4f %10.4f\n", "mean RMSE", set_names[set], mean_of(t->before + o->first[set], o->count[set]),
                   mean_of(t->after + o->first[set], o->count[set]));
}

static cJSON *views_json(const tune_run *t, int set)
{
    cJSON *arr = cJSON_CreateArray();
    for (int u = t->o->first[set]; u < t->o->first[set] + t->o->count[set]; ++u) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "view", t->views[u].spec);
        cJSON_AddNumberToObject(e, "radius", t->radius[u]);
        cJSON_AddNumberToObject(e, "rmse_default", t->before[u]);
        cJSON_AddNumberToObject(e, "rmse_tuned", t->after[u]);
        cJSON_AddItemToArray(arr, e);
    }
    return arr;
}

/* SET_rmse_default and SET_rmse_tuned: the set's mean RMSE (none for an empty set but training). */
static void add_means(cJSON *how, const tune_run *t, int set)
{
    const int first = t->o->first[set], count = t->o->count[set];
    if (set != SET_TRAIN && !count) return;
    char key[64];
    snprintf(key, sizeof key, "%s_rmse_default", set_names[set]);
    cJSON_AddNumberToObject(how, key, mean_of(t->before + first, count));
    snprintf(key, sizeof key, "%s_rmse_tuned", set_names[set]);
    cJSON_AddNumberToObject(how, key, mean_of(t->after + first, count));
}

/* The settings file: {"method", "params", "tuned": how it was found and each view's RMSE}. */
static cJSON *settings_json(const tune_run *t, const char *method)
{
    const tune_opts *o = t->o;
    const tune_param *best = t->best;
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "method", method);
    cJSON *params = cJSON_AddObjectToObject(root, "params");
    for (int k = 0; k < t->pcount; ++k) {
        if (best[k].type == OB_PARAM_ENUM) cJSON_AddStringToObject(params, best[k].name, best[k].options[(int)best[k].value]);
        else if (best[k].type == OB_PARAM_INT) cJSON_AddNumberToObject(params, best[k].name, lroundf(best[k].value));
        else {
            char v[32];
            value_text(&best[k], best[k].value, v, sizeof v);
            cJSON_AddNumberToObject(params, best[k].name, atof(v));
        }
    }
    cJSON *how = cJSON_AddObjectToObject(root, "tuned");
    cJSON_AddStringToObject(how, "objective", "mean MSE of the filtered AO against AO_R over the training views");
    cJSON_AddStringToObject(how, "filter", ob_filter_at(o->common.filters[0])->name);
    char size[32];
    snprintf(size, sizeof size, "%dx%d", o->common.width, o->common.height);
    cJSON_AddStringToObject(how, "size", size);
    cJSON_AddNumberToObject(how, "spp", o->spp);
    cJSON_AddNumberToObject(how, "passes", o->passes);
    cJSON_AddNumberToObject(how, "steps", o->steps);
    cJSON_AddNumberToObject(how, "evaluations", t->evaluations);
    cJSON_AddNumberToObject(how, "seconds", t->seconds);
    cJSON_AddItemToObject(how, "training", views_json(t, SET_TRAIN));
    cJSON_AddItemToObject(how, "validation", views_json(t, SET_VALIDATE));
    add_means(how, t, SET_TRAIN);
    add_means(how, t, SET_VALIDATE);
    cJSON_AddItemToObject(how, "check", views_json(t, SET_CHECK));
    add_means(how, t, SET_CHECK);
    /* Which shard ran each view (as compare's results.json records it); the numbers are the
     * unsharded run's. */
    if (t->sharded) cli_shard_json(how, &o->shard, o->units, o->owner, o->unit_count);
    return root;
}

/* The file's text, with a final newline, malloc'd; NULL when out of memory. */
static char *settings_text(const tune_run *t, const char *method)
{
    cJSON *root = settings_json(t, method);
    char *json = cJSON_Print(root);
    cJSON_Delete(root);
    if (!json) return NULL;
    size_t jl = strlen(json);
    char *withnl = realloc(json, jl + 2);
    if (withnl) {
        json = withnl;
        json[jl] = '\n';
        json[jl + 1] = '\0';
    }
    return json;
}

static int tune_checked(const tune_opts *op);

int cmd_tune(int argc, char **argv)
{
    tune_opts o;
    cli_outputs outs = {0};
    int code = parse(argc, argv, &o, &outs);
    if (code == EXIT_OK) code = tune_checked(&o);
    code = cli_outputs_finish(&outs, code < 0 ? EXIT_OK : code);
    if (code == EXIT_OK && o.shard.index == 0 && o.out) printf("\nwrote %s\n", o.out);
    else if (code == EXIT_OK && o.shard.index > 0)
        printf("\nshard %d/%d done: shard 0 writes the settings\n", o.shard.index, o.shard.count);
    return code;
}

/* --params into t->ps, each at its starting value: the settings as the options give them (defaults,
 * --settings, --set), clamped into the searched range. */
static int start_params(tune_run *t)
{
    const tune_opts *o = t->o;
    const char *method = ob_method_at(o->common.methods[0])->name;
    char list[1024];
    snprintf(list, sizeof list, "%s", o->params_text);
    int code = EXIT_OK;
    for (char *save = NULL, *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (t->pcount >= MAX_TUNE) return cli_fail(EXIT_USAGE, "--params: at most %d parameters", MAX_TUNE);
        if ((code = parse_param(method, tok, &t->ps[t->pcount])) != EXIT_OK) return code;
        for (int j = 0; j < t->pcount; ++j)
            if (!strcmp(t->ps[j].name, t->ps[t->pcount].name))
                return cli_fail(EXIT_USAGE, "--params: %s.%s twice", method, t->ps[j].name);
        ++t->pcount;
    }
    if (t->pcount == 0) return cli_fail(EXIT_USAGE, "--params: no parameter");
    ob_settings start;
    if ((code = settings_with(o, t->ps, 0, &start)) != EXIT_OK) return code;
    for (int k = 0; k < t->pcount; ++k) {
        tune_param *p = &t->ps[k];
        p->value = ob_settings_get(&start, p->name);
        if (p->type != OB_PARAM_ENUM && (p->value < p->lo || p->value > p->hi))
            p->value = fminf(fmaxf(p->value, p->lo), p->hi); /* the start clamped into the range */
    }
    return EXIT_OK;
}

/* With shards: the exchange folder opened (before anything slow, so an earlier run's records are
 * refused at once), and one line saying which views this shard loads. */
static int open_exchange(tune_run *t)
{
    const tune_opts *o = t->o;
    if (o->shard.count < 2) return EXIT_OK;
    char run[TUNE_RUN_ID_LEN + 1];
    tune_run_id(o->argc, o->argv, run);
    t->sharded = true;
    int code = tune_exchange_open(&t->x, o->exchange, &o->shard, run, o->owner, o->unit_count, o->exchange_timeout);
    if (code != EXIT_OK) return code;
    int mine = 0;
    for (int u = 0; u < o->unit_count; ++u) mine += o->owner[u] == o->shard.index;
    printf("tune: shard %d/%d loads %d of %d views", o->shard.index, o->shard.count, mine, o->unit_count);
    for (int u = 0, n = 0; u < o->unit_count; ++u)
        if (o->owner[u] == o->shard.index) printf("%s%s", n++ ? ", " : " (", o->units[u]);
    printf("%s; records in %s\n", mine ? ")" : "", t->x.dir);
    fflush(stdout);
    return EXIT_OK;
}

static int tune_checked(const tune_opts *op)
{
    tune_run *t = calloc(1, sizeof *t);
    if (!t) return cli_fail(EXIT_RUNTIME, "out of memory");
    t->o = op;
    const char *method = ob_method_at(op->common.methods[0])->name;
    char *json = NULL;
    int code = start_params(t);
    if (code == EXIT_OK) code = open_exchange(t);
    if (code == EXIT_OK) code = load_views(t);
    if (code == EXIT_OK) code = search(t);
    if (code == EXIT_OK) print_table(t, method);
    if (code == EXIT_OK && op->shard.index == 0) {
        json = settings_text(t, method);
        /* Committed by cmd_tune, which prints "wrote" only then. */
        code = json ? cli_outputs_write_text(op->outs, op->out_index, json) : cli_fail(EXIT_RUNTIME, "out of memory");
    }
    /* The other shards stop at their next wait, naming this one and why. */
    if (code != EXIT_OK && t->sharded) tune_exchange_fail(&t->x, cli_last_failure());
    tune_exchange_close(&t->x);
    ob_progress_end(&t->bar);
    free(json);
    free(t->ao);
    free_views(t);
    free(t);
    return code;
}
