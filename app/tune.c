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
 * objective is the mean over training views of the MSE over geometry pixels of the filtered AO. */
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

enum { MAX_VIEWS = 32, MAX_TUNE = 8, MAX_CANDIDATES = 64 }; /* 32 views a list: every check view of scenes/views.json in one --check */

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
    float radius;
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
} tune_opts;

static void tune_usage(FILE *f, const cli_common *c)
{
    fputs("usage: obscura tune --method M --params LIST --train S:C[,S:C] [--validate S:C[,S:C]] [--check S:C[,S:C]]\n"
          "                   --out FILE.json\n"
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
          "  --no-cache            recompute the references\n",
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

static int parse(int argc, char **argv, tune_opts *o, cli_outputs *outs)
{
    *o = (tune_opts){.passes = 3, .steps = 9, .spp = 512, .outs = outs, .out_index = -1};
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
                                          "--spp"};
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
        else code = parse_int(a, v, 2, 1 << 20, &o->spp);
        if (code != EXIT_OK) return code;
    }
    if (!o->common.method_count) return cli_fail(EXIT_USAGE, "--method is required (see obscura tune --help)");
    if (!o->params_text) return cli_fail(EXIT_USAGE, "--params is required (see obscura tune --help)");
    if (o->train_count == 0) return cli_fail(EXIT_USAGE, "--train: no training view (see obscura tune --help)");
    if (!o->out || !*o->out) return cli_fail(EXIT_USAGE, "--out FILE.json is required (see obscura tune --help)");
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
    o->common.renderers = o->train_count + o->validate_count + o->check_count; /* every view keeps its renderer */
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
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
static int view_mse(const tune_opts *o, tune_view *v, const ob_settings *s, float *ao, double *mse)
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
    (void)o;
    return EXIT_OK;
}

typedef struct tune_run {
    const tune_opts *o;
    tune_view *train, *validate;
    float *ao;
    int evaluations, total;
    double start;
    ob_progress bar;
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

/* Mean MSE over a set of views, and each view's RMSE into rmse (may be NULL). */
static int mean_mse(tune_run *t, tune_view *views, int count, const tune_param *ps, int pcount, double *mean,
                    double *rmse)
{
    ob_settings s;
    int code = settings_with(t->o, ps, pcount, &s);
    if (code != EXIT_OK) return code;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        double mse = 0.0;
        if ((code = view_mse(t->o, &views[i], &s, t->ao, &mse)) != EXIT_OK) return code;
        sum += mse;
        if (rmse) rmse[i] = sqrt(mse);
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

/* earlier, earlier_n and also, also_n: the views loaded before this one (training, validation),
 * whose scenes it shares when it names the same one: each copy of a scene is memory that
 * --max-memory counted once. */
static int load_view(const tune_opts *o, ob_context *ctx, const char *spec, tune_view *v, size_t *max_px,
                     const tune_view *earlier, int earlier_n, const tune_view *also, int also_n)
{
    const cli_common *c = &o->common;
    if (strlen(spec) >= sizeof v->name)
        return cli_fail(EXIT_USAGE, "%.80s...: a view of %zu bytes; expected SCENE:CAMERA of at most %zu", spec,
                        strlen(spec), sizeof v->name - 1);
    snprintf(v->spec, sizeof v->spec, "%s", spec);
    snprintf(v->name, sizeof v->name, "%s", spec);
    const char *camera = NULL;
    char *colon = strrchr(v->name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    v->scene = loaded_scene(earlier, earlier_n, v->name);
    if (!v->scene) v->scene = loaded_scene(also, also_n, v->name);
    v->owns_scene = !v->scene;
    int code = v->scene ? EXIT_OK : cli_common_load_scene(c, v->name, &v->scene);
    if (code != EXIT_OK) return code;
    code = cli_common_camera(c, v->scene, camera, &v->cam);
    if (code != EXIT_OK) return code;
    v->r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height});
    if (!v->r || ob_renderer_set_scene(v->r, v->scene) != OB_OK) return cli_fail_from_library();
    if ((code = cli_common_prepare(c, v->r)) != EXIT_OK) return code;
    if ((code = cli_view_frame_make(v->r, &v->cam, c->width, c->height, &v->frame)) != EXIT_OK) return code;
    size_t px = (size_t)c->width * (size_t)c->height;
    v->ref = malloc(px * sizeof(float));
    if (!v->ref) return cli_fail(EXIT_RUNTIME, "out of memory");
    v->radius = ob_query_scene_ao_radius(v->scene);
    /* Before the reference is traced: a view with nothing in it has no error to tune against
     * (--allow-empty does not apply). */
    for (size_t i = 0; i < px; ++i) v->pixels += v->frame.depth[i] > 0.0f;
    if (v->pixels == 0)
        return cli_fail(c->has_eye ? EXIT_USAGE : EXIT_INPUT, "%s: nothing visible from this camera (%s:%s)", spec,
                        ob_query_scene_name(v->scene), v->cam.name);
    char key[900];
    cli_reference_key(c, v->name, v->cam.name, key, sizeof key);
    cli_reference_info info;
    if ((code = cli_reference_ao(v->scene, &v->frame, key, v->radius, o->spp, o->no_cache, c->verbose, v->ref, &info)) != EXIT_OK)
        return code;
    if (px > *max_px) *max_px = px;
    return EXIT_OK;
}

static void free_views(tune_view *v, int n)
{
    for (int i = 0; i < n; ++i) {
        cli_view_frame_free(&v[i].frame);
        free(v[i].ref);
        if (v[i].r) ob_destroy_renderer(v[i].r);
    }
}

/* After every view's renderer is gone: the scenes, each by the view that loaded it. */
static void free_scenes(tune_view *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (v[i].scene && v[i].owns_scene) ob_destroy_scene(v[i].scene);
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

static cJSON *views_json(tune_view *v, int n, const double *before, const double *after)
{
    cJSON *arr = cJSON_CreateArray();
    for (int i = 0; i < n; ++i) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "view", v[i].spec);
        cJSON_AddNumberToObject(e, "radius", v[i].radius);
        cJSON_AddNumberToObject(e, "rmse_default", before[i]);
        cJSON_AddNumberToObject(e, "rmse_tuned", after[i]);
        cJSON_AddItemToArray(arr, e);
    }
    return arr;
}

static double mean_of(const double *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += v[i];
    return n ? s / n : 0.0;
}

static int tune_checked(const tune_opts *op);

int cmd_tune(int argc, char **argv)
{
    tune_opts o;
    cli_outputs outs = {0};
    int code = parse(argc, argv, &o, &outs);
    if (code == EXIT_OK) code = tune_checked(&o);
    code = cli_outputs_finish(&outs, code < 0 ? EXIT_OK : code);
    if (code == EXIT_OK && o.out) printf("\nwrote %s\n", o.out);
    return code;
}

static int tune_checked(const tune_opts *op)
{
    const tune_opts o = *op;
    int code = EXIT_OK;
    const cli_common *c = &o.common;
    const char *method = ob_method_at(c->methods[0])->name;
    tune_param ps[MAX_TUNE];
    int pcount = 0;
    char list[1024];
    snprintf(list, sizeof list, "%s", o.params_text);
    for (char *save = NULL, *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (pcount >= MAX_TUNE) return cli_fail(EXIT_USAGE, "--params: at most %d parameters", MAX_TUNE);
        if ((code = parse_param(method, tok, &ps[pcount])) != EXIT_OK) return code;
        for (int j = 0; j < pcount; ++j)
            if (!strcmp(ps[j].name, ps[pcount].name)) return cli_fail(EXIT_USAGE, "--params: %s.%s twice", method, ps[j].name);
        ++pcount;
    }
    if (pcount == 0) return cli_fail(EXIT_USAGE, "--params: no parameter");
    /* The starting point: the settings as the options give them (defaults, --settings, --set). */
    ob_settings start;
    if ((code = settings_with(&o, ps, 0, &start)) != EXIT_OK) return code;
    for (int k = 0; k < pcount; ++k) {
        ps[k].value = ob_settings_get(&start, ps[k].name);
        if (ps[k].type != OB_PARAM_ENUM && (ps[k].value < ps[k].lo || ps[k].value > ps[k].hi))
            ps[k].value = fminf(fmaxf(ps[k].value, ps[k].lo), ps[k].hi); /* the start clamped into the range */
    }

    ob_context *ctx = cli_make_context(c->gpu, c->verbose);
    if (!ctx) return cli_fail_library_as(EXIT_NO_GPU);
    tune_view train[MAX_VIEWS] = {0}, validate[MAX_VIEWS] = {0}, checks[MAX_VIEWS] = {0};
    int loaded_train = 0, loaded_validate = 0, loaded_check = 0;
    size_t max_px = 0;
    tune_run t = {.o = &o, .train = train, .validate = validate};
    tune_param best[MAX_TUNE];
    double *rmse = calloc(6 * MAX_VIEWS, sizeof(double));
    double *train_before = rmse, *train_after = rmse + MAX_VIEWS, *val_before = rmse + 2 * MAX_VIEWS,
           *val_after = rmse + 3 * MAX_VIEWS, *check_before = rmse + 4 * MAX_VIEWS, *check_after = rmse + 5 * MAX_VIEWS;
    char *json = NULL;
    if (!rmse) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto done;
    }
    for (; loaded_train < o.train_count && code == EXIT_OK; ++loaded_train)
        code = load_view(&o, ctx, o.train[loaded_train], &train[loaded_train], &max_px, train, loaded_train, NULL, 0);
    for (; loaded_validate < o.validate_count && code == EXIT_OK; ++loaded_validate)
        code = load_view(&o, ctx, o.validate[loaded_validate], &validate[loaded_validate], &max_px, validate,
                         loaded_validate, train, loaded_train);
    for (; loaded_check < o.check_count && code == EXIT_OK; ++loaded_check)
        code = load_view(&o, ctx, o.check[loaded_check], &checks[loaded_check], &max_px, checks, loaded_check, train,
                         loaded_train);
    if (code != EXIT_OK) goto done;
    t.ao = malloc(max_px * sizeof(float));
    if (!t.ao) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto done;
    }
    /* Evaluations: the start on both sets, then per pass and parameter its candidates (at most
     * steps + 1, or the enum's options), then the result on the validation views. */
    t.total = o.check_count ? 4 : 2;
    for (int pass = 0; pass < o.passes; ++pass)
        for (int k = 0; k < pcount; ++k) t.total += ps[k].type == OB_PARAM_ENUM ? (int)(ps[k].hi - ps[k].lo) + 1 : o.steps + 1;
    t.start = now_s();
    ob_progress_begin(&t.bar, "tune", t.total);
    double best_mse = 0.0, val_mse = 0.0;
    if ((code = mean_mse(&t, train, o.train_count, ps, pcount, &best_mse, train_before)) != EXIT_OK) goto done;
    progress(&t, "defaults, training views", best_mse, false);
    if (o.validate_count && (code = mean_mse(&t, validate, o.validate_count, ps, pcount, &val_mse, val_before)) != EXIT_OK)
        goto done;
    progress(&t, "defaults, validation views", best_mse, false);
    double check_mse = 0.0;
    if (o.check_count) {
        if ((code = mean_mse(&t, checks, o.check_count, ps, pcount, &check_mse, check_before)) != EXIT_OK) goto done;
        progress(&t, "defaults, check views", best_mse, false);
    }
    memcpy(best, ps, sizeof best);
    for (int pass = 0; pass < o.passes && code == EXIT_OK; ++pass) {
        for (int k = 0; k < pcount && code == EXIT_OK; ++k) {
            float cand[MAX_CANDIDATES];
            int n = candidates(&best[k], o.steps, cand);
            tune_param trial[MAX_TUNE];
            memcpy(trial, best, sizeof trial);
            float chosen = best[k].value;
            for (int j = 0; j < n && code == EXIT_OK; ++j) {
                trial[k].value = cand[j];
                double m = 0.0;
                if ((code = mean_mse(&t, train, o.train_count, trial, pcount, &m, NULL)) != EXIT_OK) break;
                /* Strictly better only: on a tie the earlier candidate (the current value first) stays. */
                if (m < best_mse) {
                    best_mse = m;
                    chosen = cand[j];
                }
                char what[160], v[32];
                value_text(&best[k], cand[j], v, sizeof v);
                snprintf(what, sizeof what, "pass %d %.60s=%.30s", pass + 1, best[k].name, v);
                progress(&t, what, best_mse, false);
            }
            best[k].value = chosen;
            if (best[k].type != OB_PARAM_ENUM) {
                /* Halve the range around the best value, inside the registry's. */
                float half = 0.25f * (best[k].hi - best[k].lo);
                float lo = fmaxf(ps[k].lo, chosen - half), hi = fminf(ps[k].hi, chosen + half);
                best[k].lo = lo;
                best[k].hi = hi;
            }
        }
    }
    if (code != EXIT_OK) goto done;
    double check = 0.0;
    if ((code = mean_mse(&t, train, o.train_count, best, pcount, &check, train_after)) != EXIT_OK) goto done;
    double val_after_mse = 0.0;
    if (o.validate_count && (code = mean_mse(&t, validate, o.validate_count, best, pcount, &val_after_mse, val_after)) != EXIT_OK)
        goto done;
    if (o.check_count) {
        progress(&t, "tuned, validation views", best_mse, false);
        if ((code = mean_mse(&t, checks, o.check_count, best, pcount, &check_mse, check_after)) != EXIT_OK) goto done;
        progress(&t, "tuned, check views", best_mse, true);
    } else {
        progress(&t, "tuned, validation views", best_mse, true);
    }
    ob_progress_end(&t.bar);
    double seconds = now_s() - t.start;

    /* The table on stdout. */
    printf("\n%s tuned over %d training view(s), %d evaluations in %.0f s:\n", method, o.train_count, t.evaluations,
           seconds);
    for (int k = 0; k < pcount; ++k) {
        char a[32], b[32];
        value_text(&ps[k], ps[k].value, a, sizeof a);
        value_text(&best[k], best[k].value, b, sizeof b);
        printf("  %-16s %s -> %s\n", ps[k].name, a, b);
    }
    printf("\n  %-40s %-10s %10s %10s\n", "view", "role", "default", "tuned");
    for (int i = 0; i < o.train_count; ++i)
        printf("  %-40s %-10s %10.4f %10.4f\n", train[i].spec, "training", train_before[i], train_after[i]);
    for (int i = 0; i < o.validate_count; ++i)
        printf("  %-40s %-10s %10.4f %10.4f\n", validate[i].spec, "validation", val_before[i], val_after[i]);
    for (int i = 0; i < o.check_count; ++i)
        printf("  %-40s %-10s %10.4f %10.4f\n", checks[i].spec, "check", check_before[i], check_after[i]);
    printf("  %-40s %-10s %10.4f %10.4f\n", "mean RMSE", "training", mean_of(train_before, o.train_count),
           mean_of(train_after, o.train_count));
    if (o.validate_count)
        printf("  %-40s %-10s %10.4f %10.4f\n", "mean RMSE", "validation", mean_of(val_before, o.validate_count),
               mean_of(val_after, o.validate_count));
    if (o.check_count)
        printf("  %-40s %-10s %10.4f %10.4f\n", "mean RMSE", "check", mean_of(check_before, o.check_count),
               mean_of(check_after, o.check_count));

    /* The settings file, whole or not at all. */
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "method", method);
    cJSON *params = cJSON_AddObjectToObject(root, "params");
    for (int k = 0; k < pcount; ++k) {
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
    cJSON_AddStringToObject(how, "filter", ob_filter_at(c->filters[0])->name);
    char size[32];
    snprintf(size, sizeof size, "%dx%d", c->width, c->height);
    cJSON_AddStringToObject(how, "size", size);
    cJSON_AddNumberToObject(how, "spp", o.spp);
    cJSON_AddNumberToObject(how, "passes", o.passes);
    cJSON_AddNumberToObject(how, "steps", o.steps);
    cJSON_AddNumberToObject(how, "evaluations", t.evaluations);
    cJSON_AddNumberToObject(how, "seconds", seconds);
    cJSON_AddItemToObject(how, "training", views_json(train, o.train_count, train_before, train_after));
    cJSON_AddItemToObject(how, "validation", views_json(validate, o.validate_count, val_before, val_after));
    cJSON_AddNumberToObject(how, "training_rmse_default", mean_of(train_before, o.train_count));
    cJSON_AddNumberToObject(how, "training_rmse_tuned", mean_of(train_after, o.train_count));
    if (o.validate_count) {
        cJSON_AddNumberToObject(how, "validation_rmse_default", mean_of(val_before, o.validate_count));
        cJSON_AddNumberToObject(how, "validation_rmse_tuned", mean_of(val_after, o.validate_count));
    }
    cJSON_AddItemToObject(how, "check", views_json(checks, o.check_count, check_before, check_after));
    if (o.check_count) {
        cJSON_AddNumberToObject(how, "check_rmse_default", mean_of(check_before, o.check_count));
        cJSON_AddNumberToObject(how, "check_rmse_tuned", mean_of(check_after, o.check_count));
    }
    json = cJSON_Print(root);
    cJSON_Delete(root);
    if (!json) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto done;
    }
    size_t jl = strlen(json);
    char *withnl = realloc(json, jl + 2);
    if (withnl) {
        json = withnl;
        json[jl] = '\n';
        json[jl + 1] = '\0';
    }
    /* Committed by cmd_tune, which prints "wrote" only then. */
    code = cli_outputs_write_text(o.outs, o.out_index, json);
done:
    ob_progress_end(&t.bar);
    free(json);
    free(t.ao);
    free(rmse);
    free_views(train, loaded_train);
    free_views(validate, loaded_validate);
    free_views(checks, loaded_check);
    free_scenes(train, loaded_train);
    free_scenes(validate, loaded_validate);
    free_scenes(checks, loaded_check);
    ob_destroy_context(ctx);
    return code;
}
